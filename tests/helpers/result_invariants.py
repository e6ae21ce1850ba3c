"""An independent check of a drive simulation's result from its channels alone.

:func:`check_result` takes a :class:`leadscrew.Result` (or anything with
``t``, ``events``, ``channels``, ``integrator`` and item access to the
channels), the scene as ``Scene.to_dict()`` gives it (SI numbers) and the
options ``simulate`` was called with, and returns one entry per invariant::

    {name: {"ok": bool, "value": worst measured value, "bound": its bound,
            "time": where the worst value is [s] (None if not a point),
            "detail": a one-line text}}

It does not use the simulator's own checks (``Result.checks``, once it has
them): it is a second net, written from the channel definitions in
``docs/physics/drive_models.md`` ("Energy account") and the README's
conventions.

Scales: F_ref = max(max |friction_force|, mu' max |normal_force|) [N] and
v_ref = max |slip_velocity| [m/s] over the output points; the force scale of
the drive F_sys = max(F_ref, max |normal_force|, max |axial_force|,
max |drive_torque| / r_m) [N] (r_m the mean radius of the thread: a run
whose flanks carry round-off forces only, free flight in the play from the
start, still has the loads' scale). A force below FORCE_FLOOR = 1e-9 N is
round-off wherever it appears: below any load a lead-screw drive carries,
and above the flank forces of runs whose thread carries nothing (free flight
or an unloaded speed-controlled drive: 1e-51 to 1e-11 N seen, of either
sign). The energy scale E_ref [J] is the largest of
max_t (|work_drive| + |work_axial|), max_t (kinetic + elastic) and max_t of
the sum of the four losses, at least 1e-15 J (a drive that never moves has
round-off energies only). rtol is the one given to simulate (default 1e-8).

The invariants and their tolerances (the constants below; "observed" refers
to the valid random scenes of ``helpers.scene_fuzz`` on the code of 2026-12:
distributions from about 500 runs, gaps and violations from two runs of
10,000 cases; event-driven and ODE integrators unless said otherwise):

- ``finite``: every channel and output time finite. Exact: NaN or an
  infinity is never a tolerance matter.
- ``time_axis``: output times non-decreasing (an event's time appears
  twice), in [0, t_end], the last one at the end of the run (``t_end``, or
  the last of ``t_eval``) to 1e-9 t_end: a run that stops early must raise,
  not return.
- ``event_times``: every event time finite and in [0, t_end]. Exact: an
  event is a root located inside the run.
- ``friction_power``: friction_force * slip_velocity <= 1e-6 F_ref v_ref +
  (1e-9 m/s F_sys + 1e-9 N v_ref) + 1e-9 E_ref / t_end at every output
  point. At a stick/slip event the slip velocity is a root located to
  round-off, in stick the drives report zero slip
  (docs/physics/drive_models.md, "Stick at exactly zero slip"); the 1e-9 m/s
  floor covers a drive that only ever creeps at round-off speed (Moreau-Jean
  in stick: 1e-20 m/s), the force floors a run whose flanks carry round-off
  forces only, the energy term a power that books less than 1e-9 E_ref over
  the run. Observed: at most 3e-12 F_ref v_ref in 95 % of the runs, then
  violations from 1e-2 F_ref v_ref up (a gap of ten decades). Not for
  ``arctan_acceleration``: eq. (3.15) opposes the slip *acceleration* and
  lets friction do positive work by construction (its energy balance is
  checked).
- ``friction_loss`` (not for ``arctan_acceleration``) and ``other_losses``
  (damping_loss, contact_loss, impact_loss, and the train stages'
  motor_friction_loss and gear_loss where present): a loss never falls between two
  output points, nor lies below zero, by more than max(1e-5, 1e3 rtol) E_ref
  + 1e-15 J (Moreau-Jean: 1e-5 E_ref). They are integrals of non-negative
  rates, but computed as quadratures whose Runge-Kutta weights have both
  signs (dopri5 has a negative one) or interpolated at output times (CVODE):
  a spike of the rate (a penalty contact closing) can make the quadrature
  dip by its local error. Observed: up to 3.6e-6 E_ref at rtol 1e-8 (a
  penalty contact); a loss falling by more is booked wrongly.
- ``friction_cone`` (every law): |friction_force| <= mu' |normal_force|
  (with a preloaded nut of preload P: mu' (|normal_force| + 2 P / (cos a -
  mu' sin a)), both halves' friction bounded by the triangle inequality;
  with lift-off, P the largest of P and the spring force preload_force)
  (1 + 1e-6) + 1e-9 F_sys + 1e-9 N, mu' = mu / cos(flank_angle / 2): the
  arctan laws stay inside too (|(2/pi) atan| < 1). In slip the two sides are
  equal to round-off, a stick phase leaves the cone at a root located to the
  integrator's resolution; mu = 0 leaves round-off friction (5e-14 N against
  5e-3 N). An excursion from the cone shorter than an integrator step that
  the simulator misses (README, "Limits") is reported: it is a violation all
  the same. Observed: at most 3.7e-12 F_ref in 95 % of the Coulomb runs,
  violations from 4e-2 F_ref up; the arctan laws 0.
- ``friction_law``: ``coulomb``: where the drive slips (``stick`` = 0 and
  |slip_velocity| above the friction_power's velocity tolerance, 1e-6 v_ref +
  1e-9 m/s) friction is on the cone: |friction_force| >= mu' |normal_force|
  (1 - 1e-6) - 1e-9 F_sys - 1e-9 N (with the cone: equal; its direction
  is the friction_power check's). ``arctan_velocity``: friction_force = -(2/pi)
  mu' atan(k_V slip_velocity) |normal_force| (eq. 3.16) to 1e-6 F_ref (+ the
  cone's floor). Observed: 2.5e-12 F_ref (Coulomb) and 2.2e-14 F_ref
  (arctan) in 95 % of the runs, violations at 0.2 to 1 F_ref (a penalty flank
  with no friction, issue 17's reproduction 11). Not for
  ``arctan_acceleration``: its law needs the slip acceleration, which is no
  channel.
- ``energy_balance``: event-driven and ODE integrators: the bound that
  docs/physics/result_checks.md derives from the integrator's tolerances,
  |energy_residual| <= K (max(rtol, 64 eps) E + atol G) with K = 1000, E
  the largest energy flow at an output point (the absolute work, energy and
  loss channels summed) and G = 6 + sqrt(2 kinetic sum m) + sqrt(2 elastic
  sum k) (the springs at their stiffest over the screw, a penalty flank at
  its stiffness; here the maxima of the two roots separately, a little
  above the simulator's maximum of their sum), written here from that page
  and the scene's model. A residual above it that stays at a tighter rtol
  is a booking defect (issue 17's reproductions 8 and 9: 5e-4 to 4e-2 of
  the work); one that shrinks is a result not accurate to its tolerances.
  Moreau-Jean (``integrator="moreau"``): its
  numerical dissipation shows as a positive residual, which is allowed;
  energy created shows as a negative one: residual >= -(1e-3 E_ref + X +
  1e-15 J), X the friction booking's term of the page (the negative parts of
  (1 - theta) P_T (gamma_1 - gamma_0) summed over the steps, from the rows
  where they are the steps; with t_eval the simulator's bound), at most 1e-2
  E_ref (a larger one is a step that does not resolve the slip). Observed: 90
  % of the Moreau runs create less than 1.1e-3 E_ref; the rest up to 5.5e-2
  (issue 17, reproduction 10: a step that does not resolve the scene).
- ``flank_penetration`` (exact play only): gap >= -bound, the flanks are
  unilateral. Event-driven: bound 1e-3 c_a + 10 atol (the simulator's own
  ``kFlankTolerance``, drive/hybrid.hpp, and the positions' absolute
  tolerance, as docs/physics/result_checks.md documents; observed at most
  1e-5 c_a until a 10,000-case run met 1.4e-3 c_a = 0.6 atol: a rigid drive
  with exact play and penalty end stops, speed-controlled).
  Moreau-Jean keeps the flanks at the velocity level, so a contact closes
  one step late: bound min(c_a, 1e-3 c_a + 3 dt max |d play / dt|), the
  latter from the output points (observed: up to 2.9 steps of it; beyond
  that the load falls through the thread, issue 17's reproduction 6: 1.3e3
  c_a), but never the whole clearance beyond a flank; with t_eval, whose
  points miss the steps' rates, the simulator's bound from its steps.

The drive train's invariants (the DC motor, the rotor's torque, LuGre's
bristles, the end stops) are :mod:`helpers.train_invariants`'s, added to the
report here.

``checker`` is no invariant: :func:`helpers.scene_fuzz.run_case` reports a
result this checker could not read (it raised) under that name.
"""

