"""Studies: parameter sweeps over :func:`leadscrew.simulate` that return a
pandas DataFrame and draw a diagram (thesis chapters 3 and 5).

``STUDIES`` maps each study's name to its function (the command line and
notebooks look studies up there). Sweeps take ``executor=`` (any
``concurrent.futures.Executor``; default a thread pool over all cores, the
C++ core releasing the GIL) and ``progress=`` (a tqdm bar).

One rule for the loads of every study: the scene's own loads are the
default, and a study argument that gives an excitation overrides them.
``stick_slip``, ``compare_concepts`` and ``work_precision`` run the scene's
loads as they are; ``position_holding`` and the creep studies take the
amplitude (and, where they do not sweep it, the frequency) of the scene's
alternating axial force, a sine ``loads.axial_force`` (30 N and 20 Hz for a
scene without one), unless ``amplitude=`` / ``frequency=`` give them;
``min_holding_preload`` takes the whole sine (amplitude, omega, phase,
offset) unless ``excitation=`` gives one; ``efficiency_vs_mu`` replaces the
loads by its definition (a speed-controlled motor raising each of its
``loads``); ``motor_characteristics`` runs the scene's DC motor (section
``motor``, a constant voltage) raising each of its ``loads``;
``preload_tradeoff`` raises the scene's static load and vibrates it with the
scene's sine (30 N and 20 Hz without one) for each preload; ``end_stop_jam``
runs the scene's constant drive torque or DC motor into its end stop and
reverses it; ``holding_under_vibration`` takes the scene's load at its
``where`` (default ``loads.base_acceleration``) unless ``excitation=``
gives one, realised once per seed if it is random. Where a study may take its excitation from either,
``attrs["summary"]["excitation_from"]`` says where it came from:
``"arguments"``, ``"scene"`` or ``"defaults"``.

One rule for cases that raise (a :class:`~leadscrew.JammingError`, a
:class:`~leadscrew.SimulationError`, ...): the case's row carries the
message (``error``; work_precision's ``failure``) and decides nothing; every
study that aggregates rows counts them in ``attrs["summary"]`` (``raised``,
and ``raised_reasons``: the exception types with their counts and the first
message, or ``"none"``) and warns with :class:`~leadscrew.StudyWarning`.

The holding and creep studies start every run at rest (their scenes'
``initial`` section does not decide); :func:`min_holding_preload` starts
each from the static equilibrium under the loads at t = 0.

Arguments with a unit (an amplitude [N], frequencies [Hz], loads [N], a
speed [rad/s], times [s], clearances [m], a sine ``excitation``'s values)
take SI numbers or, as a scene's fields, strings with units (``"20 N"``,
``["5 Hz", "10 Hz"]``, ``"100 rpm"``, ``{"type": "sine", "amplitude": "20 N",
"omega": "10 Hz"}``), converted by :func:`leadscrew.units.to_si`; a string of
another dimension raises ``ValueError`` naming the argument.

Each study has a ``plot_...`` function drawing its figure from the frame it
returned (``leadscrew study`` writes it as a PNG beside the CSV);
:func:`plot` draws any study's frame with its own.
"""

import functools
import pathlib
from typing import Optional

from . import concepts as _concepts
from . import creep as _creep
from . import drive_efficiency as _drive_efficiency
from . import end_stop as _end_stop
from . import holding as _holding
from . import motor as _motor
from . import preload as _preload
from . import stickslip as _stickslip
from . import vibration as _vibration
from . import work_precision as _work_precision_module
from ..files import writing
from ._sweep import SerialExecutor
from .concepts import CONCEPTS, compare_concepts, plot_compare_concepts
from .creep import creep_map, creep_vs_backlash, creep_vs_frequency, plot_creep, plot_creep_map
from .drive_efficiency import efficiency_vs_mu, plot_efficiency_vs_mu
from .end_stop import end_stop_jam, plot_end_stop_jam
from .motor import motor_characteristics, plot_motor_characteristics
from .preload import (lift_off_spring_force, plot_preload_tradeoff, preload_tradeoff,
                      preloaded_holding_band)
from .holding import (
    alternating_scene,
    cycle_response,
    min_holding_preload,
    plot_min_holding_preload,
    plot_position_holding,
    position_holding,
    static_holding_band,
)
from .stickslip import plot_stick_slip, stick_slip, stick_slip_phases
from .vibration import SCATTER_KEYS, holding_under_vibration, plot_holding_under_vibration
from .work_precision import (
    ATOL_PER_RTOL,
    COLUMNS,
    CONFIGURATION_KEYS,
    REFERENCE_OPTIONS,
    default_configurations,
    exact_reference,
    plot_work_precision,
    work_precision,
)

