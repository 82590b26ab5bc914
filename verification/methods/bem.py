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


def _solve(problem_cfg: dict, settings: dict, spacing: float):
    """(problem, result, seconds) of the BEM on one grid of node spacing ``spacing`` (m);
    the truncation resolves the grid (``Nt = ceil(factor L / 2a)``)."""
    from bem.case import problem_from_config
    from bem.problem import solve_frictionless

    period = settings.get("period", 0.2)
    nt = math.ceil(settings.get("truncation_factor", 1.0) * period / (2 * spacing) - 1e-9)
    cfg = {k: dict(v) for k, v in problem_cfg.items()}
    cfg["grid"] = {"spacing": spacing, "period": period, "truncation": nt, "half_width": settings["half_width"]}
    problem, _ = problem_from_config(cfg)
    t = time.perf_counter()
    res, _ = solve_frictionless(problem)
    return problem, res, time.perf_counter() - t


def run(problem_cfg: dict, settings: dict, spacing: float) -> Run:
    """The BEM on one grid of node spacing ``spacing`` (m)."""
    problem, res, seconds = _solve(problem_cfg, settings, spacing)
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
    layer dissipates (W/m) and the pressure's work rate over V, ``sum F ds/dx`` (N/m)."""
    problem, res, seconds = _solve(problem_cfg, settings, spacing)
    scalars = {q: getattr(res, q) for q in ("rolling_resistance", "rolling_resistance_energy", "indentation",
                                            "leading_edge", "trailing_edge", "peak_pressure", "load")}
    speed = problem.loading.speed
    if speed > 0:
        scalars["rolling_resistance_slope"] = _work_rate(problem.indenter.profile, res.force, np.asarray(res.x),
                                                         spacing)
        scalars["dissipation"] = res.rolling_resistance_energy * speed
    return Run("bem", spacing, scalars, np.asarray(res.x), np.asarray(res.pressure_profile), seconds)


def _work_rate(profile, force, x, spacing: float) -> float:
    """``sum F ds/dx``: the pressure's work rate over V (N, or N/m in plane strain), the
    indenter's slope by a central difference of its ``profile(x)`` (m) at the nodes."""
    step = 1e-3 * spacing
    slope = (profile(x + step) - profile(x - step)) / (2 * step)
    return float(np.sum(np.asarray(force).reshape(np.shape(slope)) * slope))


def run_rolling(problem_cfg: dict, settings: dict, spacing: float) -> Run:
    """Steady rolling of a round indenter on one grid of node spacing ``spacing`` (m):
    ``Run.r`` holds the signed ``x`` of the nodes on the line ``y = 0`` (m, ``x > 0``
    ahead) and ``Run.pressure`` their pressure; the scalars add the contact's trailing
    and leading edges on that line (m), the pressure centroid (m), the power the layer
    dissipates (W, :func:`bem.energy.viscous_dissipation`, from the loss modulus) and the
    pressure's work rate over V, ``sum F ds/dx`` (N, the indenter's exact slope by a
    central difference), which the dissipation must balance."""
    from bem.energy import viscous_dissipation
    from bem.plane import edges_along

    problem, res, seconds = _solve(problem_cfg, settings, spacing)
    g = problem.grid
    row = g.shape[0] // 2  # the grid is centred: a row of nodes on y = 0
    trailing, leading = edges_along(g.x, g.spacing_x, res.force[row], res.gap[row])
    zero = np.zeros_like(res.force)
    X, Y = g.coordinates()
    scalars = {
        "rolling_resistance": res.rolling_resistance,
        "indentation": res.indentation,
        "peak_pressure": res.peak_pressure,
        "load": res.load,
        "trailing_edge": trailing,
        "leading_edge": leading,
        "pressure_centroid_x": res.pressure_centroid_x,
        "rolling_resistance_slope": _work_rate(lambda x: problem.indenter.profile(x, Y), res.force, X, spacing),
        "dissipation": viscous_dissipation(g, problem.layer, problem.loading.speed, -res.force, zero, zero),
    }
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
