"""Batches of drive simulations run in C++ (``leadscrew._core.DriveBatch``).

A sweep whose cases differ only in a few scalar parameters of one scene (the
friction coefficient, a constant load, ...) need not build a Scene, a model
and a Result per case in Python: :class:`DriveBatch` holds the scene's
resolved parameters once, and :meth:`DriveBatch.run` sends a whole chunk of
cases (one row of parameter values each) to the core, which simulates them
with the GIL released, on the calling thread or on ``workers`` threads of
its own, and returns only the requested channels at the requested times. A
case that fails becomes its row's error message, as
:func:`leadscrew.studies._sweep.run_cases` gives it (``"ExceptionType:
message"``), and its samples are NaN.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .. import _core
from .._hints import did_you_mean
from ..errors import JammingError, SimulationError
from ..scene import Scene
from ..simulation import (ADAPTIVE_OPTIONS, MOREAU_OPTIONS, _OPTION_DEFAULTS,
                          _check_scene_friction, _drive_arguments, _choose_integrator,
                          _stored_option_errors, scene_options)
from ._common import check_count

__all__ = ["DriveBatch", "check_simulate_options"]

# The exception a failure kind of the core stands for (the name its message
# carries, as a per-case simulate() call would have raised it).
_EXCEPTION_NAMES = {"invalid_argument": ValueError.__name__,
                    "simulation": SimulationError.__name__,
                    "jamming": JammingError.__name__,
                    "other": RuntimeError.__name__}


def _core_arguments(scene: Scene, t_end: float, t_eval: Sequence[float],
                    options: Dict[str, Any]) -> Dict[str, Any]:
    """The core's simulation arguments from :func:`leadscrew.simulate`'s
    keywords, with its defaults (as simulate passes them for a Scene).

    Raises:
        TypeError: an unknown keyword (or ``t_eval``, which the batch sets).
        ValueError: ``friction`` or ``k_v`` differs from the scene's
            (``friction.law``, ``friction.k_v``), or the integrator would
            ignore an option given (as simulate refuses it).
    """
    # A lookup rather than inspect's Signature.bind (~15 us: a tenth of the
    # Python around a fast sweep).
    unknown = [name for name in options if name not in _OPTION_DEFAULTS]
    if unknown:
        valid = [name for name in _OPTION_DEFAULTS if name != "t_eval"]
        raise TypeError(f"got an unexpected keyword argument {unknown[0]!r}"
                        f"{did_you_mean(unknown[0], valid)} (the options are those of "
                        f"leadscrew.simulate, but t_eval)")
    # (the scene's [simulation] options where these leave one out, as simulate)
    options, stored = scene_options(scene, options)
    a = dict(_OPTION_DEFAULTS, **options)
    _check_scene_friction(scene, a["friction"], a["k_v"])
    with _stored_option_errors(stored):
        arguments = _drive_arguments(
            t_end, a["integrator"], a["smooth_integrator"], a["rtol"], a["atol"], a["dt"],
            a["theta"], np.asarray(t_eval, dtype=float).ravel().tolist(), a["max_steps"],
            a["max_events"], a["max_step"], a["first_step"], a["bounce_threshold"],
            a["max_order"], a["check"])
        given = {name: options.get(name) for name in (*ADAPTIVE_OPTIONS, *MOREAU_OPTIONS,
                                                      "bounce_threshold")}
        arguments["integrator"] = _choose_integrator(
            arguments["integrator"], lambda: _core.drive_integrators(scene.model().parameters),
            given, scene)
    return arguments


def check_simulate_options(scene: Scene, options: Dict[str, Any], t_end: float) -> None:
    """Check :func:`leadscrew.simulate`'s keywords for a study's simulations
    of ``scene``, once, before they run (otherwise every case fails alike and
    the sweep returns rows of the same message).

    Args:
        scene: the scene the cases vary (their concept, friction law and
            backlash contact decide which integrators fit).
        options: the keywords (``rtol``, ``integrator``, ``max_steps``, ...;
            not ``t_eval``, which the study sets).
        t_end: the shortest case's end time [s], > 0 (Moreau's fixed steps
            over it are counted against ``max_steps``: a case too long for
            them fails on its own, but one this short fails in every case).

    Raises:
        TypeError: an unknown keyword.
        ValueError: a value of the wrong kind or out of range, or an
            integrator that does not fit the scene (naming the option, the
            value and what is valid).
    """
    arguments = _core_arguments(scene, t_end, [], options)
    with _stored_option_errors(scene_options(scene, options)[1]):
        _core.check_drive_options(scene.model(), **arguments)


class DriveBatch:
    """Simulations of one scene that differ in a few scalar parameters.

    Args:
        scene: the base :class:`~leadscrew.Scene`; its parameters apply
            wherever a case does not set them.
        parameters: names of the fields each case sets, one column of the
            values each: ``"mu"``, ``"axial_force"`` (a constant [N]),
            ``"drive_torque"`` [N*m] or ``"drive_speed"`` [rad/s] (constants,
            the one the scene's motor takes), ``"rotor_speed"``, ... (any
            numeric attribute of ``leadscrew._core.DriveParameters``, in SI).
            They are set as given: values the Scene derives from them (e.g. a
            default damping from a mass) keep the base scene's, so vary only
            fields nothing else follows.
        channels: names of the result channels to sample (see
            :class:`leadscrew.Result`).
        t_end: simulated time [s], > 0.
        t_eval: the sample times [s], non-empty, within [0, t_end].
        **simulate_options: as :func:`leadscrew.simulate` (``rtol``,
            ``integrator``, ``max_steps``, ...).

    Raises:
        TypeError: an unknown keyword.
        ValueError: the scene's model is invalid, ``friction`` or ``k_v``
            is not the scene's (``friction.law``, ``friction.k_v``), a
            parameter name is unknown (the message lists those allowed), or
            ``rotor_speed`` varies for a speed-controlled scene (which
            starts at drive_speed(0)).

    A DriveBatch pickles (as its scene and arguments; a process-based executor
    rebuilds the core parameters once per task).
    """

    def __init__(self, scene: Scene, parameters: Sequence[str], channels: Sequence[str],
                 t_end: float, t_eval: Sequence[float], **simulate_options: Any):
        self._scene = scene
        self._parameters = [str(name) for name in parameters]
        if "rotor_speed" in self._parameters and "drive_speed" in scene["loads"]:
            # as the scene refuses initial.rotor_speed other than drive_speed(0)
            raise ValueError("parameters entry 'rotor_speed' is invalid for a speed-controlled "
                             "scene (loads.drive_speed): it starts at drive_speed(0); vary "
                             "drive_speed instead")
        self._channels = [str(name) for name in channels]
        self._options = dict(simulate_options)
        self._arguments = _core_arguments(scene, t_end, t_eval, self._options)
        with _stored_option_errors(scene_options(scene, self._options)[1]):
            self._core = _core.DriveBatch(scene.model().parameters, self._parameters,
                                          self._channels, **self._arguments)

    def __reduce__(self):
        return (_restore_batch, (self._scene, self._parameters, self._channels,
                                 self._arguments["t_end"], self._arguments["t_eval"],
                                 self._options))

    @property
    def parameters(self) -> List[str]:
        return list(self._parameters)

    @property
    def channels(self) -> List[str]:
        return list(self._channels)

    def run(self, values: Any, workers: int = 1
            ) -> Tuple[np.ndarray, List[Optional[str]], np.ndarray]:
        """Simulate one case per row of ``values`` (one column per parameter).

        Args:
            values: (cases, parameters) array of the parameters' values [SI].
            workers: threads of the core that share the rows, an integer >= 1
                (at most one per row is started; 1: the calling thread only).
                Each thread takes the next row when it is free, so cheap and
                costly cases balance; every row is the same for any count
                (but the message of an exception that a Python-callable load
                raised lists the Python frames of the thread that called it).

        Returns:
            ``(samples, errors, wall_time)``: samples (cases, channels,
            sample times), NaN for a failed case; errors, one per case: None
            or ``"ExceptionType: message"``; wall_time (cases,) [s], each
            simulation's C++ clock (NaN for a failed case).

        Raises:
            ValueError: ``values`` has the wrong number of columns, or
                ``workers`` is not an integer >= 1.
        """
        workers = check_count("workers", workers, 1)
        values = np.asarray(values, dtype=float)
        if values.ndim != 2 or values.shape[1] != len(self._parameters):
            raise ValueError(f"values has shape {values.shape}: must be (cases, "
                             f"{len(self._parameters)})")
        # The core starts at most one thread per row; capping here also keeps
        # a huge count within its int.
        result = self._core.run(values, min(workers, max(1, len(values))))
        if result.failure_count == 0:  # the usual case: no failure names to convert
            errors: List[Optional[str]] = [None] * len(values)
        else:
            errors = [None if kind == "none" else f"{_EXCEPTION_NAMES[kind]}: {message}"
                      for kind, message in zip(result.failures, result.messages)]
        return result.samples, errors, result.wall_time


def _restore_batch(scene, parameters, channels, t_end, t_eval, options) -> DriveBatch:
    return DriveBatch(scene, parameters, channels, t_end, t_eval, **options)
