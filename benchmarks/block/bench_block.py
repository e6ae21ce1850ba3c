"""Friction benchmark of thesis section 3.2.6 (Table 3.1): leadscrew against
scipy.integrate.solve_ivp on the same equations, at matched error.

Run from the repository root (leadscrew installed, e.g. ``pip install -e .``):

    python benchmarks/block/bench_block.py

It prints a markdown table and writes it to benchmarks/block/results.md.
A benchmark, not a test: nothing here runs in CI.

Model (eq. 3.9): m u'' = V sin(omega t) - lambda_T, lambda_N = m g, with
m = 1 kg, g = 10 m/s^2, mu = 0.3, V = 6 N, omega = 4 pi rad/s, u(0) = u'(0) = 0,
0 <= t <= 2 s. Cases:

* exact Coulomb friction (the thesis's "LCP" row), V = 6 N and V = 4 N (real
  stick phases): ours ``event_driven``; solve_ivp as an event-driven Python
  implementation (smooth phases with RK45 or Radau, terminal events at u' = 0
  and |F| = mu m g, the mode after each event chosen by the friction cone);
  error against the exact piecewise closed form (tests/helpers/block_reference.py).
* arctan acceleration law (eq. 3.15), k_V = 1, 10, 100: a scalar Newton solve
  for u'' in every right-hand side (ours in C++, the solve_ivp one in Python);
* arctan velocity law (eq. 3.16), k_V = 1, 10, 100.
  For the regularized laws the error is against the same equations solved by
  solve_ivp DOP853 at rtol 1e-13 (dense output), independent of our code and
  cross-checked against our cvode_bdf at rtol 1e-12.

Matched error: every solver sweeps rtol over 10^-2, 10^-2.25, ..., 10^-13
(atol = 1e-2 rtol, the same rule for all) from loose to tight and is timed at
the loosest rtol whose max error of u over its own output points (every step
and event) is <= the target (1e-9 m for exact Coulomb, 1e-6 m for the
regularized laws). Times are medians over repeats after a warm-up; ours both
inside C++ (stats["wall_time"]) and through Python (around leadscrew.simulate);
solve_ivp through Python. Ratio = solve_ivp time / our fastest time at the
same target (through Python, and inside C++).
"""

from __future__ import annotations

import argparse
import functools
import gc
import math
import os
import platform
import statistics
import sys
import time

# BLAS worker threads (scipy's Radau uses LAPACK) keep spinning after their
# calls and take the second core from the timed single-threaded runs.
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import numpy as np  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

import leadscrew as ls  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tests"))
from helpers.block_reference import solve_block  # noqa: E402

MASS, MU, G, OMEGA, T_END = 1.0, 0.3, 10.0, 4.0 * math.pi, 2.0
FRICTION_LIMIT = MU * MASS * G
ARCTAN_SCALE = 2.0 / math.pi * FRICTION_LIMIT  # (2/pi) mu lambda_N of eq. 3.15/3.16
ATOL_PER_RTOL = 1e-2
TOLERANCES = [10.0 ** (-k / 4.0) for k in range(8, 53)]  # 1e-2 ... 1e-13, 4 per decade
EXACT_TARGET, REGULARIZED_TARGET = 1e-9, 1e-6
OURS_REGULARIZED = ("rk_verner6", "rk_dopri5", "cvode_bdf")
THESIS_TABLE = {  # Table 3.1: Matlab, ode45 at e_R = 1e-4; time [s], iterations
    ("coulomb", None): (0.135, 727),
    ("arctan_acceleration", 1.0): (3.3816, 229),
    ("arctan_acceleration", 10.0): (7.0668, 463),
    ("arctan_acceleration", 100.0): (11.45, 613),
    ("arctan_velocity", 1.0): (0.012, 151),
    ("arctan_velocity", 10.0): (0.027, 409),
    ("arctan_velocity", 100.0): (0.049, 859),
}


def excitation(amplitude, t):
    return amplitude * math.sin(OMEGA * t)


