"""The drive train's invariants, checked from a result's channels and the
scene alone (issue 31, "What to build" 3): the part of
:func:`helpers.result_invariants.check_result` that concerns the DC motor,
the rotor's drive torque, LuGre's bristles and the end stops. Written from
the physics pages, not from ``Result.checks`` nor from the core:

- ``kinetic_energy``: kinetic = sum m v^2 / 2 over the bodies, from the
  scene's geometry (``Scene.derived()``: masses and inertias, as overridden)
  and the velocity channels (docs/physics/drive_models.md, the models'
  bodies): the rotor turns at omega_drive and the driven part at
  omega_drive / n (a gear stage of ratio n reflects the rotor onto it as n^2
  J); a body rigidly joined to another moves with it (the rigid concept's
  screw or nut with the rotor and the load, a nut-driven flexible_nut's
  screw with the load). To 1e-9 of the largest kinetic energy.
- ``motor_torque``: the rotor's torque channel is the motor's: drive_torque
  = k_t motor_current (docs/physics/dc_motor.md, "Equations"); a torque
  load's rotor reports T(t) (Moreau-Jean: T at the row or at the step's
  theta point, t_k + theta h, where its step takes the load). To
  round-off, 1e-9 of the torque's scale.
- ``driver_voltage``: the driver never puts out more than U(t):
  |motor_voltage| <= |U(t)| (Moreau-Jean: U(t_k + theta h), the voltage its
  step takes, dc_motor.md "Moreau-Jean", or U at the row); without a
  current limit it puts
  out U(t) itself. To 1e-9 of the voltage's scale.
- ``current_limit``: |motor_current| <= i_max (1 + 1e-9), except at rows
  where the driver is at its bound |U_d| = |U|: there a back-EMF beyond the
  supply drives the current past the limit, and no voltage within U(t) can
  hold it (issue 31, reproduction 2).
- ``armature``: L di/dt = U_d - R i - k_e omega with k_e the scene's
  back_emf_constant (default k_t). L = 0: pointwise, to 1e-9 of the terms
  (Moreau-Jean: with omega_theta = (1 - theta) omega_k + theta omega_k+1,
  each row its step's driver voltage and quasi-static current, dc_motor.md
  "Moreau-Jean": the limit x = h R / L -> infinity of the step; row 0 at
  its own speed).
  L > 0, event-driven and ODE integrators: between two output points L
  (i_1 - i_0) is k_e times the rotor's turn (phi_drive, a state: exact)
  less the integral of g = U_d - R i, which lies
  within h |g_1 - g_0| / 2 of the trapezoid h (g_0 + g_1) / 2 wherever g
  is monotone between them (the integral lies between the two rectangle
  sums; the output points include every event, where g may jump); allowed:
  twice that, with the largest |Delta g| of the interval and its two
  neighbours (a rate that turns inside an interval), plus
  the integrator's local errors, K (rtol |L i| + L atol) and those of the
  angle, K k_e (rtol |Delta phi| + atol), with the energy
  check's K = 1000. Moreau-Jean: its exact armature step
  (dc_motor.md, "Moreau-Jean"), L (i+ - i) = h (U_d - R i_mean - k_e
  omega_theta) with omega_theta = (1 - theta) omega + theta omega+ held over
  the step, i_inf = (U_d - k_e omega_theta) / R, x = h R / L and i_mean =
  i_inf + (i - i_inf) (1 - e^-x) / x: it holds exactly where i+ = i_inf +
  (i - i_inf) e^-x, to round-off.
- ``motor_energy``: magnetic_energy = L i^2 / 2 (stored, to round-off), and
  the copper loss and the drive's work as integrals of R i^2 and of U_d i
  + (k_t - k_e) i omega (dc_motor.md, "State and energy account"; a
  constant torque T: T times the rotor's turn, docs/physics/drive_models.md,
  "Energy account"; a varying torque load or a speed drive's reaction
  torque, which output points do not resolve, unchecked on the event-driven
  and ODE integrators), each increment within the trapezoid's bound above
  (Moreau-Jean: the exact step's integral of R i^2 (dc_motor.md,
  "Moreau-Jean") and h (U_d + (k_t - k_e) omega_theta) i_mean, to
  round-off).
- ``lugre_bristle``: |bristle_deflection| <= max(mu, mu_static) / sigma0:
  the set is invariant under z' = v - sigma0 |v| z / mu(|v|) from z = 0
  (docs/physics/friction_laws.md), so a deflection beyond it is the
  integration's error alone: to the integration's resolution of the state
  the integrators carry, z / z_max (its local error rtol |w| + atol <= rtol
  + atol per step), times the energy check's K = 1000 (BDF's steps overshoot
  the saturated set by tens of local errors), and at least 1e-6 of the
  bound.
- ``friction_law`` (LuGre, the main checker's entry for the other laws):
  friction_force = -|N|' (sigma0 z + sigma1 z') - c v where the flanks
  touch, |N|' = |N| / cos(beta / 2), z' from the bristles' equation at the
  channels (docs/physics/friction_laws.md), to round-off (1e-9 of the
  force's scale); with it and the bristles' bound the friction stays in
  its cone mu_static' |N| + sigma1 |N|' |z'| + c |v|. Not with a preloaded
  nut (each half's bristles, no one channel).
- ``stop_travel``: the load stays between its exact stops: lower - b <=
  u_load <= upper + b, b the root's resolution, 1e-9 |face| + 10 atol
  (event-driven and ODE; docs/physics/end_stops.md, "Exact stops": the
  position is snapped onto the face), Moreau-Jean 3 dt max |v_load| (it
  meets the face a step late on the velocity level, at most (1 - theta) h
  |u'| per closing, as its flanks, and keeps that depth: no position
  projection).
- ``stop_force``: a stop pushes and never pulls, and only at its face:
  stop_force > 0 (toward +u) only where u_load is at or below the lower
  face, < 0 only at or above the upper one (to the resolution above; a
  penalty stop's F = max(0, k d + c d') acts only where d > 0); a force
  below 1e-9 (max |stop_force| + 1 N) is round-off.

The increments' checks have a floor of 1e-9 of the integral's largest value
(round-off) and skip an interval of zero length (an event's two rows: an
impulse's work, such as a speed-controlled rotor's at an impact, has no
rate).
"""