#: Each study's figure: a function ``plot(frame, ax)`` drawing the frame
#: the study returned (``leadscrew study`` writes it beside the CSV).
PLOTS = {
    "work_precision": plot_work_precision,
    "stick_slip": plot_stick_slip,
    "compare_concepts": plot_compare_concepts,
    "position_holding": plot_position_holding,
    "creep_vs_frequency": functools.partial(plot_creep, x="frequency"),
    "creep_vs_backlash": functools.partial(plot_creep, x="backlash"),
    "creep_map": plot_creep_map,
    "min_holding_preload": plot_min_holding_preload,
    "efficiency_vs_mu": plot_efficiency_vs_mu,
    "motor_characteristics": plot_motor_characteristics,
    "preload_tradeoff": plot_preload_tradeoff,
    "end_stop_jam": plot_end_stop_jam,
    "holding_under_vibration": plot_holding_under_vibration,
}


def save_figure(name: str, frame, path, title: Optional[str] = None,
                dpi: int = 110) -> Optional[pathlib.Path]:
    """Draw a study's figure (:data:`PLOTS`) and write it to ``path``.

    The figure is a :class:`matplotlib.figure.Figure` of its own, written by
    matplotlib's Agg renderer: no pyplot state, no display needed.

    Args:
        name: the study's name in :data:`STUDIES`.
        frame: the DataFrame the study returned.
        path: the file to write; its suffix picks the format (``.png``).
        title: the figure's title (default none).
        dpi: resolution [dots per inch].

    Returns:
        The path written, or None for a study without a figure in :data:`PLOTS`.
    """
    plot = PLOTS.get(name)
    if plot is None:
        return None
    from matplotlib.figure import Figure

    figure = Figure(figsize=(8.0, 5.0), layout="constrained")
    plot(frame, ax=figure.subplots())
    if title:
        figure.suptitle(title, fontsize="medium")
    with writing(path) as temporary:
        figure.savefig(temporary, dpi=dpi)
    return pathlib.Path(path)


def _tagged(name: str, function):
    """``function`` whose frame says which study made it (``attrs["study"]``,
    which :func:`plot` reads)."""
    @functools.wraps(function)
    def study(*args, **kwargs):
        frame = function(*args, **kwargs)
        frame.attrs["study"] = name
        return frame

    return study


STUDIES = {name: _tagged(name, function) for name, function in {
    "work_precision": work_precision,
    "stick_slip": stick_slip,
    "compare_concepts": compare_concepts,
    "position_holding": position_holding,
    "creep_vs_frequency": creep_vs_frequency,
    "creep_vs_backlash": creep_vs_backlash,
    "creep_map": creep_map,
    "min_holding_preload": min_holding_preload,
    "efficiency_vs_mu": efficiency_vs_mu,
    "motor_characteristics": motor_characteristics,
    "preload_tradeoff": preload_tradeoff,
    "end_stop_jam": end_stop_jam,
    "holding_under_vibration": holding_under_vibration,
}.items()}
# The studies under their names are the tagged ones: a frame of any of them
# plots with plot(frame).
globals().update(STUDIES)


def plot(frame, ax=None):
    """Draw a study's frame: the figure of the study that returned it
    (:data:`PLOTS`), e.g. ``ls.studies.plot(ls.studies.efficiency_vs_mu(scene,
    mu, loads))``.

    Args:
        frame: a DataFrame a study of :data:`STUDIES` returned (its
            ``attrs["study"]`` names the study).
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes drawn on.

    Raises:
        ValueError: a frame no study returned, or of a study without a figure.
    """
    name = getattr(frame, "attrs", {}).get("study")
    if name not in PLOTS:
        raise ValueError(f"frame is invalid: it is none of a study's frames with a figure "
                         f"(attrs['study'] = {name!r}; the studies are {', '.join(PLOTS)})")
    return PLOTS[name](frame, ax=ax)


__all__ = [
    "STUDIES",
    "PLOTS",
    "save_figure",
    "plot",
    "SerialExecutor",
    *_work_precision_module.__all__,
    *_stickslip.__all__,
    *_concepts.__all__,
    *_holding.__all__,
    *_creep.__all__,
    *_drive_efficiency.__all__,
    *_motor.__all__,
    *_preload.__all__,
    *_end_stop.__all__,
    *_vibration.__all__,
]