# --------------------------------------------------------------------------
# The same equations for solve_ivp (Python right-hand sides)

def arctan_velocity_rhs(amplitude, k_v):
    def rhs(t, y):
        return [y[1], (amplitude * math.sin(OMEGA * t) - ARCTAN_SCALE * math.atan(k_v * y[1]))
                / MASS]
    return rhs


def arctan_acceleration_value(force, k_v):
    """u'' from m a + (2/pi) mu lambda_N arctan(k_V a) = F (eq. 3.15): the left
    side increases strictly in a, and the root lies in [(F - mu N)/m, (F + mu N)/m]
    ((2/pi) |arctan| < 1); Newton steps, bisection when a step leaves the bracket."""
    low, high = (force - FRICTION_LIMIT) / MASS, (force + FRICTION_LIMIT) / MASS
    # Start from the linearized law inside the cone, from the bracket end outside.
    if abs(force) <= FRICTION_LIMIT:
        a = force / (MASS + ARCTAN_SCALE * k_v)
    else:
        a = low if force > 0.0 else high
    for _ in range(200):
        residual = MASS * a + ARCTAN_SCALE * math.atan(k_v * a) - force
        if residual > 0.0:
            high = a
        else:
            low = a
        slope = MASS + ARCTAN_SCALE * k_v / (1.0 + (k_v * a) ** 2)
        step = a - residual / slope
        if not low < step < high:
            step = 0.5 * (low + high)
        if abs(step - a) <= 4e-16 * max(1.0, abs(a)):
            return step
        a = step
    raise RuntimeError("arctan acceleration: Newton did not converge")


def arctan_acceleration_rhs(amplitude, k_v):
    def rhs(t, y):
        return [y[1], arctan_acceleration_value(amplitude * math.sin(OMEGA * t), k_v)]
    return rhs


class CoulombSolveIvp:
    """Event-driven exact Coulomb friction on top of solve_ivp.

    Slip with direction s: u'' = (F - s mu m g)/m until u' = 0 (terminal event,
    s u' falling). Stick: u' = 0, u constant, until |F| reaches mu m g
    (terminal events F = +N rising, F = -N falling). After a velocity zero the
    block sticks if |F| <= mu m g, else slips in the direction of F.
    """

    def __init__(self, amplitude):
        self.amplitude = amplitude
        n = FRICTION_LIMIT

        def slip_rhs(direction):
            def rhs(t, y):
                return [y[1], (amplitude * math.sin(OMEGA * t) - direction * n) / MASS]
            return rhs

        def stick_rhs(t, y):
            return [0.0, 0.0]

        def leaves_up(t, y):
            return amplitude * math.sin(OMEGA * t) - n

        def leaves_down(t, y):
            return amplitude * math.sin(OMEGA * t) + n

        for event, direction in ((leaves_up, 1.0), (leaves_down, -1.0)):
            event.terminal, event.direction = True, direction
        forward_stop = lambda t, y: y[1]  # noqa: E731
        backward_stop = lambda t, y: y[1]  # noqa: E731
        forward_stop.terminal, forward_stop.direction = True, -1.0
        backward_stop.terminal, backward_stop.direction = True, 1.0
        self.phases = {
            1: (slip_rhs(1.0), [forward_stop], None),
            -1: (slip_rhs(-1.0), [backward_stop], None),
            # The stick phase has a zero right-hand side: bound its steps so the
            # event functions see every crossing of the forcing (period / 8).
            0: (stick_rhs, [leaves_up, leaves_down], 2.0 * math.pi / OMEGA / 8.0),
        }

    def mode_at_rest(self, t):
        force = excitation(self.amplitude, t)
        if abs(force) <= FRICTION_LIMIT:
            return 0
        return 1 if force > 0.0 else -1

    def __call__(self, method, rtol, atol, max_phases=1000):
        t, y = 0.0, [0.0, 0.0]
        mode = self.mode_at_rest(0.0)
        times, positions = [np.array([0.0])], [np.array([0.0])]
        stats = {"steps": 0, "rhs_evaluations": 0, "events": 0}
        for _ in range(max_phases):
            rhs, events, max_step = self.phases[mode]
            options = {} if max_step is None else {"max_step": max_step}
            sol = solve_ivp(rhs, (t, T_END), y, method=method, rtol=rtol, atol=atol,
                            events=events, **options)
            if sol.status < 0:
                raise RuntimeError(f"solve_ivp failed: {sol.message}")
            stats["steps"] += len(sol.t) - 1
            stats["rhs_evaluations"] += sol.nfev
            times.append(sol.t[1:])
            positions.append(sol.y[0, 1:])
            if sol.status == 0:  # reached t_end
                break
            stats["events"] += 1
            t, u = sol.t[-1], sol.y[0, -1]
            if mode == 0:
                which = 0 if sol.t_events[0].size else 1
                mode = 1 if which == 0 else -1
            else:
                mode = self.mode_at_rest(t)
            y = [u, 0.0]
        else:
            raise RuntimeError("too many phases")
        return np.concatenate(times), np.concatenate(positions), stats


