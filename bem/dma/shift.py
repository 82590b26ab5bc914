"""Time-temperature shift factors: the WLF and Arrhenius laws, their fits, and the
horizontal (and vertical) shifts that overlap neighbouring isotherms.

Convention: the modulus at temperature ``T`` is the reference master curve at the
reduced frequency ``a_T omega``, scaled by the vertical factor ``b_T``::

    G*(omega; T) = b_T G*_ref(a_T omega),     G*_ref(a_T omega) = G*(omega; T) / b_T

so ``a_T < 1`` above ``T_ref`` (the material relaxes faster when hot), ``a_T(T_ref) = 1``,
and a relaxation time at ``T`` is ``a_T`` times the reference one. All logarithms here
are decimal (``log10 a_T``).

- WLF: ``log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref)``, defined only for
  ``T > T_ref - C2`` (at ``T = T_ref - C2`` the shift is infinite).
- Arrhenius: ``log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref)``, ``R = 8.314462618 J/(mol K)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Union

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import minimize_scalar

from .errors import ShiftError

__all__ = ["WLF", "Arrhenius", "ShiftLaw", "GAS_CONSTANT", "fit_wlf", "fit_arrhenius", "overlap_shifts"]

GAS_CONSTANT = 8.314462618  # J/(mol K), exact since the 2019 SI


def _positive(owner: str, name: str, value, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise ShiftError(f"{owner}.{name} must be a finite number > 0 {unit}, got {value!r}")
    return float(value)


@dataclass(frozen=True)
class WLF:
    """Williams-Landel-Ferry shift law ``log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref)``.

    Parameters
    ----------
    C1 : float
        Dimensionless constant, > 0.
    C2 : float
        Temperature constant (K), > 0; the law is singular at ``T = T_ref - C2``.
    T_ref : float
        Reference temperature (K), > 0.
    """

    C1: float
    C2: float
    T_ref: float

    def __post_init__(self) -> None:
        for name, unit in (("C1", "(dimensionless)"), ("C2", "K"), ("T_ref", "K")):
            object.__setattr__(self, name, _positive("WLF", name, getattr(self, name), unit))

    @property
    def singular_temperature(self) -> float:
        """``T_ref - C2`` (K): the law holds only above it."""
        return self.T_ref - self.C2

    def log_aT(self, temperature) -> np.ndarray:
        """``log10 a_T`` at ``temperature`` (K, array-like).

        Raises
        ------
        ShiftError
            If any temperature is at or below ``T_ref - C2``.
        """
        T = np.asarray(temperature, dtype=float)
        bad = ~(T > self.singular_temperature)
        if np.any(bad):
            t = float(np.ravel(T)[np.argmax(np.ravel(bad))])
            raise ShiftError(
                f"temperature {t:.6g} K is at or below the WLF singularity T_ref - C2 = "
                f"{self.T_ref:.6g} - {self.C2:.6g} = {self.singular_temperature:.6g} K; the WLF law holds only above it"
            )
        d = T - self.T_ref
        return -self.C1 * d / (self.C2 + d)


@dataclass(frozen=True)
class Arrhenius:
    """Arrhenius shift law ``log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref)``.

    Parameters
    ----------
    activation_energy : float
        ``E_a`` (J/mol), > 0.
    T_ref : float
        Reference temperature (K), > 0.
    """

    activation_energy: float
    T_ref: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "activation_energy",
                           _positive("Arrhenius", "activation_energy", self.activation_energy, "J/mol"))
        object.__setattr__(self, "T_ref", _positive("Arrhenius", "T_ref", self.T_ref, "K"))

    def log_aT(self, temperature) -> np.ndarray:
        """``log10 a_T`` at ``temperature`` (K, array-like, > 0)."""
        T = np.asarray(temperature, dtype=float)
        if np.any(~(T > 0)):
            raise ShiftError(f"temperatures must be > 0 K, got {T.min()!r}")
        return self.activation_energy / (GAS_CONSTANT * math.log(10.0)) * (1.0 / T - 1.0 / self.T_ref)


ShiftLaw = Union[WLF, Arrhenius]


def _check_fit_input(T, log_a, need: int):
    T, log_a = np.asarray(T, dtype=float), np.asarray(log_a, dtype=float)
    if T.shape != log_a.shape or T.ndim != 1:
        raise ShiftError(f"temperatures and shifts must be 1-D of the same length, got {T.shape} and {log_a.shape}")
    if len(np.unique(T)) < need:
        raise ShiftError(
            f"fitting this law needs shifts at {need} or more distinct temperatures, got {len(np.unique(T))}"
        )
    return T, log_a


def _linear_fit(A: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, float]:
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    return coef, float(np.sum((A @ coef - y) ** 2))


def fit_wlf(temperature, log_aT, T_ref: float, *, offset: bool = False) -> tuple[WLF, float]:
    """Fit ``C1``, ``C2`` of the WLF law (``T_ref`` given, K) to shifts ``log10 a_T``.

    With ``offset=True`` the shifts are known up to a constant ``c`` (as the overlap of
    isotherms gives them) and ``log_aT = WLF(T) + c`` is fitted. For a fixed ``C2`` the
    model is linear in ``C1`` and ``c``; ``C2`` is found by a bounded scalar search of
    the remaining residual over ``(T_ref - min T, T_ref - min T + 10^4 K)``.

    Returns
    -------
    (WLF, float)
        The law and the offset ``c`` (0 when ``offset`` is False).

    Raises
    ------
    ShiftError
        Too few temperatures, or shifts without WLF curvature (best ``C2`` at the
        search's upper end: use :class:`Arrhenius` or give the constants).
    """
    T, y = _check_fit_input(temperature, log_aT, 3 if offset else 2)
    T_ref = _positive("fit_wlf", "T_ref", T_ref, "K")
    lower = max(T_ref - T.min(), 0.0)

    def solve(c2: float):
        d = T - T_ref
        A = (-d / (c2 + d))[:, None]
        if offset:
            A = np.hstack([A, np.ones_like(A)])
        return _linear_fit(A, y)

    # search u = log(C2 - lower) on a grid, then refine between the best point's neighbours
    grid = np.linspace(math.log(1e-3), math.log(1e4), 141)
    cost = [solve(lower + math.exp(u))[1] for u in grid]
    k = int(np.argmin(cost))
    if k == len(grid) - 1:
        raise ShiftError(
            "the shifts show no WLF curvature (C2 would exceed 1e4 K); "
            "fit an Arrhenius law or give C1 and C2"
        )
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    best = minimize_scalar(lambda u: solve(lower + math.exp(u))[1], bounds=(lo, hi), method="bounded",
                           options={"xatol": 1e-10})
    c2 = lower + math.exp(best.x)
    coef, _ = solve(c2)
    if coef[0] <= 0:
        raise ShiftError(f"fitted WLF C1 = {coef[0]:.4g} is not > 0: the shifts do not decrease with temperature")
    return WLF(float(coef[0]), float(c2), T_ref), float(coef[1]) if offset else 0.0


def fit_arrhenius(temperature, log_aT, T_ref: float, *, offset: bool = False) -> tuple[Arrhenius, float]:
    """Fit the activation energy (J/mol) of the Arrhenius law (``T_ref`` given, K).

    Linear least squares of ``log_aT = E_a / (R ln 10) (1/T - 1/T_ref) + c`` (``c`` only
    with ``offset=True``). Returns the law and ``c``.
    """
    T, y = _check_fit_input(temperature, log_aT, 2 if offset else 1)
    T_ref = _positive("fit_arrhenius", "T_ref", T_ref, "K")
    A = ((1.0 / T - 1.0 / T_ref) / (GAS_CONSTANT * math.log(10.0)))[:, None]
    if offset:
        A = np.hstack([A, np.ones_like(A)])
    coef, _ = _linear_fit(A, y)
    if coef[0] <= 0:
        raise ShiftError(
            f"fitted activation energy {coef[0]:.4g} J/mol is not > 0: the shifts do not decrease with temperature"
        )
    return Arrhenius(float(coef[0]), T_ref), float(coef[1]) if offset else 0.0


def _features(iso, quantity: str):
    """Per isotherm: ``x = log10 omega`` and the curves to overlap (log10 |G*|, log10 tan delta)."""
    x = np.log10(iso.omega)
    out = []
    if quantity in ("modulus", "both"):
        out.append(("modulus", np.log10(np.hypot(iso.storage, iso.loss))))
    if quantity in ("tan_delta", "both"):
        if np.any(iso.loss <= 0):
            raise ShiftError(f"isotherm at {iso.temperature:.2f} K has a loss modulus of 0: "
                             "its loss tangent has no logarithm; shift on quantity='modulus'")
        out.append(("tan_delta", np.log10(iso.loss / iso.storage)))
    return x, [(name, y, CubicSpline(x, y) if len(x) > 2 else None) for name, y in out]


def _interp(x, y, spline, at):
    return spline(at) if spline is not None else np.interp(at, x, y)


def _pair_cost(a, b, delta: float, min_overlap: float, vertical: bool):
    """Mismatch of isotherm ``b`` shifted by ``delta`` (decades) against ``a``.

    Residuals ``b - a`` of every curve at the points of each isotherm inside the overlap
    of the two ranges, each side read from the other's cubic spline. With ``vertical``
    the modulus residuals lose their mean (the optimal vertical shift). Returns
    ``(mean square, vertical shift)``.
    """
    (xa, fa), (xb, fb) = a, b
    lo, hi = max(xa[0], xb[0] + delta), min(xa[-1], xb[-1] + delta)
    if hi - lo < min_overlap * (1 - 1e-12):
        return math.inf, 0.0
    ia = (xa >= lo) & (xa <= hi)
    ib = (xb + delta >= lo) & (xb + delta <= hi)
    if ia.sum() + ib.sum() < 3:
        return math.inf, 0.0
    total, v = 0.0, 0.0
    for (name, ya, sa), (_, yb, sb) in zip(fa, fb):
        r = np.concatenate([yb[ib] - _interp(xa, ya, sa, xb[ib] + delta), _interp(xb, yb, sb, xa[ia] - delta) - ya[ia]])
        if vertical and name == "modulus":
            v = float(r.mean())
            r = r - v
        total += float(np.mean(r * r))
    return total, v


def overlap_shifts(data, *, quantity: str = "both", vertical: bool = False, min_overlap: float = 0.5,
                   step: float = 0.02) -> tuple[np.ndarray, np.ndarray]:
    """Shifts that overlap each isotherm with its colder neighbour.

    For each pair of neighbours (sorted by temperature) the relative horizontal shift
    ``delta = log10 a_hot - log10 a_cold`` minimizes the mean square mismatch of the
    chosen curves (``log10 |G*|``, ``log10 tan delta`` or both; cubic splines in
    ``log10 omega``) over the overlap of the two frequency ranges, which must span at
    least ``min_overlap`` decades: a grid search in steps of ``step`` decades, refined by a
    bounded scalar search. Shifts are then summed from the coldest isotherm.

    Parameters
    ----------
    data : DMAData
        At least two isotherms.
    quantity : {"both", "modulus", "tan_delta"}
        Curves to overlap; the loss tangent does not depend on a vertical shift.
    vertical : bool
        Also fit a vertical shift ``log10 b_T`` (mean log-modulus mismatch).
    min_overlap : float
        Least overlap of two neighbours' ranges (decades of frequency).
    step : float
        Grid step of the search (decades).

    Returns
    -------
    (log_a, log_b) : arrays
        ``log10 a_T`` and ``log10 b_T`` per isotherm, relative to the coldest (0 there).

    Raises
    ------
    ShiftError
        Fewer than two isotherms, an unknown ``quantity``, or two neighbours whose
        frequency ranges cannot overlap by ``min_overlap`` decades.
    """
    if quantity not in ("both", "modulus", "tan_delta"):
        raise ShiftError(f"quantity must be 'both', 'modulus' or 'tan_delta', got {quantity!r}")
    if quantity == "tan_delta" and vertical:
        raise ShiftError(
            "a vertical shift cannot be fitted from the loss tangent alone; use quantity='both' or 'modulus'"
        )
    iso = data.isotherms
    if len(iso) < 2:
        raise ShiftError(
            f"{data.source}: shifting needs at least 2 isotherms, got 1 (at {iso[0].temperature:.2f} K)"
        )
    feats = [_features(s, quantity) for s in iso]
    log_a, log_b = np.zeros(len(iso)), np.zeros(len(iso))
    for k in range(1, len(iso)):
        a, b = feats[k - 1], feats[k]
        dmin, dmax = a[0][0] - b[0][-1] + min_overlap, a[0][-1] - b[0][0] - min_overlap
        if dmax < dmin:
            raise ShiftError(
                f"{data.source}: isotherms at {iso[k - 1].temperature:.2f} K and {iso[k].temperature:.2f} K "
                f"cannot overlap by min_overlap = {min_overlap} decades (their ranges are too short)"
            )
        grid = np.linspace(dmin, dmax, max(int(math.ceil((dmax - dmin) / step)) + 1, 2))
        cost = [_pair_cost(a, b, d, min_overlap, vertical)[0] for d in grid]
        j = int(np.argmin(cost))
        lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, len(grid) - 1)]
        res = minimize_scalar(lambda d: _pair_cost(a, b, d, min_overlap, vertical)[0], bounds=(lo, hi),
                              method="bounded", options={"xatol": 1e-7})
        d = res.x if res.fun <= cost[j] else grid[j]
        log_a[k] = log_a[k - 1] + d
        log_b[k] = log_b[k - 1] + _pair_cost(a, b, d, min_overlap, vertical)[1]
    return log_a, log_b