from __future__ import annotations

import math
from typing import Any, Callable, Dict, Optional

import numpy as np

__all__ = ["check_train", "TRAIN_INVARIANTS", "excitation_at"]

TRAIN_INVARIANTS = ("kinetic_energy", "motor_torque", "driver_voltage", "current_limit",
                    "armature", "motor_energy", "lugre_bristle", "stop_travel", "stop_force")

ROUND_OFF_REL = 1e-9     # of a channel's scale: a quantity the core computes from the state
LIMIT_SATURATED = 1e-6   # of |U|: the driver at its bound
QUADRATURE_FACTOR = 1e3  # K of docs/physics/result_checks.md: a state's local errors
BRISTLE_REL = 1e-6       # of max(mu, mu_static) / sigma0
STOP_REL = 1e-9          # of |face|
STOP_ATOL = 10.0         # atol's: the positions' absolute tolerance, as the flanks'
MOREAU_STOP_STEPS = 3.0  # steps of the largest load speed: Moreau-Jean beyond a face


def excitation_at(load: Any, t: np.ndarray) -> Optional[np.ndarray]:
    """A load of a scene dict (a number, a constant, sine or table dict) at
    the times ``t`` (the excitation's definitions, python/leadscrew/
    excitation.py: a sine offset + amplitude sin(omega t + phase), a table
    piecewise linear, held beyond its ends); None for what is no dict (a
    callable)."""
    if isinstance(load, (int, float)) and not isinstance(load, bool):
        return np.full(len(t), float(load))
    if not isinstance(load, dict):
        return None
    kind = load.get("type")
    if kind == "constant":
        return np.full(len(t), float(load["value"]))
    if kind == "sine":
        return (float(load.get("offset", 0.0)) + float(load["amplitude"])
                * np.sin(float(load["omega"]) * t + float(load.get("phase", 0.0))))
    if kind == "table":
        return np.interp(t, np.asarray(load["times"], float), np.asarray(load["values"], float))
    return None