# --------------------------------------------------------------------------
# Cases: each gives ours(rtol) and theirs(method, rtol) -> (t, u, stats)

def block(amplitude):
    return ls.FrictionBlock(MASS, MU, g=G, force=ls.Sine(amplitude, OMEGA))


def ours(amplitude, friction, integrator, k_v=None):
    model = block(amplitude)
    extra = {} if k_v is None else {"k_v": k_v}

    def run(rtol):
        result = ls.simulate(model, T_END, friction=friction, integrator=integrator, rtol=rtol,
                             atol=ATOL_PER_RTOL * rtol, **extra)
        # What a user needs of the run: t and u; the statistics (a dict
        # converted from the core's result) are read after the clock stops.
        return result.t, result["u"], result
    return run


def theirs(amplitude, friction, k_v=None):
    if friction == "coulomb":
        coulomb = CoulombSolveIvp(amplitude)
        return lambda method, rtol: coulomb(method, rtol, ATOL_PER_RTOL * rtol)
    rhs = (arctan_velocity_rhs if friction == "arctan_velocity" else arctan_acceleration_rhs)(
        amplitude, k_v)

    def run(method, rtol):
        sol = solve_ivp(rhs, (0.0, T_END), [0.0, 0.0], method=method, rtol=rtol,
                        atol=ATOL_PER_RTOL * rtol)
        if sol.status != 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        return sol.t, sol.y[0], {"steps": len(sol.t) - 1, "rhs_evaluations": sol.nfev,
                                 "events": 0}
    return run


def regularized_reference(amplitude, friction, k_v):
    rhs = (arctan_velocity_rhs if friction == "arctan_velocity" else arctan_acceleration_rhs)(
        amplitude, k_v)
    sol = solve_ivp(rhs, (0.0, T_END), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-15,
                    dense_output=True)
    assert sol.status == 0, sol.message
    check = ls.simulate(block(amplitude), T_END, friction=friction, k_v=k_v,
                        integrator="cvode_bdf", rtol=1e-12, atol=1e-14,
                        t_eval=np.linspace(0.0, T_END, 401))
    agreement = float(np.max(np.abs(check["u"] - sol.sol(check.t)[0])))
    return (lambda t: sol.sol(t)[0]), agreement


# --------------------------------------------------------------------------
# Matched error and timing

def errors_of(reference, t, u):
    difference = np.abs(np.asarray(u) - reference(np.asarray(t)))
    return float(np.max(difference)), float(difference[-1])


def loosest_meeting(run, reference, target):
    """(rtol, max error, final error, stats) at the loosest rtol of TOLERANCES
    with max error <= target; None if none reaches it."""
    for rtol in TOLERANCES:
        t, u, stats = run(rtol)
        error_max, error_final = errors_of(reference, t, u)
        if error_max <= target:
            return rtol, error_max, error_final, stats_of(stats)
    return None


