#!/usr/bin/env bash
# Imports plantarch glTF files into Blender with the add-on plantarch ships
# (blender/plantarch_import.py) and checks the labels it brings in as face attributes
# (tests/blender/check_labels.py): plants as .glb through the add-on's operator, and a small
# canopy as .gltf through its script mode, saved as a .blend and checked when opened; then the
# export variants (--nodes organ, --instancing gpu, --skin, --lod, --materials textured;
# check_variants.py).
# Usage: check_blender_labels.sh SOURCE_DIR PLANTARCH_BINARY.
# Exits 1 on a mismatch, 77 (skipped) when Blender is missing.
set -euo pipefail
src=$(realpath "${1:?usage: check_blender_labels.sh SOURCE_DIR PLANTARCH_BINARY}")
cli=$(realpath "${2:?usage: check_blender_labels.sh SOURCE_DIR PLANTARCH_BINARY}")
addon="$src/blender/plantarch_import.py"
check="$src/tests/blender/check_labels.py"
if ! command -v blender > /dev/null; then
    echo "check_blender_labels: blender is not installed (skipped)" >&2
    exit 77
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
status=0
report() {  # report NAME OUTPUT: the check's line, or all of Blender's output when none
    local line
    line=$(grep '^PLANTARCH_LABELS ' <<< "$2" | head -1) || true
    case "$line" in
        "PLANTARCH_LABELS ok "*) echo "check_blender_labels: $1: ${line#PLANTARCH_LABELS ok }" ;;
        *) echo "check_blender_labels: $1: ${line:-no result}"
           [ -n "$line" ] || echo "$2" | tail -20
           status=1 ;;
    esac
}
# Through the add-on's operator: a bean; a strawberry with peduncles and closed and open
# flowers; a young vine with its trellis (organ obstacle).
"$cli" --seed 3 build bean --age 30 -o "$out/bean.glb" > /dev/null
"$cli" --seed 3 build strawberry --age 60 -o "$out/strawberry.glb" > /dev/null
"$cli" --seed 3 build grapevine_VSP --age 60 -o "$out/vine.glb" > /dev/null
for name in bean strawberry vine; do
    result=$(cd "$out" && blender -b --factory-startup --python-exit-code 1 --python "$check" -- \
             "$out/$name.glb" --addon "$addon" 2>&1) || true
    report "$name.glb, the add-on's operator" "$result"
done
"$cli" --seed 5 canopy bean --count 2x2 --spacing 0.4x0.4 --age 20 -o "$out/canopy.gltf" > /dev/null
result=$(cd "$out" && blender -b --factory-startup --python-exit-code 1 --python "$addon" -- \
         "$out/canopy.gltf" --out "$out/canopy.blend" 2>&1) || true
if [ ! -s "$out/canopy.blend" ]; then
    echo "check_blender_labels: canopy.gltf: the script mode wrote no .blend"
    echo "$result" | tail -20
    status=1
else
    result=$(cd "$out" && blender -b --factory-startup "$out/canopy.blend" --python-exit-code 1 \
             --python "$check" -- "$out/canopy.gltf" 2>&1) || true
    report "canopy.gltf, the script mode's .blend" "$result"
fi
# The export variants (tests/blender/check_variants.py): a node per organ (instanced organs
# labelled by their custom properties), a skin, a level of detail, textured materials, through
# the operator; a node per organ with --split-instances through the script mode's .blend.
# The reduced level of --lod is left out: Blender drops the few zero-area triangles
# meshoptimizer leaves in it, so its count differs. --meshopt is left out: Blender 3.4 cannot
# read EXT_meshopt_compression.
check_variants="$src/tests/blender/check_variants.py"
# --instancing gpu: Blender 3.4's importer refuses EXT_mesh_gpu_instancing; the add-on
# expands the instances into objects first.
for variant in "organ:--nodes organ" "gpu:--nodes organ --instancing gpu" "skin:--skin" \
               "lod:--lod cards" "textured:--materials textured --texture-size 64"; do
    name=${variant%%:*}
    # shellcheck disable=SC2086  # the options are words
    "$cli" --seed 3 build strawberry --age 60 ${variant#*:} -o "$out/$name.glb" > /dev/null
    result=$(cd "$out" && blender -b --factory-startup --python-exit-code 1 \
             --python "$check_variants" -- "$out/$name.glb" --addon "$addon" 2>&1) || true
    report "strawberry $name.glb (${variant#*:}), the add-on's operator" "$result"
done
result=$(cd "$out" && blender -b --factory-startup --python-exit-code 1 --python "$addon" -- \
         "$out/organ.glb" --split-instances --out "$out/split.blend" 2>&1) || true
if [ ! -s "$out/split.blend" ]; then
    echo "check_blender_labels: organ.glb --split-instances: the script mode wrote no .blend"
    echo "$result" | tail -20
    status=1
else
    result=$(cd "$out" && blender -b --factory-startup "$out/split.blend" --python-exit-code 1 \
             --python "$check_variants" -- "$out/organ.glb" --split 2>&1) || true
    report "strawberry organ.glb, --split-instances in the script mode's .blend" "$result"
fi
echo "check_blender_labels: --meshopt files skipped: Blender 3.4 cannot read EXT_meshopt_compression"
exit "$status"