from __future__ import annotations

import math
from typing import Any, Dict, Optional

import numpy as np

from helpers.train_invariants import TRAIN_INVARIANTS, check_train

__all__ = ["check_result", "checked_run", "failed", "INVARIANTS"]

INVARIANTS = ("finite", "time_axis", "event_times", "friction_power", "friction_loss",
              "other_losses", "friction_cone", "friction_law", "energy_balance",
              "flank_penetration") + TRAIN_INVARIANTS + ("checker",)

END_REL = 1e-9              # of t_end: where the output ends
POWER_REL = 1e-6            # of F_ref v_ref: friction power
POWER_FLOOR = 1e-9          # m/s, times F_sys: friction power
POWER_ENERGY_REL = 1e-9     # of E_ref / t_end: friction power
CONE_REL = 1e-6             # of mu' |N|: friction cone
CONE_FLOOR = 1e-9           # of F_sys: friction cone and law
FORCE_FLOOR = 1e-9          # N: friction cone and law; times v_ref: friction power
LAW_REL = 1e-6              # of F_ref: eq. (3.16)
LOSS_REL = (1e-5, 1e3)      # (floor, factor of rtol), of E_ref: a loss's fall
ENERGY_FACTOR = 1e3         # K of docs/physics/result_checks.md: |residual| <= K (rtol E + atol G)
DEFAULT_ATOL = 1e-10        # simulate's
MOREAU_CREATION_REL = 1e-3  # of E_ref: -residual of Moreau-Jean
MOREAU_BOOKING_REL = 1e-2   # of E_ref: the friction booking's term, at most
ENERGY_FLOOR = 1e-15        # J
FLANK_REL = 1e-3            # of the clearance: play beyond a flank
MOREAU_FLANK_STEPS = 3.0    # steps of the largest play rate: Moreau-Jean's play beyond a flank
DEFAULT_RTOL = 1e-8         # simulate's


