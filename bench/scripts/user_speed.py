#!/usr/bin/python3
"""Speed as a user meets it: whole processes of plantarch's command and of the reference
system's driver (bench/reference/), run in turn (A B A B ...) on the same jobs, each run a fresh
process. Prints, per job, the median whole-process wall time of each, the ratio (reference /
plantarch: how many times faster plantarch is), the median in-process time of the job's main
step where both report the same one (plantarch's -v line, the driver's JSON: a build with its
species loading, a canopy, a plant file's read).

Usage: user_speed.py --plantarch build/plantarch --reference REF_BUILD/reference_driver
                     [--runs 7] [--jobs empty,bean,species,canopy,...] [--threads 1]

Jobs: empty (a process that makes nothing: plantarch --version, the driver making a Context),
bean (a bean at 50 days, no output), species (every library species both have at its picture
age, bench/data/reference_species.tsv), canopy (10 x 10 beans at 40 days), canopy-ply,
canopy-obj (the same written as binary PLY / OBJ), soft (the canopy with soft collision
avoidance), xml-write and xml-read (a bean's plant structure file at 50 days).
The reference driver runs in its own folder (it reads its assets from there); outputs go to a
temporary folder that is removed at the end.
"""

import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SPECIES_TABLE = os.path.join(HERE, "..", "data", "reference_species.tsv")


