"""The paper's section 11.4-11.7 findings, and the checks a verification case makes on a
sweep's table (Zehil and Gavin 2013).

* Tables 2 and 3: the fitted laws' 95 % intervals (:data:`TABLE2`, :data:`TABLE3`);
  :func:`paper_fit` turns a column into a :class:`sweeps.fits.Fit` (the interval's
  midpoint as the value) and :func:`law_gap` measures the largest relative difference of
  two laws over a range.
* Section 11.6: the friction share below 1.55 % up to ``P = 150 N``
  (:func:`friction_share_max`); its maximum for ``H`` between 6 and 8 mm (fig. 9,
  :func:`peak_position` on the thickness); what we find instead, a share that rises
  towards thin layers (:func:`share_rise`). The paper's "contribution of friction" can be
  read two ways, and both are here: the part of the dissipated power lost by slip
  (the table's ``friction_share``, the reading of section 11.2's "less than 0.05 N
  originate from slipping friction"), or how much friction raises ``R_r`` over the
  frictionless solution at the same point (:func:`friction_effect`, the reading of the
  with/without curves of figures 7 and 8).
* Section 11.7: the speed of the rolling-resistance peak (fig. 10, :func:`peak_position`
  on ``log V``).
* :func:`grid_estimate` (:mod:`sweeps.grid_error`): the limit and grid error of a figure from two or more grids
  halved in turn (docs/sweeps.md, "Figure 9 under each kinematics").

Units: SI (N, m, m/s); shares are fractions (0.0155 for 1.55 %).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from .fits import Fit
from .grid_error import grid_estimate  # noqa: F401  (public here too)
from .report import curves
from .table import as_float

__all__ = ["TABLE2", "TABLE3", "FRICTION_SHARE_LIMIT", "SHARE_PEAK_RANGE", "read_table", "paper_fit", "law_gap",
           "friction_share_max", "friction_effect", "peak_position", "curve", "QUICK", "findings", "run_quick",
           "SHARE_RISE_THICKNESS", "share_rise", "grid_estimate"]

#: the quick (coarse-grid) sweep files for CI, relative to the repository's root
QUICK = {"loads": "examples/sweeps/quick/quick-table2.toml", "thickness": "examples/sweeps/quick/quick-table3.toml",
         "speed": "examples/sweeps/quick/quick-fig10.toml"}

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
#: fig. 9 as we find it: the thin and the thick layer (m) whose friction shares measure
#: the rise towards thin layers (:func:`share_rise`)
SHARE_RISE_THICKNESS = (1e-3, 5e-3)


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


def share_rise(rows: list[dict], thin: float = SHARE_RISE_THICKNESS[0], thick: float = SHARE_RISE_THICKNESS[1],
               **fixed) -> float:
    """``share(thick) / share(thin)``: the friction share on the ``thick`` layer in units
    of the share on the ``thin`` one (thicknesses in m), over the ``ok`` rows whose other
    columns equal ``fixed`` (:func:`curve`). Small when the share rises towards thin
    layers; ``nan`` when either thickness is missing."""
    H, share = curve(rows, "layer.thickness", "friction_share", **fixed)
    pick = {t: share[np.isclose(H, t, rtol=1e-9, atol=0.0)] for t in (thin, thick)}
    if any(v.size != 1 or not math.isfinite(v[0]) for v in pick.values()):
        return math.nan
    return float(pick[thick][0] / pick[thin][0])


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


def findings(load_rows: list[dict], thickness_rows: list[dict], speed_rows: list[dict],
             y: str = "rolling_resistance_energy") -> dict:
    """What a verification case compares with the paper, from the tables of three sweeps
    with friction (those of :data:`QUICK`, or of ``examples/sweeps/table2-power-law``,
    ``table3-two-exponential`` and ``fig10*``):

    ``load_rows`` over ``layer.thickness`` (5 and 30 mm) x ``loading.load``;
    ``thickness_rows`` over ``loading.load`` (50 and 125 N) x ``layer.thickness``;
    ``speed_rows`` over ``layer.thickness`` or ``loading.load`` x ``loading.speed``.

    Returns a dict: ``table2`` and ``table3`` (per H in m, per P in N: our :class:`Fit` of
    ``y``, the paper's law, and ``gap``, the largest relative difference of the two over
    our fitted range), ``friction_share_max`` (P <= 150 N, over the load sweep),
    ``share_peak_thickness`` (per P, m, :func:`peak_position` of the friction share over
    the thickness sweep), ``share_rise`` (per P, :func:`share_rise` over the thickness
    sweep: the share at 5 mm over that at 1 mm) and ``peak_speed`` (per remaining label of the speed sweep, m/s,
    :func:`peak_position` in ``log V``).
    """
    out: dict = {"y": y, "table2": {}, "table3": {}, "share_peak_thickness": {}, "share_rise": {}, "peak_speed": {}}
    from .fits import fit_power, fit_two_exponential

    for H in TABLE2:
        P, R = curve(load_rows, "loading.load", y, **{"layer.thickness": H})
        if P.size > 2:
            ours = fit_power(P, R)
            theirs = paper_fit(TABLE2, H, (P[0], P[-1]))
            out["table2"][H] = {"ours": ours, "paper": theirs, "gap": law_gap(ours, theirs, P[0], P[-1])}
    for load in TABLE3:
        H, R = curve(thickness_rows, "layer.thickness", y, **{"loading.load": load})
        if H.size > 4:
            ours = fit_two_exponential(H, R)
            theirs = paper_fit(TABLE3, load, (H[0], H[-1]))
            out["table3"][load] = {"ours": ours, "paper": theirs, "gap": law_gap(ours, theirs, H[0], H[-1])}
        Hs, share = curve(thickness_rows, "layer.thickness", "friction_share", **{"loading.load": load})
        if Hs.size >= 3:
            out["share_peak_thickness"][load] = peak_position(Hs, share)
        rise = share_rise(thickness_rows, **{"loading.load": load})
        if math.isfinite(rise):
            out["share_rise"][load] = rise
    out["friction_share_max"] = friction_share_max(load_rows)
    labels = {(k, r[k]) for r in speed_rows for k in ("layer.thickness", "loading.load") if k in r}
    keys = sorted({k for k, _ in labels})
    for combo in sorted({tuple((k, r[k]) for k in keys) for r in speed_rows}):
        V, R = curve(speed_rows, "loading.speed", y, **dict(combo))
        if V.size >= 3:
            out["peak_speed"][combo] = peak_position(V, R, log=True)
    return out


def run_quick(out: str | Path, root: str | Path = ".", client=None, cache: str | Path | None = None,
              y: str = "rolling_resistance_energy") -> dict:
    """Run the :data:`QUICK` sweeps (coarse grids, 40 frictional points) into
    ``out/<name>`` on ``client`` (default a local cluster, started once for the three)
    and return their :func:`findings`."""
    from .engine import connect, run_sweep
    from .spec import read_sweep

    own = client is None
    client = client or connect()
    try:
        rows = {k: run_sweep(read_sweep(Path(root) / f), Path(out) / Path(f).stem, client=client, cache=cache,
                             stream=None).rows for k, f in QUICK.items()}
    finally:
        if own:
            cluster = getattr(client, "cluster", None)
            client.close()
            if cluster is not None:
                cluster.close()
    return findings(rows["loads"], rows["thickness"], rows["speed"], y)
