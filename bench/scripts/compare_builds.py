#!/usr/bin/python3
"""Compares two plantarch_bench binaries (a baseline and a candidate) on the same benchmarks,
in alternating rounds so that both see the same machine load.

Usage: compare_builds.py BASE_BENCH NEW_BENCH FILTER [ROUNDS]

FILTER is a Google Benchmark regular expression (--benchmark_filter); ROUNDS (default 3)
alternating runs of each binary, 3 repetitions a run. Prints, per benchmark, the median real
time of each binary over all its repetitions and the ratio new / base (below 1: faster).
"""

import json
import statistics
import subprocess
import sys


def run(binary, bench_filter):
    out = subprocess.run(
        [binary, f'--benchmark_filter={bench_filter}', '--benchmark_repetitions=3',
         '--benchmark_format=json'],
        check=True, capture_output=True, text=True).stdout
    times = {}
    for b in json.loads(out)['benchmarks']:
        if b.get('run_type') != 'iteration':
            continue
        scale = {'ns': 1e-6, 'us': 1e-3, 'ms': 1.0, 's': 1e3}[b['time_unit']]
        times.setdefault(b['run_name'], []).append(b['real_time'] * scale)
    return times


def main(argv):
    if len(argv) not in (4, 5):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    base, new, bench_filter = argv[1:4]
    rounds = int(argv[4]) if len(argv) == 5 else 3
    if rounds < 1:
        print('compare_builds.py: ROUNDS must be at least 1', file=sys.stderr)
        return 2
    samples = {base: {}, new: {}}
    for _ in range(rounds):
        for binary in (base, new):
            for name, t in run(binary, bench_filter).items():
                samples[binary].setdefault(name, []).extend(t)
    names = [n for n in samples[base] if n in samples[new]]
    if not names:
        print(f'compare_builds.py: no benchmark matches {bench_filter!r} in both', file=sys.stderr)
        return 2
    width = max(len(n) for n in names)
    print(f'{"benchmark":<{width}}  {"base ms":>10}  {"new ms":>10}  {"new/base":>8}')
    for n in names:
        b = statistics.median(samples[base][n])
        c = statistics.median(samples[new][n])
        print(f'{n:<{width}}  {b:10.3f}  {c:10.3f}  {c / b:8.3f}')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
