"""The paper's section 11.4-11.7 findings, and the checks a verification case makes on a
sweep's table (Zehil and Gavin 2013).

* Tables 2 and 3: the fitted laws' 95 % intervals (:data:`TABLE2`, :data:`TABLE3`);
  :func:`paper_fit` turns a column into a :class:`sweeps.fits.Fit` (the interval's
  midpoint as the value) and :func:`law_gap` measures the largest relative difference of
  two laws over a range.
* Section 11.6: the friction share below 1.55 % up to ``P = 150 N``
  (:func:`friction_share_max`); its maximum for ``H`` between 6 and 8 mm (fig. 9,
  :func:`peak_position` on the thickness). The paper's "contribution of friction" can be
  read two ways, and both are here: the part of the dissipated power lost by slip
  (the table's ``friction_share``, the reading of section 11.2's "less than 0.05 N
  originate from slipping friction"), or how much friction raises ``R_r`` over the
  frictionless solution at the same point (:func:`friction_effect`, the reading of the
  with/without curves of figures 7 and 8).
* Section 11.7: the speed of the rolling-resistance peak (fig. 10, :func:`peak_position`
  on ``log V``).

Units: SI (N, m, m/s); shares are fractions (0.0155 for 1.55 %).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from .fits import Fit
from .report import curves
from .table import as_float

__all__ = ["TABLE2", "TABLE3", "FRICTION_SHARE_LIMIT", "SHARE_PEAK_RANGE", "read_table", "paper_fit", "law_gap",
           "friction_share_max", "friction_effect", "peak_position", "curve"]

#: Table 2, R_r = a P^b (P in N, R_r in N), with friction; key: H (m)
TABLE2 = {
    5e-3: {"a": (2.701e-3, 3.056e-3), "b": (1.381, 1.407), "r2": 0.9999},
    30e-3: {"a": (2.554e-3, 2.701e-3), "b": (1.510, 1.521), "r2": 1.0},
}
#: Table 3, R_r = a exp(b H) + c exp(d H) (H in m, R_r in N), with friction; key: P (N)
TABLE3 = {
    50.0: {"a": (0.9306, 0.9403), "b": (1.555, 1.954), "c": (-0.8799, -0.8555), "d": (-233.0, -223.2), "r2": 0.9999},
    125.0: {"a": (3.738, 3.768), "b": (1.706, 2.0), "c": (-3.704, -3.662), "d": (-198.6, -193.8), "r2": 1.0},
}
#: section 11.6: friction's share of R_r stays below this up to P = 150 N
FRICTION_SHARE_LIMIT = 0.0155
#: section 11.6, fig. 9: the thickness (m) of the friction share's maximum
SHARE_PEAK_RANGE = (6e-3, 8e-3)


def read_table(path: str | Path) -> list[dict]:
    """The rows of a sweep's ``results.csv`` (cells as strings; :func:`sweeps.table.as_float`)."""
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def paper_fit(table: dict, key: float, x_range: tuple[float, float]) -> Fit:
    """Column ``key`` of :data:`TABLE2` or :data:`TABLE3` as a :class:`Fit` over
    ``x_range`` (the paper does not state its data range; give the sweep's)."""
    col = table[key]
    names = tuple(k for k in ("a", "b", "c", "d") if k in col)
    law = "power" if len(names) == 2 else "two_exponential"
    lower = tuple(col[n][0] for n in names)
    upper = tuple(col[n][1] for n in names)
    values = tuple((lo + hi) / 2 for lo, hi in zip(lower, upper))
    return Fit(law, names, values, lower, upper, col["r2"], 0, float(x_range[0]), float(x_range[1]))


def law_gap(ours, theirs, x_min: float, x_max: float, n: int = 201) -> float:
    """``max |ours(x) / theirs(x) - 1|`` over ``n`` points of ``[x_min, x_max]`` (two
    callables, e.g. :class:`Fit` objects)."""
    x = np.linspace(x_min, x_max, n)
    return float(np.max(np.abs(np.asarray(ours(x)) / np.asarray(theirs(x)) - 1)))


def friction_share_max(rows: list[dict], load_max: float = 150.0, load_key: str = "loading.load") -> float:
    """The largest ``friction_share`` of the ``ok`` rows with friction and load (N) up to
    ``load_max`` (``nan`` if none)."""
    shares = [as_float(r.get("friction_share")) for r in rows
              if r.get("status") == "ok" and as_float(r.get(load_key, r.get("load"))) <= load_max * (1 + 1e-12)]
    shares = [s for s in shares if math.isfinite(s)]
    return max(shares) if shares else math.nan


def friction_effect(rows: list[dict], x: str, y: str = "rolling_resistance", with_case: str = "base-friction",
                    without_case: str = "base-frictionless") -> tuple[np.ndarray, np.ndarray]:
    """``(xs, R_f / R_0 - 1)``: how much friction raises result ``y`` at each ``x``, from a
    sweep whose ``case`` axis holds a frictional and a frictionless base case (figures 7
    and 8); only the ``x`` values both curves have."""
    xf, rf = curve(rows, x, y, case=with_case)
    x0, r0 = curve(rows, x, y, case=without_case)
    common, i, j = np.intersect1d(xf, x0, return_indices=True)
    return common, rf[i] / r0[j] - 1


def peak_position(x, y, log: bool = False, window: int = 5) -> float:
    """Abscissa of the maximum of sampled ``y(x)``: the vertex of the least-squares
    parabola through the ``window`` samples nearest the largest one (in ``log10 x`` with
    ``log``), which smooths the small steps the spatial discretization of slip leaves in
    the friction share (section 11.6). A maximum at an end of the range returns that end.

    Raises
    ------
    ValueError
        Fewer than three finite samples.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = np.isfinite(x) & np.isfinite(y)
    x, y = x[keep], y[keep]
    if x.size < 3:
        raise ValueError(f"a peak needs at least 3 finite samples, got {x.size}")
    order = np.argsort(x)
    x, y = x[order], y[order]
    u = np.log10(x) if log else x
    k = int(np.argmax(y))
    if k in (0, x.size - 1):
        return float(x[k])
    w = min(window, x.size)
    lo = min(max(0, k - w // 2), x.size - w)
    c2, c1, _ = np.polyfit(u[lo:lo + w], y[lo:lo + w], 2)
    vertex = -c1 / (2 * c2) if c2 < 0 else u[k]
    vertex = float(np.clip(vertex, u[lo], u[lo + w - 1]))
    return 10 ** vertex if log else vertex


def curve(rows: list[dict], x: str, y: str, **fixed) -> tuple[np.ndarray, np.ndarray]:
    """``(xs, ys)`` of the ``ok`` rows whose other columns equal ``fixed`` (compared as
    numbers where both are numbers), e.g. ``curve(rows, "loading.speed",
    "rolling_resistance", **{"loading.load": 150})``."""
    def match(r):
        for k, v in fixed.items():
            a, b = as_float(r.get(k)), as_float(v)
            if math.isfinite(a) and math.isfinite(b):
                if not math.isclose(a, b, rel_tol=1e-9):
                    return False
            elif str(r.get(k)) != str(v):
                return False
        return True

    [(_, xs, ys)] = curves([r for r in rows if match(r)], x, y, []) or [({}, np.array([]), np.array([]))]
    return xs, ys
