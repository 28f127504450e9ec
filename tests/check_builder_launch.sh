#!/usr/bin/env bash
# The plantarch command loads none of the builder's server libraries, and starts the builder
# through plantarch-builder beside it; without it, `plantarch builder` says so in one line and
# exits 2. Usage: check_builder_launch.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: check_builder_launch.sh BUILD_DIR}
fail() { echo "check_builder_launch: $*" >&2; exit 1; }

needed=$(readelf -d "$build/plantarch" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
[[ -n "$needed" ]] || fail "readelf found no NEEDED entries in $build/plantarch"
for lib in httplib ssl crypto brotli zip bz2; do
    if grep -q "$lib" <<< "$needed"; then fail "plantarch needs a server library: $(grep "$lib" <<< "$needed")"; fi
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
echo "check_builder_launch: ok"
