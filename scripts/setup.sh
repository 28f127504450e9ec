#!/usr/bin/env bash
# Installs every Debian package plantarch needs (idempotent, quiet on success), then
# configures and builds the project into build/ (Release) unless --no-build is given: the
# command-line tool, the builder and the Python module, which is all a user needs. --tests also
# installs what the test binary, the benchmarks and the fuzz targets need and builds
# everything (scripts/test.sh passes it).
# Usage: bash scripts/setup.sh [--no-build] [--tests] [--sanitize]
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libglm-dev libpugixml-dev libembree-dev libstb-dev libtinyobjloader-dev
  libtinygltf-dev nlohmann-json3-dev libcli11-dev libfmt-dev libpcg-cpp-dev
  libomp-dev pybind11-dev python3 python3-dev python3-numpy
  libcpp-httplib-dev libzip-dev libnlopt-dev libmeshoptimizer-dev
)
# The test binary, the benchmarks, the fuzz targets (clang's libFuzzer) and the plot of a
# physiology series (scripts/plot_physiology.py, run by the Python tests) only.
TEST_PACKAGES=(libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev
  python3-matplotlib)

build=1
tests=OFF
sanitize=OFF
for a in "$@"; do
  case "$a" in
    --no-build) build=0 ;;
    --tests) tests=ON ;;
    --sanitize) sanitize=ON ;;
    *) echo "setup: unknown option '$a' (valid: --no-build, --tests, --sanitize)" >&2; exit 2 ;;
  esac
done
[ "$tests" = ON ] && PACKAGES+=("${TEST_PACKAGES[@]}")

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node.js and npm bundle the builder's web front end (the machine's own when it has them).
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  missing+=(nodejs npm)
fi
if ((${#missing[@]})); then
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: missing packages (${missing[*]}); run as root or install them" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >/dev/null
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The web front end's npm packages (three.js, esbuild) at the versions its package-lock.json
# pins, from the npm registry; again only when the lock file changed since the last install.
web=builder/web
if [ ! -f "$web/node_modules/.package-lock.json" ] || [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  npm ci --prefix "$web" --no-audit --no-fund --loglevel=error >/dev/null
fi

((build)) || exit 0

dir=build
[ "$sanitize" = ON ] && dir=build-asan
type=Release
[ "$sanitize" = ON ] && type=RelWithDebInfo
# Without --tests the build folder keeps whatever it was configured with (a fresh one: no
# tests) and only the user's targets are built.
options=()
targets=(--target plantarch plantarch_python_package)
if [ "$tests" = ON ]; then
  options=(-DPLANTARCH_BUILD_TESTS=ON -DPLANTARCH_BUILD_BENCH=ON)
  targets=()
fi
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE="$type" -DPLANTARCH_SANITIZE="$sanitize" \
  "${options[@]}" >/dev/null
cmake --build "$dir" --parallel "$(nproc)" "${targets[@]}" >"$dir/build.log" 2>&1 ||
  { tail -50 "$dir/build.log" >&2; exit 1; }

# The Python module: a .pth file in /usr/bin/python3's site directory (the user's own when
# that is not writable) puts build/python on its path, so `import plantarch` works from any
# directory without PYTHONPATH.
if [ "$sanitize" = OFF ] && [ -d "$dir/python/plantarch" ]; then
  site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
  if ! mkdir -p "$site" 2>/dev/null || [ ! -w "$site" ]; then
    site=$(/usr/bin/python3 -m site --user-site)
    mkdir -p "$site"
  fi
  echo "$PWD/$dir/python" >"$site/plantarch.pth.tmp"
  mv "$site/plantarch.pth.tmp" "$site/plantarch.pth"
fi
