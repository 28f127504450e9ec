#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer, in
# build-fuzz/) and runs one of them for a number of seconds on one core:
#
#   bash scripts/fuzz.sh plant_xml 600      # TARGET: plant_xml, plant_string, species, obj,
#                                           #         ply, gltf, project, builder, fit_target, skeleton or dataset_spec
#   bash scripts/fuzz.sh plant_xml 7200 10000000   # stop at 10 M executions or two hours
#
# The corpus in fuzz/corpus/TARGET/ (hand-made seeds and the inputs of earlier runs that
# reach code nothing else does; kept in the repository) starts the run; inputs the fuzzer
# finds interesting go to build-fuzz/corpus/TARGET/ (kept between runs). After a long run,
# keep the new ones that add coverage:
#   build-fuzz/fuzz_TARGET -merge=1 -max_len=16384 fuzz/corpus/TARGET build-fuzz/corpus/TARGET
# A crash, sanitizer report, timeout (10 s) or memory blow-up (2 GB) stops the run with a
# non-zero status and saves the input under build-fuzz/artifacts/TARGET/; replay it with
#   build-fuzz/fuzz_TARGET FILE
# which shows the full stacks. PLANTARCH_FUZZ_TIMEOUT (seconds, default 10) raises the
# timeout on a machine busy with other work, where a niced fuzzer's wall time stretches.
#
# Speed: the allocator is not purged every second (libFuzzer's default): under ASan, with a
# heap of hundreds of MB, the purges took a third of fuzz_obj's time. ASan records two frames
# of each allocation's stack, does not fill new allocations and keeps 16 MB of freed memory in
# quarantine (set ASAN_OPTIONS to override): storing 30-frame stacks took 44 % of fuzz_obj's
# time, filling and recycling a 256 MB quarantine another 15 %.
set -euo pipefail

usage="usage: scripts/fuzz.sh TARGET SECONDS [RUNS]   (TARGET: plant_xml, plant_string, species, obj, ply, gltf, project, builder, fit_target, skeleton, dataset_spec)"
target=${1:?$usage}
seconds=${2:?$usage}
runs=${3:--1}
case "$target" in
    plant_xml | species | obj | ply | gltf | project | builder | fit_target | skeleton | dataset_spec) max_len=16384 ;;
    plant_string) max_len=8192 ;;
    *) echo "$usage" >&2; exit 2 ;;
esac
timeout=${PLANTARCH_FUZZ_TIMEOUT:-10}
[[ "$seconds" =~ ^[0-9]+$ && "$runs" =~ ^(-1|[0-9]+)$ && "$timeout" =~ ^[1-9][0-9]*$ ]] ||
    { echo "$usage" >&2; exit 2; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${PLANTARCH_FUZZ_BUILD:-$root/build-fuzz}
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" \
    -DPLANTARCH_FUZZ=ON -DPLANTARCH_BUILD_TESTS=OFF -DPLANTARCH_BUILD_BENCH=OFF \
    -DPLANTARCH_BUILD_PYTHON=OFF > /dev/null
cmake --build "$build" --parallel 2 --target "fuzz_$target"

corpus="$build/corpus/$target"
artifacts="$build/artifacts/$target"
mkdir -p "$corpus" "$artifacts"
export ASAN_OPTIONS=${ASAN_OPTIONS:-malloc_context_size=2:max_malloc_fill_size=0:quarantine_size_mb=16}
exec "$build/fuzz_$target" "$corpus" "$root/fuzz/corpus/$target" \
    -dict="$root/fuzz/$target.dict" -max_total_time="$seconds" -runs="$runs" -max_len="$max_len" \
    -timeout="$timeout" -rss_limit_mb=2048 -purge_allocator_interval=-1 \
    -artifact_prefix="$artifacts/" -print_final_stats=1
