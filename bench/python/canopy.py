"""Python against C++ on the 10 x 10 bean canopy at 40 days, in one run.

Builds the canopy from Python (plantarch module) and from C++ (plantarch_bench's
BM_BeanCanopy10x10At40Days: a new Context, the species loaded, the canopy built, the Context
freed) in alternating rounds and prints the medians and their ratio, and the time
getMeshArrays takes to hand the canopy's mesh to numpy.

Usage: /usr/bin/python3 bench/python/canopy.py [ROUNDS]   (from the repository, after a build)
"""

import gc
import json
import pathlib
import statistics
import subprocess
import sys
import time

import plantarch

ROOT = pathlib.Path(__file__).resolve().parents[2]
BENCH = ROOT / "build" / "plantarch_bench"


def python_build():
    """The same calls as the C++ benchmark's loop body, Context teardown included."""
    start = time.perf_counter()
    context = plantarch.Context()
    arch = plantarch.PlantArchitecture(context)
    arch.loadPlantModelFromLibrary("bean")
    arch.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (10, 10), 40)
    del arch, context
    gc.collect()
    return time.perf_counter() - start


def canopy():
    arch = plantarch.PlantArchitecture(plantarch.Context())
    arch.loadPlantModelFromLibrary("bean")
    arch.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (10, 10), 40)
    return arch


def cpp_build():
    out = subprocess.run([str(BENCH), "--benchmark_filter=^BM_BeanCanopy10x10At40Days/real_time$",
                          "--benchmark_repetitions=1", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    run = json.loads(out)["benchmarks"][0]
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[run["time_unit"]]
    return run["real_time"] * scale


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    py, cpp, mesh = [], [], []
    arch = canopy()
    for _ in range(rounds):
        py.append(python_build())
        cpp.append(cpp_build())
        for _ in range(5):
            start = time.perf_counter()
            m = arch.getMeshArrays(normals=False)
            mesh.append(time.perf_counter() - start)
        triangles = len(m["triangles"])
    p, c = statistics.median(py), statistics.median(cpp)
    print(f"canopy 10x10 bean 40 d: Python {p * 1e3:.0f} ms, C++ {c * 1e3:.0f} ms, "
          f"ratio {p / c:.3f} (medians of {rounds} rounds)")
    print(f"getMeshArrays(normals=False), {triangles} triangles: "
          f"{statistics.median(mesh) * 1e3:.1f} ms (median of {len(mesh)})")


if __name__ == "__main__":
    main()
