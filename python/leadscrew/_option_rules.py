"""The rules of a run's integrator options, shared by :func:`leadscrew.simulate`,
the study batches, the command line and the Scene's [simulation] section:
which options each integrator takes, which option names a scheme where the
integrator is left to the default, which integrator runs, and the options a
scene stores for its runs. (Split from simulation.py: the option rules
apart from the run.)"""

from __future__ import annotations

import math
from typing import Any, Callable, Dict, Optional, Sequence, Tuple

import numpy as np

from .scene import SCHEMA, Scene

__all__ = ["ADAPTIVE_OPTIONS", "MOREAU_OPTIONS", "SCENE_OPTIONS", "unused_option",
           "option_conflict", "integrator_taking", "takes_option", "scene_options",
           "check_integrator_name"]


def _scalar(value):
    """A 0-d array as its number (``np.array(1.0)`` is a number here)."""
    return value.item() if isinstance(value, np.ndarray) and value.ndim == 0 else value


#: Options of the adaptive integrators (error and step-size control), which
#: the fixed-step Moreau-Jean scheme does not take.
ADAPTIVE_OPTIONS = ("rtol", "atol", "max_order", "max_step", "first_step")
#: Options of the Moreau-Jean scheme only (its fixed step and theta).
MOREAU_OPTIONS = ("dt", "theta")


def _shown(value) -> str:
    """A value in a message, a float as the core writes one (its
    format_value: the shortest of 12 to 17 significant digits that reads
    back, so that ``-1.0`` is ``-1`` in either's messages); others' repr."""
    value = _scalar(value)
    if not isinstance(value, float):
        return repr(value)
    if not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    for digits in range(12, 18):
        text = f"{value:.{digits}g}"
        if float(text) == value:
            break
    return text


def _play_of(scene: Scene) -> str:
    """The scene's play for messages: "" for an exact backlash (or exact end
    stops), else what it has."""
    if "end_stops" in scene and scene["end_stops"]["contact"] == "exact":
        return ""  # (exact end stops' impacts take it too)
    if "backlash" not in scene:
        return "no backlash"
    contact = scene["backlash"]["contact"]
    return "" if contact == "exact" else f"backlash.contact = {contact!r}"


def unused_option(integrator: str, given: Dict[str, Any], scene: Optional[Scene] = None,
                  spell=str, moreau_only: bool = False) -> Optional[Tuple[str, bool, str]]:
    """The first option given that a run would ignore, and why.

    ``dt`` and ``theta`` are Moreau-Jean's alone; ``rtol``, ``atol``,
    ``max_order``, ``max_step`` and ``first_step`` the other integrators'
    (:data:`ADAPTIVE_OPTIONS`); ``bounce_threshold`` that of a Scene with an
    exact backlash run by ``"event_driven"`` (its plastic impacts). Shared by
    :func:`simulate`, the study batches and the command line.

    Args:
        integrator: the integrator that runs (the model's default resolved).
        given: option name -> value as the caller passed it (None: left out).
        scene: the Scene that runs (None: a FrictionBlock).
        spell: how the caller spells an option in messages (the command
            line: ``--dt``).
        moreau_only: whether the model runs on ``"moreau"`` alone (then no
            other integrator is offered).

    Returns:
        ``(name, of_scene, why)``: the option, whether the scene (True) or
        the integrator (False) leaves it unused, and which integrator or
        scene takes it; None if the run uses every option given.
    """
    if integrator == "moreau":
        for name in ADAPTIVE_OPTIONS:
            if given.get(name) is not None:
                return name, False, (
                    f"moreau is a fixed-step scheme without error or step-size control (its "
                    f"step is {spell('dt')}); " + (
                        f"this scene runs on Moreau-Jean only, so {spell(name)} has no use "
                        f"here: a shorter {spell('dt')} makes the run more accurate"
                        if moreau_only else
                        f"{spell(name)} is taken by the other integrators (event_driven, "
                        "cvode_bdf, ...)"))
    else:
        for name in MOREAU_OPTIONS:
            if given.get(name) is not None:
                return name, False, (f"{spell(name)} is taken by moreau only (the fixed-step "
                                     "Moreau-Jean scheme)")
    if given.get("bounce_threshold") is not None and scene is not None:
        play = _play_of(scene)
        if play:
            return "bounce_threshold", True, (
                f"it has {play}, and {spell('bounce_threshold')} is taken by a Scene with an "
                "exact backlash (backlash.contact = 'exact') only, whose flank impacts it "
                "makes plastic")
        if integrator == "moreau":
            return "bounce_threshold", False, (
                f"{spell('bounce_threshold')} is taken by integrator 'event_driven' only "
                "(Moreau-Jean has no impact events)")
    return None


