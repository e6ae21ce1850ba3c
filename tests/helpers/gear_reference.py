"""Closed forms of an ideal gear stage between the rotor and the driven part
(issue 19, item 2; docs/physics/gear.md), written from the kinematics
phi_rotor = n phi_driven and the power balance of a stage that stores and
dissipates nothing, independent of the leadscrew package. SI units.

The rotor (inertia J, motor torque T) behind an ideal stage of ratio n acts
on the driven part as a rotor of inertia n^2 J under the torque n T:
  J omega_rotor' = T - tau_in,  n tau_in = tau_out  (power tau_in omega_rotor =
  tau_out omega_driven),  omega_rotor = n omega_driven
  =>  n^2 J omega_driven' = n T - tau_out.
So the geared drive moves its load as the drive without a gear whose rotor
has the inertia n^2 J and the torque n T (reflected_drive, reflected_torque,
reflected_scene); its rotor turns n times the driven part's angle.

DC motor (L di/dt = U - R i - k_e omega_rotor, torque k_t i on the rotor): at
the steady state the driven part needs the torque T_d of the bare drive
(dc_motor_reference.steady_torque, slipping in the direction of the driven
part, sign(n) times the rotor's), so i = T_d / (n k_t) and
omega_rotor = (U - R i) / k_e = n omega_driven.

A speed-controlled rotor (omega_rotor prescribed) turns the driven part at
omega_rotor / n; at a constant speed the rotor's torque is T_d / n.

Efficiency: the stage passes the power T omega_rotor = (n T) omega_driven on
whole, so the train's efficiency F v / (T omega_rotor) is the thread's.

Lossy stage (type "lossy", not yet run by the simulator; the closed form of
docs/physics/gear.md, Modelica's LossyGear with constant efficiencies eta
forward and eta_b backward): at a steady motion, with T_d the torque the
driven part takes along its motion (> 0: it absorbs power; < 0: its load
drives), the rotor's torque along its own motion is T_d / (n eta) where the
rotor drives and eta_b T_d / n where the driven part drives
(lossy_rotor_torque, |n|); the stage locks under a load alone where
eta_b <= 0 (lossy_stage_locks).
"""

from __future__ import annotations

import copy
import dataclasses
import math

from . import dc_motor_reference
from .rigid_drive_reference import Harmonic, RigidDrive

__all__ = ["reflected_drive", "reflected_torque", "reflected_scene", "steady_state",
           "lossy_rotor_torque", "lossy_stage_locks"]


def reflected_drive(drive: RigidDrive, ratio: float) -> RigidDrive:
    """The rigid drive without a gear that the geared drive ``drive`` (its
    rotor_inertia the rotor's own) is on its driven part: rotor inertia n^2 J."""
    return dataclasses.replace(drive, rotor_inertia=ratio * ratio * drive.rotor_inertia)


def reflected_torque(torque: Harmonic, ratio: float) -> Harmonic:
    """The torque n M(t) on the driven part of a torque M(t) on the rotor."""
    return Harmonic(ratio * torque.mean, ratio * torque.amplitude, torque.omega, torque.phase)


def _scaled_load(load, factor: float):
    """A scene load (a number or a constant / sine / table dict) times ``factor``."""
    if isinstance(load, (int, float)):
        return factor * load
    load = dict(load)
    kind = load["type"]
    keys = {"constant": ("value",), "sine": ("amplitude", "offset"), "table": ("values",)}[kind]
    for key in keys:
        if key in load:
            value = load[key]
            load[key] = [factor * x for x in value] if isinstance(value, list) else factor * value
    return load


def reflected_scene(scene: dict, ratio: float) -> dict:
    """The scene without a gear whose rotor is the geared scene's reflected
    onto the driven part: inertia n^2 J, drive torque n T(t), a prescribed
    speed omega(t) / n, an initial speed omega_0 / n and a DC motor's
    constants n k_t, n k_e (the geared scene has the section
    gear = {ratio = n}; this one has none)."""
    out = copy.deepcopy(scene)
    out.pop("gear", None)
    out["rotor"] = {**out.get("rotor", {}), "inertia": ratio * ratio * scene["rotor"]["inertia"]}
    loads = out["loads"]
    if "drive_torque" in loads:
        loads["drive_torque"] = _scaled_load(loads["drive_torque"], ratio)
    if "drive_speed" in loads:
        loads["drive_speed"] = _scaled_load(loads["drive_speed"], 1.0 / ratio)
    initial = out.get("initial", {})
    if "rotor_speed" in initial:
        initial["rotor_speed"] = initial["rotor_speed"] / ratio
    motor = out.get("motor")
    if motor is not None:  # a DC motor: n k_t i on the driven part, back-EMF k_e n omega
        motor["back_emf_constant"] = ratio * motor.get("back_emf_constant",
                                                       motor["torque_constant"])
        motor["torque_constant"] = ratio * motor["torque_constant"]
    return out


def steady_state(drive: RigidDrive, ratio: float, axial_force: float, voltage: float,
                 resistance: float, torque_constant: float, back_emf_constant: float):
    """(current [A], rotor speed [rad/s], rotor torque [N m]) of a DC motor
    turning its rotor forward (omega_rotor > 0) through an ideal stage of
    ratio n at the steady state: the driven part slips in the direction
    sign(n) needing T_d, i = T_d / (n k_t), omega_rotor = (U - R i) / k_e."""
    driven_torque = dc_motor_reference.steady_torque(drive, axial_force,
                                                     math.copysign(1.0, ratio))
    torque = driven_torque / ratio
    current = torque / torque_constant
    omega = (voltage - resistance * current) / back_emf_constant
    return current, omega, torque


def lossy_rotor_torque(driven_torque: float, ratio: float, efficiency: float,
                       efficiency_backdrive: float) -> float:
    """The rotor's torque [N m] along its motion at a steady motion through a
    lossy stage of ratio |n| (> 0), the driven part taking ``driven_torque``
    T_d along its motion: T_d / (n eta) where the rotor drives (T_d >= 0),
    eta_b T_d / n where the driven part drives (T_d < 0; >= 0 where
    eta_b <= 0: the rotor must drive even then)."""
    if driven_torque >= 0.0:
        return driven_torque / (ratio * efficiency)
    return efficiency_backdrive * driven_torque / ratio


def lossy_stage_locks(efficiency_backdrive: float) -> bool:
    """A lossy stage holds a load on its driven part with a free rotor (and
    lowering it needs the rotor to drive) where eta_b <= 0."""
    return efficiency_backdrive <= 0.0
