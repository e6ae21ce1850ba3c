"""One Moreau-Jean run of the position-holding scene on flexible_nut, for
counting instructions per step under callgrind (results.md, "Instructions
per Moreau-Jean step"): dt 3e-5 over 0.5 s (16,667 steps), output at t = 0
and 0.5 s only. ``--exact``: the same scene with exact play
(``backlash.contact = "exact"``). Count with

    valgrind --tool=callgrind --toggle-collect='leadscrew::integrate::simulate_moreau*' \\
        --callgrind-out-file=cg.out python benchmarks/position_holding/moreau_step.py
    callgrind_annotate cg.out | grep "PROGRAM TOTALS"

(the total is simulate_moreau's inclusive count: divide by 16,667).
"""

import argparse

import leadscrew as ls


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--exact", action="store_true", help="exact play instead of the bistop")
    args = parser.parse_args()
    scene = ls.scenes.load("position_holding").replace(concept="flexible_nut")
    if args.exact:
        data = scene.to_dict()
        data["backlash"]["contact"] = "exact"
        scene = ls.Scene(data)
    result = ls.simulate(scene, 0.5, integrator="moreau", dt=3e-5, t_eval=[0.0, 0.5])
    print(f"phi_drive(0.5 s) = {result['phi_drive'][-1]!r} rad")


if __name__ == "__main__":
    main()