def _entry(ok, value, bound, when, detail) -> dict:
    return {"ok": bool(ok), "value": float(value), "bound": float(bound),
            "time": None if when is None else float(when), "detail": detail}


def _worst(name: str, t: np.ndarray, excess: np.ndarray, bound: np.ndarray,
           describe: Callable[[int], str]) -> dict:
    """The entry of a pointwise check: excess[i] <= bound[i] everywhere."""
    if len(excess) == 0:
        return _entry(True, 0.0, 0.0, None, f"{name}: nothing to check")
    margin = excess - bound
    i = int(np.argmax(margin))
    return _entry(margin[i] <= 0, excess[i], bound[i], t[min(i, len(t) - 1)], describe(i))


def _angle_round_off(phi: np.ndarray) -> float:
    """The round-off of a difference of two rotor angles [rad]: an angle
    started at -1e15 rad (a hostile initial.rotor_angle) keeps its turns
    only to 4 ulp of its size."""
    return 4 * np.finfo(float).eps * float(np.max(np.abs(phi)))


def _theta_times(t: np.ndarray, theta: float) -> np.ndarray:
    """Moreau-Jean's row k + 1 is the step from t_k: the times its step
    takes the loads at, t_k + theta h (row 0: t_0)."""
    return np.concatenate([t[:1], t[:-1] + theta * np.diff(t)])


def _increments(t, integral, rate, moreau_rate, tol_state, known=0.0) -> tuple:
    """The increments of an integral channel against its rate: (the misfit
    per interval, its bound) -- the trapezoid of ``rate`` plus the part of
    the increment ``known`` exactly (per interval), within the bound of the
    module docstring; Moreau-Jean: its step's own rate ``moreau_rate`` (per
    interval), to round-off."""
    h = np.diff(t)
    delta = np.diff(integral)
    # Round-off of the integral's own scale; an interval of zero length (an
    # event's two rows) holds an impulse's work, which no rate gives.
    floor = ROUND_OFF_REL * float(np.max(np.abs(integral))) + 1e-300
    if moreau_rate is not None:
        expected = h * moreau_rate
        misfit = np.where(h > 0, np.abs(delta - expected), 0.0)
        return misfit, ROUND_OFF_REL * (np.abs(delta) + np.abs(expected)) + floor
    trapezoid = h * (rate[1:] + rate[:-1]) / 2 + known
    misfit = np.where(h > 0, np.abs(delta - trapezoid), 0.0)
    # The rate's variation over the interval and its neighbours (a rate
    # that turns inside an interval, a product such as U_d i, has the
    # neighbours' variation there); the rectangle sums' half difference of
    # a monotone rate, h |Delta rate| / 2, times 2.
    change = np.abs(np.diff(rate))
    spread = np.maximum(change, np.maximum(np.append(change[1:], 0.0),
                                           np.insert(change[:-1], 0, 0.0)))
    return misfit, h * spread + tol_state + floor


def check_train(result: Any, scene: dict, options: dict, ch: Dict[str, np.ndarray],
                rtol: float, atol: float) -> Dict[str, dict]:
    """The train's invariants that apply to the scene (module docstring).

    Args:
        result: the Result (its ``t`` and ``integrator``).
        scene: ``Scene.to_dict()``.
        options: ``simulate``'s keywords.
        ch: the channels as float arrays.
        rtol, atol: the run's tolerances (rtol 0 for Moreau-Jean).
    """
    t = np.asarray(result.t, dtype=float)
    moreau = result.integrator == "moreau"
    theta = float(options.get("theta", 0.5) or 0.5) if moreau else None
    requested = options.get("t_eval")
    requested = requested is not None and not isinstance(requested, str)
    interpolated = moreau and requested
    report: Dict[str, dict] = {}
    if interpolated:  # rows between Moreau-Jean's steps: no step relation holds there
        return report
    # Rows at requested times (event-driven and ODE): the state's dense
    # output, without the events between them (a current limit engaging, a
    # voltage table's step), so the increments between rows have no bound
    # from their end values; the pointwise relations still hold, the
    # friction law to the interpolation's error.
    sampled = requested
    load_times = _theta_times(t, theta) if moreau else t
    report["kinetic_energy"] = _kinetic(t, scene, ch)
    motor = scene.get("motor")
    if motor is not None and motor.get("type") == "dc":
        report.update(_motor(t, load_times, motor, ch, moreau, theta, rtol, atol, sampled))
    elif not sampled:
        report.update(_torque(t, load_times, scene, ch, moreau, theta, rtol, atol))
    if scene["friction"]["law"] == "lugre" and "bristle_deflection" in ch:
        report.update(_lugre(t, scene, ch, rtol if sampled else 0.0, rtol, atol))
    stops = scene.get("end_stops")
    # (the faces relative to the load's start: an equilibrium start moves
    # them by its u_load, docs/physics/end_stops.md, "The scene")
    equilibrium = scene.get("initial", {}).get("state") == "equilibrium"
    if stops is not None and "stop_force" in ch and (not equilibrium or t[0] == 0.0):
        start = float(ch["u_load"][0]) if equilibrium else 0.0
        report.update(_stops(t, stops, ch, moreau, options, atol, start))
    return report


