"""Scenes shipped with leadscrew, as TOML scene files.

- ``default``: a small motor-driven trapezoidal lead screw (Tr 10x2) lifting a
  2 kg slide under an alternating torque; rigid model, exact Coulomb friction.
- ``thesis_table_5_1``: the thesis's Table 5.1 drive with load case (5.1),
  F = -10 N, M = -40 sin(4 pi t) N*mm, mu = 0.3, flexible screw and nut.
- ``position_holding``: the thesis's section 5.2 case: the same drive with
  0.2 mm axial play (a BISTOP penalty contact), no axial preload, a static
  5 N*mm drive torque that only the thread holds, and a 50 N, 20 Hz
  alternating axial force; flexible screw and nut with exact Coulomb friction
  (the thesis's Adams model regularized it: the file says how to get its
  arctan law) and its run's tolerance stored with it (``[simulation] rtol =
  1e-6``). In flight across the play the torque turns the screw and the load
  creeps.
- ``seat_adjuster``: a power-seat longitudinal adjuster: a 12 V DC motor
  turning, through a 5:1 stage, the POM nut of a Tr 8x1.5 steel spindle with
  0.1 mm play; a 90 kg seat between penalty end stops 240 mm apart, 10 mm from
  its rear stop; flexible spindle and nut, exact Coulomb friction with
  mu_static. (Its stage is ideal: the worm stage runs on the rigid concept without play
  only.)
- ``seat_adjuster_worm``: the same seat adjuster with its real reduction on the
  rigid concept without play: a self-locking 10:1 worm stage, the motor's own
  friction, a spindle turned by the worm wheel, penalty end stops; the seat
  runs 5 mm into its rear stop, where the motor stalls and the thread clamps.

Each file states in its comments where every value comes from. Use them as
templates: ``leadscrew.scenes.path(name)`` is the file.

Example::

    import leadscrew as ls
    scene = ls.scenes.load("thesis_table_5_1")
    result = ls.simulate(scene.replace(concept="rigid"), 2.0)
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path
from typing import List

from ..scene import Scene, _from_toml_text

__all__ = ["available", "load", "path"]

_SUFFIX = ".toml"


def available() -> List[str]:
    """The names of the shipped scenes, sorted (e.g. ``"default"``)."""
    return sorted(entry.name[: -len(_SUFFIX)] for entry in resources.files(__name__).iterdir()
                  if entry.name.endswith(_SUFFIX))


def _resource(name: str):
    stem = name[: -len(_SUFFIX)] if name.endswith(_SUFFIX) else name
    names = available()
    if stem not in names:
        raise ValueError(f"scene name = {name!r} is invalid: the shipped scenes are "
                         f"{', '.join(names)}")
    return resources.files(__name__).joinpath(stem + _SUFFIX)


def path(name: str) -> Path:
    """The file of a shipped scene.

    Args:
        name: a name from :func:`available` (``".toml"`` may be appended).

    Returns:
        Its path (a file inside the installed package).

    Raises:
        ValueError: no shipped scene has that name (the message lists them).
    """
    return Path(str(_resource(name)))


def load(name: str) -> Scene:
    """Read a shipped scene.

    Args:
        name: a name from :func:`available` (``".toml"`` may be appended).

    Returns:
        The validated :class:`~leadscrew.Scene`.

    Raises:
        ValueError: no shipped scene has that name (the message lists them).
    """
    resource = _resource(name)
    return _from_toml_text(resource.read_bytes(), str(resource))
