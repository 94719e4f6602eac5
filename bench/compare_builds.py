#!/usr/bin/env python3
"""Every Google Benchmark of two builds, in one alternating session: B's time over A's.

    python3 bench/compare_builds.py BUILD_A BUILD_B [--rounds 5] [--min-time 0.2] [--filter REGEX] [--cpu N]

For each bench/bench_* program present in both builds, and each benchmark the two programs
share by name, the two builds run that benchmark in turn, `--rounds` pairs of runs, the pair's
order alternating (A B, then B A, ...), so a drift of the machine's speed falls on both. Each
run reports the benchmark's CPU time; a pair gives a ratio B / A. The table gives the median
time of each side and the median of the pairs' ratios, with their range (below 1: B is faster).
Programs that are not Google Benchmarks (bench_memory prints a table) are skipped, by name.
`--cpu N` runs every benchmark on processor N alone (fewer migrations; the other processors
keep the rest of the machine's work).

The ratio is the figure to quote: absolute times move with the machine's load, paired ratios
from one alternating session much less. Running a build against itself (A = B) shows the
session's noise: a ratio inside that spread is no difference.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys

NOT_GOOGLE_BENCHMARK = {"bench_memory"}


def programs(build):
    folder = os.path.join(build, "bench")
    if not os.path.isdir(folder):
        sys.exit(f"error: {folder}: no bench folder (build with -DADJOIN_BUILD_BENCH=ON)")
    return {name for name in os.listdir(folder)
            if name.startswith("bench_") and os.access(os.path.join(folder, name), os.X_OK)
            and os.path.isfile(os.path.join(folder, name)) and name not in NOT_GOOGLE_BENCHMARK}


def listed(build, program, pattern):
    command = [os.path.join(build, "bench", program), "--benchmark_list_tests"]
    if pattern:
        command.append(f"--benchmark_filter={pattern}")
    out = subprocess.run(command, capture_output=True, text=True, check=True).stdout
    return [line.strip() for line in out.splitlines() if line.strip()]


def cpu_times(build, program, names, min_time, cpu=None):
    """One run of `program` over `names`: {name: CPU time in ns}."""
    pattern = "^(" + "|".join(map(escape, names)) + ")$"
    command = [os.path.join(build, "bench", program), f"--benchmark_filter={pattern}",
               f"--benchmark_min_time={min_time}", "--benchmark_format=json"]
    pin = (lambda: os.sched_setaffinity(0, {cpu})) if cpu is not None else None
    report = json.loads(subprocess.run(command, capture_output=True, text=True, check=True,
                                       preexec_fn=pin).stdout)
    scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}
    return {b["name"]: b["cpu_time"] * scale[b["time_unit"]] for b in report["benchmarks"]
            if b.get("run_type", "iteration") == "iteration"}


def escape(name):
    return "".join("\\" + c if c in ".^$*+?()[]{}|\\" else c for c in name)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build_a")
    parser.add_argument("build_b")
    parser.add_argument("--rounds", type=int, default=5, help="pairs of runs per benchmark")
    parser.add_argument("--min-time", type=float, default=0.2, help="seconds per benchmark per run")
    parser.add_argument("--filter", default="", help="only benchmarks matching this regex")
    parser.add_argument("--cpu", type=int, default=None, help="run the benchmarks on this processor only")
    args = parser.parse_args()

    rows = []
    for program in sorted(programs(args.build_a) & programs(args.build_b)):
        shared = sorted(set(listed(args.build_a, program, args.filter)) & set(listed(args.build_b, program, args.filter)))
        for name in shared:
            a_times, b_times, ratios = [], [], []
            for r in range(args.rounds):
                order = (("a", args.build_a), ("b", args.build_b))
                got = {}
                for side, build in (order if r % 2 == 0 else order[::-1]):
                    got[side] = cpu_times(build, program, [name], args.min_time, args.cpu).get(name)
                if got["a"] and got["b"]:
                    a_times.append(got["a"])
                    b_times.append(got["b"])
                    ratios.append(got["b"] / got["a"])
            if ratios:
                rows.append((program, name, statistics.median(a_times), statistics.median(b_times),
                             statistics.median(ratios), min(ratios), max(ratios)))
        if shared:
            print(f"{program}: {len(shared)} benchmarks", file=sys.stderr, flush=True)

    print(f"{'program':<20} {'benchmark':<60} {'A [ms]':>10} {'B [ms]':>10} {'B / A':>7}  {'pairs':>13}")
    for program, name, a, b, ratio, low, high in rows:
        print(f"{program:<20} {name:<60} {a / 1e6:>10.4f} {b / 1e6:>10.4f} {ratio:>7.3f}  {low:>5.3f}..{high:<5.3f}")
    if rows:
        ratios = [r[4] for r in rows]
        print(f"\n{len(rows)} benchmarks: B / A median {statistics.median(ratios):.3f}, "
              f"range {min(ratios):.3f} .. {max(ratios):.3f}")


if __name__ == "__main__":
    main()
