#!/usr/bin/env python3
"""Plots a physiology series (the CSV of `plantarch build|canopy|grow|project run --series`)
over the season: the carbon fluxes, the carbon pools and the nitrogen, summed over the plants
of each day (or one plant's with --plant). Needs matplotlib (Debian: python3-matplotlib).

    python3 scripts/plot_physiology.py SERIES.csv -o season.png [--plant ID] [--title TEXT]
"""

import argparse
import csv
import math
import os
import sys

FLUXES = [("input", "net photosynthesis"), ("growth", "growth"),
          ("growth_respiration", "growth respiration"), ("maintenance", "maintenance"),
          ("root_growth", "roots beyond their share"), ("losses", "losses")]
POOLS = [("sugar", "sugar"), ("starch", "starch")]
MAX_BYTES = 256 << 20
NITROGEN = [("nitrogen_available", "available"), ("nitrogen_in_leaves", "in leaves")]


def fail(message):
    sys.exit(f"plot_physiology: {message}")


def read_series(path, plant):
    """Rows of the series as {column: [values by age]}, summed over plants (or one plant)."""
    if os.path.exists(path) and not os.path.isfile(path):
        fail(f"{path}: not a regular file (a series is a CSV file)")
    if os.path.isfile(path) and os.path.getsize(path) > MAX_BYTES:
        fail(f"{path}: larger than {MAX_BYTES >> 20} MiB: not a series this script draws")
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"{path}: cannot read: {e.strerror}")
    except (csv.Error, UnicodeDecodeError) as e:
        fail(f"{path}: not a physiology series: {e}")
    needed = {"plant", "age"} | {c for c, _ in FLUXES + POOLS + NITROGEN} | {"nitrogen_stress"}
    if not rows or not needed <= set(rows[0]):
        fail(f"{path}: not a physiology series (columns {', '.join(sorted(needed))})")
    by_age = {}
    for line, row in enumerate(rows, start=2):
        try:
            values = {k: float(row[k]) for k in needed}
        except (TypeError, ValueError):
            fail(f"{path}:{line}: a value that is not a number")
        if not all(math.isfinite(v) for v in values.values()):
            fail(f"{path}:{line}: a value that is not finite")
        if plant is not None and int(values["plant"]) != plant:
            continue
        day = by_age.setdefault(values["age"], {k: 0.0 for k in needed} | {"plants": 0})
        for k in needed:
            day[k] += values[k]
        day["plants"] += 1
    if not by_age:
        fail(f"{path}: no rows" + ("" if plant is None else f" of plant {plant}"))
    ages = sorted(by_age)
    series = {k: [by_age[a][k] for a in ages] for k in needed}
    # The stress is a factor: the mean over the plants, not the sum.
    series["nitrogen_stress"] = [by_age[a]["nitrogen_stress"] / by_age[a]["plants"] for a in ages]
    return ages, series, max(by_age[a]["plants"] for a in ages)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("series", help="the CSV written by --series")
    p.add_argument("-o", "--output", required=True, help="the picture (.png, .svg or .pdf)")
    p.add_argument("--plant", type=int, help="one plant's rows (default: all plants summed)")
    p.add_argument("--title", default="", help="a title over the plots")
    a = p.parse_args()
    ext = os.path.splitext(a.output)[1].lower()
    if ext not in (".png", ".svg", ".pdf"):
        fail(f"{a.output}: give a .png, .svg or .pdf name")
    ages, s, plants = read_series(a.series, a.plant)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail("needs matplotlib (Debian: apt install python3-matplotlib)")
    what = f"plant {a.plant}" if a.plant is not None else (
        "one plant" if plants == 1 else f"{plants} plants, summed")
    fig, axes = plt.subplots(3, 1, figsize=(7.5, 8.5), sharex=True, constrained_layout=True)
    for key, label in FLUXES:
        axes[0].plot(ages, s[key], label=label)
    axes[0].set_ylabel("mol C per day")
    axes[0].set_title(f"Carbon fluxes ({what})", loc="left", fontsize=10)
    for key, label in POOLS:
        axes[1].plot(ages, s[key], label=label)
    axes[1].axhline(0.0, color="0.6", linewidth=0.8)
    axes[1].set_ylabel("mol C")
    axes[1].set_title("Carbon pools at the end of each day", loc="left", fontsize=10)
    for key, label in NITROGEN:
        axes[2].plot(ages, s[key], label=label)
    axes[2].set_ylabel("g N")
    axes[2].set_xlabel("plant age (days)")
    axes[2].set_title("Nitrogen (stress on the right axis)", loc="left", fontsize=10)
    stress = axes[2].twinx()
    stress.plot(ages, s["nitrogen_stress"], color="0.35", linestyle="--", label="stress")
    stress.set_ylim(0.0, 1.05)
    stress.set_ylabel("stress factor (1: none)")
    for ax in axes:
        ax.grid(True, color="0.9")
        ax.legend(fontsize=8, loc="upper left", frameon=False)
    stress.legend(fontsize=8, loc="upper right", frameon=False)
    if a.title:
        fig.suptitle(a.title)
    tmp = a.output + ".part"
    try:
        fig.savefig(tmp, dpi=110, format=ext[1:])
        os.replace(tmp, a.output)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        fail(f"{a.output}: cannot write: {e.strerror}")


if __name__ == "__main__":
    main()
