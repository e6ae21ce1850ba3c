"""Figures of a simulation's result (:meth:`leadscrew.Result.plot`).

Each figure is a :class:`matplotlib.figure.Figure` of its own, drawn without
pyplot's state (no display needed): save it with ``figure.savefig(path)``,
or show it in a notebook as it is.
"""

from __future__ import annotations

from typing import Optional

__all__ = ["plot_result", "KINDS"]


def _shade_stick(ax, result) -> None:
    """Shade the stick phases (the ``stick`` flag) on an Axes."""
    t = result.t
    if "stick" in result and len(t) > 1:
        stick = result["stick"] > 0.5
        ax.fill_between(t, 0, 1, where=stick, transform=ax.get_xaxis_transform(),
                        color="0.85", step="mid", label="stick")
        if stick.any():
            ax.legend(loc="best")


def _finish(figure, axes, title: Optional[str]):
    axes[-1].set_xlabel("time t [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    if title:
        figure.suptitle(title, fontsize="medium")
    return figure


def _block_time_series(result, title: Optional[str]):
    """A FrictionBlock's position (stick phases shaded), its velocity (and a
    transverse slip's), and its forces over time (a Figure)."""
    from matplotlib.figure import Figure

    t = result.t
    figure = Figure(figsize=(8.0, 7.0), layout="constrained")
    axes = figure.subplots(3, 1, sharex=True)
    axes[0].plot(t, result["u"] * 1e3, color="C0")
    _shade_stick(axes[0], result)
    axes[0].set_ylabel("block position u [mm]")
    axes[1].plot(t, result["v"] * 1e3, color="C1", label="velocity v")
    if "transverse_velocity" in result:
        axes[1].plot(t, result["transverse_velocity"] * 1e3, color="C2", lw=0.8,
                     label="transverse slip w")
        axes[1].legend(loc="best")
    axes[1].set_ylabel("velocity [mm/s]")
    for name, label in (("force", "applied force F"), ("friction_force", "friction"),
                        ("normal_force", "normal N"), ("spring_force", "spring"),
                        ("transverse_friction", "friction across (along w)")):
        if name in result and (result[name] != 0).any():
            axes[2].plot(t, result[name], label=label)
    axes[2].set_ylabel("force [N]")
    axes[2].legend(loc="best")
    return _finish(figure, axes, title)


def _time_series(result, title: Optional[str]):
    """Load position, rotor speed, forces (with an end stop's), drive torque and
    a DC motor's current over time (a Figure)."""
    from matplotlib.figure import Figure

    t = result.t
    motor = "motor_current" in result  # a DC motor: its current in a panel of its own
    figure = Figure(figsize=(8.0, 11.0 if motor else 9.0), layout="constrained")
    axes = figure.subplots(5 if motor else 4, 1, sharex=True)
    axes[0].plot(t, result["u_load"] * 1e3, color="C0")
    _shade_stick(axes[0], result)
    axes[0].set_ylabel("load position u [mm]")
    axes[1].plot(t, result["omega_drive"], color="C1")
    axes[1].set_ylabel("rotor speed [rad/s]")
    for name, label in (("axial_force", "axial load F"), ("normal_force", "flank normal N"),
                        ("friction_force", "flank friction T"), ("stop_force", "end stop"),
                        ("base_force", "base inertial force")):
        if name in result:
            axes[2].plot(t, result[name], label=label)
    axes[2].set_ylabel("force [N]")
    axes[2].legend(loc="best")
    axes[3].plot(t, result["drive_torque"] * 1e3, color="C3")
    axes[3].set_ylabel("drive torque [N*mm]")
    if motor:
        axes[4].plot(t, result["motor_current"], color="C4")
        axes[4].set_ylabel("motor current [A]")
    return _finish(figure, axes, title)


def _energy(result, title: Optional[str]):
    """The energy account: work in, losses, stored energy, residual (a Figure)."""
    from matplotlib.figure import Figure

    t = result.t
    figure = Figure(figsize=(8.0, 6.0), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True)
    for name in ("work_drive", "work_axial", "work_force", "work_transverse", "friction_loss", "damping_loss", "contact_loss",
                 "impact_loss", "kinetic", "elastic"):
        if name in result and (result[name] != 0).any():
            top.plot(t, result[name], label=name)
    top.set_ylabel("energy [J]")
    top.legend(loc="best")
    bottom.plot(t, result["energy_residual"], color="k")
    bottom.set_ylabel("energy residual [J]")
    return _finish(figure, (top, bottom), title)


#: The figures :func:`plot_result` draws, by name.
KINDS = {"time_series": _time_series, "energy": _energy}


def plot_result(result, kind: str = "time_series", title: Optional[str] = None):
    """Draw a simulation's result.

    Args:
        result: a :class:`leadscrew.Result` of a drive (a Scene's run) or
            of a :class:`~leadscrew.FrictionBlock`.
        kind: ``"time_series"``: the load's position (stick phases shaded)
            [mm], the rotor's speed [rad/s], the forces (axial load, flank
            normal and friction, an end stop's, a base excitation's inertial
            force) [N], the drive torque [N mm]
            and a DC motor's current [A] over time [s] (a block's: its
            position [mm], velocity and transverse slip [mm/s], and forces
            [N]); ``"energy"``: the
            energy account (work in, losses, stored energy) and its residual
            [J].
        title: the figure's title (default none).

    Returns:
        A :class:`matplotlib.figure.Figure`.

    Raises:
        ValueError: an unknown ``kind`` (naming the kinds), or a result
            without the channels the figure draws.
    """
    if kind not in KINDS:
        raise ValueError(f"kind = {kind!r} is invalid: must be one of {', '.join(KINDS)}")
    block = "u_load" not in result and "u" in result  # a FrictionBlock's result
    if kind == "time_series" and block:
        return _block_time_series(result, title)
    needed = ("u_load", "omega_drive", "drive_torque") if kind == "time_series" else \
        ("energy_residual",)
    missing = [name for name in needed if name not in result]
    if missing:
        raise ValueError(f"result = {result!r} is invalid for kind = {kind!r}: it has no "
                         f"channel {missing[0]!r} (a drive's result has)")
    return KINDS[kind](result, title)
