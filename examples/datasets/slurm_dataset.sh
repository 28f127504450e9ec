#!/usr/bin/env bash
# A plantarch dataset made by a Slurm job array: task K of N makes the samples i with
# i % N == K (`plantarch dataset --shard K/N`) and writes its shard's manifest; a job that
# starts when all of them succeeded merges the manifests. Sample i is a function of the spec
# and i alone, so the dataset has the same bytes however it is split over tasks.
#
# Submit it from the folder the paths are relative to (OUT on a file system every node sees):
#
#   jobid=$(sbatch --parsable examples/datasets/slurm_dataset.sh spec.json /shared/dataset)
#   sbatch --dependency=afterok:$jobid \
#          --wrap 'plantarch dataset spec.json --out /shared/dataset --merge'
#
# More tasks: `sbatch --array=0-31 ...` (the task IDs must run from 0 to N-1; `%8` after the
# range runs at most 8 at once). If tasks failed or were cut by their time limit, submit the
# same array again: --resume keeps every sample already finished and makes only the others
# (a killed task leaves no half-written sample); merge when every task has succeeded.
#
# Arguments: SPEC OUT [SAMPLES], or the environment variables SPEC, OUT and SAMPLES (sbatch
# passes the submitting shell's environment by default). SAMPLES, when given, is passed as
# --samples (the spec's own count otherwise; give the merge the same --samples). PLANTARCH
# is the plantarch command (default: `plantarch` on the PATH).
#
#SBATCH --job-name=plantarch-dataset
#SBATCH --array=0-3
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --output=plantarch-dataset-%A_%a.out
set -euo pipefail

spec=${1:-${SPEC:-}}
out=${2:-${OUT:-}}
samples=${3:-${SAMPLES:-}}
plantarch=${PLANTARCH:-plantarch}
usage="usage: sbatch slurm_dataset.sh SPEC OUT [SAMPLES]"
[[ -n "$spec" && -n "$out" ]] || { echo "$usage" >&2; exit 2; }
# Run as an array task: the shard is the task's ID among the array's tasks, counted from 0.
if [[ -z "${SLURM_ARRAY_TASK_ID:-}" || -z "${SLURM_ARRAY_TASK_COUNT:-}" ]]; then
    echo "slurm_dataset.sh: not a Slurm array task (submit it with sbatch; $usage)" >&2
    exit 2
fi
if [[ "${SLURM_ARRAY_TASK_MIN:-0}" != 0 ||
      "${SLURM_ARRAY_TASK_MAX:-$((SLURM_ARRAY_TASK_COUNT - 1))}" != $((SLURM_ARRAY_TASK_COUNT - 1)) ]]; then
    echo "slurm_dataset.sh: the array must be 0-$((SLURM_ARRAY_TASK_COUNT - 1)) (it is" \
         "${SLURM_ARRAY_TASK_MIN}-${SLURM_ARRAY_TASK_MAX}): task IDs are shard numbers" >&2
    exit 2
fi

args=(dataset "$spec" --out "$out" --shard "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT" --resume)
[[ -n "$samples" ]] && args+=(--samples "$samples")
echo "task $SLURM_ARRAY_TASK_ID of $SLURM_ARRAY_TASK_COUNT on $(hostname): $plantarch ${args[*]}"
exec "$plantarch" "${args[@]}"
