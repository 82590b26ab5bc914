"""A finished sweep's plots and fits, from its table.

A *curve* is the set of ``ok`` rows that share the values of every axis but the
abscissa ``x``, sorted by ``x``. Each requested result is drawn against ``x`` with one
curve per combination of the other axes (``plot-<result>.png``); each requested law is
fitted to each curve (``fits.csv`` and ``fits.json``, :mod:`sweeps.fits`).
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np

from .fits import fit_law
from .spec import Sweep
from .table import as_float

__all__ = ["curves", "plot_results", "fit_curves", "write_report"]

_LABELS = {
    "rolling_resistance": "R_r, equilibrium (N)", "rolling_resistance_energy": "R_r, energy (N)",
    "rolling_resistance_friction": "R_r from friction (N)", "rolling_resistance_viscous": "R_r, viscous part (N)",
    "friction_share": "friction share of R_r (-)", "contact_radius": "contact radius (m)",
    "indentation": "indentation (m)", "peak_pressure": "peak pressure (Pa)",
    "loading.load": "P (N)", "layer.thickness": "H (m)", "loading.speed": "V (m/s)",
}


def curves(rows: list[dict], x: str, y: str, others: list[str]) -> list[tuple[dict, np.ndarray, np.ndarray]]:
    """``(label, xs, ys)`` per combination of the ``others`` axes' values, over the ``ok``
    rows with a finite ``y``; ``label`` maps each other axis to its value."""
    groups: dict = {}
    for r in rows:
        if r.get("status") != "ok":
            continue
        xv, yv = as_float(r[x]), as_float(r.get(y))
        if not (math.isfinite(xv) and math.isfinite(yv)):
            continue
        label = tuple((k, r[k]) for k in others)
        groups.setdefault(label, []).append((xv, yv))
    out = []
    for label, pts in groups.items():
        pts.sort()
        out.append((dict(label), np.array([p[0] for p in pts]), np.array([p[1] for p in pts])))
    return out


def _others(sweep: Sweep) -> list[str]:
    return [a.key for a in sweep.axes if a.key != sweep.x_axis]


def plot_results(sweep: Sweep, rows: list[dict], folder: Path) -> list[Path]:
    """``plot-<result>.png`` for each result of ``[output] plot``; returns the files."""
    from matplotlib.figure import Figure

    x = sweep.x_axis
    logx = any(a.key == x and len(a.values) > 2 and a.values[-1] / a.values[0] > 50
               for a in sweep.axes if a.key != "case" and all(isinstance(v, (int, float)) and v > 0 for v in a.values))
    written = []
    for y in sweep.plot:
        fig = Figure(figsize=(6.4, 4.4))
        ax = fig.add_subplot()
        for label, xs, ys in curves(rows, x, y, _others(sweep)):
            text = ", ".join(f"{k.split('.')[-1]} = {v}" for k, v in label.items()) or y
            ax.plot(xs, ys, "o-", ms=3, label=text)
        if logx:
            ax.set_xscale("log")
        ax.set_xlabel(_LABELS.get(x, x))
        ax.set_ylabel(_LABELS.get(y, y))
        ax.set_title(sweep.name)
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
        path = folder / f"plot-{y}.png"
        fig.savefig(path, dpi=120, bbox_inches="tight")
        written.append(path)
    return written


def fit_curves(sweep: Sweep, rows: list[dict]) -> list[dict]:
    """Each ``[[fit]]`` law on each curve: one dict per fit (curve label, ``y``, law,
    coefficients with ``_lower`` / ``_upper`` bounds, ``r2``, ``n``, range), or its
    ``error``."""
    out = []
    for req in sweep.fits:
        for label, xs, ys in curves(rows, sweep.x_axis, req.y, _others(sweep)):
            entry = {**label, "x": sweep.x_axis, "y": req.y}
            try:
                entry.update(fit_law(req.law, xs, ys).as_dict())
            except (ValueError, RuntimeError) as exc:
                entry.update(law=req.law, error=str(exc))
            out.append(entry)
    return out


def write_report(sweep: Sweep, rows: list[dict], folder: str | Path, plots: bool = True) -> dict:
    """Plots and fits of a finished sweep in ``folder``; returns ``{"plots": [...], "fits": [...]}``."""
    folder = Path(folder)
    written = plot_results(sweep, rows, folder) if plots and sweep.plot else []
    fits = fit_curves(sweep, rows)
    if fits:
        (folder / "fits.json").write_text(json.dumps(fits, indent=2, default=str))
        keys = list(dict.fromkeys(k for f in fits for k in f))
        with open(folder / "fits.csv", "w", newline="", encoding="utf-8") as fh:
            w = csv.DictWriter(fh, fieldnames=keys)
            w.writeheader()
            w.writerows(fits)
    return {"plots": [str(p) for p in written], "fits": fits}