def option_conflict(given: Dict[str, Any], spell=str, equals: str = " = ") -> Optional[str]:
    """Why options given together conflict, whatever integrator runs: one of
    Moreau-Jean's (:data:`MOREAU_OPTIONS`) beside one of the adaptive
    integrators' (:data:`ADAPTIVE_OPTIONS`), which no integrator takes both
    of. The one rule for options left to the default integrator, shared by
    :func:`simulate` (through :func:`_choose_integrator`), the study
    batches, the command line and the Scene's ``[simulation]`` section.

    Args:
        given: option name -> value (None: left out).
        spell: how the caller spells an option (``--dt``, ``simulation.dt``).
        equals: what stands between a name and its value (the command
            line's ``" "``).

    Returns:
        The message naming both options with their values and the scheme
        each belongs to; None where they do not conflict.
    """
    # (Plain loops, Moreau-Jean's first: a run given rtol alone, the common
    # case, returns after two lookups; generators cost 1 us a call here.)
    for moreau in MOREAU_OPTIONS:
        if given.get(moreau) is not None:
            break
    else:
        return None
    for adaptive in ADAPTIVE_OPTIONS:
        if given.get(adaptive) is not None:
            break
    else:
        return None
    shown = [f"{spell(name)}{equals}{_shown(given[name])}" for name in (moreau, adaptive)]
    return (f"{shown[0]} and {shown[1]} conflict: {spell(moreau)} is taken by moreau only "
            f"(the fixed-step Moreau-Jean scheme), {spell(adaptive)} by the adaptive "
            "integrators only (event_driven, cvode_bdf, ...: error and step-size control), "
            f"and none takes both; give one of them, or the integrator "
            f"({spell('integrator')}{equals}{'moreau' if equals == ' ' else _shown('moreau')} "
            f"takes {spell(moreau)}, "
            f"another {spell(adaptive)})")


def check_integrator_name(name: str, key: str = "integrator", shown: Optional[str] = None,
                          fitting: Sequence[str] = ()) -> str:
    """``name`` where it names one of the integrators (:data:`INTEGRATORS
    <leadscrew.scene_schema.INTEGRATORS>`; "" the default), so that a name
    no integrator has is refused as such, listing them all (the core lists
    those that fit a model, as if the name were one that does not).

    Args:
        name: the integrator's name as given.
        key: the option's name in the message.
        shown: the option and its value as the caller writes them (the
            command line's ``--integrator foo``; default ``key = "name"``, as
            the core writes it).
        fitting: the integrators that fit the model, where known (listed).

    Raises:
        ValueError: naming ``key``, the value, the closest name and the
            integrators.
    """
    if not name:  # (the default: every call without one, no import on its path)
        return name
    from .scene_schema import INTEGRATORS

    if name not in INTEGRATORS:
        from ._hints import did_you_mean

        which = (f"; this scene takes {', '.join(fitting)}" if fitting else
                 " (which fit a model depends on its friction law, play and drive train: an "
                 "integrator that does not fit is refused naming those that do)")
        shown = shown or f'{key} = "{name}"'
        raise ValueError(f"{shown} is invalid: no integrator has that "
                         f"name{did_you_mean(name, INTEGRATORS)}; the integrators are "
                         f"{', '.join(INTEGRATORS)}{which}")
    return name


def integrator_taking(allowed: Sequence[str], given: Dict[str, Any],
                      scene: Optional[Scene] = None) -> str:
    """The integrator a run left to its default takes: the default (the
    first of ``allowed``, those that fit the model) unless it would ignore an
    option given (:func:`unused_option`) that another of them takes (``dt``,
    ``theta``: Moreau-Jean's; ``rtol``, ``atol``, ... on a Moreau-Jean
    default: the first adaptive one), so that an option names its scheme;
    the default where none of them uses every option given (it refuses one).
    Shared by :func:`simulate`, the study batches and the command line.
    """
    for candidate in allowed:
        if unused_option(candidate, given, scene,
                         moreau_only=list(allowed) == ["moreau"]) is None:
            return candidate
    return allowed[0]


