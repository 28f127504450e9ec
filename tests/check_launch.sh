#!/usr/bin/env bash
# What the plantarch command loads when it starts: none of the builder's server libraries (it
# starts the builder through plantarch-builder beside it; without it, `plantarch builder` says
# so in one line and exits 2) and not Embree (loaded when a picture, scan or collision
# avoidance first needs it; a library that cannot be loaded is one line and exit 2).
# Usage: check_launch.sh BUILD_DIR EMBREE   (EMBREE: loaded, a release build's way; linked, a
# sanitized build's, where LeakSanitizer cannot scan the threads of a library loaded later)
set -euo pipefail
usage="usage: check_launch.sh BUILD_DIR loaded|linked"
build=${1:?$usage}
embree=${2:?$usage}
[[ $embree == loaded || $embree == linked ]] || { echo "$usage" >&2; exit 2; }
fail() { echo "check_launch: $*" >&2; exit 1; }

needed=$(readelf -d "$build/plantarch" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
[[ -n "$needed" ]] || fail "readelf found no NEEDED entries in $build/plantarch"
loaded_on_use=(httplib ssl crypto brotli zip bz2)
[[ $embree == loaded ]] && loaded_on_use+=(embree tbb)
[[ $embree == linked ]] && { grep -q embree <<< "$needed" || fail "a sanitized plantarch does not link Embree"; }
for lib in "${loaded_on_use[@]}"; do
    if grep -q "$lib" <<< "$needed"; then fail "plantarch needs a library it loads only on use: $(grep "$lib" <<< "$needed")"; fi
done
readelf -d "$build/plantarch-builder" | grep -q 'NEEDED.*httplib' ||
    fail "plantarch-builder does not link the HTTP library: is it the builder?"

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cp "$build/plantarch" "$scratch/plantarch"
status=0
"$scratch/plantarch" builder --port 0 > "$scratch/out" 2> "$scratch/err" || status=$?
[[ $status -eq 2 ]] || fail "without plantarch-builder: exit $status, expected 2"
[[ $(wc -l < "$scratch/err") -eq 1 ]] || fail "without plantarch-builder: not one line: $(cat "$scratch/err")"
grep -q "cannot start the builder: No such file or directory (valid: plantarch-builder installed beside plantarch)" "$scratch/err" ||
    fail "unexpected message: $(cat "$scratch/err")"
# A bad option is refused by plantarch itself, before the builder is looked for.
status=0
"$scratch/plantarch" builder --port 70000 2> "$scratch/err" || status=$?
[[ $status -eq 2 ]] && grep -q -- "--port = 70000" "$scratch/err" || fail "--port 70000: exit $status: $(cat "$scratch/err")"
# Embree on first use: a picture works, and a library that cannot be loaded is one line.
"$build/plantarch" build bean --age 5 -o "$scratch/bean.png" --image-size 64x48 > /dev/null ||
    fail "a picture of a bean failed"
[[ -s "$scratch/bean.png" ]] || fail "no picture written"
status=0
PLANTARCH_EMBREE_LIBRARY=/nonexistent/libembree3.so.3 "$build/plantarch" build bean --age 5 \
    -o "$scratch/none.png" > /dev/null 2> "$scratch/err" || status=$?
[[ $status -eq 2 && $(wc -l < "$scratch/err") -eq 1 ]] || fail "no Embree: exit $status: $(cat "$scratch/err")"
grep -q "PLANTARCH_EMBREE_LIBRARY = /nonexistent/libembree3.so.3: cannot load the ray tracing library" "$scratch/err" ||
    fail "no Embree: unexpected message: $(cat "$scratch/err")"
[[ ! -e "$scratch/none.png" ]] || fail "no Embree: a picture was written anyway"
# A command that draws nothing and steers nothing never asks for Embree: a library that cannot
# be loaded is no matter to it.
PLANTARCH_EMBREE_LIBRARY=/nonexistent/libembree3.so.3 "$build/plantarch" build bean --age 5 \
    -o "$scratch/bean.obj" > /dev/null 2> "$scratch/err" || fail "a mesh without Embree: $(cat "$scratch/err")"
[[ -s "$scratch/bean.obj" ]] || fail "a mesh without Embree: nothing written"
echo "check_launch: ok"
