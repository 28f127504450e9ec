#!/usr/bin/env bash
# A stand-in for `plantarch dataset` used by run_slurm_test.sh --stand-in: it checks the
# arguments the batch script passes and writes OUT/shard-K-of-N.txt for a shard, or
# OUT/merged.txt (the shards' files in order) for --merge.
set -euo pipefail
[[ "${1:-}" == dataset ]] || { echo "stand-in: only 'dataset'" >&2; exit 2; }
shift
spec=$1
shift
out="" shard="" merge=0 resume=0
while (($#)); do
    case $1 in
    --out) out=$2; shift 2 ;;
    --shard) shard=$2; shift 2 ;;
    --samples) shift 2 ;;
    --resume) resume=1; shift ;;
    --merge) merge=1; shift ;;
    *) echo "stand-in: unknown argument $1" >&2; exit 2 ;;
    esac
done
[[ -f "$spec" && -n "$out" ]] || { echo "stand-in: no spec file or no --out" >&2; exit 2; }
mkdir -p "$out"
if ((merge)); then
    ls "$out"/shard-*.txt > /dev/null
    cat "$out"/shard-*.txt > "$out/merged.txt"
    exit 0
fi
[[ $shard =~ ^([0-9]+)/([0-9]+)$ && $resume == 1 ]] || { echo "stand-in: bad --shard '$shard' or no --resume" >&2; exit 2; }
echo "shard ${BASH_REMATCH[1]} of ${BASH_REMATCH[2]}" > "$out/shard-${BASH_REMATCH[1]}-of-${BASH_REMATCH[2]}.txt"