def _kinetic(t, scene, ch) -> dict:
    """kinetic = sum m v^2 / 2 from the geometry (module docstring)."""
    import leadscrew as ls

    derived = ls.Scene.from_dict(scene).derived()
    concept, drive = scene["concept"], scene.get("drive", "screw")
    driven, other = ("screw", "nut") if drive == "screw" else ("nut", "screw")
    ratio = float(scene.get("gear", {}).get("ratio", 1.0)) if scene.get("gear") else 1.0
    inertia = float(scene["rotor"]["inertia"]) * ratio ** 2  # on the driven part's angle
    load = float(scene["load"]["mass"])
    bodies = []  # (mass or inertia, velocity channel) of the bodies of their own
    if concept == "rigid" or (concept == "flexible_nut" and drive == "screw"):
        inertia += derived[f"{driven}_inertia"]  # the driven part turns with the rotor
    if concept == "rigid":
        load += derived[f"{other}_mass"]  # the translating part carries the load
    elif concept == "flexible_nut" and drive == "nut":
        load += derived["screw_mass"]  # the rigid screw carries the load
    for part in ("screw", "nut"):
        for kind, channel in (("mass", f"v_{part}"), ("inertia", f"omega_{part}")):
            if channel in ch:
                bodies.append((derived[f"{part}_{kind}"], ch[channel]))
    expected = 0.5 * (inertia * (ch["omega_drive"] / ratio) ** 2 + load * ch["v_load"] ** 2
                      + sum(m * v ** 2 for m, v in bodies))
    kinetic = ch["kinetic"]
    error = np.abs(kinetic - expected)
    scale = ROUND_OFF_REL * max(float(np.max(np.abs(expected))), 1e-300)
    return _worst("kinetic_energy", t, error, np.full(len(t), scale),
                  lambda i: f"kinetic {kinetic[i]:.6g} J where the bodies' sum m v^2 / 2 is "
                            f"{expected[i]:.6g} J at t = {t[i]:.6g} s")


