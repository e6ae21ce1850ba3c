"""Named random-vibration profiles of the vehicle body.

``profiles.load(name, seed=..., duration=...)`` gives a
:class:`~leadscrew.RandomVibration` (an axial acceleration in m/s^2, for
``loads.base_acceleration``); ``profiles.names()`` lists them and
``profiles.info(name)`` gives each one's source and whether its table was
checked against that source.

A profile whose table could not be checked against the text of its source
is shipped with ``verified=False``: loading it warns (:class:`ProfileWarning`)
and its note says what is known to be uncertain. Check its breakpoints
against your copy of the standard before relying on a verdict it gives.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Dict, List, Tuple

from .excitation_sampled import RandomVibration

__all__ = ["Profile", "ProfileWarning", "names", "info", "checked", "load"]


class ProfileWarning(UserWarning):
    """A profile's table was not checked against its source."""


@dataclass(frozen=True)
class Profile:
    """A random-vibration profile: breakpoints and where they come from.

    Attributes:
        name: its key for :func:`load`.
        title: what it describes.
        frequencies: breakpoints [Hz].
        psd: the acceleration PSD at them [(m/s^2)^2/Hz].
        source: the standard (edition, clause or table).
        verified: whether the table was checked against that source's text.
        note: what a user must know (the check's outcome, its gaps).
    """

    name: str
    title: str
    frequencies: Tuple[float, ...]
    psd: Tuple[float, ...]
    source: str
    verified: bool
    note: str


_PROFILES: Dict[str, Profile] = {
    p.name: p for p in (
        Profile(
            name="iso16750_3_test_iv",
            title="passenger car, sprung masses (vehicle body), random vibration",
            frequencies=(10.0, 55.0, 180.0, 300.0, 360.0, 1000.0, 2000.0),
            psd=(20.0, 6.5, 0.25, 0.25, 0.14, 0.14, 0.14),
            source="ISO 16750-3 (Road vehicles - Environmental conditions and testing for "
                   "electrical and electronic equipment - Part 3: Mechanical loads), "
                   "Test IV, passenger car, sprung masses (vehicle body)",
            verified=False,
            note="breakpoints as widely reproduced, not checked against the standard's text "
                 "(which could not be consulted): log-log integrated they give an RMS of "
                 "30.2 m/s^2, where 27.8 m/s^2 is the RMS quoted with this test; one of the "
                 "two is misremembered. Check the table against your copy of ISO 16750-3."),
    )
}


def names() -> List[str]:
    """The profiles' names, sorted."""
    return sorted(_PROFILES)


def info(name: str) -> Profile:
    """A profile's table and source.

    Raises:
        ValueError: naming ``name`` and the profiles there are.
    """
    if name not in _PROFILES:
        raise ValueError(f"name = {name!r} is invalid: must be one of "
                         f"{', '.join(map(repr, names()))}")
    return _PROFILES[name]


def checked(name: str, stacklevel: int = 2) -> Profile:
    """A profile's table, with a :class:`ProfileWarning` if it is unverified.

    Raises:
        ValueError: an unknown name (as :func:`info`).
    """
    profile = info(name)
    if not profile.verified:
        warnings.warn(f"profile {name!r} is not verified against {profile.source}: "
                      f"{profile.note}", ProfileWarning, stacklevel=stacklevel)
    return profile


def load(name: str, seed: int = 0, duration: float = 10.0) -> RandomVibration:
    """A realisation of a named profile, an acceleration in m/s^2.

    Args:
        name: one of :func:`names`.
        seed: the phases' seed (an integer in [0, 2^53]).
        duration: the realisation's period [s] (or a string with a unit).

    Returns:
        A :class:`~leadscrew.RandomVibration` with unit ``"m/s^2"``.

    Raises:
        ValueError: an unknown name, an invalid seed or duration.

    Warns:
        ProfileWarning: the profile's table is not verified against its source.
    """
    profile = checked(name, stacklevel=3)
    psd = [f"{value!r} (m/s^2)^2/Hz" for value in profile.psd]
    return RandomVibration(list(profile.frequencies), psd, seed=seed, duration=duration)
