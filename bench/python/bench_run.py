#!/usr/bin/env python3
"""Benchmarks of the Python package (issue 22's figures): adjoin.run against `adjoin run` on the
two-frame example, and run_many's throughput against serial runs.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_run.py [--adjoin build/adjoin] [--repeat 5]

Prints the median of `--repeat` timings of each. `adjoin run`'s time is its own report of the
run (summary.json's solver.wall_seconds and the companion's) besides the process's wall time,
so the process start-up and file writing are seen apart from the computation.
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import adjoin

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "records" / "scenes" / "buildings" / "two-frames.toml"


def median_time(f, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--adjoin", default=str(ROOT / "build" / "adjoin"))
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    overrides = {"solver.t_end": 1.0}  # the "1-second run"

    with tempfile.TemporaryDirectory() as tmp:
        cli = [args.adjoin, "run", str(SCENE), "--out", os.path.join(tmp, "out"), "--quiet", "--set", "solver.t_end=1.0"]
        # (stderr: the warning that the run ends before the record does, expected here)
        cli_time = median_time(lambda: subprocess.run(cli, check=True, stderr=subprocess.DEVNULL), args.repeat)
        summary = json.loads(pathlib.Path(tmp, "out", "summary.json").read_text())
    scene = adjoin.load_scene(SCENE, set=overrides)
    py_time = median_time(lambda: adjoin.run(scene), args.repeat)
    print(f"adjoin run (process, 1 s of two-frames): {cli_time * 1e3:8.1f} ms "
          f"(its run: {summary['solver']['wall_seconds'] * 1e3:.1f} ms)")
    print(f"adjoin.run (same scene):                 {py_time * 1e3:8.1f} ms ({py_time / cli_time:.2f} x the process)")

    scenes = [adjoin.load_scene(SCENE, set={"solver.t_end": 60.0, "link.1.slip_ratio": 0.02 * (i + 1)}) for i in range(8)]
    serial = median_time(lambda: [adjoin.run(s) for s in scenes], args.repeat)
    threaded = median_time(lambda: adjoin.run_many(scenes, jobs=2), args.repeat)
    print(f"8 runs of 60 s: serial {serial:.3f} s, run_many(jobs=2) {threaded:.3f} s: {serial / threaded:.2f} x "
          f"on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