def _lugre(t, scene, ch, interpolation, rtol, atol) -> Dict[str, dict]:
    """LuGre's bristles within their bound, and its law at every output
    point (module docstring)."""
    from helpers.result_invariants import stribeck_curve

    friction = scene["friction"]
    mu = float(friction["mu"])
    mu_static = friction.get("mu_static")
    largest = max(mu, mu if mu_static is None else float(mu_static))
    sigma0 = float(friction.get("sigma0") or 1e5)  # the registry's defaults
    sigma1 = float(friction.get("sigma1") or 0.0)
    viscous = float(friction.get("viscous") or 0.0)
    bound = largest / sigma0 * (1 + max(BRISTLE_REL, QUADRATURE_FACTOR * (rtol + atol)))
    z = ch["bristle_deflection"]
    report = {"lugre_bristle": _worst(
        "lugre_bristle", t, np.abs(z), np.full(len(z), bound),
        lambda i: f"|bristle_deflection| {abs(z[i]):.6g} m > max(mu, mu_static) / sigma0 = "
                  f"{largest:.4g} / {sigma0:.4g} at t = {t[i]:.6g} s")}
    if float(scene.get("nut", {}).get("preload", 0.0) or 0.0) > 0.0:
        return report  # (two halves, each with its bristles: no one channel)
    slip, normal, force = ch["slip_velocity"], ch["normal_force"], ch["friction_force"]
    rate = slip - sigma0 * np.abs(slip) * z / stribeck_curve(friction, np.abs(slip))
    loaded = np.abs(normal) / math.cos(float(scene["thread"]["flank_angle"]) / 2)
    expected = -loaded * (sigma0 * z + sigma1 * rate) - (np.abs(normal) > 0) * viscous * slip
    error = np.abs(force - expected)
    # A normal force at the round-off of its own scale (a flank opening,
    # N crossing zero) has no reliable sign: the law may take it either way.
    opening = np.abs(normal) <= ROUND_OFF_REL * float(np.max(np.abs(normal)))
    error = np.where(opening, np.minimum(error, np.abs(force + expected)), error)
    # (the friction's own scale, or its cone's, mu_max' |N|: a run whose
    # friction stays at round-off of its normal force, 1e-64 N against 4e-25
    # N at the first step of a flank, has no sign of its own to compare)
    scale = (max(ROUND_OFF_REL, QUADRATURE_FACTOR * interpolation)
             * max(float(np.max(np.abs(force))), float(np.max(np.abs(expected))),
                   largest * float(np.max(loaded)), 1e-300))
    report["friction_law"] = _worst(
        "friction_law", t, error, np.full(len(t), scale),
        lambda i: f"friction {force[i]:.6g} N where LuGre's law gives -|N|' (sigma0 z + sigma1 "
                  f"z') - c v = {expected[i]:.6g} N (z {z[i]:.4g} m, slip {slip[i]:.4g} m/s, "
                  f"normal {normal[i]:.6g} N) at t = {t[i]:.6g} s")
    return report


def _torque(t, load_times, scene, ch, moreau, theta, rtol, atol) -> Dict[str, dict]:
    """A torque-driven rotor: its channel is the load's torque; the drive's
    work, the integral of drive_torque omega_drive."""
    report = {}
    torque = ch["drive_torque"]
    omega = ch["omega_drive"]
    load = scene.get("loads", {}).get("drive_torque")
    given = excitation_at(load, load_times)
    if given is not None and "drive_speed" not in scene.get("loads", {}):
        scale = ROUND_OFF_REL * max(float(np.max(np.abs(given))), 1e-300)
        # (Moreau-Jean: the load at the step's theta point or at the row)
        error = np.minimum(np.abs(torque - given), np.abs(torque - excitation_at(load, t)))
        report["motor_torque"] = _worst(
            "motor_torque", t, error, np.full(len(t), scale),
            lambda i: f"drive_torque {torque[i]:.6g} N m where the load gives "
                      f"{given[i]:.6g} N m at t = {t[i]:.6g} s")
    work = ch["work_drive"]
    power = torque * omega
    moreau_rate = None
    tol_state = QUADRATURE_FACTOR * (rtol * np.abs(work[1:]) + atol)
    if moreau:
        # The step's work h T omega_theta, T the row's torque or (a torque
        # load) the load at the theta point.
        omega_theta = (1 - theta) * omega[:-1] + theta * omega[1:]
        misfit, bound = _increments(t, work, power, torque[1:] * omega_theta, tol_state)
        if given is not None:
            other, _ = _increments(t, work, power, given[1:] * omega_theta, tol_state)
            misfit = np.minimum(misfit, other)
    elif given is not None and np.all(given == given[0]) and "drive_speed" not in scene.get(
            "loads", {}):
        # A constant torque's work is T times the rotor's turn, exactly (the
        # speed may ring between output points; the angle is a state). A
        # varying torque, or a speed drive's reaction torque, is not resolved
        # by the output points: no check.
        misfit, bound = _increments(t, work, 0.0 * power, None,
                                    tol_state + abs(given[0]) * _angle_round_off(ch["phi_drive"]),
                                    known=given[0] * np.diff(ch["phi_drive"]))
    else:
        return report
    report["motor_energy"] = _worst(
        "motor_energy", t[1:], misfit, bound,
        lambda i: f"work_drive grows by {work[i + 1] - work[i]:.6g} J from t = {t[i]:.6g} s "
                  f"to {t[i + 1]:.6g} s where drive_torque omega_drive gives it within "
                  f"{bound[i]:.3g} J (misfit {misfit[i]:.3g} J)")
    return report


