"""Before/after: the same cases timed with two builds of leadscrew, side by
side in one run.

Each build runs in a worker process of its own (two builds cannot share an
interpreter: both are the module ``leadscrew``), started with its package
directory first on PYTHONPATH. The workers are timed in alternation, round
after round, so that both meet the same moments of this machine (its vCPUs
change speed within seconds): in each round each worker runs every case
``--batch`` times and reports the simulations' own clock (``stats
["wall_time"]``, inside C++) and the call's (``perf_counter`` around
``simulate``). The table gives per case the median of each build over all
rounds, and the median over the rounds of the paired ratio after / before.

Usage (from the repository root)::

    python benchmarks/before_after/bench_before_after.py BEFORE_DIR AFTER_DIR

with each DIR a directory that holds a built ``leadscrew`` package (e.g. a
copy of an installed one, or ``python`` of a checkout with its extension
built in place). ``--rounds``, ``--batch``, ``--cases`` (comma-separated
names) and ``--output FILE`` (markdown) as usual.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import textwrap

# The cases: name -> Python source of a zero-argument function returning
# (model, t_end, simulate keywords). Only options both builds know.
CASES = {
    "block, exact Coulomb, event-driven (V = 6 N, 2 s)": """
        import math
        import leadscrew as ls
        def case():
            block = ls.FrictionBlock(1.0, 0.3, 10.0, ls.Sine(6.0, 4 * math.pi))
            return block, 2.0, {}
    """,
    "rigid drive, exact Coulomb, event-driven (eq. 5.1, 2 s, rtol 1e-6)": """
        import math
        import leadscrew as ls
        def case():
            scene = ls.Scene.from_dict({
                "concept": "rigid", "thread": {"pitch": 1e-3, "mean_diameter": 20e-3},
                "friction": {"law": "coulomb", "mu": 0.3},
                "rotor": {"inertia": 1e-6}, "load": {"mass": 1.0},
                "loads": {"drive_torque": {"type": "sine", "amplitude": -40e-3,
                                           "omega": 4 * math.pi},
                          "axial_force": -10.0}})
            return scene, 2.0, {"rtol": 1e-6, "atol": 1e-8, "t_eval": [2.0]}
    """,
    "flexible screw and nut, bistop play, cvode_bdf (1 s, rtol 1e-6, atol 1e-6)": """
        import math
        import leadscrew as ls
        def case():
            scene = ls.Scene.from_dict({
                "concept": "flexible", "thread": {"pitch": 1e-3, "mean_diameter": 20e-3},
                "friction": {"law": "arctan_velocity", "mu": 0.3, "k_v": 1e3},
                "backlash": {"axial": 0.1e-3, "contact": "bistop"},
                "screw": {"radius": 10e-3, "length": 0.5, "youngs_modulus": 210e9},
                "nut": {"outer_radius": 12e-3, "length": 20e-3, "youngs_modulus": 2e9,
                        "position": 0.1},
                "loads": {"drive_torque": {"type": "sine", "amplitude": -40e-3,
                                           "omega": 4 * math.pi},
                          "axial_force": -10.0}})
            return scene, 1.0, {"integrator": "cvode_bdf", "rtol": 1e-6, "atol": 1e-6,
                                "t_eval": [i / 200 for i in range(201)]}
    """,
}

WORKER = textwrap.dedent("""
    import json, sys, time, textwrap
    cases = json.loads(sys.argv[1])
    functions = {}
    for name, source in cases.items():
        scope = {}
        exec(textwrap.dedent(source), scope)
        functions[name] = scope["case"]
    import leadscrew as ls
    print(json.dumps({"file": ls.__file__}), flush=True)
    for line in sys.stdin:
        batch = int(line)
        out = {}
        for name, make in functions.items():
            model, t_end, options = make()
            ls.simulate(model, t_end, **options)  # warm
            inside, call = [], []
            for _ in range(batch):
                start = time.perf_counter()
                result = ls.simulate(model, t_end, **options)
                call.append(time.perf_counter() - start)
                inside.append(result.stats["wall_time"])
            out[name] = {"inside": inside, "call": call}
        print(json.dumps(out), flush=True)
""")


def start_worker(package_dir: str, cases: dict) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=os.path.abspath(package_dir), OMP_NUM_THREADS="1",
               OPENBLAS_NUM_THREADS="1")
    worker = subprocess.Popen([sys.executable, "-c", WORKER, json.dumps(cases)], env=env,
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    hello = json.loads(worker.stdout.readline())
    print(f"{package_dir}: {hello['file']}", file=sys.stderr)
    return worker


def round_of(worker: subprocess.Popen, batch: int) -> dict:
    worker.stdin.write(f"{batch}\n")
    worker.stdin.flush()
    return json.loads(worker.stdout.readline())


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--rounds", type=int, default=21)
    parser.add_argument("--batch", type=int, default=20)
    parser.add_argument("--cases", default="", help="comma-separated case names (default: all)")
    parser.add_argument("--output", default="")
    args = parser.parse_args(argv)
    cases = {name: source for name, source in CASES.items()
             if not args.cases or any(part and part in name for part in args.cases.split(","))}
    workers = {"before": start_worker(args.before, cases),
               "after": start_worker(args.after, cases)}
    samples = {which: {name: {"inside": [], "call": []} for name in cases} for which in workers}
    ratios = {name: {"inside": [], "call": []} for name in cases}
    for k in range(args.rounds):
        order = ("before", "after") if k % 2 == 0 else ("after", "before")
        medians = {}
        for which in order:
            got = round_of(workers[which], args.batch)
            medians[which] = {}
            for name in cases:
                for clock in ("inside", "call"):
                    samples[which][name][clock] += got[name][clock]
                medians[which][name] = {clock: statistics.median(got[name][clock])
                                        for clock in ("inside", "call")}
        for name in cases:
            for clock in ("inside", "call"):
                ratios[name][clock].append(medians["after"][name][clock] /
                                           medians["before"][name][clock])
    for worker in workers.values():
        worker.stdin.close()
        worker.wait(timeout=60)
    lines = ["| case | clock | before (median) | after (median) | after / before (median of "
             "paired rounds, range) |", "|---|---|---|---|---|"]
    for name in cases:
        for clock in ("inside", "call"):
            before = statistics.median(samples["before"][name][clock])
            after = statistics.median(samples["after"][name][clock])
            r = ratios[name][clock]
            lines.append(f"| {name} | {'C++' if clock == 'inside' else 'Python call'} | "
                         f"{before * 1e6:.1f} us | {after * 1e6:.1f} us | "
                         f"{statistics.median(r):.3f} ({min(r):.3f}-{max(r):.3f}) |")
    table = "\n".join(lines)
    print(table)
    if args.output:
        with open(args.output, "w") as f:
            f.write(table + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
