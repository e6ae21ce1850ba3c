"""The rigid efficiency sweep, serial against the default path, on a shared machine (not a test).

efficiency_vs_mu over 50 values of mu x 3 loads on the thesis's Table 5.1
drive (rigid concept, 0.2 s per case, ~11 us of C++ each), run in interleaved
blocks of:

- serial: ``executor=SerialExecutor()`` (the default path's batch calls with
  the calling thread as the only worker);
- default: ``executor=None`` (one call of the C++ batch on its own
  ``default_workers()`` threads);
- a reused ``ThreadPoolExecutor`` (Python threads sending chunks);
- the C++ batch alone on 1 and on 2 workers (no Python around it): the ratio
  is the speed-up the machine's two cores give at that moment, the ceiling of
  the sweep's.

The whole sweep takes a few milliseconds, so a compiler starting on the other
core changes a timing by half. For each block the script reads the CPU time
the whole machine spent (/proc/stat) and subtracts this process's own: a
block in which other processes used more than ``--quiet`` of a core is
"busy". It reports minima and medians over the quiet blocks (and over all),
and the median of the per-iteration ratios (serial and default timed next to
each other).

Run: python benchmarks/studies/bench_rigid_threads.py [--blocks N] [--per-block N]
"""

from __future__ import annotations

import argparse
import concurrent.futures
import os
import sys
import time
from pathlib import Path

import numpy as np

import leadscrew as ls
from leadscrew.studies._sweep import SerialExecutor, default_workers
from leadscrew.studies.drive_efficiency import _efficiency_batch, efficiency_vs_mu

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from helpers.scenes import thesis_scene  # noqa: E402


def machine_busy_seconds() -> float:
    """CPU time every process of the machine has used [s] (/proc/stat)."""
    with open("/proc/stat") as stat:
        fields = [int(x) for x in stat.readline().split()[1:]]
    idle = fields[3] + fields[4]  # idle, iowait
    return (sum(fields[:8]) - idle) / os.sysconf("SC_CLK_TCK")


def own_seconds() -> float:
    times = os.times()
    return times.user + times.system


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blocks", type=int, default=60)
    parser.add_argument("--per-block", type=int, default=10)
    parser.add_argument("--quiet", type=float, default=0.05,
                        help="most CPU of other processes in a quiet block [cores]")
    args = parser.parse_args()

    scene = ls.Scene.from_dict(thesis_scene())
    mu, loads = np.linspace(0.0, 0.5, 50), [10.0, 50.0, 100.0]
    batch = _efficiency_batch(scene, 10.0, 0.2, (0.1, 0.2), {"rtol": 1e-8, "atol": 1e-10})
    values = np.column_stack([np.repeat(mu, 3), -np.tile(loads, 50)])
    workers = default_workers()
    with concurrent.futures.ThreadPoolExecutor(workers) as pool:
        runs = {
            "serial": lambda: efficiency_vs_mu(scene, mu, loads, executor=SerialExecutor(),
                                               progress=False),
            "default": lambda: efficiency_vs_mu(scene, mu, loads, progress=False),
            "default, progress bar": lambda: efficiency_vs_mu(scene, mu, loads, progress=True),
            "reused thread pool": lambda: efficiency_vs_mu(scene, mu, loads, executor=pool,
                                                           progress=False),
            "C++ batch, 1 worker": lambda: batch.run(values, 1),
            f"C++ batch, {workers} workers": lambda: batch.run(values, workers),
        }
        for run in runs.values():  # warm up
            run()
        times = {name: [] for name in runs}
        quiet, load = [], []
        for _ in range(args.blocks):
            busy, own, wall = machine_busy_seconds(), own_seconds(), time.perf_counter()
            block = {name: [] for name in runs}
            for _ in range(args.per_block):
                for name, run in runs.items():
                    start = time.perf_counter()
                    run()
                    block[name].append(time.perf_counter() - start)
            wall = time.perf_counter() - wall
            others = (machine_busy_seconds() - busy) - (own_seconds() - own)
            load.append(others / wall)
            quiet.extend([others / wall <= args.quiet] * args.per_block)
            for name in runs:
                times[name].extend(block[name])
    quiet = np.array(quiet)
    times = {name: np.array(t) for name, t in times.items()}
    cxx = list(runs)[-2:]
    print(f"{os.cpu_count()} cores, {workers} workers; {args.blocks} blocks of "
          f"{args.per_block} interleaved iterations, {quiet.sum()} iterations in quiet blocks "
          f"(other processes <= {args.quiet:g} core); load average now "
          f"{os.getloadavg()[0]:.2f}; other processes per block: minimum "
          f"{min(load):.2f}, median {np.median(load):.2f} cores\n")
    for label, keep in (("quiet blocks", quiet), ("all blocks", np.ones_like(quiet))):
        if not keep.any():
            print(f"{label}: none\n")
            continue
        print(f"{label} ({keep.sum()} iterations)\n")
        print("| run | min [ms] | median [ms] |")
        print("|---|---|---|")
        for name, t in times.items():
            print(f"| {name} | {t[keep].min() * 1e3:.3f} | {np.median(t[keep]) * 1e3:.3f} |")

        def ratios(a, b):
            paired = np.median(times[a][keep] / times[b][keep])
            return (f"{times[a][keep].min() / times[b][keep].min():.2f}x (minima), "
                    f"{np.median(times[a][keep]) / np.median(times[b][keep]):.2f}x (medians), "
                    f"{paired:.2f}x (median of paired ratios)")

        print(f"\nserial / default: {ratios('serial', 'default')}")
        print(f"serial / reused thread pool: {ratios('serial', 'reused thread pool')}")
        print(f"C++ ceiling, {cxx[0]} / {cxx[1]}: {ratios(*cxx)}")
        python = times["default"][keep].min() - times[cxx[1]][keep].min()
        print(f"Python around the default sweep (minimum of default - minimum of the C++ "
              f"batch on {workers} workers): {python * 1e3:.3f} ms\n")


if __name__ == "__main__":
    main()
