"""Benchmark of the shipped seat adjuster (issue 19): not a timed test.

1. A 2 s run to the rear end stop and back (+12 V for 1 s, then -12 V) per
   concept, with exact Coulomb friction and exact end stops (where the model
   takes them: the flexible concept, whose load hangs on the spindle's
   spring; the rigid and flexible_nut concepts clamp a rigid part against the
   stop, statically indeterminate, and take penalty stops only), against the
   same run with penalty stops and with the regularized friction law
   (arctan_velocity, k_v = 1e4 s/m) and penalty stops: wall time (median of
   `--repeats`), events and the run's largest stop force; ratios against the
   first variant of each concept.
   The worm scene (seat_adjuster_worm: the rigid concept through its
   self-locking worm and the motor's friction) runs the same 2 s with exact
   Coulomb friction and penalty stops (the train's friction stages take no
   other), its ratio against the rigid concept's first run.
2. 50 reversing runs of end_stop_jam's sequence (into the stop, then each of
   50 reverse voltages) serially and on a thread pool of 2 workers (each
   leadscrew.simulate releases the GIL): wall time and the ratio.

    PYTHONPATH=python python3 benchmarks/drive_train/bench_seat_adjuster.py [--repeats 5]

Prints a Markdown table (results.md holds the last run's).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import statistics
import time

import numpy as np

import leadscrew as ls

T_SWITCH, T_END = 1.0, 2.0
BACK_AND_FORTH = {"type": "table", "times": [0.0, T_SWITCH, T_SWITCH + 1e-6, T_END],
                  "values": [12.0, 12.0, -12.0, -12.0]}
ARCTAN = {"law": "arctan_velocity", "mu": 0.12, "k_v": 1e4}
PENALTY = {"contact": "penalty", "stiffness": 5e6, "damping": 5e3, "restitution": 0.0}
EXACT = {"contact": "exact", "restitution": 0.0}


def variants(concept):
    """(name, scene) of the concept's runs, the reference first."""
    base = ls.scenes.load("seat_adjuster").replace(concept=concept,
                                                   motor={"voltage": BACK_AND_FORTH})
    def changed(**sections):
        d = base.to_dict()
        d.update(sections)
        return ls.Scene.from_dict(d)

    out = []
    if concept == "flexible":
        lower, upper = base["end_stops"]["lower"], base["end_stops"]["upper"]
        out.append(("Coulomb, exact stops",
                    changed(end_stops={"lower": lower, "upper": upper, **EXACT})))
    out.append(("Coulomb, penalty stops", base.replace(end_stops=PENALTY)))
    # (a regularized law takes no mu_static)
    out.append(("arctan k_v=1e4, penalty stops", changed(friction=ARCTAN,
                                                         end_stops={**base["end_stops"],
                                                                    **PENALTY})))
    return out


def worm_scene():
    """seat_adjuster_worm with the back-and-forth voltage (rigid, exact
    Coulomb, penalty stops)."""
    return ls.scenes.load("seat_adjuster_worm").replace(motor={"voltage": BACK_AND_FORTH})


def worm_flexible_scene():
    """seat_adjuster_worm_flexible with the back-and-forth voltage (flexible,
    0.1 mm exact play, the worm and the motor's friction, exact stops: only
    Moreau-Jean runs it)."""
    return ls.scenes.load("seat_adjuster_worm_flexible").replace(
        motor={"voltage": BACK_AND_FORTH})


def timed(scene, repeats, **options):
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = ls.simulate(scene, T_END, **options)
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def reversing_runs(voltages, workers):
    scene = ls.scenes.load("seat_adjuster")

    def run(voltage):
        table = {"type": "table", "times": [0.0, 1.5, 1.5 + 1e-9, 1.7],
                 "values": [12.0, 12.0, -voltage, -voltage]}
        result = ls.simulate(scene.replace(motor={"voltage": table}), 1.7, t_eval=[1.7])
        return float(result["stop_force"][-1]) == 0.0

    start = time.perf_counter()
    if workers == 1:
        freed = [run(v) for v in voltages]
    else:
        with concurrent.futures.ThreadPoolExecutor(workers) as pool:
            freed = list(pool.map(run, voltages))
    return time.perf_counter() - start, freed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    print("## Seat adjuster: 2 s to the rear stop and back (+12 V, then -12 V at 1 s)\n")
    print("| concept | run | wall time [ms] | ratio | events | largest stop force [N] |")
    print("|---|---|---|---|---|---|")
    rigid = flexible = None
    for concept in ("rigid", "flexible_nut", "flexible"):
        reference = None
        for name, scene in variants(concept):
            wall, result = timed(scene, args.repeats)
            reference = reference or wall
            print(f"| {concept} | {name} | {1e3 * wall:.1f} | {wall / reference:.2f} | "
                  f"{len(result.events)} | {np.max(np.abs(result['stop_force'])):.0f} |",
                  flush=True)
        rigid = rigid or reference
        flexible = reference
    wall, result = timed(worm_scene(), args.repeats)
    print(f"| rigid, worm (seat_adjuster_worm) | Coulomb, penalty stops | {1e3 * wall:.1f} | "
          f"{wall / rigid:.2f} | {len(result.events)} | "
          f"{np.max(np.abs(result['stop_force'])):.0f} |", flush=True)
    # The flexible seat with its worm: Moreau-Jean's fixed steps (ratio
    # against the flexible concept's event-driven run with the ideal stage).
    # Its stop force column is the clamp just before the reversal at 1 s: an
    # exact stop's closing step books its impulse over dt (83 kN at 1e-5 s).
    for dt in (1e-4, 1e-5):
        wall, result = timed(worm_flexible_scene(), args.repeats, dt=dt)
        clamp = abs(float(np.interp(0.999, result.t, result["stop_force"])))
        print(f"| flexible, worm (seat_adjuster_worm_flexible) | Coulomb, exact stops, "
              f"Moreau-Jean dt = {dt:g} s | {1e3 * wall:.1f} | {wall / flexible:.2f} | "
              f"{len(result.events)} (time stepping) | {clamp:.0f} (clamp at 1 s) |", flush=True)
    voltages = np.linspace(1.0, 12.0, 50)
    serial, freed = reversing_runs(voltages, 1)
    pooled, freed_pool = reversing_runs(voltages, 2)
    assert freed == freed_pool
    print("\n## 50 reversing runs (end_stop_jam's sequence, reverse 1 to 12 V)\n")
    print("| workers | wall time [s] | ratio |")
    print("|---|---|---|")
    print(f"| 1 | {serial:.2f} | 1.00 |")
    print(f"| 2 (thread pool) | {pooled:.2f} | {pooled / serial:.2f} |")
    print(f"\nfreed at {sum(freed)} of 50 voltages (smallest {voltages[freed.index(True)]:.3g} V)"
          if any(freed) else "\nnone freed")


if __name__ == "__main__":
    main()