def _entry(ok: bool, value: float, bound: float, when: Optional[float], detail: str) -> dict:
    return {"ok": bool(ok), "value": float(value), "bound": float(bound),
            "time": None if when is None else float(when), "detail": detail}


def failed(report: Dict[str, dict]) -> list:
    """The names of the invariants a report says were violated."""
    return [name for name, entry in report.items() if not entry["ok"]]


def _number(options: dict, name: str, default: float) -> float:
    value = options.get(name)
    return default if value is None else float(value)


# Laws whose friction may do positive work: eq. (3.15)'s follows the slip
# acceleration, LuGre's bristles give back what they stored.
NON_DISSIPATIVE_LAWS = ("arctan_acceleration", "lugre")


def stribeck_curve(friction: dict, speed: np.ndarray) -> np.ndarray:
    """Stribeck's curve mu(v) = mu + (mu_static - mu) exp(-(v / v_s)^delta)
    (docs/physics/friction_laws.md), with the registry's defaults."""
    mu = float(friction["mu"])
    mu_static = friction.get("mu_static")
    mu_static = mu if mu_static is None else float(mu_static)
    velocity = float(friction.get("stribeck_velocity", 1e-3) or 1e-3)
    exponent = float(friction.get("stribeck_exponent", 2.0) or 2.0)
    return mu + (mu_static - mu) * np.exp(-(speed / velocity) ** exponent)


