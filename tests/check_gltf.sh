#!/usr/bin/env bash
# Writes glTF files of library plants with the plantarch command (a bean as .glb and .gltf,
# a canopy, a trellis vine with its posts and wires, an almond, a growth animation, and the
# examples of docs/formats.md) and checks each with the Khronos glTF validator: no errors, no warnings.
# Usage: check_gltf.sh PROJECT_DIR PLANTARCH_BINARY. Exits 1 on any problem, 2 when node or
# the validator (tests/js, installed by scripts/test.sh) is missing.
set -euo pipefail
root=${1:?usage: check_gltf.sh PROJECT_DIR PLANTARCH_BINARY}
cli=$(realpath "${2:?usage: check_gltf.sh PROJECT_DIR PLANTARCH_BINARY}")
command -v node > /dev/null || { echo "check_gltf: node is not installed (scripts/test.sh installs it)" >&2; exit 2; }
[ -d "$root/tests/js/node_modules/gltf-validator" ] ||
    { echo "check_gltf: the glTF validator is not installed (run: npm ci --prefix tests/js)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$cli" --seed 3 build bean --age 40 -o "$out/bean.glb" -o "$out/bean.gltf" > /dev/null
"$cli" --seed 3 canopy bean --count 2x2 --age 30 -o "$out/canopy.glb" > /dev/null
# Skinned plants (--skin): a bean, and a tomato bent under its load with a node pulled.
"$cli" --seed 3 build bean --age 40 --skin -o "$out/skinned.glb" -o "$out/skinned.gltf" > /dev/null
"$cli" --seed 3 build tomato --age 80 --bend --pull 0:5:0.5,0,0 --skin -o "$out/bent_skinned.glb" > /dev/null
"$cli" --seed 3 build grapevine_VSP --age 270 -o "$out/vine.glb" > /dev/null
"$cli" --seed 3 build almond --age 400 -o "$out/almond.glb" > /dev/null
"$cli" --seed 3 build bean --frames 0:20:10 -o "$out/growth.glb" -o "$out/growth.gltf" > /dev/null
# Procedural textures, embedded (binary buffer and base64), and an animation with them. The
# bean's two leaf colours share an atlas (KHR_texture_transform, required); without it
# (--no-texture-atlas) each has its own images.
"$cli" --seed 3 build bean --age 40 --materials textured --texture-size 64 \
    -o "$out/textured.glb" -o "$out/textured.gltf" > /dev/null
"$cli" --seed 3 build bean --age 40 --materials textured --texture-size 64 --no-texture-atlas \
    -o "$out/textured_no_atlas.glb" > /dev/null
"$cli" --seed 3 build tomato --age 60 --materials textured --texture-size 64 -o "$out/tomato_textured.glb" > /dev/null
"$cli" --seed 3 build bean --age 40 --materials textured --texture-size 64 --lod reduced,cards \
    -o "$out/textured_lod.glb" > /dev/null
"$cli" --seed 3 build bean --age 40 --materials textured --texture-size 64 --nodes organ \
    -o "$out/textured_organs.glb" > /dev/null
"$cli" --seed 3 build bean --frames 10:20:5 --materials textured --texture-size 64 \
    -o "$out/textured_growth.glb" > /dev/null
# GPU instancing (EXT_mesh_gpu_instancing, required): the validator checks the document and
# lists the extension as one it does not check (three.js draws the instances: check_three.sh).
"$cli" --seed 3 build tomato --age 60 --nodes organ --instancing gpu \
    -o "$out/tomato_gpu.glb" -o "$out/tomato_gpu.gltf" > /dev/null
"$cli" --seed 3 canopy bean --count 2x2 --age 30 --nodes organ --instancing gpu \
    -o "$out/canopy_gpu.glb" > /dev/null
# Levels of detail (MSFT_lod) and EXT_meshopt_compression: the validator checks the document and
# lists both as extensions it does not check (three.js decodes them: check_three.sh).
"$cli" --seed 3 build bean --age 40 --lod reduced,cards -o "$out/lod.glb" -o "$out/lod.gltf" > /dev/null
"$cli" --seed 3 build tomato --age 60 --lod reduced:0.1,cards --meshopt \
    -o "$out/lod_meshopt.glb" -o "$out/lod_meshopt.gltf" > /dev/null
# The tiles of a field (plantarch field: one GLB per tile).
"$cli" field "$root/examples/fields/bean_field.json" --out "$out/field" --tile-size 0.6 > /dev/null
# The examples of docs/formats.md, run as written (build/plantarch is the binary under test).
mkdir -p "$out/doc"
awk '/^```sh$/{on=1; next} /^```$/{on=0} on' "$root/docs/formats.md" |
    sed "s|build/plantarch|$cli|" | (cd "$out/doc" && bash -euo pipefail) > /dev/null
report=$(node "$root/tests/js/validate_gltf.mjs" "$out"/*.glb "$out"/*.gltf "$out"/doc/out/*.gl* \
    "$out"/field/*.glb) ||
    { echo "$report"; exit 1; }
echo "$report" | grep -q '"warnings":[1-9]' && { echo "$report"; exit 1; }
echo "$report" | sed 's/"messages".*//'
echo "check_gltf: $(echo "$report" | wc -l) files, no errors or warnings"
