"""The BEM (:mod:`bem`) as a verification method: one grid per level."""

from __future__ import annotations

import math
import time

import numpy as np

from ..metrics import fit_contact_radius
from ..results import Level, Run
from ..schema import Field, check_table

__all__ = ["FIELDS", "check", "run", "run_line", "run_rolling", "solve"]

FIELDS = {
    "spacings": Field("numbers", True, positive=True, doc="node spacings a (m), coarse to fine"),
    "period": Field("number", positive=True, doc="period L of the Fourier series (m), default 0.2"),
    "half_width": Field("number", True, positive=True, doc="candidate region |x|, |y| <= half_width (m)"),
    "truncation_factor": Field("number", positive=True, doc="Nt = ceil(factor L / 2a), default 1"),
}


def check(settings: dict, problem: dict, where: str) -> None:
    """``[bem]``: the keys above and nothing else."""
    check_table(settings, FIELDS, where)


def _solve(problem_cfg: dict, settings: dict, spacing: float, energy: bool = True):
    """(problem, result, seconds) of the BEM on one grid of node spacing ``spacing`` (m);
    the truncation resolves the grid (``Nt = ceil(factor L / 2a)``); ``energy``: compute
    the layer's dissipation (a sum over every mode, seconds at ``Nt = 3000``)."""
    import bem
    from bem.case import problem_from_config

    period = settings.get("period", 0.2)
    nt = math.ceil(settings.get("truncation_factor", 1.0) * period / (2 * spacing) - 1e-9)
    cfg = {k: dict(v) for k, v in problem_cfg.items()}
    cfg["grid"] = {"spacing": spacing, "period": period, "truncation": nt, "half_width": settings["half_width"]}
    problem, _ = problem_from_config(cfg)
    t = time.perf_counter()
    res = bem.solve(problem, energy=energy)
    return problem, res, time.perf_counter() - t


def _energy_balance(res) -> dict:
    """The rolling figures under the harness's names: ``dissipation`` (W, or W/m) and
    ``rolling_resistance_slope``, the pressure's work rate over V (N, or N/m)."""
    return {"dissipation": res.dissipation, "rolling_resistance_slope": res.pressure_power / res.speed,
            "rolling_resistance_energy": res.dissipation / res.speed}


def run(problem_cfg: dict, settings: dict, spacing: float) -> Run:
    """The BEM on one grid of node spacing ``spacing`` (m): the contact's scalars, without
    the dissipation."""
    problem, res, seconds = _solve(problem_cfg, settings, spacing, energy=False)
    X, Y = problem.grid.coordinates()
    r = np.hypot(X, Y)
    scalars = {
        "contact_radius": fit_contact_radius(r, res.gap, res.contact, spacing),
        "indentation": res.indentation,
        "peak_pressure": res.peak_pressure,
        "load": res.load,
        "rolling_resistance": res.rolling_resistance,
    }
    return Run("bem", spacing, scalars, r.ravel(), res.pressure.ravel(), seconds, problem.grid, res.pressure)


def run_line(problem_cfg: dict, settings: dict, spacing: float) -> Run:
    """The plane-strain BEM (a line contact, per unit length) on one grid of node
    spacing ``spacing`` (m); ``Run.r`` holds the signed ``x`` of the nodes (m, ``x > 0``
    ahead) and the scalars are per unit length (N/m); a rolling one adds the power the
    layer dissipates (W/m) and the pressure's work rate over V (N/m)."""
    problem, res, seconds = _solve(problem_cfg, settings, spacing)
    scalars = {q: getattr(res, q) for q in ("rolling_resistance", "rolling_resistance_energy", "indentation",
                                            "leading_edge", "trailing_edge", "peak_pressure", "load")}
    if res.speed > 0:
        scalars.update(_energy_balance(res))
    return Run("bem", spacing, scalars, np.asarray(res.x), np.asarray(res.pressure_profile), seconds)


def run_rolling(problem_cfg: dict, settings: dict, spacing: float) -> Run:
    """Steady rolling of a round indenter on one grid of node spacing ``spacing`` (m):
    ``Run.r`` holds the signed ``x`` of the nodes on the line ``y = 0`` (m, ``x > 0``
    ahead) and ``Run.pressure`` their pressure; the scalars add the contact's trailing
    and leading edges on that line (m), the pressure centroid (m), the power the layer
    dissipates (W, from the loss modulus) and the pressure's work rate over V (N, with
    the indenter's exact slope), which the dissipation must balance."""
    problem, res, seconds = _solve(problem_cfg, settings, spacing)
    g = problem.grid
    row = g.shape[0] // 2  # the grid is centred: a row of nodes on y = 0
    scalars = {q: getattr(res, q) for q in ("rolling_resistance", "indentation", "peak_pressure", "load",
                                            "trailing_edge", "leading_edge", "pressure_centroid_x")}
    scalars.update(_energy_balance(res))
    return Run("bem", spacing, scalars, np.asarray(g.x), res.pressure[row], seconds, g, res.pressure)


def solve(problem: dict, level: Level) -> Run:
    """The method protocol: the case's ``[problem]`` at one level of ``[bem] spacings``
    (a line contact in plane strain for ``[indenter] shape = "line"``; steady rolling on
    the line ``y = 0`` for a round indenter with ``[loading] speed > 0``)."""
    if problem["indenter"].get("shape") == "line":
        return run_line(problem, level.settings, level.size)
    if problem["loading"].get("speed", 0.0) > 0:
        return run_rolling(problem, level.settings, level.size)
    return run(problem, level.settings, level.size)
