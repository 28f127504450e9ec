#!/usr/bin/env bash
# The Slurm example of docs/datasets.md (examples/datasets/slurm_dataset.sh) run on a private
# single-node Slurm cluster that this script starts in a temporary folder and always stops:
# munged on its own socket and key, slurmctld and slurmd on free ports with their own
# slurm.conf (SLURM_CONF), state, spool, logs and pid files in the folder. Nothing of the
# system's /etc/slurm or munge is read or changed. The 4-task array makes a 4-sample dataset
# as 4 shards, a dependent job merges the manifests, and the samples must equal a serial
# run's byte for byte.
#
# Usage: run_slurm_test.sh SOURCE_DIR PLANTARCH [--stand-in]
#   PLANTARCH: the plantarch command. --stand-in: run the jobs with tests/slurm/
#   stand_in_plantarch.sh instead (the cluster and the batch script alone).
# Exit: 0 passed; 77 skipped (Slurm or munge not installed: `apt-get install slurm-wlm
# munge`); 1 failed. Without root, Slurm cannot run jobs as the daemons' user here, and the
# script says so and runs the batch script's tasks directly instead, as it does when the
# daemons cannot start on this machine (the reason printed) or PLANTARCH_SLURM_TEST_DIRECT
# is set; with PLANTARCH_SLURM_TEST_REQUIRE set, not running through Slurm is a failure.
set -euo pipefail
usage="usage: run_slurm_test.sh SOURCE_DIR PLANTARCH [--stand-in]"
src=$(cd "${1:?$usage}" && pwd)
plantarch=${2:?$usage}
stand_in=0
[[ "${3:-}" == --stand-in ]] && stand_in=1
started=$SECONDS
say() { echo "slurm test [$((SECONDS - started))s]: $*"; }
fail() {
    echo "slurm test: FAILED: $*" >&2
    exit 1
}

for cmd in slurmctld slurmd sbatch sinfo squeue scontrol munged munge; do
    if ! command -v "$cmd" > /dev/null; then
        echo "slurm test: skipped: $cmd not found (apt-get install slurm-wlm munge)"
        exit 77
    fi
done
[[ -x "$plantarch" ]] || fail "$plantarch is not an executable"
plantarch=$(cd "$(dirname "$plantarch")" && pwd)/$(basename "$plantarch")
script=$src/examples/datasets/slurm_dataset.sh
[[ -f "$script" ]] || fail "no $script"