def checked_run(scene: dict, t_end: float, **options):
    """Runs ``leadscrew.simulate`` on the scene dict for ``t_end`` [s] with
    ``options`` and asserts that every check of the run's own that applies
    and every invariant here (:func:`check_result`) pass.

    Returns:
        the Result.

    Raises:
        AssertionError: naming the checks or invariants that failed.
    """
    import leadscrew as ls

    s = ls.Scene.from_dict(scene)
    result = ls.simulate(s, t_end, **options)
    assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
    run_options = {"t_end": t_end, "integrator": result.integrator, **options}
    assert failed(check_result(result, s.to_dict(), run_options)) == []
    return result


def check_result(result: Any, scene: dict, options: dict) -> Dict[str, dict]:
    """Check a returned drive result (module docstring).

    Args:
        result: the Result.
        scene: the scene as ``Scene.to_dict()`` (SI numbers).
        options: ``simulate``'s keywords, ``t_end`` among them.

    Returns:
        ``{invariant: entry}`` for every invariant that applies.
    """
    # Its invariants hold step by step: a run's default output samples a
    # long run's steps, which would check fewer of them.
    assert not getattr(result, "_sampled", False), \
        "check_result needs every step: simulate(..., t_eval='steps')"
    report: Dict[str, dict] = {}
    t_end = float(options["t_end"])
    t = np.asarray(result.t, dtype=float)
    ch = {name: np.asarray(result[name], dtype=float) for name in result.channels}
    law = scene["friction"]["law"]
    integrator = result.integrator
    moreau = integrator == "moreau"

    # finite
    bad = [name for name, x in ch.items() if not np.all(np.isfinite(x))]
    if not np.all(np.isfinite(t)):
        bad.insert(0, "t")
    report["finite"] = _entry(not bad, len(bad), 0, None,
                              "non-finite values in " + ", ".join(bad) if bad else "all finite")
    if bad:
        return report  # the other checks would only repeat it

    # time axis
    problems = []
    if len(t) == 0:
        problems.append("no output point")
    else:
        if np.any(np.diff(t) < 0):
            i = int(np.argmin(np.diff(t)))
            problems.append(f"time falls at t = {t[i]:.6g} s")
        if t[0] < 0 or t[-1] > t_end * (1 + END_REL):
            problems.append(f"times [{t[0]:.6g}, {t[-1]:.6g}] s beyond [0, {t_end:.6g}] s")
        t_eval = options.get("t_eval")
        end = float(max(t_eval)) if t_eval is not None and len(t_eval) else t_end
        if abs(t[-1] - end) > END_REL * t_end:
            problems.append(f"the output ends at t = {t[-1]!r} s, not at {end!r} s")
    report["time_axis"] = _entry(not problems, len(problems), 0, None,
                                 "; ".join(problems) or "ordered, within the run, to its end")
    if len(t) == 0:
        return report

    # event times
    times = [event.time for event in result.events]
    outside = [x for x in times if not (math.isfinite(x) and 0.0 <= x <= t_end)]
    report["event_times"] = _entry(
        not outside, len(outside), 0, outside[0] if outside else None,
        f"{len(outside)} event(s) outside [0, {t_end:.6g}] s, first at {outside[0]!r} s"
        if outside else f"{len(times)} event(s) within the run")

    # The rows recorded just before an event at its located root (the next
    # row has the same time): where a load's derivative jumps (a table's
    # knot) or a load jumps, the forces there already jump with it, and a
    # flank's normal force has the sign that ends the mode: they describe the
    # instant the mode ends. The pointwise force checks skip them, as the
    # simulator's own do (docs/physics/result_checks.md).
    at_event = np.append(t[1:] == t[:-1], False)
    friction_section = scene["friction"]
    mu = float(friction_section["mu"])
    flank_factor = 1 / math.cos(float(scene["thread"]["flank_angle"]) / 2)
    mu_eff = mu * flank_factor
    # The cone's coefficient: the static one where the law has it (the stick
    # limit; Stribeck's curve and its regularization stay below it).
    mu_static = friction_section.get("mu_static")
    mu_static = mu if mu_static is None else float(mu_static)
    mu_cone = max(mu, mu_static) * flank_factor
    viscous = float(friction_section.get("viscous", 0.0) or 0.0)
    force, normal, slip = ch["friction_force"], ch["normal_force"], ch["slip_velocity"]
    f_ref = max(float(np.max(np.abs(force))), mu_cone * float(np.max(np.abs(normal))))
    n_ref = float(np.max(np.abs(normal)))
    radius = float(scene["thread"]["mean_diameter"]) / 2
    torque = float(np.max(np.abs(ch["drive_torque"])))
    f_sys = max(f_ref, n_ref, float(np.max(np.abs(ch["axial_force"]))),
                torque / radius if radius > 0 else 0.0)
    v_ref = float(np.max(np.abs(slip)))
    # (the train's elements book their own: a DC motor's copper loss and
    # its inductance's magnetic energy, docs/physics/dc_motor.md; the
    # motor's friction and a lossy or worm stage, docs/physics/gear.md)
    losses = ("friction_loss", "damping_loss", "contact_loss", "impact_loss") + tuple(
        name for name in ("copper_loss", "motor_friction_loss", "gear_loss") if name in ch)
    stored = ch["kinetic"] + ch["elastic"] + ch.get("magnetic_energy", 0.0)
    e_ref = max(float(np.max(np.abs(ch["work_drive"]) + np.abs(ch["work_axial"]))),
                float(np.max(stored)),
                float(np.max(sum(ch[name] for name in losses))), ENERGY_FLOOR)
    rtol = 0.0 if moreau else _number(options, "rtol", DEFAULT_RTOL)
    # The energies' round-off (docs/physics/result_checks.md): the work of
    # the largest force over the round-off of the screw's length.
    length = float(scene.get("screw", {}).get("length", 0.5))
    round_off = 64 * np.finfo(float).eps * f_sys * length + ENERGY_FLOOR
    atol = _number(options, "atol", DEFAULT_ATOL)

    def loss_tol(x: np.ndarray) -> float:
        """A loss's integration error (docs/physics/result_checks.md): K (rtol
        max |loss| + atol) for the error-controlled integrators, round-off for
        Moreau-Jean, whose losses are sums of non-negative step terms."""
        largest = float(np.max(np.abs(x)))
        if moreau:
            return 64 * np.finfo(float).eps * largest + round_off
        return ENERGY_FACTOR * (max(rtol, 64 * np.finfo(float).eps) * largest + atol) + round_off

    # Moreau-Jean's outputs at requested times interpolate between its steps:
    # a force and a slip velocity there come from two steps, and their product
    # is not the scheme's (each step's friction impulse opposes its own slip,
    # by its LCP): the pointwise force checks skip them, as the simulator's do.
    pointwise = ~at_event & ~np.full(len(t), moreau and bool(options.get("t_eval")))

    # friction power and friction loss
    if law not in NON_DISSIPATIVE_LAWS:
        power = np.where(pointwise, force * slip, -np.inf)
        i = int(np.argmax(power))
        bound = (f_ref * POWER_REL * v_ref + f_sys * POWER_FLOOR + FORCE_FLOOR * v_ref
                 + POWER_ENERGY_REL * e_ref / t_end)
        report["friction_power"] = _entry(
            power[i] <= bound, power[i], bound, t[i],
            f"friction does positive work: {power[i]:.4g} W (friction {force[i]:.4g} N at slip "
            f"velocity {slip[i]:.4g} m/s) at t = {t[i]:.6g} s, bound {bound:.3g} W")
        report["friction_loss"] = _monotone("friction_loss", t, ch["friction_loss"],
                                            loss_tol(ch["friction_loss"]))

    # other losses
    entries = [_monotone(name, t, ch[name], loss_tol(ch[name])) for name in losses[1:]]
    worst = max(entries, key=lambda e: e["value"] - e["bound"])
    report["other_losses"] = worst if not all(e["ok"] for e in entries) else _entry(
        True, worst["value"], worst["bound"], None, "damping, contact and impact losses grow")

    # friction cone (every law but LuGre's: |kappa| < mu_static' for the
    # regularized laws too; plus the viscous term)
    floor = CONE_FLOOR * f_sys + FORCE_FLOOR
    # A preloaded split nut (docs/physics/preloaded_nut.md): both halves rub,
    # the bound is mu' (|N - N_B| + |N_B|) with half B's normal force
    # |N_B| = P / (cos a - s mu' sin a) for the slip sign s; bounded here
    # independently of the simulator's split by mu' (|N| + 2 max_s |N_B|).
    preload = float(scene.get("nut", {}).get("preload", 0.0) or 0.0)
    if preload > 0.0 and "preload_force" in ch:
        # With lift-off (flexible, penalty play) half B's spring force S
        # changes with the play: bounded by its largest value.
        preload = max(preload, float(np.max(np.abs(ch["preload_force"]))))
    if preload > 0.0:
        thread = scene["thread"]
        alpha = math.atan(float(thread["pitch"]) * int(thread.get("starts", 1))
                          / (math.pi * float(thread["mean_diameter"])))
        half_b = preload / (math.cos(alpha) - mu_cone * math.sin(alpha))
    else:
        half_b = 0.0
    if law != "lugre":
        excess = np.where(pointwise, np.abs(force) - mu_cone * (np.abs(normal) + 2 * half_b)
                          * (1 + CONE_REL) - viscous * np.abs(slip), -np.inf)
        i = int(np.argmax(excess))
        report["friction_cone"] = _entry(
            excess[i] <= floor, excess[i], floor, t[i],
            f"|friction| {abs(force[i]):.6g} N > mu_static' |normal| + viscous |slip| = "
            f"{mu_cone:.4g} * {abs(normal[i]):.6g} N + {viscous:.4g} * {abs(slip[i]):.4g} N "
            f"at t = {t[i]:.6g} s (excess {excess[i]:.3g} N, bound {floor:.3g} N)")

    # the friction law where it follows from the channels
    if law == "stribeck":
        curve = stribeck_curve(friction_section, np.abs(slip)) * flank_factor
    else:
        curve = np.full(len(slip), mu_eff)
    # The viscous term acts where the flanks touch (docs/physics/friction_laws.md).
    touching = np.abs(normal) > 0
    regularized = law == "arctan_velocity" or (law == "stribeck" and integrator
                                               not in ("event_driven", "moreau"))
    if law in ("coulomb", "stribeck") and not regularized and not (moreau and law == "stribeck"):
        # In slip, |friction| = mu(|slip|)' |normal| + viscous |slip|: below
        # that by the check's floor is a slipping contact short of its law
        # (Moreau-Jean's stribeck friction is the curve's at the step's start
        # speed, which is no channel).
        slipping = ((ch["stick"] == 0) & (np.abs(slip) > POWER_REL * v_ref + POWER_FLOOR)
                    & pointwise)
        short = np.where(slipping, curve * np.abs(normal) * (1 - CONE_REL)
                         + touching * viscous * np.abs(slip) - np.abs(force), -np.inf)
        i = int(np.argmax(short))
        report["friction_law"] = _entry(
            short[i] <= floor, max(float(short[i]), 0.0), floor, t[i],
            f"slipping at {slip[i]:.4g} m/s with |friction| {abs(force[i]):.6g} N < mu' "
            f"|normal| = {curve[i]:.4g} * {abs(normal[i]):.6g} N at t = {t[i]:.6g} s (short by "
            f"{short[i]:.3g} N, bound {floor:.3g} N)")
    elif regularized:
        k_v = float(friction_section["k_v"])
        # (A preloaded nut: both halves' flanks take the law, the channel
        # flank_normal = |N_A| + |N_B| in place of |normal_force|.)
        law_normal = ch["flank_normal"] if "flank_normal" in ch else np.abs(normal)
        expected = (-2 / math.pi * curve * np.arctan(k_v * slip) * law_normal
                    - touching * viscous * slip)
        error = np.where(pointwise, np.abs(force - expected), -np.inf)
        i = int(np.argmax(error))
        bound = LAW_REL * f_ref + floor
        report["friction_law"] = _entry(
            error[i] <= bound, error[i], bound, t[i],
            f"friction {force[i]:.6g} N where eq. (3.16) gives -(2/pi) mu' atan(k_V "
            f"{slip[i]:.4g} m/s) |{normal[i]:.6g} N| = {expected[i]:.6g} N at t = {t[i]:.6g} s "
            f"(bound {bound:.3g} N)")

    # energy balance
    residual = ch["energy_residual"]
    # E, the largest energy flow at an output point, as the simulator's own
    # check (docs/physics/result_checks.md).
    flow = float(np.max(np.abs(ch["work_drive"]) + np.abs(ch["work_axial"]) + stored
                        + sum(np.abs(ch[name]) for name in losses)))
    if moreau:
        bound = (MOREAU_CREATION_REL * flow
                 + min(_moreau_friction_excess(result, options, ch, _speed_controlled(scene)),
                       MOREAU_BOOKING_REL * flow)
                 + round_off)
        i = int(np.argmin(residual))
        report["energy_balance"] = _entry(
            residual[i] >= -bound, -residual[i], bound, t[i],
            f"Moreau-Jean creates energy: residual {residual[i]:.4g} J at t = {t[i]:.6g} s "
            f"(energy scale {e_ref:.4g} J, bound -{bound:.3g} J)")
    else:
        # docs/physics/result_checks.md: K (max(rtol, 64 eps) E + atol G), E
        # the largest energy flow at an output point, G the energy's gradient
        # bound over the state (written here from that page).
        gradient = _energy_gradient(scene, ch)
        bound = (ENERGY_FACTOR * (max(rtol, 64 * np.finfo(float).eps) * flow + atol * gradient)
                 + round_off)
        i = int(np.argmax(np.abs(residual)))
        report["energy_balance"] = _entry(
            abs(residual[i]) <= bound, abs(residual[i]), bound, t[i],
            f"energy account off by {residual[i]:.4g} J at t = {t[i]:.6g} s (energy scale "
            f"{e_ref:.4g} J, bound {bound:.3g} J)")

    # flank penetration (exact play)
    backlash = scene.get("backlash")
    if backlash is not None and backlash["contact"] == "exact" and "gap" in ch:
        clearance = float(backlash["axial"])
        gap = ch["gap"]
        # (event-driven: the free flight's tolerance and the positions'
        # absolute tolerance, docs/physics/result_checks.md, flank_gap)
        bound = FLANK_REL * clearance + (0.0 if moreau else 10.0 * atol)
        if moreau:
            steps = np.diff(t)
            moving = steps > 0
            rate = float(np.max(np.abs(np.diff(ch["play"])[moving] / steps[moving]),
                                initial=0.0))
            bound = min(clearance, bound + MOREAU_FLANK_STEPS * _number(options, "dt", 1e-4)
                        * rate)
            if options.get("t_eval") is not None:
                # The steps are not in the output (their play rate is): the
                # simulator's bound from its steps' largest rate stands in.
                bound = max(bound, float(result.checks["flank_gap"]["bound"]))
        bound += 1e-15
        i = int(np.argmin(gap))
        report["flank_penetration"] = _entry(
            gap[i] >= -bound, -gap[i], bound, t[i],
            f"the play goes {-gap[i]:.4g} m beyond a flank at t = {t[i]:.6g} s (clearance "
            f"{clearance:.4g} m, bound {bound:.3g} m)")
    # the drive train's elements (helpers.train_invariants)
    report.update(check_train(result, scene, options, ch, rtol, atol))
    return report


