"""Position holding under static and alternating axial load (thesis section 5.2, Fig. 5.4).

:func:`position_holding` runs one scene twice, under a static axial force and
under an alternating one without static part, and compares how the load
holds its position (the creep per cycle, the flights across the play);
:func:`plot_position_holding` draws both. The physics is told in
:mod:`leadscrew.studies.holding`; the runs are those of
:mod:`leadscrew.studies._holding_runs`.
"""

from __future__ import annotations

from typing import Any, Optional

import pandas as pd

from .._progress import shown
from ..thread import is_self_locking
from ._batch import check_simulate_options
from ._common import annotate, as_scene, axes, check_finite, with_tolerances
from ._holding_runs import (_AT_REST, SUMMARY_UNITS, UNITS, _alternating_excitation,
                            _constant_torque, _holds, alternating_scene, check_cycles,
                            cycle_response, static_holding_band)

__all__ = ["position_holding", "plot_position_holding"]


def position_holding(
    scene: Any,
    amplitude: Optional[float] = None,
    frequency: Optional[float] = None,
    static_force: Optional[float] = None,
    cycles: int = 8,
    settle_cycles: int = 1,
    points_per_cycle: int = 200,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    executor=None,
    progress: bool = True,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Static against dynamic position holding (thesis Fig. 5.4).

    Two runs of the scene, both with its (constant) drive torque and the nut
    starting in the middle of the backlash: under the static axial force
    ``static_force``, and under the alternating axial force
    ``amplitude sin(2 pi f t)`` without static part.

    The excitation follows the rule of every study (:mod:`leadscrew.studies`):
    an argument given overrides, the scene's own load is the default: here
    the amplitude and frequency of the scene's ``loads.axial_force`` if it
    is a sine (not its phase and offset: the force is purely alternating),
    else 30 N and 20 Hz.

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict) with a constant
            ``loads.drive_torque`` and, for flight, a backlash section.
        amplitude: amplitude of the alternating axial force [N], > 0
            (default: that of the scene's axial force if it is a sine, else
            30 N; ``attrs["summary"]["excitation_from"]`` says which was used).
        frequency: its frequency [Hz], > 0 (default: the scene's sine's,
            else 20 Hz).
        static_force: static axial force along +x [N] (default ``-amplitude``:
            the alternating force's peak, held statically).
        cycles: excitation cycles simulated (both runs last cycles / f).
        settle_cycles: cycles before the creep fit.
        points_per_cycle: output points per cycle.
        rtol, atol: integration tolerances (relative [1], absolute [SI];
            default the scene's [simulation] ones, else simulate's, 1e-8 and
            1e-10; not with integrator "moreau").
        executor: a :class:`concurrent.futures.Executor` on which the two
            runs go, at once (default: the calling thread, one after the
            other: each takes milliseconds; a Dask client's executor runs
            them on the cluster).
        progress: True or False, checked as by every study; two runs show no
            bar.
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        DataFrame with ``t`` [s], ``axial_force_static``, ``u_load_static``,
        ``axial_force_dynamic`` [N], ``u_load_dynamic`` [m],
        ``phi_drive_dynamic`` [rad] and ``gap_dynamic`` [m] (with backlash).
        ``attrs["summary"]``: closed form ``self_locking`` (tan a < mu',
        eq. 3.5), ``holding_torque`` [N*m], ``static_band_low`` and
        ``static_band_high`` [N*m] (:func:`static_holding_band` under
        ``static_force``), ``holds_statically`` (the torque inside the band);
        from the
        simulations ``static_creep_per_cycle``, ``static_max_displacement``,
        ``dynamic_creep_per_cycle``, ``dynamic_max_displacement`` [m],
        ``dynamic_separations`` [1], ``dynamic_flight_fraction`` [1] (see
        :func:`cycle_response`), ``amplitude`` [N], ``frequency`` [Hz],
        ``excitation_from`` (``"arguments"``; ``"scene"`` or ``"defaults"``
        if amplitude or frequency was not given), ``static_force`` [N].

    Raises:
        ValueError: invalid scene or arguments (a time-varying or
            speed-controlled drive).
        TypeError: an unknown keyword in ``simulate_options``.
        SimulationError, JammingError: a simulation failed.
    """
    progress = shown(progress)
    scene = as_scene(scene)
    torque = _constant_torque(scene)
    amplitude, frequency, excitation_from = _alternating_excitation(scene, amplitude, frequency)
    static_force = -amplitude if static_force is None else check_finite("static_force",
                                                                         static_force, unit="N")
    cycles, settle_cycles, points_per_cycle = check_cycles(cycles, settle_cycles,
                                                           points_per_cycle)
    options = with_tolerances(simulate_options, rtol, atol)
    check_simulate_options(scene, options, cycles / frequency)
    centred = scene.replace(initial=dict(_AT_REST, play_position=0.0))
    runs = [centred.replace(loads={"axial_force": static_force}),
            alternating_scene(scene, amplitude, frequency)]
    arguments = (frequency, cycles, settle_cycles, points_per_cycle)
    if executor is None:  # in turn: a failed static run ends the study
        static, dynamic = [cycle_response(run, *arguments, series=True, **options)
                           for run in runs]
    else:
        # Each future's result() raises its run's own exception (SimulationError, ...).
        futures = [executor.submit(cycle_response, run, *arguments, series=True, **options)
                   for run in runs]
        try:
            static, dynamic = [future.result() for future in futures]
        except BaseException:  # one run failed: the other is not waited for
            for future in futures:
                future.cancel()
            raise
    s, d = static["result"], dynamic["result"]
    frame = pd.DataFrame({
        "t": static["t"],
        "axial_force_static": s["axial_force"],
        "u_load_static": s["u_load"],
        "axial_force_dynamic": d["axial_force"],
        "u_load_dynamic": d["u_load"],
        "phi_drive_dynamic": d["phi_drive"],
    })
    if "gap" in d:
        frame["gap_dynamic"] = d["gap"]
    self_locking = bool(is_self_locking(scene.thread, scene["friction"]["mu"]))
    band = static_holding_band(scene, static_force)
    return annotate(
        frame, UNITS, summary_units=SUMMARY_UNITS,
        self_locking=self_locking,
        holding_torque=torque,
        static_band_low=float(band[0]),
        static_band_high=float(band[1]),
        holds_statically=_holds(band, torque, static_force),
        static_creep_per_cycle=static["creep_per_cycle"],
        static_max_displacement=static["max_displacement"],
        dynamic_creep_per_cycle=dynamic["creep_per_cycle"],
        dynamic_max_displacement=dynamic["max_displacement"],
        dynamic_separations=dynamic["separations"],
        dynamic_flight_fraction=dynamic["flight_fraction"],
        amplitude=amplitude,
        frequency=frequency,
        excitation_from=excitation_from,
        static_force=static_force,
    )


def plot_position_holding(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw the load position [mm] under static and alternating load (Fig. 5.4).

    Args:
        frame: the DataFrame :func:`position_holding` returned.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes.
    """
    ax = axes(ax)
    ax.plot(frame["t"], frame["u_load_static"] * 1e3, "-", label="static axial force")
    ax.plot(frame["t"], frame["u_load_dynamic"] * 1e3, "--", label="alternating axial force")
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("load position u [mm]")
    ax.legend(loc="best")
    return ax
