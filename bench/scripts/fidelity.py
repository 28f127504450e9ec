#!/usr/bin/python3
"""Differential fidelity check: the same plant statistics from plantarch and from the reference
system (its driver, bench/reference/), species by species, age by age, over many seeds, side
by side.

Usage: fidelity.py [--plantarch build/plantarch] --reference REF_BUILD/reference_driver
                   [--species bean,maize] [--ages 20,35,50] [--seeds 40] [--jobs 2]
                   [--table OUT.tsv] [--write-reference tests/data/reference_stats.tsv]
                   [--cache REF_CACHE.json]

For each species (default: every species both have) and age (default: three per species, see
default_ages), each system grows seeds 1 to N in fresh plants and reports height (top of the
box, m), one-sided leaf area (m^2), leaf count, box widths along x and y, widths along the
plant's own horizontal axes (its longest extent over every direction and the extent square to
it), flower and fruit objects, shoots, phytomers, shoots and phytomers by rank, the main
shoot's node count and the leaf area's inclination histogram (9 bins of 10 degrees, reported
as its mean angle). Printed: one row per species, age and quantity with both means and each
system's min and max over the seeds, and the ratio plantarch / reference. --table writes the
same rows as TSV; --write-reference writes the reference's means, minima and maxima as the
committed table the FidelityStats tests read. --cache keeps the reference's plants in a JSON
file between runs (by species and age, seeds 1 to as many as were grown; a run grows only the
seeds missing): the reference does not change while plantarch does.

The reference driver runs in its own folder (it reads its assets from there). Not part of CI:
the reference is built outside the repository (bench/reference/build.sh).
"""

import argparse
import concurrent.futures
import json
import math
import os
import re
import subprocess
import sys

QUANTITIES = ["height", "leaf_area", "leaf_count", "width_x", "width_y", "width_long",
              "width_short", "flowers", "fruit", "shoots", "max_rank", "phytomers",
              "main_nodes", "inclination_mean"]

REFERENCE_HEADER = """\
# The reference system's plants (version 1.3.80, built from its public repository) at three
# ages per species, seeds 1 to {seeds} (mean, min, max over the seeds), written by
# bench/scripts/fidelity.py --write-reference. Quantities: height (top of the box, m),
# leaf_area (one-sided, m^2), leaf_count (leaflets counted one by one), width_x and width_y
# (box widths, m), width_long and width_short (along the plant's own horizontal axes: its
# longest extent and the extent square to it, m), flowers and fruit (objects drawn), shoots,
# max_rank, phytomers, main_nodes (the main shoot's nodes) and inclination_mean (the leaf
# area's mean inclination from horizontal, degrees, from 9 bins of 10).
# Columns, tab-separated: species  age_days  quantity  mean  min  max
species\tage_days\tquantity\tmean\tmin\tmax
"""


def default_ages(picture_age):
    """Three ages: a tree's or vine's first and second season and its picture age; otherwise
    four tenths, seven tenths and the whole of the picture age."""
    if picture_age >= 600:
        return [200, 400, picture_age]
    if picture_age >= 250:
        return [90, 180, picture_age]
    return [round(picture_age * 0.4), round(picture_age * 0.7), picture_age]


def picture_ages(table):
    ages = {}
    with open(table) as f:
        for line in f:
            cells = line.rstrip("\n").split("\t")
            if line.startswith("#") or cells[0] == "species" or len(cells) != 6:
                continue
            ages[cells[0]] = max(ages.get(cells[0], 0.0), float(cells[1]))
    return ages


def derived(stats):
    """The quantities computed from a system's JSON: rank and inclination summaries."""
    shoots = stats["shoots_by_rank"]
    hist = stats["leaf_inclination"]
    total = sum(hist)
    stats["shoots"] = sum(shoots)
    stats["max_rank"] = len(shoots) - 1
    stats["phytomers"] = sum(stats["phytomers_by_rank"])
    stats["inclination_mean"] = (
        sum((10 * i + 5) * h for i, h in enumerate(hist)) / total if total > 0 else 0.0)
    return stats


def run_reference(driver, species, age, first, last):
    """The reference's plants of seeds first to last, in order."""
    proc = subprocess.run([os.path.abspath(driver), "stats", species, f"{age:g}", str(first),
                           str(last)],
                          cwd=os.path.dirname(os.path.abspath(driver)), capture_output=True,
                          text=True)
    if proc.returncode != 0:
        sys.exit(f"fidelity: reference {species} {age}: exit {proc.returncode}: "
                 f"{proc.stderr[-300:]}")
    # Its progress bar shares stdout, with carriage returns: take each JSON object.
    rows = [json.loads(m) for m in re.findall(r'\{"species".*\}', proc.stdout)]
    if [r["seed"] for r in rows] != list(range(first, last + 1)):
        sys.exit(f"fidelity: reference {species} {age}: {len(rows)} plants, not seeds {first} "
                 f"to {last}")
    return [derived(r) for r in rows]