def _speed_controlled(scene: dict) -> bool:
    """The rotor's speed is prescribed (``loads.drive_speed``)."""
    return scene.get("loads", {}).get("drive_speed") is not None


def _moreau_friction_excess(result: Any, options: dict, ch: Dict[str, np.ndarray],
                            speed_controlled: bool = False) -> float:
    """What Moreau-Jean's friction booking may create (docs/physics/
    result_checks.md): the sum over the slipping steps of max(0, -(1 - theta)
    P_T (gamma_1 - gamma_0)), P_T = h friction_force, first order in dt, and
    the same of the train's rotor contact (below). From
    the output rows where they are the steps (no t_eval); with t_eval the
    steps are not in the output and the simulator's own bound stands in (its
    excess is what that bound holds beyond 1e-3 E)."""
    theta = _number(options, "theta", 0.5)
    if options.get("t_eval") is not None:
        entry = result.checks["energy_balance"]
        return float(entry["bound"])
    t = np.asarray(result.t, dtype=float)
    h = np.diff(t)
    force, slip = ch["friction_force"][1:], ch["slip_velocity"]
    slipping = ch["stick"][1:] == 0
    terms = -(1 - theta) * h * force * np.diff(slip)
    excess = float(np.sum(np.where(slipping, np.maximum(terms, 0.0), 0.0)))
    # The train's rotor contact (the motor's friction, a lossy or worm
    # stage, docs/physics/gear.md): a slipping step books its impulse Q at
    # the step's end speed, Q w+ (the loss channels' increment), where the
    # scheme's work is Q w_theta: (1 - theta) Q (w+ - w0) beyond it. The
    # rotor turns with the driven part (w = n omega_drive), so Q w+ (w+ -
    # w0) / w+ is the same in omega_drive. A step that ends stuck books
    # nothing, and its Q (which the simulator's bound takes) is no channel:
    # where the rotor stops within a step, the simulator's own bound stands
    # in, as with t_eval. A speed-controlled rotor's stages book at w_theta,
    # where the motor's impulse works (docs/physics/gear.md, "The smooth
    # thread laws and a prescribed rotor speed"): no excess.
    train = [ch[name] for name in ("motor_friction_loss", "gear_loss") if name in ch]
    if train and not speed_controlled:
        booked = np.diff(sum(train))
        omega = ch["omega_drive"]
        end = omega[1:]
        moving = end != 0
        if np.any(~moving & (omega[:-1] != 0)):
            return float(result.checks["energy_balance"]["bound"])
        rotor_terms = (1 - theta) * booked * np.diff(omega) / np.where(moving, end, 1.0)
        excess += float(np.sum(np.where(moving, np.maximum(rotor_terms, 0.0), 0.0)))
    return excess