def stats_of(stats):
    """The statistics dict of a run: solve_ivp's runs return one, ours the
    Result, whose stats are converted here (outside the timed region)."""
    return stats if isinstance(stats, dict) else dict(stats.stats)


def time_interleaved(ours_runs, theirs_runs, repeats_ours, repeats_theirs):
    """Times our runs and solve_ivp's in alternation, so that both see the same
    machine (the shared vCPUs change speed within seconds): repeats_theirs
    rounds, each running every one of ours about repeats_ours / repeats_theirs
    times and every one of theirs once.

    Args:
        ours_runs: callables returning (t, u, result) (result.stats["wall_time"]
            is the C++ clock).
        theirs_runs: callables.

    Returns:
        (ours, theirs): per run of ours (median C++, median Python, min C++,
        min Python) [s]; per run of theirs the median [s].
    """
    per_round = max(1, round(repeats_ours / repeats_theirs))
    for run in (*ours_runs, *theirs_runs):
        run()  # warm-up
    core = [[] for _ in ours_runs]
    python = [[] for _ in ours_runs]
    theirs = [[] for _ in theirs_runs]
    gc.collect()
    for _ in range(repeats_theirs):
        for i, run in enumerate(ours_runs):
            for _ in range(per_round):
                start = time.perf_counter()
                _, _, stats = run()
                python[i].append(time.perf_counter() - start)
                core[i].append(stats_of(stats)["wall_time"])
        for j, run in enumerate(theirs_runs):
            start = time.perf_counter()
            run()
            theirs[j].append(time.perf_counter() - start)
    median = statistics.median
    return ([(median(c), median(p), min(c), min(p)) for c, p in zip(core, python)],
            [median(t) for t in theirs])


def cases():
    yield ("exact Coulomb (LCP), V = 6", 6.0, "coulomb", None)
    yield ("exact Coulomb (LCP), V = 4", 4.0, "coulomb", None)
    for friction in ("arctan_acceleration", "arctan_velocity"):
        for k_v in (1.0, 10.0, 100.0):
            yield (f"{friction} (eq. {'3.15' if 'acc' in friction else '3.16'}), "
                   f"k_V = {k_v:g}", 6.0, friction, k_v)


