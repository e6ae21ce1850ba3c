"""The nearest valid name for a misspelled one, in every message that
refuses a name (a scene key or section, a simulate or study option, a
study)."""

from __future__ import annotations

import difflib
from typing import Iterable

__all__ = ["did_you_mean"]


def did_you_mean(name: str, valid: Iterable[str]) -> str:
    """`` (did you mean 'x'?)`` with the valid name closest to ``name``, or
    ``""`` where none is close (difflib's ratio below 0.6)."""
    close = difflib.get_close_matches(str(name), [str(v) for v in valid], n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""