def _choose_integrator(integrator: str, integrators: Callable[[], Sequence[str]],
                       given: Dict[str, Any], scene: Optional[Scene] = None) -> str:
    """The integrator that runs: ``integrator`` where given, else
    (``integrator`` "": the default) :func:`integrator_taking` among
    ``integrators()``, those that fit the model (called only if an option is
    given: without one it returns ""); "" where that is the model's default
    (the core resolves it, for each case of a batch its own). Raises if it would ignore an option
    given (:func:`unused_option`); an integrator not among them is left to
    the core, which lists those that fit.

    Raises:
        ValueError: naming the option, its value, the integrator and which
            integrator or scene takes the option; left to the default, two
            options no integrator takes together (:func:`option_conflict`).
    """
    for value in given.values():
        if value is not None:
            break
    else:  # nothing given (the common case: no lookup)
        return integrator
    conflict = None if integrator else option_conflict(given)
    if conflict is not None:
        raise ValueError(conflict)
    allowed = integrators()
    runs = integrator or integrator_taking(allowed, given, scene)
    if runs not in allowed:
        return integrator
    unused = unused_option(runs, given, scene, moreau_only=list(allowed) == ["moreau"])
    if unused is not None:
        name, of_scene, why = unused
        which = ("for this Scene" if of_scene else f"with integrator {runs!r}"
                 + ("" if integrator else " (the default here)"))
        raise ValueError(f"{name} = {_shown(given[name])} is invalid {which}: {why}")
    # (The default itself stays "": the core resolves it for each model, so
    # a batch's cases each take their own, as without options.)
    return integrator or ("" if runs == allowed[0] else runs)


#: The run's options a scene may store in its ``[simulation]`` section
#: (simulate's keywords of the same names).
SCENE_OPTIONS = tuple(SCHEMA["simulation"])


def takes_option(integrator: str, name: str) -> bool:
    """Whether a run on ``integrator`` takes the option ``name`` at all
    (``dt``, ``theta``: Moreau-Jean alone; :data:`ADAPTIVE_OPTIONS` and
    ``bounce_threshold``: the others; ``smooth_integrator``: "event_driven"
    alone)."""
    if name == "smooth_integrator":
        return integrator == "event_driven"
    if integrator == "moreau":
        return name not in ADAPTIVE_OPTIONS and name != "bounce_threshold"
    return name not in MOREAU_OPTIONS


def scene_options(scene: Scene, given: Dict[str, Any]) -> Tuple[Dict[str, Any], Tuple[str, ...]]:
    """The options a run of ``scene`` takes: those given, and for each left
    out (None) the scene's own (its ``[simulation]`` section), so that an
    option given overrides the scene's. Where ``integrator`` is given, the
    scene's options that integrator does not take (:func:`takes_option`:
    the scene's ``rtol`` under ``integrator="moreau"``, its ``dt`` under
    another) are left out: they were the scene's settings of another
    scheme. So are they where an option given names the other scheme
    without an integrator (``dt`` given: the scene's ``rtol`` and ``atol``
    give way, as ``dt`` names Moreau-Jean). Shared by :func:`simulate`, the study batches and the command
    line, so that one rule holds.

    Args:
        scene: the Scene that runs.
        given: option name -> value as the caller passed it (None: left
            out); any of :data:`SCENE_OPTIONS` (others are passed through).

    Returns:
        ``(options, stored)``: the options with the scene's filled in, and
        the names of those taken from the scene (their errors name
        ``simulation.<name>``: :func:`_stored_option_errors`).
    """
    stored = scene._data.get("simulation")
    if not stored:
        return dict(given), ()
    options, taken = dict(given), []
    chosen = given.get("integrator")
    if not chosen:  # (an option given names its scheme: the other's stored give way)
        if any(given.get(name) is not None for name in MOREAU_OPTIONS):
            chosen = "moreau"
        elif any(given.get(name) is not None for name in ADAPTIVE_OPTIONS):
            chosen = "event_driven"
    for name, value in stored.items():
        if options.get(name) is not None or (chosen and not takes_option(chosen, name)):
            continue
        options[name] = value
        taken.append(name)
    return options, tuple(taken)


class _stored_option_errors:
    """Rewrites a ValueError about an option taken from the scene's
    ``[simulation]`` section (its message starts ``"<name> = "``) to name
    its key path, ``simulation.<name>``, and how to override it."""

    def __init__(self, stored: Sequence[str]):
        self._stored = stored

    def __enter__(self):
        return self

    def __exit__(self, kind, error, traceback):
        if kind is None or not issubclass(kind, ValueError) or type(error) is not ValueError:
            return False
        text = str(error)
        for name in self._stored:
            if text.startswith(f"{name} = "):
                raise ValueError(f"simulation.{text} (the scene's [simulation] section; "
                                 f"simulate's {name}=... overrides it)") from None
        return False