def _motor(t, load_times, motor, ch, moreau, theta, rtol, atol, sampled) -> Dict[str, dict]:
    """The DC motor's invariants (module docstring)."""
    report = {}
    k_t = float(motor["torque_constant"])
    k_e = float(motor.get("back_emf_constant") or k_t)
    resistance = float(motor["resistance"])
    inductance = float(motor.get("inductance") or 0.0)
    limit = motor.get("current_limit")
    current, voltage = ch["motor_current"], ch["motor_voltage"]
    omega, torque = ch["omega_drive"], ch["drive_torque"]

    expected = k_t * current
    scale = ROUND_OFF_REL * max(float(np.max(np.abs(expected))), 1e-300)
    report["motor_torque"] = _worst(
        "motor_torque", t, np.abs(torque - expected), np.full(len(t), scale),
        lambda i: f"drive_torque {torque[i]:.6g} N m where k_t motor_current = {k_t:.4g} * "
                  f"{current[i]:.6g} A = {expected[i]:.6g} N m at t = {t[i]:.6g} s")

    supply = excitation_at(motor["voltage"], load_times)
    # Moreau-Jean may report a step's voltage at its theta point or at its
    # end, t_k + h: either is the step's (rows at the end time are t itself).
    at_row = excitation_at(motor["voltage"], t)
    if supply is not None:
        tol = ROUND_OFF_REL * max(float(np.max(np.abs(supply))), 1e-300)
        if limit is None:  # the driver puts out U(t)
            excess = np.minimum(np.abs(voltage - supply), np.abs(voltage - at_row))
            what = "differs from"
        else:
            excess = np.abs(voltage) - np.maximum(np.abs(supply), np.abs(at_row))
            what = "exceeds"
        report["driver_voltage"] = _worst(
            "driver_voltage", t, excess, np.full(len(t), tol),
            lambda i: f"motor_voltage {voltage[i]:.6g} V {what} the supply U = {supply[i]:.6g} V "
                      f"at t = {t[i]:.6g} s")
        if limit is not None:
            i_max = float(limit)
            saturated = np.abs(voltage) >= np.abs(supply) * (1 - LIMIT_SATURATED) - tol
            over = np.where(saturated, -np.inf, np.abs(current) - i_max)
            report["current_limit"] = _worst(
                "current_limit", t, over, np.full(len(t), ROUND_OFF_REL * i_max),
                lambda i: f"|motor_current| {abs(current[i]):.6g} A beyond the limit {i_max:.4g} "
                          f"A while the driver puts out {voltage[i]:.6g} V of U = "
                          f"{supply[i]:.6g} V at t = {t[i]:.6g} s")

    emf = voltage - resistance * current - k_e * omega  # L di/dt
    if inductance == 0.0:
        if moreau:  # the step's quasi-static current, at its theta point's speed
            w_theta = np.concatenate([omega[:1], (1 - theta) * omega[:-1] + theta * omega[1:]])
            emf = voltage - resistance * current - k_e * w_theta
        terms = np.abs(voltage) + resistance * np.abs(current) + k_e * np.abs(omega)
        report["armature"] = _worst(
            "armature", t, np.abs(emf), ROUND_OFF_REL * terms + 1e-300,
            lambda i: f"U_d - R i - k_e omega = {emf[i]:.4g} V (inductance 0: must be 0; U_d "
                      f"{voltage[i]:.6g} V, i {current[i]:.6g} A, omega {omega[i]:.6g} rad/s, "
                      f"k_e {k_e:.4g}) at t = {t[i]:.6g} s")
    elif not sampled:
        flux = inductance * current
        moreau_rate = None
        if moreau:
            w_theta = (1 - theta) * omega[:-1] + theta * omega[1:]
            i_mean, _ = _armature_step(t, current, voltage, w_theta, resistance, inductance, k_e)
            moreau_rate = voltage[1:] - resistance * i_mean - k_e * w_theta
        # The back-EMF's integral is k_e times the rotor's turn, exactly: the
        # rotor's speed may ring between output points (a flexible drive),
        # its angle is a state.
        misfit, bound = _increments(t, flux, voltage - resistance * current, moreau_rate,
                                    QUADRATURE_FACTOR * (rtol * np.abs(flux[1:])
                                                         + inductance * atol)
                                    # (the angle is a state too: its own local
                                    # errors over the interval, times K)
                                    + k_e * QUADRATURE_FACTOR
                                    * (rtol * np.abs(np.diff(ch["phi_drive"])) + atol)
                                    + k_e * _angle_round_off(ch["phi_drive"]),
                                    known=-k_e * np.diff(ch["phi_drive"]))
        report["armature"] = _worst(
            "armature", t[1:], misfit, bound,
            lambda i: f"L di = {flux[i + 1] - flux[i]:.6g} V s from t = {t[i]:.6g} s to "
                      f"{t[i + 1]:.6g} s where U_d - R i - k_e omega (k_e {k_e:.4g}) integrates "
                      f"to it within {bound[i]:.3g} V s (misfit {misfit[i]:.3g} V s)")
    if sampled:
        return report
    report["motor_energy"] = _motor_energy(t, ch, k_t, k_e, resistance, inductance, moreau,
                                           theta, rtol, atol)
    return report


