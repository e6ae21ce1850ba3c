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

The machine's noise is measured in the same run: a third worker runs the
BEFORE build again (an A/A control, timed in the same rotation), and the
table gives its ratio to the first beside after / before. A median's 95 %
interval comes from the order statistics of the paired ratios (the
binomial interval of the median, no distribution assumed). "No slower
beyond the noise" reads: after / before's interval reaches down to the A/A
control's. Many short rounds measure better than few long ones on this
machine (its vCPUs change speed within seconds): the defaults are 301
rounds of 10 calls.
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
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
    "position holding on flexible_nut, Moreau-Jean (dt 3e-5, 0.5 s)": """
        import leadscrew as ls
        def case():
            scene = ls.scenes.load("position_holding").replace(concept="flexible_nut")
            return scene, 0.5, {"integrator": "moreau", "dt": 3e-5, "t_eval": [0.0, 0.5]}
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


def median_interval(values: list) -> str:
    """The median and its 95 % distribution-free interval: the order
    statistics k and n - 1 - k with k the binomial(n, 1/2) quantile
    (normal approximation, n >= 10; fewer rounds give the range)."""
    ordered = sorted(values)
    n = len(ordered)
    median = statistics.median(ordered)
    if n < 10:
        return f"{median:.3f} [{ordered[0]:.3f}-{ordered[-1]:.3f}]"
    k = max(0, int(math.floor(n / 2 - 1.96 * math.sqrt(n) / 2)))
    return f"{median:.3f} [{ordered[k]:.3f}-{ordered[n - 1 - k]:.3f}]"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--rounds", type=int, default=301)
    parser.add_argument("--batch", type=int, default=10)
    parser.add_argument("--cases", default="", help="comma-separated case names (default: all)")
    parser.add_argument("--output", default="")
    args = parser.parse_args(argv)
    cases = {name: source for name, source in CASES.items()
             if not args.cases or any(part and part in name for part in args.cases.split(","))}
    workers = {"before": start_worker(args.before, cases),
               "after": start_worker(args.after, cases),
               "control": start_worker(args.before, cases)}
    samples = {which: {name: {"inside": [], "call": []} for name in cases} for which in workers}
    ratios = {which: {name: {"inside": [], "call": []} for name in cases}
              for which in ("after", "control")}
    rotations = list(itertools.permutations(workers))
    for k in range(args.rounds):
        order = rotations[k % len(rotations)]
        medians = {}
        for which in order:
            got = round_of(workers[which], args.batch)
            medians[which] = {}
            for name in cases:
                for clock in ("inside", "call"):
                    samples[which][name][clock] += got[name][clock]
                medians[which][name] = {clock: statistics.median(got[name][clock])
                                        for clock in ("inside", "call")}
        for which in ratios:
            for name in cases:
                for clock in ("inside", "call"):
                    ratios[which][name][clock].append(medians[which][name][clock] /
                                                      medians["before"][name][clock])
    for worker in workers.values():
        worker.stdin.close()
        worker.wait(timeout=60)
    lines = [f"{args.rounds} rounds of {args.batch} calls; ratios: median of the paired "
             "rounds [95 % interval of the median]", "",
             "| case | clock | before (median) | after (median) | after / before | "
             "A/A control (before again / before) |", "|---|---|---|---|---|---|"]
    for name in cases:
        for clock in ("inside", "call"):
            before = statistics.median(samples["before"][name][clock])
            after = statistics.median(samples["after"][name][clock])
            lines.append(f"| {name} | {'C++' if clock == 'inside' else 'Python call'} | "
                         f"{before * 1e6:.1f} us | {after * 1e6:.1f} us | "
                         f"{median_interval(ratios['after'][name][clock])} | "
                         f"{median_interval(ratios['control'][name][clock])} |")
    table = "\n".join(lines)
    print(table)
    if args.output:
        with open(args.output, "w") as f:
            f.write(table + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