tmp=$(mktemp -d /tmp/plantarch-slurm.XXXXXX)
pids=()
cleanup() {
    local status=$?
    # Jobs first (their steps end with them), then the daemons by the ids started here.
    if [[ -f "$tmp/slurm.conf" ]] && ((${#pids[@]} > 1)); then
        export SLURM_CONF=$tmp/slurm.conf
        timeout 5 scancel --full --quiet --user="$(id -un)" > /dev/null 2>&1 || true
        for _ in $(seq 20); do
            [[ -z $(timeout 5 squeue --noheader --format=%i 2> /dev/null) ]] && break
            sleep 0.5
        done
    fi
    local p
    for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done
    for p in "${pids[@]}"; do
        for _ in $(seq 50); do kill -0 "$p" 2> /dev/null || break; sleep 0.1; done
        kill -KILL "$p" 2> /dev/null || true
    done
    if ((status != 0 && status != 77)) && [[ -d "$tmp/log" ]]; then
        for f in "$tmp"/log/*; do
            [[ -s "$f" ]] || continue
            echo "---- $(basename "$f") (last lines)" >&2
            tail -n 15 "$f" >&2
        done
    fi
    rm -rf "$tmp"
    exit "$status"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

# wait_for SECONDS DESCRIPTION COMMAND...: runs COMMAND every 0.2 s until it succeeds.
wait_for() {
    local limit=$1 what=$2
    shift 2
    local end=$((SECONDS + limit))
    until "$@" > /dev/null 2>&1; do
        ((SECONDS < end)) || return 1
        sleep 0.2
    done
    say "$what"
}

# ---- the jobs' command and spec -----------------------------------------------------------
mkdir -p "$tmp/work" "$tmp/log"
if ((stand_in)); then
    command=$src/tests/slurm/stand_in_plantarch.sh
    spec=$tmp/work/spec.json
    echo '{}' > "$spec"
else
    command=$plantarch
    spec=$src/examples/datasets/tiny.json # else the smallest spec there
    [[ -f "$spec" ]] || spec=$(ls -S -r "$src"/examples/datasets/*.json 2> /dev/null | head -n 1 || true)
    [[ -n "$spec" ]] || fail "no dataset spec (*.json) in $src/examples/datasets"
    timeout 20 "$plantarch" dataset --help > /dev/null 2>&1 || fail "$plantarch has no 'dataset' command"
fi
samples=4
shards=4

# ---- checks of a finished dataset --------------------------------------------------------
check_dataset() { # OUT
    local out=$1
    if ((stand_in)); then
        local k
        for ((k = 0; k < shards; ++k)); do
            [[ $(cat "$out/shard-$k-of-$shards.txt") == "shard $k of $shards" ]] ||
                fail "shard $k's file missing or wrong"
        done
        [[ $(wc -l < "$out/merged.txt") -eq $shards ]] || fail "the merge did not list the $shards shards"
        return
    fi
    check_real_dataset "$out"
}

check_real_dataset() { # OUT
    local out=$1
    timeout 120 "$plantarch" dataset "$spec" --out "$tmp/serial" --samples "$samples" > "$tmp/log/serial.out" 2>&1 ||
        fail "the serial run failed: $(tail -n 3 "$tmp/log/serial.out")"
    say "serial run done"
    /usr/bin/python3 - "$out" "$tmp/serial" "$samples" "$shards" << 'EOF' || fail "the dataset is not the serial run's"
import json, os, sys
out, serial, n, shards = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])

def load(path):
    if not os.path.isfile(path):
        sys.exit(f"no {os.path.relpath(path, out)}")
    with open(path) as f:
        return json.load(f)

def listed(path):  # the samples a manifest lists, each entry checked against its folder
    m = load(path)
    entries = m.get("entries") if isinstance(m, dict) else None
    if not isinstance(entries, list) or m.get("samples") != n:
        sys.exit(f"{os.path.basename(path)}: no entries, or not {n} samples")
    for e in entries:
        folder = os.path.join(out, e["folder"])
        sizes = {f: os.path.getsize(os.path.join(folder, f)) for f in os.listdir(folder)}
        if e["folder"] != f"samples/{e['sample']:06d}" or e["files"] != sizes:
            sys.exit(f"{os.path.basename(path)}: entry of sample {e['sample']} unlike its folder")
    return sorted(e["sample"] for e in entries)

# Each sample folder once, nothing half-written left beside them.
names = sorted(os.listdir(os.path.join(out, "samples")))
expected = [f"{i:06d}" for i in range(n)]
if names != expected:
    sys.exit(f"sample folders {names}, not {expected}")
if any(f.startswith(".") for f in os.listdir(out)):
    sys.exit(f"left in the dataset folder: {[f for f in os.listdir(out) if f.startswith('.')]}")
# Each shard's manifest lists its samples, the merged index all of them.
for k in range(shards):
    mine = listed(os.path.join(out, f"manifest-{k}-of-{shards}.json"))
    if mine != [i for i in range(n) if i % shards == k]:
        sys.exit(f"manifest-{k}-of-{shards}.json lists samples {mine}")
merged = listed(os.path.join(out, "dataset.json"))
if merged != list(range(n)):
    sys.exit(f"dataset.json lists samples {merged}, not 0 to {n - 1}")

def files(d):
    result = {}
    for root, _, names in os.walk(d):
        for name in names:
            with open(os.path.join(root, name), "rb") as f:
                result[os.path.relpath(os.path.join(root, name), d)] = f.read()
    return result

# The samples, byte for byte those of the serial run.
a, b = files(os.path.join(out, "samples")), files(os.path.join(serial, "samples"))
if sorted(a) != sorted(b):
    sys.exit(f"files unlike the serial run's: {sorted(set(a) ^ set(b))[:5]}")
different = sorted(rel for rel in a if a[rel] != b[rel])
if different:
    sys.exit(f"{len(different)} files differ from the serial run's: {different[:5]}")
# The index and the per-split COCO files too (the shard manifests name their shard).
tops = sorted(f for f in os.listdir(serial) if f == "dataset.json" or f.startswith("coco_"))
if sorted(f for f in os.listdir(out) if f == "dataset.json" or f.startswith("coco_")) != tops:
    sys.exit(f"index and COCO files unlike the serial run's {tops}")
for f in tops:
    with open(os.path.join(out, f), "rb") as x, open(os.path.join(serial, f), "rb") as y:
        if x.read() != y.read():
            sys.exit(f"{f} differs from the serial run's")
print(f"slurm test: {n} sample folders, {len(a)} files and {', '.join(tops)} equal to "
      f"the serial run's; the {shards} shard manifests and dataset.json list the samples")
EOF
}

# ---- the batch script's tasks run by hand (when Slurm cannot run here) -------------------
run_directly() { # REASON
    say "Slurm cannot run jobs here: $1"
    [[ -z "${PLANTARCH_SLURM_TEST_REQUIRE:-}" ]] || fail "PLANTARCH_SLURM_TEST_REQUIRE is set"
    say "running the batch script's ${shards} array tasks and the merge directly instead"
    local out=$tmp/work/direct k
    for ((k = 0; k < shards; ++k)); do
        (cd "$tmp/work" && SLURM_ARRAY_TASK_ID=$k SLURM_ARRAY_TASK_COUNT=$shards \
            SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=$((shards - 1)) PLANTARCH=$command \
            timeout 120 bash "$script" "$spec" "$out" "$samples") > "$tmp/log/task-$k.out" 2>&1 ||
            fail "task $k: $(tail -n 3 "$tmp/log/task-$k.out")"
    done
    (cd "$tmp/work" && timeout 120 "$command" dataset "$spec" --out "$out" --samples "$samples" --merge) > "$tmp/log/merge.out" 2>&1 ||
        fail "merge: $(tail -n 3 "$tmp/log/merge.out")"
    check_dataset "$out"
    say "passed (tasks run directly, not through Slurm)"
    exit 0
}

if [[ $(id -u) -ne 0 ]]; then
    run_directly "not root (the private cluster runs its daemons and jobs as root)"
fi
if [[ -n "${PLANTARCH_SLURM_TEST_DIRECT:-}" ]]; then
    run_directly "PLANTARCH_SLURM_TEST_DIRECT is set"
fi

# ---- munge: its own key, socket, pid, seed and log ---------------------------------------
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool"
chmod 711 "$tmp/munge" # clients need to reach the socket (root only here)
head -c 1024 /dev/urandom > "$tmp/munge/munge.key"
chmod 400 "$tmp/munge/munge.key"
socket=$tmp/munge/munge.socket
munged --foreground --force --socket="$socket" --key-file="$tmp/munge/munge.key" \
    --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/munged.seed" \
    --log-file="$tmp/log/munged.log" > "$tmp/log/munged.out" 2>&1 &
pids+=($!)
munge_works() { munge -n -S "$socket" | unmunge -S "$socket"; }
wait_for 15 "munged answers on its socket" munge_works ||
    run_directly "munged does not start: $(tail -n 2 "$tmp/log/munged.log" "$tmp/log/munged.out" 2> /dev/null | tr '\n' ' ')"

# ---- slurm.conf: this machine as the one node, as slurmd -C sees it -----------------------
free_ports=$(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(" ".join(str(x.getsockname()[1]) for x in s))')
read -r ctld_port slurmd_port <<< "$free_ports"
node=$(hostname -s 2> /dev/null || uname -n)
hardware=$(timeout 20 slurmd -C | head -n 1 | sed -e 's/^NodeName=[^ ]* //')
[[ $hardware == *CPUs=* ]] || run_directly "slurmd -C does not describe this machine: $hardware"
touch "$tmp/plugstack.conf"
cat > "$tmp/slurm.conf" << EOF
ClusterName=plantarchtest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
PlugStackConfig=$tmp/plugstack.conf
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SlurmdTimeout=60
MinJobAge=300
KillWait=5
NodeName=$node NodeAddr=127.0.0.1 $hardware State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=10 State=UP
EOF
# Only this cluster's settings (the suite may itself run in a job of another cluster).
while read -r name; do unset "$name"; done < <(compgen -e | grep -E '^(SLURM|SBATCH|SQUEUE|SINFO)_' || true)
export SLURM_CONF=$tmp/slurm.conf

slurmctld -D -f "$SLURM_CONF" > "$tmp/log/slurmctld.out" 2>&1 &
pids+=($!)
wait_for 20 "slurmctld answers" scontrol ping ||
    run_directly "slurmctld does not start: $(tail -n 2 "$tmp/log/slurmctld.log" "$tmp/log/slurmctld.out" 2> /dev/null | tr '\n' ' ')"
slurmd -D -f "$SLURM_CONF" -N "$node" > "$tmp/log/slurmd.out" 2>&1 &
pids+=($!)
node_idle() { [[ $(sinfo --noheader --nodes="$node" --format=%T) == idle ]]; }
wait_for 30 "node $node is idle" node_idle ||
    run_directly "the node does not become idle: sinfo says '$(sinfo --noheader --format='%T %E' 2> /dev/null)'; $(tail -n 2 "$tmp/log/slurmd.log" "$tmp/log/slurmd.out" 2> /dev/null | tr '\n' ' ')"

# ---- the example: a 4-task array, then the merge as a dependent job ------------------------
out=$tmp/work/dataset
cd "$tmp/work"
export PLANTARCH=$command
status=0
jobid=$(timeout 100 sbatch --parsable --wait --time=5 --output="$tmp/log/task-%a.out" \
    "$script" "$spec" "$out" "$samples") || status=$?
jobid=${jobid%%;*}
((status == 0)) || fail "the array job ${jobid:-?} ended with status $status: $(cat "$tmp"/log/task-*.out 2> /dev/null | tail -n 5)"
say "array job $jobid: $shards tasks done"
tasks=$(ls "$tmp"/log/task-*.out | wc -l)
((tasks == shards)) || fail "$tasks task outputs, not $shards"
status=0
# shellcheck disable=SC2016 # the job's shell expands them, from --export
merge_id=$(timeout 60 sbatch --parsable --wait --time=5 --dependency=afterok:"$jobid" \
    --output="$tmp/log/merge.out" \
    --wrap '"$PLANTARCH" dataset "$SPEC" --out "$OUT" --samples "$SAMPLES" --merge' \
    --export=ALL,SPEC="$spec",OUT="$out",SAMPLES="$samples") || status=$?
((status == 0)) || fail "the merge job ${merge_id:-?} ended with status $status: $(tail -n 5 "$tmp/log/merge.out" 2> /dev/null)"
say "merge job ${merge_id%%;*} done"
check_dataset "$out"
say "passed on a single-node Slurm cluster"