def benchmark(repeats_ours, repeats_theirs, progress=print):
    rows, notes = [], []
    for title, amplitude, friction, k_v in cases():
        if friction == "coulomb":
            exact = solve_block(MASS, MU, G, amplitude, OMEGA, t_end=T_END)
            reference, target = exact.position, EXACT_TARGET
            our_integrators = ("event_driven",)
        else:
            reference, agreement = regularized_reference(amplitude, friction, k_v)
            target = REGULARIZED_TARGET
            our_integrators = OURS_REGULARIZED
            notes.append(f"{title}: reference DOP853 vs our cvode_bdf at rtol 1e-12: "
                         f"max |diff| = {agreement:.1e} m")
        # Tolerances first (the loosest meeting the target), then every timing
        # of the case interleaved.
        case_rows, ours_runs, theirs_runs = [], [], []
        for integrator in our_integrators:
            run = ours(amplitude, friction, integrator, k_v)
            found = loosest_meeting(run, reference, target)
            if found is None:
                case_rows.append(dict(case=title, solver=f"leadscrew {integrator}", failed=True))
                continue
            rtol, error_max, error_final, stats = found
            case_rows.append(dict(case=title, solver=f"leadscrew {integrator}", rtol=rtol,
                                  error_max=error_max, error_final=error_final,
                                  steps=stats["steps"], rhs=stats["rhs_evaluations"],
                                  events=stats["events"], matched=True))
            ours_runs.append(functools.partial(run, rtol))
        if friction == "coulomb":
            # Not part of the matched-error comparison: the same integrator at
            # a tolerance a user would set, for the record.
            run = ours(amplitude, friction, "event_driven")
            t, u, stats = run(1e-8)
            stats = stats_of(stats)
            error_max, error_final = errors_of(reference, t, u)
            case_rows.append(dict(case=title, solver="leadscrew event_driven (fixed rtol)",
                                  rtol=1e-8, error_max=error_max, error_final=error_final,
                                  steps=stats["steps"], rhs=stats["rhs_evaluations"],
                                  events=stats["events"], matched=False))
            ours_runs.append(functools.partial(run, 1e-8))
        their_rows = []
        for method in ("RK45", "Radau"):
            run = theirs(amplitude, friction, k_v)
            found = loosest_meeting(lambda rtol: run(method, rtol), reference, target)
            if found is None:
                case_rows.append(dict(case=title, solver=f"solve_ivp {method}", failed=True))
                progress(f"  {title:45s} {method:12s} does not reach {target:g}")
                continue
            rtol, error_max, error_final, stats = found
            row = dict(case=title, solver=f"solve_ivp {method}", rtol=rtol,
                       error_max=error_max, error_final=error_final, steps=stats["steps"],
                       rhs=stats["rhs_evaluations"], events=stats["events"], core=None)
            their_rows.append(row)
            theirs_runs.append(functools.partial(run, method, rtol))
        ours_rows = [r for r in case_rows if "matched" in r]
        ours_times, theirs_times = time_interleaved(ours_runs, theirs_runs, repeats_ours,
                                                    repeats_theirs)
        for row, (core, python, core_min, python_min) in zip(ours_rows, ours_times):
            row.update(core=core, python=python, core_min=core_min, python_min=python_min)
            progress(f"  {title:45s} {row['solver']:34s} rtol {row['rtol']:.2g} err "
                     f"{row['error_max']:.1e} {core * 1e6:9.1f} us C++ {python * 1e6:9.1f} us "
                     "Python")
        matched = [r for r in ours_rows if r["matched"]]
        best_python = min(r["python"] for r in matched)
        best_core = min(r["core"] for r in matched)
        for row, python in zip(their_rows, theirs_times):
            row.update(python=python, ratio_python=python / best_python,
                       ratio_core=python / best_core)
            progress(f"  {title:45s} {row['solver']:34s} rtol {row['rtol']:.2g} err "
                     f"{row['error_max']:.1e} {python * 1e6:9.1f} us Python  "
                     f"x{python / best_python:.0f}")
        case_rows.extend(their_rows)
        for row in case_rows:
            row["target"] = target
        rows.extend(case_rows)
    return rows, notes


def microseconds(value):
    return "–" if value is None else f"{value * 1e6:,.1f}"


