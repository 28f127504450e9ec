#!/usr/bin/env python3
"""Prints the Species/<name> benchmarks as the table of docs/performance.md.

Usage: build/plantarch_bench --benchmark_filter=Species/ --benchmark_repetitions=5 \
           --benchmark_report_aggregates_only=true --benchmark_format=json > species.json
       bench/scripts/species_table.py species.json
"""
import json
import math
import sys


def main(path):
    with open(path) as f:
        runs = json.load(f)["benchmarks"]
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
        x = r.get("x_reference", 0.0)
        ratios.append(x)
        print(f"| {name} | {r['age_d']:.0f} | {ms:.3g} | {x * ms:.3g} | {x:.0f} | "
              f"{r['triangles'] / 1000:.1f}k | {r.get('tri_ratio', 0):.2f} | "
              f"{r['peak_MiB']:.1f} |")
    geo = math.exp(sum(math.log(x) for x in ratios) / len(ratios))
    print(f"\nGeometric mean: {geo:.0f} times faster; slowest ratio {min(ratios):.0f} "
          f"({min(rows, key=lambda n: rows[n].get('x_reference', 0))}).")


if __name__ == "__main__":
    main(sys.argv[1])
