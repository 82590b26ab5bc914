"""The paper's fitted laws, with 95 % confidence intervals (Tables 2 and 3).

* ``power``: ``R_r = a P^b`` (Table 2: ``a_p`` in N^(1-b), ``b_p``; ``P`` in N);
* ``two_exponential``: ``R_r = a exp(b H) + c exp(d H)`` (Table 3: ``a_e, c_e`` in N,
  ``b_e, d_e`` in 1/m; ``H`` in m; the paper's text writes ``exp^{b_e P}``, a slip: the
  curves of figure 8 are against ``H``, and ``d_e = -230`` only makes sense per metre).

Least squares by :func:`scipy.optimize.curve_fit`; the interval of each coefficient is
``value +- t_{0.975, n - k} sqrt(C_ii)`` with ``C`` the covariance scaled by the residual
variance (``absolute_sigma=False``) and ``k`` coefficients: the usual (MATLAB ``confint``)
interval the paper's tables give. ``r2 = 1 - SS_res / SS_tot``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats
from scipy.optimize import curve_fit

__all__ = ["Fit", "fit_power", "fit_two_exponential", "fit_law", "LAW_FUNCTIONS", "PARAMETERS"]


def power(x, a, b):
    """``a x^b``."""
    return a * np.power(x, b)


def two_exponential(x, a, b, c, d):
    """``a exp(b x) + c exp(d x)``."""
    return a * np.exp(b * x) + c * np.exp(d * x)


LAW_FUNCTIONS = {"power": power, "two_exponential": two_exponential}
PARAMETERS = {"power": ("a", "b"), "two_exponential": ("a", "b", "c", "d")}


@dataclass(frozen=True)
class Fit:
    """A fitted law: coefficient values, their 95 % bounds, ``r2`` and the data range."""

    law: str
    names: tuple
    values: tuple
    lower: tuple
    upper: tuple
    r2: float
    n: int
    x_min: float
    x_max: float

    def __call__(self, x):
        """The law at ``x`` (same unit as the fitted data)."""
        return LAW_FUNCTIONS[self.law](np.asarray(x, float), *self.values)

    def as_dict(self) -> dict:
        out = {"law": self.law, "r2": self.r2, "n": self.n, "x_min": self.x_min, "x_max": self.x_max}
        for name, v, lo, hi in zip(self.names, self.values, self.lower, self.upper):
            out[name], out[f"{name}_lower"], out[f"{name}_upper"] = v, lo, hi
        return out


def _data(x, y, k: int, law: str):
    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = np.isfinite(x) & np.isfinite(y)
    x, y = x[keep], y[keep]
    if x.size <= k:
        raise ValueError(f"the {law} law has {k} coefficients and needs more than {k} finite points, got {x.size}")
    order = np.argsort(x)
    return x[order], y[order]


def _finish(law, x, y, p, cov) -> Fit:
    k = len(p)
    res = y - LAW_FUNCTIONS[law](x, *p)
    ss_tot = float(((y - y.mean()) ** 2).sum())
    r2 = 1 - float((res ** 2).sum()) / ss_tot if ss_tot > 0 else math.nan
    half = stats.t.ppf(0.975, x.size - k) * np.sqrt(np.clip(np.diag(cov), 0, None))
    return Fit(law, PARAMETERS[law], tuple(map(float, p)), tuple(map(float, p - half)), tuple(map(float, p + half)),
               r2, int(x.size), float(x[0]), float(x[-1]))


def fit_power(x, y) -> Fit:
    """``y = a x^b`` through positive ``x, y``; start from the straight line in log-log.

    Raises
    ------
    ValueError
        Two or fewer finite points, or a non-positive value.
    """
    x, y = _data(x, y, 2, "power")
    if (x <= 0).any() or (y <= 0).any():
        raise ValueError("the power law needs x > 0 and y > 0")
    b0, lna0 = np.polyfit(np.log(x), np.log(y), 1)
    p, cov = curve_fit(power, x, y, p0=(math.exp(lna0), b0), maxfev=20000)
    return _finish("power", x, y, p, cov)


def fit_two_exponential(x, y) -> Fit:
    """``y = a exp(b x) + c exp(d x)`` with ``d < b`` (the fast term second).

    Separable least squares for the start: ``a, c`` are linear for fixed rates, so the
    rates are searched on a grid (``b x_max`` in [-3, 3], ``d x_max`` in [-60, -0.3]) and
    the best pair refined by :func:`curve_fit` on all four.

    Raises
    ------
    ValueError
        Four or fewer finite points.
    """
    x, y = _data(x, y, 4, "two_exponential")
    span = x[-1]
    best = None
    for bs in np.linspace(-3, 3, 61):
        for ds in -np.geomspace(0.3, 60, 80):
            if ds >= bs:
                continue
            A = np.column_stack([np.exp(bs * x / span), np.exp(ds * x / span)])
            coef, *_ = np.linalg.lstsq(A, y, rcond=None)
            err = float(((A @ coef - y) ** 2).sum())
            if best is None or err < best[0]:
                best = (err, coef[0], bs / span, coef[1], ds / span)
    p, cov = curve_fit(two_exponential, x, y, p0=best[1:], maxfev=50000)
    if p[3] > p[1]:  # keep the slow term first
        p = p[[2, 3, 0, 1]]
        cov = cov[np.ix_([2, 3, 0, 1], [2, 3, 0, 1])]
    return _finish("two_exponential", x, y, p, cov)


def fit_law(law: str, x, y) -> Fit:
    """Fit ``law`` (``"power"`` or ``"two_exponential"``)."""
    return {"power": fit_power, "two_exponential": fit_two_exponential}[law](x, y)
