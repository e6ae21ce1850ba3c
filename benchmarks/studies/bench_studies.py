"""Benchmark of the parallel study sweeps (not a test).

Two sweeps of leadscrew.studies, each run serially (SerialExecutor) and on the
default path (executor=None, os.cpu_count() workers): for efficiency_vs_mu the
C++ batch's own threads (one call of DriveBatch.run(values, workers), no Python
thread pool), for creep_map a thread pool of Python threads (the C++ core
releases the GIL while it integrates); and on a reused ThreadPoolExecutor
passed as executor (Python threads sending chunks, for both):

- efficiency_vs_mu: 50 friction coefficients x 3 axial loads on the thesis's
  Table 5.1 drive, speed-controlled at 10 rad/s for 0.2 s (the study's
  defaults): the shipped scenes/thesis_table_5_1.toml (flexible screw and
  nut), and its rigid concept;
- creep_map: 30 frequencies x 30 backlash values of the position-holding case
  (Table 5.1 drive, exact backlash, 5 N mm held torque, 30 N alternating force
  at 5-50 Hz, backlash 0.05-0.5 mm, 6 cycles each).

For each: wall time serial and threaded (the median over --repeats
interleaved runs; --cheap-repeats for the rigid efficiency sweep, which takes
milliseconds), the default path's speed-up (the median over the repeats of
the ratio of a serial run to the threaded run right after it, which sees the
same host: this VM's speed drifts by tens of percent within seconds; with
the range of those ratios and the ratio of the minima beside it), the
process's CPU time over wall time in the fastest threaded run (2.0: both
cores were ours), the time per simulation in the sweep against a single
simulation of one case run alone (the minimum over many repeats; for
efficiency_vs_mu one C++ batch call of one case with its measures, the path
the sweep takes), the share of the serial time spent inside the C++ core
(its own wall-time measurement; the rest holds the GIL: with w workers the
threaded time is at least max(Python part, total / w), so the speed-up can
reach w while the Python share stays below 1 - 1/w), the sum of the cases'
own clocks in the threaded run over that in the serial run before it (the
median over the repeats: 1.0 means each case ran as fast beside another as
alone, so the speed-up is the worker count but for the serial Python and
the imbalance at the end; above 1, the cores gave each case less while both
were busy), and the load average before and after (other work on the
machine slows the threaded runs first).
Before and after the sweeps it also times two threads each running one
C++ batch with no Python in between (two Python threads, and the batch's own
two workers): that speed-up is what the machine's cores give at the time
(other jobs, or virtual cores that share a physical one, lower it), the
ceiling for every sweep's speed-up.

Run: python benchmarks/studies/bench_studies.py [--repeats N] [--cheap-repeats N]
[--flexible] [--dask]
(--flexible adds the efficiency sweep on the flexible_nut and the flexible
concept at 0.1 s each; --dask the creep map on a local Dask cluster of two
worker processes).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

import leadscrew as ls
from leadscrew.studies._sweep import SerialExecutor, default_workers
from leadscrew.studies.creep import _creep_case, creep_map
from leadscrew.studies.drive_efficiency import (_efficiency_batch, _efficiency_chunk,
                                                efficiency_vs_mu)

# The thesis's Table 5.1 drive, shared with the tests.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from helpers.scenes import thesis_scene as thesis_dict  # noqa: E402

TARGETS = {"efficiency_vs_mu": 2.0, "creep_map": 60.0}  # s, threaded, issue 6


def thesis_scene(**changes):
    """Table 5.1 with load case (5.1) (tests/helpers/scenes.py)."""
    return ls.Scene.from_dict(thesis_dict(**changes))


def holding_scene():
    """The position-holding case: exact backlash 0.2 mm, a 5 N mm torque held."""
    return thesis_scene(backlash={"axial": 2e-4},
                        loads={"drive_torque": 5e-3, "axial_force": 0.0})


def timed(function):
    """Wall time [s], process CPU time [s] (all threads) and the value."""
    wall, cpu = time.perf_counter(), time.process_time()
    value = function()
    return time.perf_counter() - wall, time.process_time() - cpu, value


def single_case_time(case_function, case, repeats=200):
    """Minimum wall time of one case (scene edit, simulation, measures) run alone."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        case_function(case)
        times.append(time.perf_counter() - start)
    return min(times)


