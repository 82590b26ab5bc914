"""The checks every public bem dataclass runs on its numbers.

A number is a real number that is not a boolean (``True`` is not 1 m), finite, and
within its rule; numpy scalars (``np.float32``, ``np.int64``) are numbers like any other
and come back as Python ``float``/``int``. Every message names the field, its unit, the
rule and the value.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

__all__ = ["real", "integer", "NotANumber"]


class NotANumber(TypeError, ValueError):
    """A field given something that is not a number: a ``TypeError``, and a ``ValueError``
    too, as every other bad input of bem is (callers that catch ``ValueError`` see it)."""


_RULES = {">0": (lambda v: v > 0, "> 0"), ">=0": (lambda v: v >= 0, ">= 0"), "any": (lambda v: True, "finite")}


def real(name: str, value, unit: str, rule: str = ">0", *, finite: bool = True) -> float:
    """``value`` as a float, after checking it is a real number (not a bool), finite and
    ``rule`` (``">0"``, ``">=0"`` or ``"any"``); ``unit`` is said in the message.
    ``finite=False`` checks the type only (for a caller that reports non-finite entries
    itself).

    Raises :class:`NotANumber` (not a number) or ``ValueError`` (not finite, out of
    range), each naming ``name``: ``"<name> must be <rule> <unit>, got <value>"``."""
    words = f"{_RULES[rule][1]} {unit}".strip()
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise NotANumber(f"{name} must be {words}, got {value!r} (a {type(value).__name__}, not a real number)")
    out = float(value)
    if finite and not (math.isfinite(out) and _RULES[rule][0](out)):
        raise ValueError(f"{name} must be {words}, got {out!r}")
    return out


def integer(name: str, value, least: int = 1) -> int:
    """``value`` as an int, after checking it is an integer (not a bool; numpy integers
    welcome) and ``>= least``.

    Raises :class:`NotANumber` or ``ValueError`` naming ``name``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise NotANumber(f"{name} must be an integer >= {least}, got {value!r} "
                         f"(a {type(value).__name__}, not an integer)")
    if value < least:
        raise ValueError(f"{name} must be an integer >= {least}, got {value!r}")
    return int(value)
