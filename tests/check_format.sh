#!/usr/bin/env bash
# Checks that every C++ file git tracks is formatted by the repository's .clang-format.
# Usage: check_format.sh PROJECT_DIR. Prints each file that differs (and how to fix it) and
# exits 1; exits 2 when clang-format or git is missing (scripts/test.sh installs both).
set -euo pipefail
root=${1:?usage: check_format.sh PROJECT_DIR}
cd "$root"
for tool in clang-format git; do
    command -v "$tool" > /dev/null || { echo "check_format: $tool is not installed" >&2; exit 2; }
done
status=0
while IFS= read -r -d '' file; do
    if ! clang-format --style=file "$file" | cmp -s - "$file"; then
        echo "$file: not formatted (run: clang-format -i '$file')"
        status=1
    fi
done < <(git ls-files -z -- '*.cpp' '*.h' '*.inc')
[ "$status" -eq 0 ] && echo "check_format: every tracked C++ file is formatted"
exit "$status"
