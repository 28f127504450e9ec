#!/usr/bin/env bash
# Builds bench/reference/driver.cpp against a checkout of the reference system (version
# 1.3.80, CUDA off) in a folder outside this repository, for bench/scripts/user_speed.py.
#
#   bash bench/reference/build.sh HELIOS_CHECKOUT OUT_DIR
#
# HELIOS_CHECKOUT needs core/, plugins/plantarchitecture/ and plugins/collisiondetection/ of
# the reference's public repository at tag v1.3.80. About 8 minutes on two cores. Prints the
# driver's path; run it from its folder (the reference reads its assets from there).
set -euo pipefail
usage="usage: bench/reference/build.sh HELIOS_CHECKOUT OUT_DIR"
helios=${1:?$usage}
out=${2:?$usage}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
[ -f "$helios/core/CMake_project.cmake" ] || { echo "build.sh: $helios/core/CMake_project.cmake: no such file (valid: a checkout of the reference)" >&2; exit 2; }
case "$(cd "$out" 2>/dev/null && pwd || echo "$out")/" in
  "$(cd "$here/../.." && pwd)"/*) echo "build.sh: $out is inside the repository (valid: a folder outside it)" >&2; exit 2 ;;
esac
helios=$(cd "$helios" && pwd)
mkdir -p "$out/build"
cmake -S "$here" -B "$out/build" -DHELIOS_DIR="$helios" -DCMAKE_BUILD_TYPE=Release > "$out/configure.log" 2>&1 ||
  { tail -30 "$out/configure.log" >&2; exit 1; }
cmake --build "$out/build" --parallel "$(nproc)" > "$out/build.log" 2>&1 || { tail -30 "$out/build.log" >&2; exit 1; }
echo "$(cd "$out/build" && pwd)/reference_driver"