def run_plantarch(binary, species, age, seed):
    proc = subprocess.run([binary, "--seed", str(seed), "build", species, "--age", f"{age:g}",
                           "--stats"], capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"fidelity: plantarch {species} {age} seed {seed}: exit {proc.returncode}: "
                 f"{proc.stderr[-300:]}")
    stats = json.loads(proc.stdout)
    stats["leaf_count"] = stats["leaves"]
    return derived(stats)


def summary(rows, quantity):
    values = [float(r[quantity]) for r in rows]
    return sum(values) / len(values), min(values), max(values)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plantarch", help="plantarch's command (without it: the reference only)")
    parser.add_argument("--reference", required=True)
    parser.add_argument("--species", help="comma-separated (default: every species)")
    parser.add_argument("--ages", help="comma-separated days (default: three per species)")
    parser.add_argument("--seeds", type=int, default=40)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--table", help="write the side-by-side rows as TSV")
    parser.add_argument("--write-reference", help="write the reference's table")
    parser.add_argument("--cache", help="a JSON file of the reference's plants, kept between runs")
    parser.add_argument("--pictures", default=os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "data",
        "reference_stats.tsv"), help="the table whose largest age per species is its picture age")
    args = parser.parse_args()
    if args.seeds < 1:
        sys.exit("fidelity: --seeds: at least 1")
    pictures = picture_ages(args.pictures)
    species = args.species.split(",") if args.species else sorted(pictures)
    for s in species:
        if s not in pictures and not args.ages:
            sys.exit(f"fidelity: {s}: no picture age in {args.pictures} (give --ages)")
    jobs = [(s, a) for s in species
            for a in ([float(x) for x in args.ages.split(",")] if args.ages
                      else default_ages(pictures[s]))]

    cache = {}
    if args.cache and os.path.exists(args.cache):
        with open(args.cache) as f:
            cache = json.load(f)
    # The cache holds each species and age's plants of seeds 1 to however many were grown;
    # only the seeds missing are grown.
    key = lambda job: f"{job[0]}/{job[1]:g}"
    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        ref_futures = {job: pool.submit(run_reference, args.reference, *job,
                                        len(cache.get(key(job), [])) + 1, args.seeds)
                       for job in jobs if len(cache.get(key(job), [])) < args.seeds}
        for job, future in ref_futures.items():
            cache[key(job)] = cache.get(key(job), []) + future.result()
        if args.cache:
            with open(args.cache + ".part", "w") as f:
                json.dump(cache, f)
            os.replace(args.cache + ".part", args.cache)
        ours_futures = {job: [pool.submit(run_plantarch, args.plantarch, *job, seed)
                              for seed in range(1, args.seeds + 1)] if args.plantarch else []
                        for job in jobs}
        results = {job: (cache[key(job)][:args.seeds], [f.result() for f in ours_futures[job]])
                   for job in jobs}

    lines = ["species\tage\tquantity\treference\tref_min\tref_max\tplantarch\tours_min\t"
             "ours_max\tratio"]
    print(f"{'species':18} {'age':>5} {'quantity':16} {'reference':>10} {'plantarch':>10} "
          f"{'ratio':>6}   (means over seeds 1 to {args.seeds}; min-max in the TSV)")
    for (s, a), (ref, ours) in results.items():
        for q in QUANTITIES:
            rm, rlo, rhi = summary(ref, q)
            om, olo, ohi = summary(ours, q) if ours else (math.nan,) * 3
            ratio = om / rm if rm else (1.0 if om == 0 else math.inf)
            lines.append(f"{s}\t{a:g}\t{q}\t{rm:.5g}\t{rlo:.5g}\t{rhi:.5g}\t{om:.5g}\t{olo:.5g}\t"
                         f"{ohi:.5g}\t{ratio:.3f}")
            print(f"{s:18} {a:5g} {q:16} {rm:10.4g} {om:10.4g} {ratio:6.2f}")
    if args.table:
        with open(args.table, "w") as f:
            f.write("\n".join(lines) + "\n")
    if args.write_reference:
        with open(args.write_reference, "w") as f:
            f.write(REFERENCE_HEADER.format(seeds=args.seeds))
            for (s, a), (ref, _) in results.items():
                for q in QUANTITIES:
                    m, lo, hi = summary(ref, q)
                    f.write(f"{s}\t{a:g}\t{q}\t{m:.5g}\t{lo:.5g}\t{hi:.5g}\n")


if __name__ == "__main__":
    main()