def _armature_step(t, current, voltage, w_theta, resistance, inductance, k_e) -> tuple:
    """Moreau-Jean's exact armature step from each row to the next
    (dc_motor.md, "Moreau-Jean"), written from the document: L i' = u - R i
    - k_e omega_theta with u and omega_theta held over the step. Returns the
    step's mean current and its mean copper loss power (the integral of R
    i^2 over h), per interval; an interval of zero length (an event's two
    rows) gives the row's own values."""
    h = np.diff(t)
    x = h * resistance / inductance
    i_inf = (voltage[1:] - k_e * w_theta) / resistance
    d = current[:-1] - i_inf
    safe = np.where(x > 0, x, 1.0)
    f1 = np.where(x > 0, -np.expm1(-safe) / safe, 1.0)        # (1 - e^-x) / x
    f2 = np.where(x > 0, -np.expm1(-2 * safe) / (2 * safe), 1.0)  # (1 - e^-2x) / 2x
    i_mean = i_inf + d * f1
    copper = resistance * (i_inf ** 2 + 2 * i_inf * d * f1 + d ** 2 * f2)
    return i_mean, copper


def _motor_energy(t, ch, k_t, k_e, resistance, inductance, moreau, theta, rtol,
                  atol) -> dict:
    """magnetic_energy = L i^2 / 2; copper_loss and work_drive as the
    integrals of R i^2 and U_d i + (k_t - k_e) i omega."""
    current, voltage, omega = ch["motor_current"], ch["motor_voltage"], ch["omega_drive"]
    stored = 0.5 * inductance * current ** 2
    magnetic = ch.get("magnetic_energy", np.zeros(len(t)))
    error = np.abs(magnetic - stored)
    scale = ROUND_OFF_REL * max(float(np.max(stored)), 1e-300)
    entries = [_worst("magnetic_energy", t, error, np.full(len(t), scale),
                      lambda i: f"magnetic_energy {magnetic[i]:.6g} J where L i^2 / 2 = "
                                f"{stored[i]:.6g} J at t = {t[i]:.6g} s")]
    rates = {"copper_loss": (resistance * current ** 2, None),
             "work_drive": ((voltage + (k_t - k_e) * omega) * current, None)}
    if moreau:
        w_theta = (1 - theta) * omega[:-1] + theta * omega[1:]
        # (inductance 0: the quasi-static current at the theta point,
        # dc_motor.md "Moreau-Jean")
        if inductance > 0:
            i_mean, copper = _armature_step(t, current, voltage, w_theta, resistance,
                                            inductance, k_e)
        else:
            i_mean = (voltage[1:] - k_e * w_theta) / resistance
            copper = resistance * i_mean ** 2
        rates["copper_loss"] = (None, copper)
        rates["work_drive"] = (None, (voltage[1:] + (k_t - k_e) * w_theta) * i_mean)
    for name, (rate, moreau_rate) in rates.items():
        integral = ch[name]
        misfit, bound = _increments(t, integral, rate, moreau_rate,
                                    QUADRATURE_FACTOR * (rtol * np.abs(integral[1:]) + atol))
        entries.append(_worst(
            name, t[1:], misfit, bound,
            lambda i, name=name, integral=integral, misfit=misfit, bound=bound:
                f"{name} grows by {integral[i + 1] - integral[i]:.6g} J from t = {t[i]:.6g} s to "
                f"{t[i + 1]:.6g} s where its rate (dc_motor.md) gives it within {bound[i]:.3g} J "
                f"(misfit {misfit[i]:.3g} J)"))
    failing = [e for e in entries if not e["ok"]]
    return failing[0] if failing else max(entries, key=lambda e: e["value"] - e["bound"])


