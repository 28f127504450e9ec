#!/usr/bin/env python3
"""Plots a fit's convergence (the report.json of `plantarch fit --report DIR`): the objective
of every evaluation and the best so far (log scale), each fitted parameter's values over the
evaluations with its bounds, and the measured against the simulated statistics at the start
and at the end. Needs matplotlib (Debian: python3-matplotlib).

    python3 scripts/plot_fit.py DIR/report.json -o convergence.png [--title TEXT]
"""

import argparse
import json
import math
import os
import sys

MAX_BYTES = 256 << 20


def fail(message):
    sys.exit(f"plot_fit: {message}")


def read_report(path):
    if os.path.exists(path) and not os.path.isfile(path):
        fail(f"{path}: not a regular file (a report is a JSON file)")
    if os.path.isfile(path) and os.path.getsize(path) > MAX_BYTES:
        fail(f"{path}: larger than {MAX_BYTES >> 20} MiB: not a report this script draws")
    try:
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
    except OSError as e:
        fail(f"{path}: cannot read: {e.strerror}")
    except (ValueError, UnicodeDecodeError) as e:
        fail(f"{path}: not a fit report: {e}")
    if not isinstance(report, dict) or report.get("plantarch_fit_report") != 1:
        fail(f"{path}: not a fit report (no \"plantarch_fit_report\": 1)")
    try:
        evaluations = [(int(e["evaluation"]), e["objective"], [float(v) for v in e["values"]])
                       for e in report["evaluations"]]
        parameters = [(p["path"], float(p["lower"]), float(p["upper"]), float(p["start"]),
                       float(p["fitted"])) for p in report["parameters"]]
        residuals = [(float(r["age"]), str(r["statistic"]), r["measured"], r["simulated_start"],
                      r["simulated_fitted"]) for r in report["residuals"]]
    except (KeyError, TypeError, ValueError) as e:
        fail(f"{path}: not a fit report: a missing or bad entry ({e})")
    if not evaluations:
        fail(f"{path}: no evaluations")
    return report, evaluations, parameters, residuals


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("report", help="the report.json of plantarch fit --report")
    p.add_argument("-o", "--output", required=True, help="the picture (.png, .svg or .pdf)")
    p.add_argument("--title", default="", help="a title over the plots")
    a = p.parse_args()
    ext = os.path.splitext(a.output)[1].lower()
    if ext not in (".png", ".svg", ".pdf"):
        fail(f"{a.output}: give a .png, .svg or .pdf name")
    report, evaluations, parameters, residuals = read_report(a.report)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail("needs matplotlib (Debian: apt install python3-matplotlib)")

    numbers = [n for n, _, _ in evaluations]
    objective = [f if isinstance(f, (int, float)) and math.isfinite(f) else math.nan
                 for _, f, _ in evaluations]
    best, so_far = [], math.inf
    for f in objective:
        if f == f:
            so_far = min(so_far, f)
        best.append(so_far if so_far < math.inf else math.nan)
    rows = 2 + len(parameters)
    fig, axes = plt.subplots(rows, 1, figsize=(7.5, 2.4 * rows + 0.8), constrained_layout=True,
                             gridspec_kw={"height_ratios": [1] * (rows - 1) + [1.4]})
    ax = axes[0]
    ax.semilogy(numbers, [max(f, 1e-12) for f in objective], ".", color="0.55",
                label="evaluation")
    ax.semilogy(numbers, [max(f, 1e-12) for f in best], "-", color="C3", label="best so far")
    ax.set_xlabel("evaluation")
    ax.set_ylabel("objective")
    ax.set_title(f"Objective ({report.get('algorithm', '')}, {len(report.get('seeds', []))} "
                 f"seeds; {report.get('stop', '')})", loc="left", fontsize=10)
    for i, (path, lower, upper, start, fitted) in enumerate(parameters):
        ax = axes[1 + i]
        ax.plot(numbers, [v[i] for _, _, v in evaluations], ".-", color="C0", linewidth=0.6,
                markersize=3, label="evaluated")
        ax.axhline(lower, color="0.6", linestyle=":", linewidth=0.8)
        ax.axhline(upper, color="0.6", linestyle=":", linewidth=0.8, label="bounds")
        ax.axhline(start, color="C1", linestyle="--", linewidth=0.8, label=f"start {start:.4g}")
        ax.axhline(fitted, color="C3", linewidth=1.0, label=f"fitted {fitted:.4g}")
        ax.set_ylabel(path.split(".")[-1], fontsize=8)
        ax.set_xlabel("evaluation")
        ax.set_title(path, loc="left", fontsize=9)
    ax = axes[-1]
    labels = [f"{s}, {age:g} d" for age, s, _, _, _ in residuals]
    x = list(range(len(residuals)))

    def ratio(value, measured):
        if not isinstance(value, (int, float)) or not isinstance(measured, (int, float)):
            return math.nan
        return value / measured if measured else math.nan

    ax.axhline(1.0, color="0.3", linewidth=0.8, label="measured")
    ax.plot(x, [ratio(r[3], r[2]) for r in residuals], "o", color="C1", label="start")
    ax.plot(x, [ratio(r[4], r[2]) for r in residuals], "s", color="C3", label="fitted")
    ax.set_xticks(x)
    ax.set_xticklabels(labels, fontsize=7, rotation=35, ha="right", rotation_mode="anchor")
    ax.set_ylabel("simulated / measured")
    ax.set_title("Statistics, mean over the seeds", loc="left", fontsize=10)
    for ax in axes:
        ax.grid(True, color="0.9")
        ax.legend(fontsize=7, loc="best", frameon=False)
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