def run(argv, cwd, env, scratch):
    """One whole process: (wall seconds, peak resident MiB, stdout, stderr)."""
    with open(os.path.join(scratch, "stdout"), "w+b") as out, \
            open(os.path.join(scratch, "stderr"), "w+b") as err:
        start = time.perf_counter()
        proc = subprocess.Popen(argv, cwd=cwd, env=env, stdout=out, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        text_out, text_err = out.read().decode(), err.read().decode()
    if proc.returncode != 0:
        sys.exit(f"user_speed: {' '.join(argv)}: exit {proc.returncode}: {text_err[-400:]}")
    return wall, usage.ru_maxrss / 1024.0, text_out, text_err


def in_process_ms(kind, out, err):
    if kind == "plantarch":
        m = re.search(r"in ([0-9.]+) ms", err)
        return float(m.group(1)) if m else None
    try:
        report = json.loads(out.strip().splitlines()[-1])
        return float(report.get("build_ms", report.get("ms")))  # a canopy's build, as -v's
    except (ValueError, IndexError, TypeError):
        return None


def species_jobs():
    jobs = []
    with open(SPECIES_TABLE, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            name, age = line.split("\t")[:2]
            jobs.append((f"species:{name}", ["build", name, "--age", age, "--stats"],
                         ["build", name, age]))
    return jobs


def jobs_for(names, tmp):
    ply, obj = os.path.join(tmp, "canopy.ply"), os.path.join(tmp, "canopy.obj")
    xml = os.path.join(tmp, "bean50.xml")
    ref_out = os.path.join(tmp, "reference")
    table = {
        "empty": [("empty", ["--version"], ["empty"])],
        "bean": [("bean 50 d", ["build", "bean", "--age", "50", "--stats"], ["build", "bean", "50"])],
        "species": species_jobs(),
        "canopy": [("canopy 10x10 bean 40 d",
                    ["canopy", "bean", "--count", "10x10", "--spacing", "0.3x0.3", "--age", "40", "--stats"],
                    ["canopy", "bean", "10", "10", "0.3", "40"])],
        "canopy-ply": [("canopy + binary PLY",
                        ["canopy", "bean", "--count", "10x10", "--spacing", "0.3x0.3", "--age", "40", "-o", ply],
                        ["canopy", "bean", "10", "10", "0.3", "40", "ply", "--out", ref_out])],
        "canopy-obj": [("canopy + OBJ",
                        ["canopy", "bean", "--count", "10x10", "--spacing", "0.3x0.3", "--age", "40", "-o", obj],
                        ["canopy", "bean", "10", "10", "0.3", "40", "obj", "--out", ref_out])],
        "soft": [("soft avoidance canopy",
                  ["canopy", "bean", "--count", "10x10", "--spacing", "0.3x0.3", "--age", "40",
                   "--soft-collision", "--stats"],
                  ["canopy", "bean", "10", "10", "0.3", "40", "soft"])],
        "xml-write": [("plant XML write (bean 50 d)", ["build", "bean", "--age", "50", "-o", xml],
                       ["xml-write", "bean", "50", xml + ".ref.xml"])],
        "xml-read": [("plant XML read (bean 50 d)",
                      ["grow", xml, "--days", "0", "-o", os.path.join(tmp, "read.txt")],
                      ["xml-read", "bean", xml + ".ref.xml"])],
    }
    out = []
    for n in names:
        if n not in table:
            sys.exit(f"user_speed: --jobs: '{n}' is not a job (valid: {', '.join(table)})")
        out += table[n]
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--plantarch", required=True)
    ap.add_argument("--reference", required=True)
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--jobs", default="empty,bean,species,canopy,canopy-ply,canopy-obj,soft,xml-write,xml-read")
    ap.add_argument("--threads", type=int, default=1, help="OpenMP threads of both (default 1)")
    a = ap.parse_args()
    plantarch = os.path.abspath(a.plantarch)
    reference = os.path.abspath(a.reference)
    ref_dir = os.path.dirname(reference)
    env = dict(os.environ, OMP_NUM_THREADS=str(a.threads))
    tmp = tempfile.mkdtemp(prefix="plantarch-user-speed-")
    try:
        jobs = jobs_for(a.jobs.split(","), tmp)
        import resource
        floor = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
        print(f"# whole-process medians of {a.runs} alternating runs, {a.threads} thread(s); "
              f"ratio = reference / plantarch; a peak reads at least this script's own, "
              f"{floor:.0f} MiB (a child starts as its copy)")
        print("| job | reference ms | plantarch ms | ratio | in process: reference / plantarch ms "
              "| peak MiB: reference / plantarch |")
        print("|---|---|---|---|---|---|")
        ratios = []
        for name, pa_args, ref_args in jobs:
            pa_argv = [plantarch, "--threads", str(a.threads), "-v"] + pa_args if pa_args != ["--version"] else [plantarch, "--version"]
            ref_argv = [reference] + ref_args
            times = {"p": [], "r": []}
            inside = {"p": [], "r": []}
            peaks = {"p": [], "r": []}
            for _ in range(a.runs + 1):  # the first pair warms the file cache, not counted
                for key, argv, cwd, kind in (("r", ref_argv, ref_dir, "reference"),
                                             ("p", pa_argv, tmp, "plantarch")):
                    wall, peak, out, err = run(argv, cwd, env, tmp)
                    times[key].append(wall)
                    peaks[key].append(peak)
                    ms = in_process_ms(kind, out, err)
                    if ms is not None:
                        inside[key].append(ms)
            r = statistics.median(times["r"][1:]) * 1000
            p = statistics.median(times["p"][1:]) * 1000
            ratios.append(r / p)
            ip = ""
            if inside["r"][1:] and inside["p"][1:] and not name.startswith("plant XML write"):
                ir, ipa = statistics.median(inside["r"][1:]), statistics.median(inside["p"][1:])
                ip = f"{ir:.1f} / {ipa:.2f} ({ir / ipa:.1f}x)"
            mem = f"{statistics.median(peaks['r'][1:]):.0f} / {statistics.median(peaks['p'][1:]):.0f}"
            print(f"| {name} | {r:.1f} | {p:.1f} | {r / p:.1f}x | {ip} | {mem} |", flush=True)
        if len(ratios) > 1:
            geo = statistics.geometric_mean(ratios)
            print(f"\ngeometric mean of the ratios: {geo:.1f}x; lowest {min(ratios):.1f}x")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
