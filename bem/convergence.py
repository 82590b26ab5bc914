"""Grid convergence of a scalar from three levels refined by a constant ratio: the observed
order and Richardson's extrapolation with its error estimate. Used by ``bem`` for the grid
error of the frictional figures and by the verification harness for every method."""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Convergence", "richardson"]


@dataclass(frozen=True)
class Convergence:
    """Three levels refined by ``ratio``: observed order, Richardson extrapolation, the
    estimated error of the finest level (same units as the values), and whether the
    sequence looked asymptotic (an observed order in ``[0.5, 5]``)."""

    values: tuple
    order: float
    extrapolated: float
    error_finest: float
    asymptotic: bool


def richardson(values, ratio: float = 2.0) -> Convergence:
    """Observed order ``p = log(|q1 - q2| / |q2 - q3|) / log(ratio)`` and
    ``q* = q3 + (q3 - q2) / (ratio^p - 1)`` from coarse to fine values ``q1, q2, q3``.

    Richardson's estimate is used only when the observed order is plausible
    (``0.5 <= p <= 5``): a near-zero order would extrapolate without bound and a
    non-monotone sequence has no order. Otherwise ``q* = q3`` with the error estimated as
    three times the last change (Roache's safety factor), and ``asymptotic = False``.
    """
    q1, q2, q3 = (float(v) for v in values)
    d1, d2 = q2 - q1, q3 - q2
    p = math.log(abs(d1) / abs(d2)) / math.log(ratio) if d1 * d2 > 0 else math.nan
    if not (0.5 <= p <= 5.0):
        return Convergence((q1, q2, q3), p, q3, 3.0 * abs(d2), False)
    ext = q3 + d2 / (ratio**p - 1)
    return Convergence((q1, q2, q3), p, ext, abs(ext - q3), True)
