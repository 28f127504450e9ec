#!/usr/bin/env bash
# Builds plantarch (via setup.sh) and runs the whole test suite: the C++ tests through ctest
# and the Python binding's tests through pytest when the module is built.
# Usage: bash scripts/test.sh [--sanitize]   (--sanitize: ASan+UBSan build in build-asan/)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --tests "$@"
# What only the tests need: the format check's clang-format, pytest for the Python tests,
# Blender and Chromium (three.js) to load the glTF files, venv and pip for the wheel test,
# Slurm and munge for the dataset job array (a private cluster the test starts and stops),
# Dask's distributed for the samples and fields made on a local cluster.
test_packages=(clang-format python3-pytest python3-venv python3-pip blender chromium slurm-wlm munge
  python3-distributed)
missing=()
for p in "${test_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >/dev/null
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# Node.js for the format checks (the machine's own when it has one), and their npm packages
# at the versions tests/js/package-lock.json pins.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >/dev/null
  apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
fi
npm ci --prefix tests/js --no-audit --no-fund --loglevel=error >/dev/null
dir=build
for a in "$@"; do [ "$a" = --sanitize ] && dir=build-asan; done
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$dir" --output-on-failure --timeout 600 -j "$(nproc)"
# The Python module's tests, through the installed module (setup.sh's .pth file) in a plain
# build, and with the sanitizer runtimes preloaded into the interpreter in a sanitized one.
if [ "$dir" = build ]; then
  (cd /tmp && /usr/bin/python3 -c "import plantarch") || { echo "test: the Python module does not import" >&2; exit 1; }
  PLANTARCH_CLI="$PWD/$dir/plantarch" /usr/bin/python3 -m pytest -q -p no:cacheprovider python/tests
else
  PLANTARCH_CLI="$PWD/$dir/plantarch" PYTHONPATH="$PWD/$dir/python" ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
    LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
    /usr/bin/python3 -m pytest -q -p no:cacheprovider python/tests
fi
