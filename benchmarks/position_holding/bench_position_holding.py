"""Issue 34, item 5: position holding, fast and right by default.

The shipped ``position_holding`` scene on the flexible_nut concept, 0.5 s
(``ls.scenes.load("position_holding").replace(concept="flexible_nut")``: exact
Coulomb friction, event-driven at its ``[simulation]`` rtol 1e-6, atol 1e-8):

- ``simulate(scene, 0.5)`` with every default, timed side by side (in
  rotation, one process) with the same drive's independent NumPy model
  (tests/helpers/drive_python.py: the thesis's arctan law, k_v 1e6 s/m, and
  the bistop flanks; it has no exact Coulomb) under scipy's LSODA at rtol
  1e-4: medians and the median of the paired ratios (NumPy's time over ours);
- the creep after 0.5 s (10 cycles of the 20 Hz force) of each against
  converged references. The creep is the load travel the thread's turning
  gives, -p phi_drive(0.5 s) (p = lead / 2 pi, right hand; the measure of
  ``leadscrew.studies.position_holding``): u_load itself adds the nut's place
  in the 0.2 mm play, which a rattling nut changes from cycle to cycle. The
  references: the scene's exact Coulomb (event-driven, rtol 1e-11;
  Moreau-Jean converges to it as dt -> 0) and the arctan law (cvode_bdf,
  rtol 1e-11);
- a work-precision table on the creep for every scheme: the arctan law under
  cvode_bdf, exact Coulomb event-driven and Moreau-Jean at a few dt, and the
  NumPy model under LSODA.

Run: python benchmarks/position_holding/bench_position_holding.py [--rounds N]
(writes nothing: paste the table into results.md).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # (scipy's BLAS threads spin otherwise)
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import leadscrew as ls  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tests"))
from helpers.drive_python import simulate_python  # noqa: E402

T_END = 0.5
LEAD = 1e-3  # [m] the scene's pitch, one start


def creep_of(phi_drive) -> float:
    """The load travel of the thread's turning [m] (right hand: -p phi)."""
    return float(-LEAD / (2.0 * math.pi) * phi_drive[-1])


def scenes():
    """The shipped scene (exact Coulomb, its [simulation] rtol 1e-6, atol
    1e-8) and the same drive with the thesis's arctan law (k_v 1e6 s/m) and
    simulate's own defaults (rtol 1e-8: the scene's default before issue 34,
    item 5), which the NumPy model computes."""
    coulomb = ls.scenes.load("position_holding").replace(concept="flexible_nut")
    arctan = coulomb.replace(friction={"law": "arctan_velocity", "k_v": 1e6}, simulation=None)
    return arctan, coulomb


