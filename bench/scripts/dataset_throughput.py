#!/usr/bin/python3
"""Dataset throughput as a user meets it (docs/performance.md, "Datasets"): whole processes of
`plantarch dataset` making the samples of bench/data/dataset_bean9.json (a 3 x 3 bean canopy at
40 days, 512 x 512 images at 4 rays a pixel, 100k-point clouds), run in alternating rounds:

  one worker    one process, one thread (--threads 1)
  two workers   two processes at once, one thread each, --shard 0/2 and 1/2 (as a 2-task
                Slurm array or 2 single-threaded Dask workers run them)
  one process   one process with every core (OpenMP inside each sample)

Prints each round's samples per minute and, at the end, the medians and the ratios two workers
/ one worker and one process / one worker. With --dask the same samples are also made by
plantarch.dataset.generate on a dask LocalCluster of 1 and of 2 worker processes (one thread
each).

Usage: dataset_throughput.py --plantarch build/plantarch [--samples 8] [--rounds 3] [--dask]
"""

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

SPEC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data",
                    "dataset_bean9.json")


def run_cli(plantarch, out, samples, threads, shard=None):
    cmd = [plantarch, "--threads", str(threads), "dataset", SPEC, "--out", out,
           "--samples", str(samples)]
    if shard:
        cmd += ["--shard", shard]
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def timed(procs):
    start = time.monotonic()
    for p in procs:
        _, err = p.communicate()
        if p.returncode != 0:
            sys.exit(f"dataset_throughput: a run failed: {err.decode().strip()}")
    return time.monotonic() - start


def dask_run(out, samples, workers):
    code = f"""
import plantarch.dataset
from dask.distributed import Client, LocalCluster
if __name__ == "__main__":
    with LocalCluster(n_workers={workers}, processes=True, threads_per_worker=1,
                      dashboard_address=None) as c, Client(c) as client:
        client.run(lambda: None)
        import time
        t = time.monotonic()
        plantarch.dataset.generate({SPEC!r}, {out!r}, samples={samples}, client=client)
        print(time.monotonic() - t)
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    if r.returncode != 0:
        sys.exit(f"dataset_throughput: the dask run failed: {r.stderr.strip()[-400:]}")
    return float(r.stdout.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plantarch", required=True)
    ap.add_argument("--samples", type=int, default=8)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--dask", action="store_true")
    a = ap.parse_args()
    if a.samples < 2 or a.rounds < 1:
        sys.exit("dataset_throughput: --samples at least 2, --rounds at least 1")
    rates = {"one worker": [], "two workers": [], "one process": []}
    if a.dask:
        rates.update({"dask 1 worker": [], "dask 2 workers": []})
    tmp = tempfile.mkdtemp(prefix="plantarch-dataset-bench-")
    try:
        for r in range(1, a.rounds + 1):
            for name in rates:
                out = os.path.join(tmp, f"{r}-{name.replace(' ', '-')}")
                if name == "one worker":
                    t = timed([run_cli(a.plantarch, out, a.samples, 1)])
                elif name == "two workers":
                    t = timed([run_cli(a.plantarch, out, a.samples, 1, f"{k}/2") for k in (0, 1)])
                elif name == "one process":
                    t = timed([run_cli(a.plantarch, out, a.samples, 0)])
                else:
                    t = dask_run(out, a.samples, 2 if "2" in name else 1)
                rates[name].append(60.0 * a.samples / t)
                print(f"round {r}: {name:15s} {a.samples} samples in {t:6.1f} s: "
                      f"{rates[name][-1]:5.1f} samples/min", flush=True)
                shutil.rmtree(out, ignore_errors=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    med = {k: statistics.median(v) for k, v in rates.items()}
    for k, v in med.items():
        print(f"median {k:15s} {v:5.1f} samples/min")
    print(f"two workers / one worker: {med['two workers'] / med['one worker']:.2f}x")
    print(f"one process (all cores) / one worker: {med['one process'] / med['one worker']:.2f}x")
    if a.dask:
        print(f"dask 2 workers / dask 1 worker: {med['dask 2 workers'] / med['dask 1 worker']:.2f}x")


if __name__ == "__main__":
    main()
