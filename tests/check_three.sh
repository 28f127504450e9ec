#!/usr/bin/env bash
# Loads glTF files of library plants (a bean as .glb and .gltf, a trellis vine) with three.js's
# GLTFLoader in headless Chromium and checks that three.js holds the file's triangles and sees
# the label attributes (_PLANT_ID, _OBJECT_ID, _ORGAN), plays a growth animation, and reads
# textured materials with and without the texture atlas.
# Usage: check_three.sh PROJECT_DIR
# PLANTARCH_BINARY. Exits 1 on a mismatch, 2 when node, Chromium or the npm packages are
# missing (scripts/test.sh installs them).
set -euo pipefail
root=${1:?usage: check_three.sh PROJECT_DIR PLANTARCH_BINARY}
cli=$(realpath "${2:?usage: check_three.sh PROJECT_DIR PLANTARCH_BINARY}")
command -v node > /dev/null || { echo "check_three: node is not installed" >&2; exit 2; }
[ -x /usr/bin/chromium ] || { echo "check_three: chromium is not installed (scripts/test.sh installs it)" >&2; exit 2; }
[ -d "$root/tests/js/node_modules/three" ] && [ -d "$root/tests/js/node_modules/puppeteer-core" ] ||
    { echo "check_three: three.js or puppeteer-core missing (run: npm ci --prefix tests/js)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
triangles() { sed -n 's/.* \([0-9][0-9]*\) triangles in .*/\1/p'; }
bean=$("$cli" --seed 3 build bean --age 40 -o "$out/bean.glb" -o "$out/bean.gltf" | triangles)
"$cli" --seed 3 build grapevine_VSP --age 270 -o "$out/vine.glb" -o "$out/vine.ply" > /dev/null
vine=$(head -c 4096 "$out/vine.ply" | tr -d '\r' | sed -n 's/^element face \([0-9]*\)$/\1/p')
report=$(node "$root/tests/js/three_load.mjs" "$out/bean.glb" "$out/bean.gltf" "$out/vine.glb") ||
    { echo "$report"; exit 1; }
status=0
while read -r expected line; do
    got=$(echo "$line" | sed -n 's/.*"triangles":\([0-9]*\).*/\1/p')
    if [ "$got" != "$expected" ]; then
        echo "check_three: three.js holds ${got:-no} triangles, the file $expected: $line"
        status=1
    fi
    for a in _plant_id _object_id _organ _feature_id_0 normal; do
        echo "$line" | grep -q "\"$a\"" || { echo "check_three: no $a attribute: $line"; status=1; }
    done
done < <(paste -d' ' <(printf '%s\n' "$bean" "$bean" "$vine") <(echo "$report"))
# GPU instancing (--instancing gpu): GLTFLoader makes each EXT_mesh_gpu_instancing node an
# InstancedMesh, which draws as many triangles as the tomato has (instances times the mesh's),
# each instance's _OBJECT_ID the one its node's extras list for it.
tomato=$("$cli" --seed 3 build tomato --age 60 --nodes organ --instancing gpu -o "$out/gpu.glb" |
         triangles)
line=$(node "$root/tests/js/three_load.mjs" "$out/gpu.glb") || { echo "$line"; exit 1; }
drawn=$(echo "$line" | sed -n 's/.*"drawn":\([0-9]*\).*/\1/p')
instanced=$(echo "$line" | sed -n 's/.*"instanced":\([0-9]*\).*/\1/p')
if [ "$drawn" != "$tomato" ] || [ "${instanced:-0}" -lt 1 ] || ! echo "$line" | grep -q '"mislabelled":0'; then
    echo "check_three: gpu.glb draws ${drawn:-no} triangles in ${instanced:-no} InstancedMeshes, the tomato $tomato: $line"
    status=1
else
    echo "check_three: gpu.glb draws its $drawn triangles, $instanced InstancedMeshes"
fi
# A growth animation played by three.js's AnimationMixer shows, at each frame's time, the
# triangles of the plant built at that frame's age.
"$cli" --seed 3 build bean --frames 0:20:10 -o "$out/growth.glb" > /dev/null
expected=""
for age in 0 10 20; do
    expected+="${expected:+,}$("$cli" --seed 3 build bean --age "$age" -o "$out/age.ply" | triangles)"
done
expected="[$expected]"
line=$(node "$root/tests/js/three_load.mjs" "$out/growth.glb") || { echo "$line"; exit 1; }
frames=$(echo "$line" | sed -n 's/.*"frames":\(\[[0-9,]*\]\).*/\1/p')
if [ "$frames" != "$expected" ]; then
    echo "check_three: the growth animation shows ${frames:-nothing}, the plants at its ages $expected: $line"
    status=1
else
    echo "check_three: growth.glb plays in three.js, frame by frame: $frames triangles"
fi
# A textured bean (--materials textured): three.js decodes its embedded maps, the leaves'
# alpha-tested, every textured material with normal and roughness maps. Without the atlas
# (--no-texture-atlas) every map is 256 texels wide and none is transformed; with it (the
# default) the two leaf colours read their parts of one atlas (two 256-texel squares with
# 8-texel gutters one above the other: 272 x 544) through KHR_texture_transform, each material's maps
# all the same part, at the offsets and scales the file gives.
"$cli" --seed 3 build bean --age 40 --materials textured --texture-size 256 --no-texture-atlas \
    -o "$out/textured.glb" > /dev/null
"$cli" --seed 3 build bean --age 40 --materials textured --texture-size 256 \
    -o "$out/atlas.gltf" > /dev/null
lines=$(node "$root/tests/js/three_load.mjs" "$out/textured.glb" "$out/atlas.gltf") || { echo "$lines"; exit 1; }
line=$(echo "$lines" | sed -n 1p)
textured=$(echo "$line" | sed -n 's/.*"textured":\({[^}]*}\).*/\1/p')
n=$(echo "$textured" | sed -n 's/.*"materials":\([0-9]*\).*/\1/p')
if [ -z "$n" ] || [ "$n" -lt 3 ] || ! echo "$textured" | grep -q "\"normal\":$n,\"roughness\":$n," ||
    echo "$textured" | grep -q '"alphaTest":0' || ! echo "$textured" | grep -q '"width":256,"transformed":0,'; then
    echo "check_three: textured.glb's materials in three.js: ${textured:-none}: $line"
    status=1
else
    echo "check_three: textured.glb loads in three.js with its maps: $textured"
fi
line=$(echo "$lines" | sed -n 2p)
if ! verdict=$(echo "$line" | node -e '
    const fs = require("fs");
    const t = JSON.parse(fs.readFileSync(0, "utf8")).textured || {};
    const doc = JSON.parse(fs.readFileSync(process.argv[1], "utf8"));
    const filed = doc.materials.map((m) => m.pbrMetallicRoughness.baseColorTexture)
        .filter((i) => i && i.extensions).map((i) => i.extensions.KHR_texture_transform)
        .map((k) => [...k.offset, ...k.scale].map((x) => Math.round(x * 1e4) / 1e4));
    const parts = (t.parts || []).filter((p) => p.join() !== "0,0,1,1");
    const ok = t.transformed === 2 && t.sameParts === true && t.width === 272 &&
        t.normal === t.materials && t.roughness === t.materials &&
        JSON.stringify(parts.sort()) === JSON.stringify(filed.sort()) &&
        doc.extensionsRequired.includes("KHR_texture_transform");
    console.log(JSON.stringify({ transformed: t.transformed, sameParts: t.sameParts, width: t.width, parts, filed }));
    process.exit(ok ? 0 : 1);' "$out/atlas.gltf"); then
    echo "check_three: atlas.gltf in three.js: ${verdict:-nothing}: $line"
    status=1
else
    echo "check_three: atlas.gltf's leaves read their atlas parts in three.js: $verdict"
fi
# A skinned bean (--skin): three.js loads its meshes as SkinnedMeshes with a bone per joint of
# the file, the bean's triangles and labels, and at bind pose its vertices where the unskinned
# bean has them (the same world box, within 1e-5 m).
"$cli" --seed 3 build bean --age 40 --skin -o "$out/skinned.glb" > /dev/null
lines=$(node "$root/tests/js/three_load.mjs" "$out/bean.glb" "$out/skinned.glb") || { echo "$lines"; exit 1; }
if ! verdict=$(echo "$lines" | node -e '
    const [plain, skin] = require("fs").readFileSync(0, "utf8").trim().split("\n").map(JSON.parse);
    const s = skin.skinned || {};
    const off = Math.max(...plain.box.map((x, k) => Math.abs(x - skin.box[k])));
    const ok = s.meshes === skin.meshes && s.bones === s.joints && s.joints > 1 &&
        skin.triangles === plain.triangles && skin.objects === plain.objects &&
        ["_object_id", "_organ", "_plant_id", "skinIndex", "skinWeight"].every((a) => skin.attributes.includes(a)) &&
        off < 1e-5;
    console.log(JSON.stringify({ ...s, triangles: skin.triangles, boxOff: off }));
    process.exit(ok ? 0 : 1);'); then
    echo "check_three: skinned.glb in three.js: $verdict: $lines"
    status=1
else
    echo "check_three: skinned.glb loads in three.js as skinned meshes at the bean's pose: $verdict"
fi
# --wind: three.js's AnimationMixer plays the "wind" clip, a rotation track per joint but the root.
"$cli" --seed 3 build bean --age 40 --wind 15 -o "$out/wind.glb" > /dev/null
line=$(node "$root/tests/js/three_load.mjs" "$out/wind.glb") || { echo "$line"; exit 1; }
joints=$(echo "$line" | sed -n 's/.*"joints":\([0-9]*\).*/\1/p')
if ! echo "$line" | grep -q '"animation":"wind"' ||
    ! echo "$line" | grep -q "\"tracks\":$((joints - 1))[,}]"; then
    echo "check_three: wind.glb's animation in three.js: $line"
    status=1
else
    echo "check_three: wind.glb plays its wind clip in three.js: $((joints - 1)) joint tracks"
fi
# Levels of detail and meshopt compression: three.js (with its MeshoptDecoder) holds the plain
# file's triangles and objects in the compressed files, and each MSFT_lod level, loaded by its
# node, every object of the full level with fewer triangles than the level before.
"$cli" --seed 3 build bean --age 40 --lod reduced,cards -o "$out/lod.glb" --meshopt -o "$out/lod_meshopt.gltf" > /dev/null
"$cli" --seed 3 build bean --age 40 --meshopt -o "$out/meshopt.glb" > /dev/null
report=$(node "$root/tests/js/three_load.mjs" "$out/bean.glb" "$out/meshopt.glb" "$out/lod.glb" "$out/lod_meshopt.gltf") ||
    { echo "$report"; exit 1; }
objects=$(echo "$report" | head -1 | sed -n 's/.*"objects":\([0-9]*\).*/\1/p')
while read -r line; do
    echo "$line" | grep -q "\"triangles\":$bean,.*\"objects\":$objects[,}]" ||
        { echo "check_three: not the plain file's $bean triangles and $objects objects: $line"; status=1; }
done <<< "$report"
while read -r line; do
    levels=$(echo "$line" | sed -n 's/.*"levels":\(\[[^]]*\]\).*/\1/p')
    t1=$(echo "$levels" | sed -n 's/^\[{"triangles":\([0-9]*\),"objects":\([0-9]*\),"shared":\([0-9]*\)},{"triangles":\([0-9]*\),"objects":\([0-9]*\),"shared":\([0-9]*\)}\]$/\1 \2 \3 \4 \5 \6/p')
    read -r r ro rs c co cs <<< "$t1"
    if [ -z "$t1" ] || [ "$r" -ge "$bean" ] || [ "$c" -ge "$r" ] || [ "$ro" != "$objects" ] ||
        [ "$rs" != "$objects" ] || [ "$co" != "$objects" ] || [ "$cs" != "$objects" ]; then
        echo "check_three: levels of detail ${levels:-missing}, full level $bean triangles and $objects objects: $line"
        status=1
    fi
done < <(echo "$report" | tail -2)
[ "$status" -eq 0 ] && echo "check_three: meshopt and MSFT_lod files load in three.js, levels: $levels"
[ "$status" -eq 0 ] && echo "check_three: 5 files load in three.js with their triangles and labels"
exit "$status"
