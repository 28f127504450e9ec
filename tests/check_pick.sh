#!/usr/bin/env bash
# A fruit picked in three.js: a tomato with fruit, written with --nodes organ (and textured
# materials), is loaded by three.js in headless Chromium (tests/js/pick_organ.mjs); a ray from
# the camera picks one fruit node, which must carry its labels in its extras (organ "fruit",
# an objectID), and three.js must hold the file's triangles. With PLANTARCH_WRITE_DOCS_IMAGES=1
# the picture of the highlighted fruit is written to docs/images/pick-fruit.png.
# Usage: check_pick.sh PROJECT_DIR PLANTARCH_BINARY. Exits 1 on a mismatch, 2 when node,
# Chromium or the npm packages are missing (scripts/test.sh installs them).
set -euo pipefail
root=${1:?usage: check_pick.sh PROJECT_DIR PLANTARCH_BINARY}
cli=$(realpath "${2:?usage: check_pick.sh PROJECT_DIR PLANTARCH_BINARY}")
command -v node > /dev/null || { echo "check_pick: node is not installed" >&2; exit 2; }
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { echo "check_pick: chromium is not installed (scripts/test.sh installs it)" >&2; exit 2; }
[ -d "$root/tests/js/node_modules/three" ] && [ -d "$root/tests/js/node_modules/puppeteer-core" ] ||
    { echo "check_pick: three.js or puppeteer-core missing (run: npm ci --prefix tests/js)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# A tomato at 90 days bears its first fruit (8 of them, seed 42).
triangles=$("$cli" build tomato --age 90 --nodes organ --materials textured --texture-size 256 \
    -o "$out/tomato.glb" | sed -n 's/.* \([0-9][0-9]*\) triangles in .*/\1/p')
png=()
[ "${PLANTARCH_WRITE_DOCS_IMAGES:-0}" = 1 ] && png=(--png "$root/docs/images/pick-fruit.png")
line=$(node "$root/tests/js/pick_organ.mjs" "$out/tomato.glb" --organ fruit --size 800x1000 "${png[@]}") ||
    { echo "check_pick: no fruit could be picked: $line"; exit 1; }
echo "$line" | node -e '
    const r = JSON.parse(require("fs").readFileSync(0, "utf8"));
    const expected = Number(process.argv[1]);
    const p = r.picked || {}, e = p.extras || {};
    const problems = [];
    if (r.triangles !== expected) problems.push(`three.js holds ${r.triangles} triangles, the file ${expected}`);
    if (e.organ !== "fruit") problems.push(`the picked node is a ${e.organ}, not a fruit`);
    if (!Number.isInteger(e.objectID)) problems.push("the picked node has no objectID");
    if (!/^fruit_s\d+_n\d+/.test(p.name || "")) problems.push(`the picked node is named ${p.name}`);
    if (problems.length) { console.log("check_pick: " + problems.join("; ") + ": " + JSON.stringify(r)); process.exit(1); }
    console.log(`check_pick: ${p.name} (objectID ${e.objectID}, ${r.kinds.fruit} fruit) picked in three.js, ${r.triangles} triangles as in the file`);
' "$triangles"
