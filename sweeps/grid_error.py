"""The grid error of a sweep's figures, from an axis over the node spacing.

The frictional figures of the BEM converge at first order in the node spacing ``a``
(docs/derivations.md, "Grid error of the frictional figures"), so one grid's value is no
better than its grid error. A sweep whose axis ``grid.spacing`` (or ``grid.spacing_x``)
refines the grid by 2 (e.g. ``[1e-3, 0.5e-3, 0.25e-3]`` m, in any order) gives that error
for every combination of its other axes: :func:`write_grid_error` writes
``grid-error.csv`` next to ``results.csv``, one row per combination and figure, with the
figure at the finest spacing, its limit, its error and the order, by the same rule as
``bem solve`` (:func:`grid_estimate`: :func:`bem.convergence.richardson` on
the finest three spacings, the observed order when it lies in ``[0.5, 5]``, else three
times the last change; with two spacings, first order assumed).

Columns: the other axes' values, ``figure`` (a result column of ``results.csv``),
``spacings`` (the spacings used, coarse to fine, m, ``;``-separated), ``values`` (the
figure on them), ``finest``, ``limit``, ``error`` (``|limit - finest|``, or three times the
last change), in the figure's unit (SI, as ``results.csv``), ``order`` (-) and
``estimate``: ``richardson``, ``not asymptotic: 3 x last change``, ``order 1 assumed (two
spacings)``, or, with nothing else filled, ``failed at <axis> = <a>: <error>`` /
``missing at <axis> = <a>`` when a point of the combination has no result.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

from .spec import Sweep
from .table import RESULTS, as_float

__all__ = ["GRID_ERROR", "SPACING_KEYS", "FIGURES", "grid_estimate", "spacing_axis", "grid_error_rows",
           "write_grid_error"]

#: the file written next to ``results.csv``
GRID_ERROR = "grid-error.csv"
#: the axis keys that refine the grid
SPACING_KEYS = ("grid.spacing", "grid.spacing_x")
#: the figures estimated: every numeric result column but the inputs a result repeats
FIGURES = tuple(r for r in RESULTS if r not in ("mode", "mu", "speed", "load"))
#: a refinement ratio within this relative tolerance of 2 counts as 2
_RATIO_TOL = 1e-6



def grid_estimate(values, ratio: float = 2.0):
    """Limit and grid error of a figure from its values on grids refined by ``ratio``,
    coarse to fine, as a :class:`bem.convergence.Convergence`. Three or more levels:
    :func:`bem.convergence.richardson` on the finest three (the observed order; where it
    is outside ``[0.5, 5]``, three times the last change). Two levels: first order
    assumed (the frictional figures' order, docs/derivations.md): limit ``q2 + (q2 - q1)
    / (ratio - 1)``, error ``|q2 - q1| / (ratio - 1)``, ``order = 1`` and ``asymptotic =
    False`` (an assumption, not an observation).

    Raises
    ------
    ValueError
        Fewer than two values.
    """
    from bem.convergence import Convergence, richardson

    q = [float(v) for v in values]
    if len(q) < 2:
        raise ValueError(f"a grid estimate needs at least 2 grids, got {len(q)}")
    if len(q) >= 3:
        return richardson(q[-3:], ratio)
    step = (q[1] - q[0]) / (ratio - 1)
    return Convergence(tuple(q), 1.0, q[1] + step, abs(step), False)

def spacing_axis(sweep: Sweep) -> tuple[str, tuple] | tuple[None, str]:
    """``(key, spacings coarse to fine)`` of the sweep's first axis over the node spacing
    whose values (two or more, m) halve from one to the next; ``(None, why)`` when it has
    none (``why`` is ``""`` when there is no spacing axis at all)."""
    why = ""
    for axis in sweep.axes:
        if axis.key not in SPACING_KEYS:
            continue
        values = sorted({float(v) for v in axis.values}, reverse=True)
        if len(values) < 2:
            why = f"axis {axis.key} has one value"
            continue
        ratios = [a / b for a, b in zip(values, values[1:])]
        if all(abs(r - 2.0) <= 2.0 * _RATIO_TOL for r in ratios):
            return axis.key, tuple(values)
        why = f"axis {axis.key} does not refine by 2 (ratios {', '.join(f'{r:.4g}' for r in ratios)})"
    return None, why


def _same(cell, value: float) -> bool:
    return math.isclose(as_float(cell), value, rel_tol=1e-9)


def grid_error_rows(sweep: Sweep, rows: list[dict]) -> list[dict]:
    """The rows of ``grid-error.csv`` from the table ``rows`` (cells as in
    ``results.csv``); empty when the sweep has no spacing axis refining by 2."""
    key, spacings = spacing_axis(sweep)
    if key is None:
        return []
    used = spacings[-3:]  # the finest three (or two), what grid_estimate extrapolates from
    others = [a.key for a in sweep.axes if a.key != key]
    combos: dict = {}
    for r in rows:
        combos.setdefault(tuple(r.get(k, "") for k in others), {})
        level = [a for a in used if _same(r.get(key), a)]
        if level:
            combos[tuple(r.get(k, "") for k in others)][level[0]] = r
    out = []
    for combo, levels in combos.items():
        label = dict(zip(others, combo))
        broken = []
        for a in used:
            r = levels.get(a)
            if r is None:
                broken.append(f"missing at {key} = {a:g}")
            elif r.get("status") != "ok":
                broken.append(f"failed at {key} = {a:g}: {r.get('error', '')}")
        if broken:
            out.append({**label, "estimate": "; ".join(broken)})
            continue
        for fig in FIGURES:
            values = [as_float(levels[a].get(fig)) for a in used]
            if all(math.isnan(v) for v in values):
                continue  # a figure this case has not (e.g. friction's without friction)
            entry = {**label, "figure": fig, "spacings": ";".join(repr(a) for a in used),
                     "values": ";".join(repr(v) for v in values)}
            if any(math.isnan(v) for v in values):
                gaps = [f"{a:g}" for a, v in zip(used, values) if math.isnan(v)]
                out.append({**entry, "estimate": f"missing at {key} = {', '.join(gaps)}"})
                continue
            c = grid_estimate(values)
            estimate = ("richardson" if c.asymptotic else "order 1 assumed (two spacings)" if len(used) == 2
                        else "not asymptotic: 3 x last change")
            out.append({**entry, "finest": c.values[-1], "limit": c.extrapolated, "error": c.error_finest,
                        "order": c.order if math.isfinite(c.order) else "", "estimate": estimate})
    return out


def write_grid_error(sweep: Sweep, rows: list[dict], folder: str | Path) -> tuple[Path | None, str]:
    """Write ``grid-error.csv`` in ``folder`` (:func:`grid_error_rows`); returns ``(path,
    "")``, or ``(None, why)`` when the sweep has no spacing axis refining by 2 (then a
    ``grid-error.csv`` an earlier sweep left there is removed)."""
    path = Path(folder) / GRID_ERROR
    key, why = spacing_axis(sweep)
    if key is None:
        path.unlink(missing_ok=True)
        return None, why
    table = grid_error_rows(sweep, rows)
    header = [*(a.key for a in sweep.axes if a.key != key), "figure", "spacings", "values", "finest", "limit",
              "error", "order", "estimate"]
    tmp = path.with_suffix(".csv.tmp")
    with open(tmp, "w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=header, lineterminator="\n")
        w.writeheader()
        w.writerows(table)
    tmp.replace(path)
    return path, ""
