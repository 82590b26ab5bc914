"""The verification runner: cases as data, each solved by the BEM and the FEM on refined
levels and compared with analytic limits, published values and each other.

A case file (``verification/cases/*.toml``) holds the physical problem (the schema of
``bem solve``), the refinement levels of each method, the analytic reference and the
gates: which quantity of which method is compared against which reference, with its
tolerance and the reason for it. Scalars are compared by relative difference; pressure
metrics are already differences relative to the reference's peak pressure.
"""

from __future__ import annotations

import math
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

import casefile

from . import analytic
from .metrics import fit_contact_radius, pressure_difference, richardson

__all__ = ["CASES_DIR", "Gate", "CaseResult", "load_case", "list_cases", "run_case"]

CASES_DIR = Path(__file__).resolve().parent / "cases"
SCALARS = ("contact_radius", "indentation", "peak_pressure", "load", "rolling_resistance")
PRESSURE = ("pressure_rms_interior", "pressure_max_interior", "pressure_rms_edge", "pressure_max_edge")


@dataclass
class Gate:
    """One compared quantity with its verdict."""

    case: str
    quantity: str
    method: str
    against: str
    level: str
    value: float
    reference: float
    error: float
    tolerance: float
    reason: str
    report_only: bool = False

    @property
    def within(self) -> bool:
        return bool(np.isfinite(self.error) and self.error <= self.tolerance)

    @property
    def passed(self) -> bool:
        """A report-only comparison is shown with its numbers but never fails the suite."""
        return self.report_only or self.within

    @property
    def verdict(self) -> str:
        if self.report_only:
            return "REPORTED"
        return "PASS" if self.within else "FAIL"


@dataclass
class Run:
    """One method at one refinement level: scalars and the samples of its pressure."""

    method: str
    size: float
    scalars: dict
    r: np.ndarray  # radii of the pressure samples (m)
    pressure: np.ndarray  # (Pa)
    seconds: float
    grid: object = None  # BEM: the grid and 2D pressure, for maps
    field: np.ndarray | None = None


@dataclass
class CaseResult:
    name: str
    title: str
    why: str
    kind: str
    runs: dict = field(default_factory=dict)  # method -> list[Run] (coarse to fine)
    convergence: dict = field(default_factory=dict)  # (method, quantity) -> Convergence
    reference: object = None  # analytic result, or None
    gates: list = field(default_factory=list)
    extra: dict = field(default_factory=dict)  # kind-specific tables for the report
    seconds: float = 0.0

    @property
    def passed(self) -> bool:
        return all(g.passed for g in self.gates)


def list_cases(directory: Path = CASES_DIR) -> list[Path]:
    return sorted(directory.glob("*.toml"))


def load_case(path: Path) -> dict:
    """A verification case; its ``[problem]`` is checked against the case-file schema
    (:mod:`casefile`), with paths resolved against the case file's folder."""
    path = Path(path)
    try:
        with path.open("rb") as fh:
            case = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise casefile.CaseFileError(f"{path}: not a valid TOML file: {exc}") from None
    for key in ("name", "title", "kind", "gates", "problem"):
        if key not in case:
            raise casefile.CaseFileError(f"{path}: a verification case needs '{key}'")
    case["problem"] = casefile.validate(case["problem"], source=f"{path} [problem]", folder=path.parent)
    return case


# --- methods ----------------------------------------------------------------------


def run_bem(problem_cfg: dict, bem_cfg: dict, spacing: float) -> Run:
    """The BEM on one grid; the truncation resolves the grid (``Nt = ceil(L / 2a)``)."""
    from bem.case import problem_from_config
    from bem.problem import solve_frictionless

    period = bem_cfg.get("period", 0.2)
    nt = math.ceil(bem_cfg.get("truncation_factor", 1.0) * period / (2 * spacing) - 1e-9)
    cfg = {k: dict(v) for k, v in problem_cfg.items()}
    cfg["grid"] = {"spacing": spacing, "period": period, "truncation": nt, "half_width": bem_cfg["half_width"]}
    problem, _ = problem_from_config(cfg)
    t = time.perf_counter()
    res, _ = solve_frictionless(problem)
    seconds = time.perf_counter() - t
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


def run_fem(problem_cfg: dict, fem_cfg: dict, size: float) -> Run:
    """The axisymmetric (or 3D) FEM with element size ``size`` (m) at the contact."""
    import fem_reference as fr

    from fem_reference.case import problem_from_dict

    settings = {k: v for k, v in fem_cfg.items() if k not in ("element_sizes",)}
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


