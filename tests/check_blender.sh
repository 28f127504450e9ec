#!/usr/bin/env bash
# Imports glTF files of library plants (a bean as .glb and .gltf, a trellis vine with its
# posts and wires, a textured bean, and that bean as a textured OBJ with its atlas's -o/-s)
# into Blender with its own importers, headless, and checks that Blender holds
# the same number of triangles as the file's scene, and plays a growth animation. Usage: check_blender.sh PLANTARCH_BINARY.
# Exits 1 on a mismatch, 2 when Blender is missing (scripts/test.sh installs it).
set -euo pipefail
cli=$(realpath "${1:?usage: check_blender.sh PLANTARCH_BINARY}")
here=$(dirname "$(realpath "$0")")
command -v blender > /dev/null || { echo "check_blender: blender is not installed (scripts/test.sh installs it)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
status=0
check() {  # check FILE TRIANGLES
    local line
    line=$(cd "$out" && blender -b --factory-startup --python "$here/blender/import_gltf.py" -- "$1" 2>&1 |
           grep '^PLANTARCH ' | head -1 | cut -d' ' -f2-) || true
    local got
    got=$(echo "$line" | sed -n 's/.*"triangles": \([0-9]*\).*/\1/p')
    if [ "$got" != "$2" ]; then
        echo "check_blender: $1: Blender holds ${got:-no} triangles, the file's scene $2 ($line)"
        status=1
    else
        echo "check_blender: $(basename "$1"): $got triangles, as written"
    fi
}
triangles() {  # the triangle count the build printed
    sed -n 's/.* \([0-9][0-9]*\) triangles in .*/\1/p'
}
n=$("$cli" --seed 3 build bean --age 40 -o "$out/bean.glb" -o "$out/bean.gltf" | triangles)
check "$out/bean.glb" "$n"
check "$out/bean.gltf" "$n"
"$cli" --seed 3 build grapevine_VSP --age 270 -o "$out/vine.glb" -o "$out/vine.ply" > /dev/null
# The vine's file holds its trellis too: count the PLY's faces (every object in the scene).
faces=$(sed -n 's/^element face \([0-9]*\)$/\1/p' < <(head -c 4096 "$out/vine.ply" | tr -d '\r'))
check "$out/vine.glb" "$faces"
# A growth animation: at each frame Blender shows the plant built at that frame's age.
"$cli" --seed 3 build bean --frames 0:20:10 -o "$out/growth.glb" > /dev/null
expected=""
for age in 0 10 20; do
    expected+="${expected:+, }$("$cli" --seed 3 build bean --age "$age" -o "$out/age.ply" | triangles)"
done
line=$(cd "$out" && blender -b --factory-startup --python "$here/blender/import_gltf.py" -- "$out/growth.glb" 2>&1 |
       grep '^PLANTARCH ' | head -1 | cut -d' ' -f2-) || true
frames=$(echo "$line" | sed -n 's/.*"frames": \(\[[0-9, ]*\]\).*/\1/p')
if [ "$frames" != "[$expected]" ]; then
    echo "check_blender: growth.glb: Blender shows ${frames:-nothing} frame by frame, the plants at its ages [$expected] ($line)"
    status=1
else
    echo "check_blender: growth.glb plays in Blender, frame by frame: $frames triangles"
fi
# A skinned bean (--skin): one armature with a bone per joint of the file deforming its meshes,
# the bean's triangles, and at rest every vertex where the unskinned bean has it.
"$cli" --seed 3 build bean --age 40 --skin -o "$out/skinned.glb" > /dev/null
skinned=$(cd "$out" && blender -b --factory-startup --python "$here/blender/import_gltf.py" -- "$out/skinned.glb" 2>&1 |
          grep '^PLANTARCH ' | head -1 | cut -d' ' -f2-) || true
if ! verdict=$(python3 - "$out/skinned.glb" "$n" "$skinned" <<'PY'
import json, struct, sys
data = open(sys.argv[1], "rb").read()
doc = json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
joints = sum(len(s["joints"]) for s in doc["skins"])
skinned = json.loads(sys.argv[3] or "{}")
# The bean's box as written: its positions' bounds (z up, as Blender turns glTF back) moved by
# its plant node's translation.
base = next(n.get("translation", [0, 0, 0]) for n in doc["nodes"] if "plantID" in n.get("extras", {}))
low, high = [float("inf")] * 3, [float("-inf")] * 3
for mesh in doc["meshes"]:
    for p in mesh["primitives"]:
        a = doc["accessors"][p["attributes"]["POSITION"]]
        low = [min(x, m + b) for x, m, b in zip(low, a["min"], base)]
        high = [max(x, m + b) for x, m, b in zip(high, a["max"], base)]
off = max(abs(x - y) for x, y in zip(low + high, skinned.get("box", [1e9] * 6)))
ok = (skinned.get("armatures") == 1 and skinned.get("bones") == joints and
      skinned.get("skinned", 0) > 0 and skinned.get("triangles") == int(sys.argv[2]) and off < 1e-5)
print(json.dumps({k: skinned.get(k) for k in ("armatures", "bones", "skinned", "triangles")} |
                 {"joints": joints, "box_off": off}))
sys.exit(0 if ok else 1)
PY
); then
    echo "check_blender: skinned.glb in Blender: $verdict ($skinned)"
    status=1
else
    echo "check_blender: skinned.glb imports with its armature: $verdict"
fi
# Procedural textures (--materials textured): the bean's triangles, and its four textured
# materials (two leaf colours, bark, stems) each sampling the embedded maps, with a normal map;
# the two leaf colours read their parts of the atlas through a Mapping node
# (KHR_texture_transform, required by the file).
t=$("$cli" --seed 3 build bean --age 40 --materials textured --texture-size 128 -o "$out/textured.glb" | triangles)
textured=$(cd "$out" && blender -b --factory-startup --python "$here/blender/import_gltf.py" -- "$out/textured.glb" 2>&1 |
           grep '^PLANTARCH ' | head -1 | cut -d' ' -f2-) || true
if ! echo "$textured" | grep -q "\"triangles\": $t," ||
    ! echo "$textured" | grep -q '"textured_materials": 4, "normal_mapped": 4, "transformed": 2'; then
    echo "check_blender: textured.glb in Blender: ${textured:-nothing}, expected $t triangles, 4 textured materials, 2 transformed"
    status=1
else
    echo "check_blender: textured.glb imports with its maps: $textured"
fi
# The same bean as a textured OBJ: Blender's OBJ importer turns each atlas map line's -o and -s
# into a Mapping node, at the .mtl's offset and scale; the bark's and stems' maps have none.
"$cli" --seed 3 build bean --age 40 --materials textured --texture-size 128 -o "$out/textured.obj" > /dev/null
objmaps=$(cd "$out" && blender -b --factory-startup --python "$here/blender/import_obj_maps.py" -- "$out/textured.obj" 2>&1 |
          grep '^PLANTARCH ' | head -1 | cut -d' ' -f2-) || true
if ! verdict=$(echo "$objmaps" | python3 -c '
import json, sys
report = json.load(sys.stdin)
mtl = open(sys.argv[1]).read().splitlines()
filed = sorted({tuple(round(float(x), 5) for x in l.split()[2:4] + l.split()[5:7])
                for l in mtl if l.startswith("map_Kd -o ")})
seen = sorted({tuple(m) for r in report.values() for m in r["mappings"]})
atlas = [r for r in report.values() if any("atlas" in i for i in r["images"])]
plain = [r for r in report.values() if r["images"] and not any("atlas" in i for i in r["images"])]
ok = (len(filed) == 2 and seen == filed and len(atlas) == 2 and
      all(len(r["mappings"]) == 1 for r in atlas) and plain and
      all(not r["mappings"] for r in plain))
print(json.dumps({"filed": filed, "blender": seen}))
sys.exit(0 if ok else 1)' "$out/textured.mtl"); then
    echo "check_blender: textured.obj in Blender: ${verdict:-nothing}: $objmaps"
    status=1
else
    echo "check_blender: textured.obj's atlas parts as Blender Mapping nodes: $verdict"
fi
exit "$status"