def core_scaling(repeats=5, cases=1000):
    """Speed-ups of C++ batches of rigid efficiency cases (the GIL released
    throughout, no Python in between) on two threads over one: two Python
    threads each running one batch, and one batch of both on its own two
    workers (DriveBatch.run(values, 2)), against the two batches in a row.
    What the machine's cores give now, the most any sweep can reach (other
    jobs, or vCPUs that share a physical core, lower it)."""
    batch = _efficiency_batch(thesis_scene(), 10.0, 0.2, (0.1, 0.2),
                              {"rtol": 1e-8, "atol": 1e-10})
    values = np.tile([0.3, -10.0], (cases, 1))
    both = np.tile([0.3, -10.0], (2 * cases, 1))
    serial = threaded = workers = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        batch.run(values)
        batch.run(values)
        serial = min(serial, time.perf_counter() - start)
        with concurrent.futures.ThreadPoolExecutor(2) as pool:
            start = time.perf_counter()
            list(pool.map(batch.run, [values, values]))
            threaded = min(threaded, time.perf_counter() - start)
        start = time.perf_counter()
        batch.run(both, 2)
        workers = min(workers, time.perf_counter() - start)
    return serial / threaded, serial / workers


def run(name, sweep, case_function, case, n, repeats):
    """Serial, the default path (executor=None) and a reused thread pool,
    interleaved, each repeat a serial run right before its threaded one."""
    single = single_case_time(case_function, case)
    serial, threaded, pooled, core, clocks = [], [], [], [], []
    with concurrent.futures.ThreadPoolExecutor(default_workers()) as pool:
        for _ in range(repeats):
            wall, cpu, frame = timed(lambda: sweep(SerialExecutor()))
            serial.append((wall, cpu))
            serial_clocks = float(np.nansum(frame["wall_time"]))
            core.append(serial_clocks / wall)
            wall, cpu, threaded_frame = timed(lambda: sweep(None))
            threaded.append((wall, cpu))
            threaded_clocks = float(np.nansum(threaded_frame["wall_time"]))
            # (no case simulated: no ratio)
            clocks.append(threaded_clocks / serial_clocks if serial_clocks > 0 else np.nan)
            wall, cpu, _ = timed(lambda: sweep(pool))
            pooled.append((wall, cpu))
    serial_walls = np.array([w for w, _ in serial])
    threaded_walls = np.array([w for w, _ in threaded])
    # This VM's speed drifts by tens of percent over seconds (README): a
    # serial run and the threaded run right after it see the same host, so
    # the speed-up is the median of those pairs' ratios; the ratio of the
    # two minima is shown beside it.
    paired = serial_walls / threaded_walls
    fastest = min(threaded)
    return {
        "name": name, "n": n, "serial": float(np.median(serial_walls)),
        "threaded": float(np.median(threaded_walls)),
        "pooled": float(np.median([w for w, _ in pooled])),
        "speedup": float(np.median(paired)),
        "speedup_range": (float(paired.min()), float(paired.max())),
        "min_speedup": float(serial_walls.min() / threaded_walls.min()),
        "parallelism": fastest[1] / fastest[0], "per_sim": float(np.median(threaded_walls)) / n,
        "single": single, "core_share": float(np.median(core)),
        "case_clocks": float(np.median(clocks)),
        "failed": int(frame["error"].notna().sum()), "target": TARGETS.get(name.split(" ")[0]),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--cheap-repeats", type=int, default=100,
                        help="repeats of the rigid efficiency sweep (milliseconds each)")
    parser.add_argument("--flexible", action="store_true")
    parser.add_argument("--dask", action="store_true",
                        help="also run the creep map on a local Dask cluster (2 processes)")
    args = parser.parse_args()
    load_before = os.getloadavg()
    scaling_before = core_scaling()
    rows = []

    mu = np.linspace(0.0, 0.5, 50)
    loads = [10.0, 50.0, 100.0]
    # The shipped Table 5.1 scene (flexible screw and nut) with the study's
    # defaults: what `leadscrew study efficiency_vs_mu thesis_table_5_1 ...`
    # runs; then the rigid concept (one degree of freedom, ~11 us per case)
    # and, with --flexible, the other concepts at 0.1 s.
    cases = [("shipped thesis_table_5_1", ls.scenes.load("thesis_table_5_1"), 0.2),
             ("rigid", thesis_scene(concept="rigid"), 0.2)]
    if args.flexible:
        cases += [(concept, thesis_scene(concept=concept), 0.1)
                  for concept in ("flexible_nut", "flexible")]
    for concept, scene, t_end in cases:
        # A single case: one C++ batch call of one case and its measures.
        batch = _efficiency_batch(scene, 10.0, t_end, (t_end / 2, t_end),
                                  {"rtol": 1e-8, "atol": 1e-10})
        rows.append(run(
            f"efficiency_vs_mu ({concept})",
            lambda ex, s=scene, t=t_end: efficiency_vs_mu(s, mu, loads, t_end=t, executor=ex,
                                                          progress=False),
            lambda case, b=batch: _efficiency_chunk([case], b),
            (0.3, 50.0), len(mu) * len(loads),
            args.cheap_repeats if concept == "rigid" else args.repeats))

    frequencies = np.geomspace(5.0, 50.0, 30)
    backlash = np.linspace(0.05e-3, 0.5e-3, 30)
    scene = holding_scene()
    rows.append(run(
        "creep_map",
        lambda ex: creep_map(scene, frequencies, backlash, executor=ex, progress=False),
        lambda case: _creep_case(case, scene, 30.0, 6, 1, 100, {"rtol": 1e-8, "atol": 1e-10}),
        (20.0, 2e-4), len(frequencies) * len(backlash), args.repeats))

    dask_time = None
    if args.dask:
        import warnings

        import distributed

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                          dashboard_address=":0") as cluster, \
                    distributed.Client(cluster) as client:
                # pure=False: Dask would otherwise reuse the results of the
                # previous repeat (same function, same arguments, same keys).
                executor = client.get_executor(pure=False)
                dask_time = min(timed(lambda: creep_map(scene, frequencies, backlash,
                                                        executor=executor,
                                                        progress=False))[0]
                                for _ in range(args.repeats))

    load_after = os.getloadavg()
    scaling_after = core_scaling()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"thread pool of {default_workers()} workers; Python {platform.python_version()}")
    print(f"load average (1, 5, 15 min) before: {load_before[0]:.2f} {load_before[1]:.2f} "
          f"{load_before[2]:.2f}; after: {load_after[0]:.2f} {load_after[1]:.2f} "
          f"{load_after[2]:.2f}")
    print(f"two threads of pure C++ (the most a sweep can reach now): speed-up "
          f"{scaling_before[0]:.2f}x before, {scaling_after[0]:.2f}x after (two Python "
          f"threads); {scaling_before[1]:.2f}x, {scaling_after[1]:.2f}x (the batch's own two "
          f"workers)")
    print(f"medians of {args.repeats} interleaved runs per column ({args.cheap_repeats} for "
          f"the rigid efficiency sweep); speed-up: the median of the ratios serial / "
          f"threads of each repeat's two runs (their range), and the ratio of the minima\n")
    print("| sweep | sims | serial [s] | threads [s] | speed-up (range) | speed-up of minima | "
          "CPU / wall, threads | target [s] | per sim, threads [ms] | single sim [ms] | "
          "C++ share of serial | case clocks, threads / serial | failed |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        target = f"< {r['target']:g}" if r["target"] else ""
        low, high = r["speedup_range"]
        print(f"| {r['name']} | {r['n']} | {r['serial']:.4f} | {r['threaded']:.4f} | "
              f"{r['speedup']:.2f}x ({low:.2f}-{high:.2f}) | {r['min_speedup']:.2f}x | "
              f"{r['parallelism']:.2f} | {target} | {r['per_sim'] * 1e3:.3f} | "
              f"{r['single'] * 1e3:.3f} | {r['core_share']:.0%} | {r['case_clocks']:.2f} | "
              f"{r['failed']} |")
    print("\n(threads: the default, executor=None: the C++ batch's own threads for "
          "efficiency_vs_mu, a new thread pool per call for creep_map; a reused "
          "ThreadPoolExecutor passed as executor gave "
          + ", ".join(f"{r['pooled']:.4f} s" for r in rows) + ")")
    if dask_time is not None:
        print(f"creep_map on a local Dask cluster (2 worker processes, cluster started "
              f"beforehand): {dask_time:.3f} s")


if __name__ == "__main__":
    main()