def analytic_reference(spec: dict, problem_cfg: dict):
    """The analytic solution named in the case, or None."""
    name = spec.get("reference")
    if name is None:
        return None
    p = problem_cfg
    G = p["material"]["shear_modulus"]
    P, R, H = p["loading"]["load"], p["indenter"]["radius"], p["layer"]["thickness"]
    if name == "hertz":
        return analytic.hertz_contact(P, R, analytic.effective_modulus_from_shear(G))
    if name == "jaffar_thick":
        return analytic.jaffar_thick_layer_contact(P, R, H, G)
    if name == "jaffar_thin":
        return analytic.jaffar_thin_layer_contact(P, R, H, G)
    raise ValueError(f"unknown analytic reference {name!r}")


# --- comparisons ------------------------------------------------------------------


def _profile(run: Run):
    order = np.argsort(run.r)
    r, p = run.r[order], run.pressure[order]
    return lambda x: np.interp(x, r, p, right=0.0)


def _reference_value(result: CaseResult, against: str, quantity: str, level: str):
    """(value, pressure profile, contact radius) of the reference of a comparison."""
    if against == "analytic":
        ref = result.reference
        value = {"contact_radius": ref.contact_radius, "peak_pressure": ref.peak_pressure,
                 "indentation": getattr(ref, "indentation", math.nan), "load": ref.load}.get(quantity, math.nan)
        return value, ref.pressure, ref.contact_radius
    run = result.runs[against][-1]
    if level == "extrapolated" and quantity in SCALARS:
        value = result.convergence[(against, quantity)].extrapolated
    else:
        value = run.scalars.get(quantity, math.nan)
    return value, _profile(run), run.scalars["contact_radius"]


def evaluate_gates(case: dict, result: CaseResult) -> None:
    for spec in case["gates"]:
        quantity, against = spec["quantity"], spec["against"]
        levels = spec.get("levels", ["finest"])
        for method in spec["methods"]:
            if method not in result.runs:
                continue
            for level in levels:
                run = result.runs[method][-1]
                ref_value, ref_profile, ref_radius = _reference_value(result, against, quantity, level)
                if quantity in PRESSURE:
                    diff = pressure_difference(run.r, run.pressure, ref_profile, ref_radius)
                    value = getattr(diff, quantity.replace("pressure_", ""))
                    error, ref_value = value, 0.0
                    for other in PRESSURE:  # the other three metrics, shown alongside
                        if other != quantity:
                            v = float(getattr(diff, other.replace("pressure_", "")))
                            result.gates.append(Gate(result.name, other, method, against, level, v, 0.0, v,
                                                     math.inf, "Reported alongside the gated pressure metric.", True))
                else:
                    value = run.scalars[quantity]
                    if level == "extrapolated":
                        value = result.convergence[(method, quantity)].extrapolated
                    error = abs(value - ref_value) / abs(ref_value) if ref_value else math.nan
                result.gates.append(Gate(result.name, quantity, method, against, level, float(value),
                                         float(ref_value), float(error), float(spec["tolerance"]), spec["reason"],
                                         bool(spec.get("report_only", False))))


def run_case(case: dict, progress: Callable[[str], None] = print, quick: bool = False) -> CaseResult:
    """Solve one case with every method and level it names and evaluate its gates."""
    from . import kinds

    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    handler = kinds.HANDLERS.get(case["kind"])
    if handler is None:
        raise ValueError(f"case {case['name']}: unknown kind {case['kind']!r}; known: {sorted(kinds.HANDLERS)}")
    handler(case, result, progress, quick)
    result.seconds = time.perf_counter() - t0
    return result


def run_stationary(case: dict, result: CaseResult, progress, quick: bool) -> None:
    """BEM and FEM on their levels, the analytic limit, convergence and gates."""
    problem = case["problem"]
    result.reference = analytic_reference(case.get("analytic", {}), problem)
    for method, key, runner in (("bem", "spacings", run_bem), ("fem", "element_sizes", run_fem)):
        if method not in case:
            continue
        runs = []
        for size in case[method][key]:
            run = runner(problem, case[method], size)
            progress(f"  {case['name']}: {method} h = {size * 1e3:.4g} mm: r_c = "
                     f"{run.scalars['contact_radius'] * 1e3:.5f} mm, d = {run.scalars['indentation'] * 1e3:.6f} mm, "
                     f"p_max = {run.scalars['peak_pressure'] / 1e6:.5f} MPa ({run.seconds:.1f} s)")
            runs.append(run)
        result.runs[method] = runs
        if len(runs) >= 3:
            ratio = runs[-2].size / runs[-1].size
            for q in runs[-1].scalars:
                result.convergence[(method, q)] = richardson([r.scalars[q] for r in runs[-3:]], ratio)
    evaluate_gates(case, result)
