#!/usr/bin/env python3
"""The cost of a season with the carbohydrate and nitrogen budgets, as a user meets it
(docs/performance.md, "Physiology"): whole `plantarch` processes, a bean built to its final
age as usual and the same bean built to --from and grown on day by day with both budgets and
the light traced every --light-every hours of daylight, run alternately. Prints the medians
and their ratio.

    python3 bench/scripts/physiology_season.py --plantarch build/plantarch [--from 15]
        [--age 60] [--light-every 1,3] [--repeats 3] [--threads 2]
"""

import argparse
import statistics
import subprocess
import sys
import tempfile
import time


def timed(command):
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"physiology_season: {' '.join(command)} failed:\n{done.stderr.strip()}")
    return seconds


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--plantarch", required=True, help="the plantarch command to time")
    p.add_argument("--species", default="bean")
    p.add_argument("--from", dest="start", default="15", help="age the budgets start, days")
    p.add_argument("--age", default="60", help="final age, days")
    p.add_argument("--light-every", default="1,3", help="hours between traces, comma-separated")
    p.add_argument("--repeats", type=int, default=3, help="runs of each command")
    p.add_argument("--threads", default="2", help="the processes' thread count")
    a = p.parse_args()
    if a.repeats < 1:
        sys.exit("physiology_season: --repeats must be 1 or more")
    with tempfile.TemporaryDirectory() as scratch:
        base = [a.plantarch, "--threads", a.threads, "build", a.species, "--age", a.age]
        plain = base + ["--stats"]
        for every in a.light_every.split(","):
            season = base + ["--from", a.start, "--carbon", "--nitrogen", "--fertilise",
                             f"{a.start}:0.5", "--location", "38.54,-121.74", "--start",
                             "2026-06-01", "--light-every", every, "--series",
                             f"{scratch}/season.csv"]
            plains, seasons = [], []
            for _ in range(a.repeats):
                plains.append(timed(plain))
                seasons.append(timed(season))
            b, s = statistics.median(plains), statistics.median(seasons)
            print(f"{a.species} {a.start}-{a.age} d, light every {every} h, {a.threads} "
                  f"thread(s): plain build {b:.2f} s, with the budgets {s:.2f} s (medians of "
                  f"{a.repeats}): {s / b:.1f} x")


if __name__ == "__main__":
    main()
