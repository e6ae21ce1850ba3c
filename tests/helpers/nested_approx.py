"""``pytest.approx`` for the nested values a scene holds (a load's dict with
its ``"type"`` string, a table's lists of times and values).

``pytest.approx`` compares numbers, and sequences or mappings of numbers;
from pytest 9 on it refuses a mapping that holds a string or a list
(``TypeError``), which is what a scene's excitation is. :func:`nested_approx`
puts ``pytest.approx`` on each number (and each list of numbers) of the
expected value and keeps every other leaf as it is, so that ``given ==
nested_approx(expected)`` compares strings, booleans and keys exactly and
numbers to the tolerance, on every pytest version.
"""

from __future__ import annotations

from numbers import Number
from typing import Any

import pytest

__all__ = ["nested_approx"]


def nested_approx(expected: Any, **tolerance: Any) -> Any:
    """``expected`` with ``pytest.approx(number, **tolerance)`` in place of
    each number (booleans and strings kept), recursively through dicts,
    lists and tuples (a list stays a list: ``[approx, ...] == [1.0, ...]``)."""
    if isinstance(expected, bool) or isinstance(expected, str):
        return expected
    if isinstance(expected, Number):
        return pytest.approx(expected, **tolerance)
    if isinstance(expected, dict):
        return {key: nested_approx(value, **tolerance) for key, value in expected.items()}
    if isinstance(expected, (list, tuple)):
        return type(expected)(nested_approx(value, **tolerance) for value in expected)
    return expected
