"""Fuzz ``leadscrew.simulate`` over random scenes: the long run of the fuzz test.

Runs the generator of ``tests/helpers/scene_fuzz.py`` (the one
``tests/test_fuzz.py`` runs a few hundred cases of) for ``--cases`` cases,
one forked child process per case with a timeout (a crash or a hang is one
case's outcome), ``--workers`` at a time, and prints the table of outcomes:

    passed                a returned result that passed every check
    value_error_named     ValueError naming a key or option the case set
    value_error_unnamed   ValueError naming none of them
    simulation_error      leadscrew.SimulationError
    jamming_error         leadscrew.JammingError
    error_time            a SimulationError whose .time is not in [0, t_end]
    other_exception       any other exception type
    crash                 the child died (a signal)
    hang                  the child ran longer than --timeout
    non_finite            a returned result with NaN or inf
    check_failed          a returned result failing a check (by invariant)

in columns for valid cases, hostile ones (a NaN, a wrong type, ...) and all.
The first four are what issue 17 allows; every other case is written to
``--out`` (JSON lines: the scene dict, the simulate options, the outcome, the
message, the violated invariants) for reproduction::

    import json, leadscrew as ls
    case = json.loads(line)
    ls.simulate(ls.Scene.from_dict(case["scene"]), **case["options"])

or ``python3 tests/fuzz_scenes.py --replay FILE`` runs the cases of such a
file again. ``--generator train`` draws issue 19's drive trains instead
(``tests/helpers/train_fuzz.py``: motor, gear stage, end stops and preloaded
nut freely against one another and the integrator). It is not a test (pytest does not collect it: no ``test_``
prefix). Usage (from the repository, with the package on the path)::

    PYTHONPATH=python python3 tests/fuzz_scenes.py --cases 10000 --out failures.jsonl

Exit status 0 if every case had an allowed outcome, 1 otherwise.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from helpers.result_invariants import INVARIANTS  # noqa: E402
from helpers.scene_fuzz import (ALLOWED, DEFAULT_SEED, OUTCOMES, generate,  # noqa: E402
                                prepare_parent, run_isolated)
from helpers.train_fuzz import TRAIN_SEED, generate_train  # noqa: E402


def _arguments(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=10_000, help="number of cases (10000)")
    parser.add_argument("--generator", choices=("scenes", "train"), default="scenes",
                        help="scenes: helpers/scene_fuzz.py (default); train: "
                        "helpers/train_fuzz.py, issue 19's drive-train elements drawn freely "
                        "against one another (no hostile values; its default seed "
                        f"{TRAIN_SEED})")
    parser.add_argument("--seed", type=int, default=None,
                        help=f"hypothesis seed of the generator ({DEFAULT_SEED}); runs with "
                        "different seeds share some cases (hypothesis favours small case "
                        "seeds: about 15 %% of two 10,000-case runs): for more cases raise "
                        "--cases")
    parser.add_argument("--timeout", type=float, default=10.0,
                        help="seconds a case may run before it counts as a hang (10)")
    parser.add_argument("--workers", type=int, default=2, help="child processes at a time (2)")
    parser.add_argument("--out", default="fuzz_failures.jsonl",
                        help="JSON-lines file of the failing cases (fuzz_failures.jsonl)")
    parser.add_argument("--all", metavar="FILE",
                        help="also write every case with its outcome to this JSON-lines file")
    parser.add_argument("--hostile-share", type=float, default=0.15,
                        help="share of cases with a hostile value (0.15)")
    parser.add_argument("--replay", metavar="FILE",
                        help="run the cases of a JSON-lines file (as --out writes) instead")
    parser.add_argument("--progress", type=int, default=500,
                        help="print a line every N cases (500; 0: never)")
    return parser.parse_args(argv)


def _load(path: str) -> list:
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def _table(cases: list, outcomes: dict) -> str:
    """The outcome table, valid / hostile / all, and the invariants of the
    results that failed their checks."""
    counts = {kind: collections.Counter() for kind in ("valid", "hostile", "all")}
    invariants = {kind: collections.Counter() for kind in ("valid", "hostile", "all")}
    for index, outcome in outcomes.items():
        kind = "hostile" if cases[index].get("hostile") else "valid"
        for column in (kind, "all"):
            counts[column][outcome["outcome"]] += 1
            if outcome["outcome"] in ("check_failed", "non_finite"):
                invariants[column].update(outcome.get("invariants", []))
    width = max(len(o) for o in OUTCOMES) + 4
    lines = [f"{'outcome':{width}}{'valid':>8}{'hostile':>9}{'all':>8}   allowed"]
    for name in OUTCOMES:
        row = [counts[c][name] for c in ("valid", "hostile", "all")]
        lines.append(f"{name:{width}}{row[0]:8d}{row[1]:9d}{row[2]:8d}   "
                     + ("yes" if name in ALLOWED else "NO"))
    lines.append(f"{'cases':{width}}" + "".join(
        f"{sum(counts[c].values()):{w}d}" for c, w in (("valid", 8), ("hostile", 9), ("all", 8))))
    if any(invariants["all"].values()):
        lines.append("")
        lines.append("returned results failing their checks, by invariant violated (a result "
                     "may violate several):")
        for name in INVARIANTS:
            row = [invariants[c][name] for c in ("valid", "hostile", "all")]
            if row[2]:
                lines.append(f"  {name:{width - 2}}{row[0]:8d}{row[1]:9d}{row[2]:8d}")
    return "\n".join(lines)


def main(argv=None) -> int:
    args = _arguments(argv)
    prepare_parent()
    start = time.monotonic()
    if args.replay:
        cases = _load(args.replay)
        print(f"replaying {len(cases)} cases of {args.replay}", flush=True)
    else:
        if args.generator == "train":
            args.seed = TRAIN_SEED if args.seed is None else args.seed
            cases = generate_train(args.cases, args.seed)
        else:
            args.seed = DEFAULT_SEED if args.seed is None else args.seed
            cases = generate(args.cases, args.seed, args.hostile_share)
        print(f"generated {len(cases)} cases (seed {args.seed}) in "
              f"{time.monotonic() - start:.1f} s", flush=True)
    outcomes = {}
    failing = 0
    every = open(args.all, "w") if args.all else None
    with open(args.out, "w") as out:
        for index, outcome in run_isolated(enumerate(cases), args.timeout, args.workers):
            outcomes[index] = outcome
            case = cases[index]
            if outcome["outcome"] not in ALLOWED or every:
                record = {"index": case.get("index", index),  # a replayed case keeps its own
                          "generator_seed": case.get("generator_seed", args.seed),
                          "case_seed": case.get("seed", case.get("case_seed")),
                          "outcome": outcome["outcome"],
                          "message": outcome.get("message", ""),
                          "invariants": outcome.get("invariants", []),
                          "report": outcome.get("report", {}),
                          "seconds": outcome.get("seconds"),
                          "energy_accumulation": outcome.get("energy_accumulation"),
                          "tags": case.get("tags", {}), "hostile": case.get("hostile", []),
                          "scene": case["scene"], "options": case["options"]}
                line = json.dumps(record, default=repr) + "\n"
                if every:
                    every.write(line)
                if outcome["outcome"] not in ALLOWED:
                    failing += 1
                    out.write(line)
                    out.flush()
            if args.progress and len(outcomes) % args.progress == 0:
                print(f"{len(outcomes)} cases, {failing} failing, "
                      f"{time.monotonic() - start:.0f} s", flush=True)
    if every:
        every.close()
    print()
    print(_table(cases, outcomes))
    print(f"\n{len(outcomes)} cases in {time.monotonic() - start:.0f} s "
          f"({args.workers} workers, timeout {args.timeout:g} s); "
          f"{failing} failing cases written to {args.out}")
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main())
