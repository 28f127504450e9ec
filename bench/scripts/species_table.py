#!/usr/bin/env python3
"""Prints the Species/<name> benchmarks as the table of docs/performance.md.

Usage: build/plantarch_bench --benchmark_filter=Species/ --benchmark_repetitions=5 \
           --benchmark_report_aggregates_only=true --benchmark_format=json > species.json
       bench/scripts/species_table.py species.json
"""
import json
import math
import os
import sys


def main(path):
    with open(path) as f:
        runs = json.load(f)["benchmarks"]
    data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data",
                        "reference_species.tsv")
    reference = {}
    with open(data) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                cells = line.split()
                reference[cells[0]] = float(cells[2])
    rows = {}
    for r in runs:
        if r.get("aggregate_name") != "median":
            continue
        name = r["run_name"].split("/", 1)[1]
        rows[name] = r
    print("| species | age (d) | ms per plant | reference ms | times faster | triangles | "
          "x reference's triangles | peak MiB |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    ratios = []
    for name in sorted(rows):
        r = rows[name]
        ms = r["real_time"]
        ref = reference.get(name, 0.0)
        x = ref / ms
        ratios.append(x)
        print(f"| {name} | {r['age_d']:.0f} | {ms:.3g} | {ref:.3g} | {x:.0f} | "
              f"{r['triangles'] / 1000:.1f}k | {r.get('tri_ratio', 0):.2f} | "
              f"{r['peak_MiB']:.1f} |")
    geo = math.exp(sum(math.log(x) for x in ratios) / len(ratios))
    print(f"\nGeometric mean: {geo:.0f} times faster; slowest ratio {min(ratios):.0f} "
          f"({min(rows, key=lambda n: reference.get(n, 0.0) / rows[n]['real_time'])}).")


if __name__ == "__main__":
    main(sys.argv[1])