def _stops(t, stops, ch, moreau, options, atol, start=0.0) -> Dict[str, dict]:
    """The load between its exact stops; a stop's force at its face only.
    ``start``: the load's start, which the faces are relative to."""
    report = {}
    u, force = ch["u_load"], ch["stop_force"]
    faces = {side: start + float(stops[side]) for side in ("lower", "upper")
             if stops.get(side) is not None}
    exact = stops.get("contact", "penalty") == "exact"
    if moreau:
        speed = float(np.max(np.abs(ch["v_load"])))
        step = float(options.get("dt") or 1e-4)
        # (not capped at |face|: a stop near the start, 18 um away, met by a
        # load at 1.6 m/s in a step of 1e-4 s is passed by 0.14 mm before
        # the velocity-level contact holds it, and Moreau-Jean keeps no
        # position constraint that would move it back: the scheme's first
        # order, which dt -> 0 removes)
        reach = {side: MOREAU_STOP_STEPS * step * speed + STOP_REL * abs(face)
                 for side, face in faces.items()}
    else:
        reach = {side: STOP_REL * abs(face) + STOP_ATOL * atol for side, face in faces.items()}
    if exact:
        beyond = np.full(len(t), -np.inf)
        bound = np.zeros(len(t))
        for side, face in faces.items():
            sign = 1.0 if side == "upper" else -1.0
            depth = sign * (u - face)
            pick = depth - reach[side] > beyond - bound
            beyond = np.where(pick, depth, beyond)
            bound = np.where(pick, reach[side], bound)
        report["stop_travel"] = _worst(
            "stop_travel", t, beyond, bound,
            lambda i: f"u_load {u[i]:.6g} m is {beyond[i]:.4g} m beyond an exact stop "
                      f"({faces}) at t = {t[i]:.6g} s (resolution {bound[i]:.3g} m)")
    # Where a stop pushes toward +u the load is at the lower face (or in it).
    away = np.zeros(len(t))
    bound = np.zeros(len(t))
    # (a force below 1e-9 of the stops' largest, and 1e-9 N, is round-off)
    pushes = np.abs(force) > ROUND_OFF_REL * (float(np.max(np.abs(force))) + 1.0)
    for side, face in faces.items():
        sign = 1.0 if side == "upper" else -1.0
        pushing = (force * sign < 0) & pushes
        away = np.where(pushing, np.maximum(away, sign * (face - u)), away)
        bound = np.where(pushing, reach[side], bound)
    unexplained = pushes & ~np.any([(force * (1.0 if s == "upper" else -1.0) < 0)
                                         for s in faces] or [np.zeros(len(t), bool)], axis=0)
    away = np.where(unexplained, math.inf, away)
    report["stop_force"] = _worst(
        "stop_force", t, away, bound,
        lambda i: f"stop_force {force[i]:.6g} N with the load {away[i]:.4g} m off the face "
                  f"that could push that way ({faces}) at u_load = {u[i]:.6g} m, t = "
                  f"{t[i]:.6g} s (resolution {bound[i]:.3g} m)")
    return report
