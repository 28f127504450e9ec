#!/bin/bash
# The soft-avoidance canopy's time over the plain canopy's (docs/performance.md, "Collision
# avoidance"), for one or more plantarch_bench binaries run in turn, round after round: on a
# shared machine single runs vary too much to compare.
#
#   bench/scripts/soft_ratio.sh ROUNDS BENCH [BENCH...]
#
# Prints one line per round and binary: round, binary, plain ms, soft ms, ratio (medians of 7
# randomly interleaved repetitions), then each binary's median ratio over the rounds.
set -euo pipefail
if [ $# -lt 2 ] || ! [[ $1 =~ ^[1-9][0-9]*$ ]]; then
    echo "usage: $0 ROUNDS BENCH [BENCH...]  (ROUNDS: a whole number above 0)" >&2
    exit 2
fi
rounds=$1
shift
for b in "$@"; do
    [ -x "$b" ] || { echo "$0: $b: not an executable benchmark binary" >&2; exit 2; }
done
filter='BM_BeanCanopy10x10At40Days(/threads:2)?/real_time|SoftAvoidance/rays:256/interval_tenths:10(/kernel:1)?(/threads:2)?/real_time'
results=$(mktemp)
trap 'rm -f "$results"' EXIT
for r in $(seq 1 "$rounds"); do
    for b in "$@"; do
        out=$("$b" --benchmark_filter="$filter" --benchmark_repetitions=7 \
                   --benchmark_enable_random_interleaving=true \
                   --benchmark_report_aggregates_only=true 2>/dev/null | grep '_median')
        plain=$(echo "$out" | grep -v Soft | awk '{print $2}')
        soft=$(echo "$out" | grep Soft | awk '{print $2}')
        ratio=$(awk -v s="$soft" -v p="$plain" 'BEGIN {printf "%.3f", s / p}')
        echo "$r $b $plain $soft $ratio" | tee -a "$results"
    done
done
for b in "$@"; do
    awk -v b="$b" '$2 == b {print $5}' "$results" | sort -n |
        awk -v b="$b" '{v[NR] = $1} END {m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
                        printf "%s: median ratio %.3f over %d rounds (%.3f to %.3f)\n", b, m, NR, v[1], v[NR]}'
done