def markdown(rows, notes, repeats_ours, repeats_theirs):
    lines = [
        "| case | solver | target | rtol | max error [m] | final error [m] | steps | rhs evals "
        "| events | time C++ [µs] | time Python [µs] | solve_ivp / ours (Python) "
        "| solve_ivp / ours (C++) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r.get("failed"):
            lines.append(f"| {r['case']} | {r['solver']} | {r['target']:g} | does not reach the "
                         "target | | | | | | | | | |")
            continue
        ratio_p = f"{r['ratio_python']:,.0f}×" if "ratio_python" in r else ""
        ratio_c = f"{r['ratio_core']:,.0f}×" if "ratio_core" in r else ""
        lines.append(
            f"| {r['case']} | {r['solver']} | {r['target']:g} | {r['rtol']:.2g} "
            f"| {r['error_max']:.1e} | {r['error_final']:.1e} | {r['steps']} | {r['rhs']} "
            f"| {r['events']} | {microseconds(r['core'])} | {microseconds(r['python'])} "
            f"| {ratio_p} | {ratio_c} |")
    exact = [r for r in rows if r["solver"] == "leadscrew event_driven"
             and r["case"].endswith("V = 6") and not r.get("failed")]
    ratios = [r["ratio_python"] for r in rows if "ratio_python" in r]
    summary = []
    if exact:
        e = exact[0]
        summary.append(
            f"- Exact event-driven solution, 0 ≤ t ≤ 2 s, V = 6: max error {e['error_max']:.1e} m "
            f"(target {EXACT_TARGET:g}) in {e['core'] * 1e6:.1f} µs inside C++ (median; min "
            f"{e['core_min'] * 1e6:.1f} µs; target < 50 µs: "
            f"{'met' if e['core'] < 50e-6 else 'NOT met'}) and {e['python'] * 1e6:.1f} µs "
            f"through Python (median; min {e['python_min'] * 1e6:.1f} µs; target < 200 µs: "
            f"{'met' if e['python'] < 200e-6 else 'NOT met'}).")
    if ratios:
        summary.append(
            f"- solve_ivp / ours at matched error (through Python): min {min(ratios):,.0f}×, "
            f"median {statistics.median(ratios):,.0f}×, max {max(ratios):,.0f}× "
            f"(target ≥ 100×: {'met' if min(ratios) >= 100 else 'NOT met'} in every row"
            f"{'' if min(ratios) >= 100 else ' — see the rows below 100×'}).")
    thesis = ["| Table 3.1 row | thesis time [s] | thesis iterations |", "|---|---|---|"]
    for (friction, k_v), (seconds, iterations) in THESIS_TABLE.items():
        name = "LCP" if friction == "coulomb" else f"{friction}, k_V = {k_v:g}"
        thesis.append(f"| {name} | {seconds} | {iterations} |")
    header = [
        "# Friction block benchmark (thesis section 3.2.6, Table 3.1)",
        "",
        f"Machine: {platform.machine()}, {platform.system()}, Python "
        f"{platform.python_version()}, numpy {np.__version__}, scipy "
        f"{__import__('scipy').__version__}, leadscrew {ls.__version__}, {os.cpu_count()} CPUs, "
        f"load average {os.getloadavg()[0]:.1f} at the end of the run. "
        f"Medians of about {repeats_ours} runs (ours) and {repeats_theirs} runs (solve_ivp) "
        "after a warm-up, in alternation (each of the solve_ivp runs follows about "
        f"{max(1, round(repeats_ours / repeats_theirs))} of each of ours), so that both see the "
        "same machine. Matched error: each solver at the loosest rtol in 10^-2, 10^-2.25, ..., "
        "10^-13 (atol = 1e-2 rtol) whose max error of u over its own output points is <= the "
        "target. Ratios: solve_ivp time / our fastest time in the same case.",
        "",
        *summary,
        "",
        *lines,
        "",
        "References: exact cases against the closed form (tests/helpers/block_reference.py); "
        "regularized cases against solve_ivp DOP853 at rtol 1e-13:",
        "",
        *[f"- {n}" for n in notes],
        "",
        "The thesis's own Table 3.1 (Matlab 2013, ode45 at relative error 1e-4, no error "
        "reported), for comparison of magnitudes only:",
        "",
        *thesis,
        "",
    ]
    return "\n".join(header)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    # Many repeats: the machine's speed changes within seconds, and a median
    # of few runs of either side moves by several per cent between runs.
    parser.add_argument("--repeats", type=int, default=200, help="timed runs of ours")
    parser.add_argument("--repeats-solve-ivp", type=int, default=21,
                        help="timed runs of solve_ivp (rounds of the alternation)")
    parser.add_argument("--output", default=os.path.join(HERE, "results.md"),
                        help="markdown file to write ('' for none)")
    args = parser.parse_args(argv)
    if args.repeats < 1 or args.repeats_solve_ivp < 1:
        parser.error("repeats must be >= 1")
    rows, notes = benchmark(args.repeats, args.repeats_solve_ivp,
                            progress=lambda line: print(line, file=sys.stderr, flush=True))
    text = markdown(rows, notes, args.repeats, args.repeats_solve_ivp)
    print(text)
    if args.output:
        with open(args.output, "w", encoding="utf-8") as handle:
            handle.write(text)


if __name__ == "__main__":
    main()