def _energy_gradient(scene: dict, ch: Dict[str, np.ndarray]) -> float:
    """G = n_q + sqrt(2 kinetic sum m) + sqrt(2 elastic sum k), maximal over
    the output points: the momenta and the spring forces bounded by
    Cauchy-Schwarz, every spring at its stiffest over the screw (the screw's
    stiffness grows toward its ends, eq. 4.24), a penalty flank at its
    stiffness, one per work or loss integral (6)."""
    import leadscrew as ls

    model = ls.Scene.from_dict(scene).model()
    p = model.parameters
    positions = (0.5 * p.nut_length, p.nut_position, p.screw_length - 0.5 * p.nut_length)
    stiffness = p.contact_stiffness
    for spring in model.springs:
        name = spring["name"]
        if name.startswith("screw") and "torsion" in name and p.screw_torsional_stiffness <= 0:
            k = max(p.screw_torsional_rigidity / a for a in positions)
        elif name.startswith("screw") and p.screw_axial_stiffness <= 0:
            both = (scene.get("drive", "screw") == "screw"
                    and scene.get("screw", {}).get("support", "both_ends") == "both_ends")
            k = max(p.screw_axial_rigidity * (1 / a + (1 / (p.screw_length - a) if both else 0))
                    for a in positions)
        else:
            k = spring["stiffness"]
        stiffness += k
    kinetic = float(np.max(ch["kinetic"]))
    elastic = float(np.max(ch["elastic"]))
    return (6 + math.sqrt(2 * max(kinetic, 0.0) * float(np.sum(model.mass)))
            + math.sqrt(2 * max(elastic, 0.0) * stiffness))


def _monotone(name: str, t: np.ndarray, x: np.ndarray, tol: float) -> dict:
    """A loss that never falls by more than ``tol`` and never is below -tol."""
    fall = np.append(-np.diff(x), -np.inf)  # fall[i]: from point i to i + 1
    i = int(np.argmax(fall))
    j = int(np.argmin(x))
    if fall[i] >= -x[j]:
        worst, where, what = float(fall[i]), t[i + 1], f"falls by {fall[i]:.4g} J"
    else:
        worst, where, what = float(-x[j]), t[j], f"is {x[j]:.4g} J"
    return _entry(worst <= tol, worst, tol, where,
                  f"{name} {what} at t = {where:.6g} s (bound {tol:.3g} J), ends at "
                  f"{x[-1]:.4g} J")