def cases(arctan, coulomb, full):
    """name -> (call returning the creep [m], formulation of its reference)."""
    def ours(scene, **options):
        return lambda: creep_of(ls.simulate(scene, T_END, **options)["phi_drive"])

    def numpy(rtol):
        # (the call of the issue: 101 output times, the energy account, atol 1e-12)
        return lambda: creep_of(simulate_python(arctan, T_END, method="LSODA",
                                                rtol=rtol)["phi_drive"])

    def coulomb_at(rtol, atol=1e-10, **options):
        # (both tolerances given: the scene's stored atol 1e-8 overridden too)
        return ours(coulomb, rtol=rtol, atol=atol, **options), "coulomb"

    sampled = np.linspace(0.0, T_END, 101)  # (the output sampling: 101 times, not every step)
    table = {"default simulate(scene, 0.5) (coulomb, the scene's rtol 1e-6, atol 1e-8)":
                 (ours(coulomb), "coulomb"),
             "NumPy/LSODA rtol 1e-4": (numpy(1e-4), "arctan"),
             "default, 101 output times": (ours(coulomb, t_eval=sampled), "coulomb"),
             "default, every step (t_eval='steps')": (ours(coulomb, t_eval="steps"), "coulomb"),
             "arctan k_v 1e6, cvode_bdf rtol 1e-8 (the former default)": (ours(arctan), "arctan"),
             "coulomb event_driven rtol 1e-6, atol 1e-10": coulomb_at(1e-6),
             "coulomb event_driven rtol 1e-8, atol 1e-10 (simulate's)": coulomb_at(1e-8),
             "coulomb event_driven rtol 1e-3, atol 1e-10": coulomb_at(1e-3),
             "coulomb event_driven rtol 1e-4, atol 1e-10": coulomb_at(1e-4),
             "coulomb moreau dt 1e-4": (ours(coulomb, integrator="moreau", dt=1e-4), "coulomb"),
             "coulomb moreau dt 3e-5": (ours(coulomb, integrator="moreau", dt=3e-5), "coulomb"),
             "coulomb moreau dt 1e-5": (ours(coulomb, integrator="moreau", dt=1e-5), "coulomb")}
    if full:
        table["coulomb event_driven rtol 1e-5, atol 1e-10"] = coulomb_at(1e-5)
        table["coulomb event_driven rtol 1e-7, atol 1e-10"] = coulomb_at(1e-7)
        table["coulomb event_driven rtol 1e-6, atol 1e-9"] = coulomb_at(1e-6, 1e-9)
        table["coulomb event_driven rtol 1e-6, atol 1e-7"] = coulomb_at(1e-6, 1e-7)
        table["coulomb event_driven rtol 1e-5, atol 1e-8"] = coulomb_at(1e-5, 1e-8)
        table["coulomb moreau dt 3e-6"] = (ours(coulomb, integrator="moreau", dt=3e-6), "coulomb")
        for rtol in (1e-5, 1e-6, 1e-7):
            table[f"arctan cvode_bdf rtol {rtol:.0e}"] = (ours(arctan, rtol=rtol), "arctan")
        table["NumPy/LSODA rtol 1e-5"] = (numpy(1e-5), "arctan")
        table["NumPy/LSODA rtol 1e-6"] = (numpy(1e-6), "arctan")
    return table


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--full", action="store_true",
                        help="also the longer rows of the work-precision table")
    parser.add_argument("--no-reference", action="store_true",
                        help="skip the rtol 1e-11 references (relative errors then omitted)")
    args = parser.parse_args()
    arctan, coulomb = scenes()
    reference = {}
    if not args.no_reference:
        for name, scene in (("arctan", arctan), ("coulomb", coulomb)):
            start = time.perf_counter()
            reference[name] = creep_of(ls.simulate(scene, T_END, rtol=1e-11, atol=1e-14,
                                                   t_eval=[0.0, T_END])["phi_drive"])
            print(f"reference {name}: creep {reference[name]:.9e} m "
                  f"({time.perf_counter() - start:.1f} s)", flush=True)
    table = cases(arctan, coulomb, args.full)
    load_before = os.getloadavg()
    times = {name: [] for name in table}
    creep = {}
    for _ in range(args.rounds):  # in rotation: every case once per round
        for name, (call, _kind) in table.items():
            start = time.perf_counter()
            creep[name] = call()
            times[name].append(time.perf_counter() - start)
    numpy_name = "NumPy/LSODA rtol 1e-4"
    print(f"\nload average before/after: {load_before} / {os.getloadavg()}")
    print(f"\n{args.rounds} rounds; ratio: {numpy_name}'s time over the case's "
          "(median of the paired ratios of one round)\n")
    print("| case | median s | ratio | creep [um] | error vs converged |")
    print("|---|---|---|---|---|")
    for name, (_call, kind) in table.items():
        ratio = statistics.median(a / b for a, b in zip(times[numpy_name], times[name]))
        error = (f"{abs(creep[name] / reference[kind] - 1.0) * 100:.2f} % ({kind})"
                 if kind in reference else "-")
        print(f"| {name} | {statistics.median(times[name]):.4f} | {ratio:.2f}x | "
              f"{creep[name] * 1e6:.5f} | {error} |", flush=True)
    if len(reference) == 2:
        print(f"\narctan reference against Coulomb's: "
              f"{(reference['arctan'] / reference['coulomb'] - 1.0) * 100:+.2f} %")


if __name__ == "__main__":
    main()
