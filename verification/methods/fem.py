"""The finite-element reference (:mod:`fem_reference`) as a verification method."""

from __future__ import annotations

import time

import numpy as np

import casefile

from ..metrics import fit_contact_radius
from ..results import Level, Run
from ..schema import CaseError, Field, check_table

__all__ = ["FIELDS", "check", "run", "run_line", "run_rolling", "solve"]

FIELDS = {
    "element_sizes": Field("numbers", True, positive=True, doc="element sizes at the contact (m), coarse to fine"),
    "scaled": Field("strings", choices=("grading", "far_size"),
                    doc="settings multiplied by element_size / element_sizes[0] at each level, so that the "
                        "whole mesh refines (systematic refinement); given at the first level"),
}


def check(settings: dict, problem: dict, where: str) -> None:
    """``[fem]``: ``element_sizes``, ``scaled`` and any key of the case-file schema's
    ``[fem]`` section, checked by :func:`casefile.validate` as ``fem-reference solve``
    would."""
    check_table(settings, FIELDS, where, open_=True)
    rest = {k: v for k, v in settings.items() if k not in FIELDS}
    for key in settings.get("scaled", []):
        if key not in rest:
            raise CaseError(f"{where} scaled: {key!r} is scaled but not given (give its value at the first level)")
    if "element_size" in rest:
        raise CaseError(f"{where}: give the levels as element_sizes, not element_size")
    try:
        casefile.validate({**problem, "fem": {**rest, "element_size": settings["element_sizes"][0]}},
                          tool="fem", source=where)
    except casefile.CaseFileError as exc:
        raise CaseError(str(exc)) from None


def run(problem_cfg: dict, settings: dict, size: float) -> Run:
    """The axisymmetric (or 3D) FEM with element size ``size`` (m) at the contact."""
    import fem_reference as fr
    from fem_reference.case import problem_from_dict

    problem = problem_from_dict({**problem_cfg, "fem": {**settings, "element_size": size}})
    t = time.perf_counter()
    res = fr.solve(problem)
    seconds = time.perf_counter() - t
    # the same radius definition as for the BEM, from the FEM's own surface gap
    ind = problem.indenter
    rs = np.asarray(res.surface_radius)
    gap = ind.profile(np.minimum(rs, 0.99 * ind.radius)) - res.indentation - np.asarray(res.surface_uz)
    r_contact = float(np.max(res.radius[res.pressure > 0]))
    contact = rs <= r_contact * (1 + 1e-12)
    scalars = {
        "contact_radius": fit_contact_radius(rs, gap, contact, res.mesh.element_size),
        "indentation": res.indentation,
        "peak_pressure": res.peak_pressure,
        "load": res.load,
    }
    return Run("fem", size, scalars, np.asarray(res.radius), np.asarray(res.pressure), seconds)


def _moving(problem_cfg: dict, fem: dict):
    """(result, seconds) of the FEM's steady-rolling solve with ``[fem]`` = ``fem``, and
    its scalars (N or N/m, m, Pa, W or W/m) with the pressure's work rate over V."""
    import fem_reference as fr
    from fem_reference.case import problem_from_dict

    problem = problem_from_dict({**problem_cfg, "fem": fem})
    t = time.perf_counter()
    res = fr.solve(problem)
    seconds = time.perf_counter() - t
    scalars = {q: float(getattr(res, q)) for q in ("rolling_resistance", "indentation", "leading_edge",
                                                   "trailing_edge", "peak_pressure", "load", "dissipation")}
    scalars["pressure_centroid_x"] = float(res.pressure_centroid)
    if res.speed > 0:  # the pressure's work rate over V, int p ds/dx
        scalars["rolling_resistance_slope"] = float(res.pressure_power) / res.speed
        scalars["rolling_resistance_energy"] = float(res.dissipation) / res.speed  # D / V
    return res, seconds, scalars


def run_line(problem_cfg: dict, settings: dict, size: float) -> Run:
    """The plane-strain steady-rolling FEM (a line contact, per unit length) with element
    size ``size`` (m) at the contact; ``Run.r`` holds the signed ``x`` of the pressure
    samples (m, ``x > 0`` ahead), scalars per unit length (N/m, W/m)."""
    res, seconds, scalars = _moving(problem_cfg, {**settings, "element_size": size})
    return Run("fem", size, scalars, np.asarray(res.pressure_x), np.asarray(res.pressure), seconds)


def run_rolling(problem_cfg: dict, settings: dict, size: float) -> Run:
    """Steady rolling of a sphere with the 3D FEM (half layer ``y >= 0``) with element
    size ``size`` (m) at the contact: ``Run.r`` holds the ``x`` (m, ``x > 0`` ahead) of the
    multiplier nodes on ``y = 0`` and ``Run.pressure`` their pressure (Pa); the scalars
    are totals over the whole layer (N, m, W), with ``rolling_resistance_slope`` the
    pressure's work rate over V (N)."""
    res, seconds, scalars = _moving(problem_cfg, {"model": "3d", **settings, "element_size": size})
    return Run("fem", size, scalars, np.asarray(res.pressure_x), np.asarray(res.pressure), seconds)


def _at_level(level: Level) -> dict:
    """The level's settings with the ``scaled`` ones multiplied by ``size / sizes[0]``."""
    settings = {k: v for k, v in level.settings.items() if k != "scaled"}
    for key in level.settings.get("scaled", []):
        settings[key] = settings[key] * level.size / level.sizes[0]
    return settings


def solve(problem: dict, level: Level) -> Run:
    """The method protocol: the case's ``[problem]`` at one level of ``[fem] element_sizes``
    (steady rolling in plane strain for ``[indenter] shape = "line"``; of a sphere in 3D
    for a speed > 0)."""
    settings = _at_level(level)
    if problem["indenter"].get("shape") == "line":
        return run_line(problem, settings, level.size)
    if problem["loading"].get("speed", 0.0) > 0:
        return run_rolling(problem, settings, level.size)
    return run(problem, settings, level.size)
