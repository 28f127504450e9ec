#!/usr/bin/env python3
"""The cost of one simulated day of light on a canopy, as a user meets it (docs/performance.md,
"Light"): whole `plantarch` processes, the canopy's build alone (`canopy --stats`) and the
build with a clear day of hourly light (`light --series`), run alternately, at each thread
count. Prints the medians, the day's own cost (light minus build), its ratio to the build,
the rays per second it cast and the cost per million triangles.

    python3 bench/scripts/light_day.py --plantarch build/plantarch [--count 10x10]
        [--age 40] [--repeats 3] [--threads 1,2] [--samples N]
"""

import argparse
import re
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
        sys.exit(f"light_day: {' '.join(command)} failed:\n{done.stderr.strip()}")
    return seconds, done.stdout


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--plantarch", required=True, help="the plantarch command to time")
    p.add_argument("--count", default="10x10", help="canopy plants along x and y")
    p.add_argument("--spacing", default="0.3x0.3", help="canopy spacing, m")
    p.add_argument("--age", default="40", help="plant age, days")
    p.add_argument("--repeats", type=int, default=3, help="runs of each command per thread count")
    p.add_argument("--threads", default="1,2", help="thread counts, comma-separated")
    p.add_argument("--samples", default="0",
                   help="light's --samples: 0 every triangle, N sampled per object")
    a = p.parse_args()
    if a.repeats < 1:
        sys.exit("light_day: --repeats must be 1 or more")
    plant = ["bean", "--age", a.age, "--count", a.count, "--spacing", a.spacing]
    with tempfile.TemporaryDirectory() as scratch:
        for threads in a.threads.split(","):
            base = [a.plantarch, "--threads", threads]
            build = base + ["canopy"] + plant + ["--stats"]
            light = base + ["light"] + plant + ["--location", "38.54,-121.74",
                                                "--date", "2026-06-21",
                                                "--series", f"{scratch}/series.csv",
                                                "--samples", a.samples]
            builds, days, rays, triangles = [], [], 0, 0
            for _ in range(a.repeats):
                builds.append(timed(build)[0])
                seconds, out = timed(light)
                days.append(seconds)
                m = re.search(r"(\d+) triangles, (\d+) rays", out)
                triangles, rays = int(m.group(1)), int(m.group(2))
            b, d = statistics.median(builds), statistics.median(days)
            day = d - b
            print(f"samples {a.samples}, threads {threads}: build {b:.2f} s, build and a day of light {d:.2f} s "
                  f"(medians of {a.repeats}); the day {day:.2f} s = {day / b:.1f} x the build, "
                  f"{rays / day / 1e6:.2f} million rays/s, {day / (triangles / 1e6):.1f} s per "
                  f"million triangles ({triangles} triangles, {rays} rays)")


if __name__ == "__main__":
    main()
