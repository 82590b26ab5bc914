"""Frictional steady rolling of a sphere on a viscoelastic layer (3D): the BEM
(``bem.solve`` with a :class:`bem.frictional.Friction`) against the 3D frictional FEM
reference (:mod:`fem_reference.frictional.three_d`: the moving-frame half layer condensed
to its normal and tangential surface compliance, and its own semi-smooth Newton Coulomb
solver). They share the material law, Coulomb's law and the rolling kinematics, nothing
else: the BEM sums the layer's Fourier modes on a periodic grid, the FEM transports the
viscous strains through a truncated half box.

Each kinematics of ``[friction_sphere] kinematics`` ("small_slope" or "exact": the FEM
has no "paper" kinematics) and each loading of ``loadings`` ("pushed_at_top" or "towed")
is solved with Coulomb's ``mu`` by the BEM at each spacing of ``bem_spacings`` (m; the
period ``period`` and the candidate half width ``half_width``, m) and by the FEM at each
element size of ``fem_element_sizes`` (m; ``fem_grading`` (-) and ``fem_far_size`` (m)
belong to the first size and scale with the element size, so each level refines the
whole mesh). One FEM factorization per level serves every kinematics and loading.

Gates (each the largest over the kinematics and loadings, at the finest levels):
``methods = ["bem"], against = "fem"``: ``rolling_resistance`` (R_r, relative),
``rolling_resistance_friction`` (R_r^F = sum S . w / V; the difference over the FEM's
R_r: friction's share of the rolling resistance, which the FEM resolves to its R_r's
accuracy while its slip rim, thinner than an element, leaves R_r^F itself unconverged),
``stick_fraction`` (stick area over contact area, the absolute difference);
``against = "energy"`` with ``methods`` ["bem"] and/or ["fem"]: ``energy_balance``,
|R_r - (P_visc + P_fric) / V| / R_r, each method's own.
"""

from __future__ import annotations

import copy
import math
import time

from ..formatting import fmt
from ..results import CaseResult, Table
from ..schema import CaseError, Field, check_table, close
from .friction_layer import bem_fem_gates, check_levels_and_gates

ADDS_METHODS = False
SECTIONS = ("friction_sphere",)
COMPARED = ("rolling_resistance", "rolling_resistance_friction", "stick_fraction")
QUANTITIES = (*COMPARED, "energy_balance")
LOADINGS = ("pushed_at_top", "towed")
KINEMATICS = ("small_slope", "exact")
SECTION = {
    "mu": Field("number", True, positive=True, doc="Coulomb coefficient (-)"),
    "kinematics": Field("strings", True, doc="rolling geometries, one run each: small_slope, exact"),
    "loadings": Field("strings", True, choices=LOADINGS, doc="loading modes, one run each"),
    "bem_spacings": Field("numbers", True, positive=True, doc="BEM node spacings (m), coarse to fine"),
    "period": Field("number", True, positive=True, doc="the BEM's period (m)"),
    "half_width": Field("number", True, positive=True, doc="the BEM's candidate half width (m)"),
    "fem_element_sizes": Field("numbers", True, positive=True, doc="FEM element sizes (m), coarse to fine"),
    "fem_grading": Field("number", positive=True, doc="FEM size growth (-) at the first element size"),
    "fem_far_size": Field("number", positive=True, doc="FEM far element size (m) at the first element size"),
}


def check(case: dict, path, methods: dict) -> None:
    problem = case["problem"]
    if problem["indenter"].get("shape") != "sphere":
        raise CaseError(f"{path} [problem] indenter.shape = {problem['indenter'].get('shape')!r}: a friction-sphere "
                        "case needs shape = \"sphere\" (the 3D frictional FEM reference rolls a sphere only)")
    if not problem["loading"].get("speed", 0.0) > 0 or "load" not in problem["loading"]:
        raise CaseError(f"{path} [problem] loading: a friction-sphere case needs speed > 0 (m/s) and the load (N)")
    if "friction_sphere" not in case:
        raise CaseError(f"{path}: a friction-sphere case needs a [friction_sphere] section")
    s = check_table(case["friction_sphere"], SECTION, f"{path} [friction_sphere]")
    for k in s["kinematics"]:
        if k not in KINEMATICS:
            raise CaseError(f"{path} [friction_sphere] kinematics: {k!r} is not one the 3D FEM reference represents; "
                            f"give {' or '.join(KINEMATICS)}{close(k, KINEMATICS)}")
    check_levels_and_gates(case, s, path, "friction_sphere", QUANTITIES)

def _fem_runs(cfg: dict, s: dict, ctx) -> list[dict]:
    from fem_reference.case import problem_from_dict
    from fem_reference.frictional import RollingFriction, solve_frictional_3d, surface_compliance_3d

    rows = []
    h0 = s["fem_element_sizes"][0]
    for h in s["fem_element_sizes"]:
        c = copy.deepcopy(cfg)
        c["fem"] = {"model": "3d", "element_size": h}
        for key, name in (("fem_grading", "grading"), ("fem_far_size", "far_size")):
            if key in s:
                c["fem"][name] = s[key] * h / h0
        problem = problem_from_dict(c)
        t0 = time.perf_counter()
        comp = surface_compliance_3d(problem, ctx.progress)
        t_comp = time.perf_counter() - t0
        runs = [(k, mode) for k in s["kinematics"] for mode in s["loadings"]]
        for kin, mode in runs:
            t1 = time.perf_counter()
            r = solve_frictional_3d(problem, RollingFriction(s["mu"], mode, kinematics=kin), compliance=comp)
            rows.append(dict(kinematics=kin, mode=mode, method="fem", level=h, Rr=r.rolling_resistance,
                             E=r.rolling_resistance_energy, RrF=r.rolling_resistance_friction, stick=r.stick_fraction,
                             xi=r.creepage, d=r.indentation, nodes=int(comp.n), memory=comp.peak_memory,
                             seconds=t_comp / len(runs) + time.perf_counter() - t1))
            ctx.progress(f"  {kin}, {mode}, FEM h = {h:g} m: R_r {r.rolling_resistance:.5f} N, "
                         f"R_r^F {r.rolling_resistance_friction:.3e} N, stick {r.stick_fraction:.3f}")
        comp.release()
    return rows


def _bem_runs(cfg: dict, s: dict, ctx) -> list[dict]:
    from bem import solve
    from bem.case import problem_from_config
    from bem.frictional import Friction

    rows = []
    V, R = cfg["loading"]["speed"], cfg["indenter"]["radius"]
    for a in s["bem_spacings"]:
        c = copy.deepcopy(cfg)
        c["grid"] = {"spacing": a, "period": s["period"], "truncation": math.ceil(s["period"] / (2 * a) - 1e-9),
                     "half_width": s["half_width"]}
        problem = problem_from_config(c)[0]
        for kin in s["kinematics"]:
            for mode in s["loadings"]:
                t1 = time.perf_counter()
                res = solve(problem, Friction(s["mu"], mode, kinematics=kin))
                rows.append(dict(kinematics=kin, mode=mode, method="bem", level=a, Rr=float(res.rolling_resistance),
                                 E=float(res.rolling_resistance_energy), RrF=float(res.rolling_resistance_friction),
                                 stick=float(res.stick_fraction), xi=float(1 - res.omega * R / V),
                                 d=float(res.indentation), nodes=int(res.contact.sum()), memory=math.nan,
                                 seconds=time.perf_counter() - t1))
                ctx.progress(f"  {kin}, {mode}, BEM a = {a:g} m: R_r {res.rolling_resistance:.5f} N, "
                             f"R_r^F {res.rolling_resistance_friction:.3e} N, stick {res.stick_fraction:.3f}")
    return rows


def errors(bem: dict, fem: dict) -> dict:
    """The compared quantities' errors of one BEM run against one FEM run (module docstring)."""
    return {
        "rolling_resistance": abs(bem["Rr"] - fem["Rr"]) / abs(fem["Rr"]),
        "rolling_resistance_friction": abs(bem["RrF"] - fem["RrF"]) / abs(fem["Rr"]),
        "stick_fraction": abs(bem["stick"] - fem["stick"]),
    }


def run(case: dict, ctx) -> CaseResult:
    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    s, cfg = case["friction_sphere"], case["problem"]
    rows = _bem_runs(cfg, s, ctx) + _fem_runs(cfg, s, ctx)
    finest = {(r["kinematics"], r["mode"], r["method"]): r for r in rows
              if r["level"] == min(s["bem_spacings"] if r["method"] == "bem" else s["fem_element_sizes"])}
    runs = [(k, m) for k in s["kinematics"] for m in s["loadings"]]
    compared = [(finest[(k, m, "bem")], finest[(k, m, "fem")]) for k, m in runs]
    compared = [(b, f, errors(b, f)) for b, f in compared]
    key = {"rolling_resistance": "Rr", "rolling_resistance_friction": "RrF", "stick_fraction": "stick"}
    bem_fem_gates(result, case["gates"], finest, runs, compared, key, "energy (P_visc + P_fric) / V")
    result.extra["friction_sphere"] = rows
    result.seconds = time.perf_counter() - t0
    return result


def tables(result: CaseResult) -> list[Table]:
    rows = tuple((r["kinematics"], r["mode"], r["method"], fmt(r["level"] * 1e6), fmt(r["Rr"]), fmt(r["E"]),
                  f"{r['RrF']:.4e}", f"{r['stick']:.4f}", f"{r['xi']:.4e}", fmt(r["d"] * 1e3), str(r["nodes"]),
                  "-" if not math.isfinite(r["memory"]) else f"{r['memory'] / 1e9:.2f}", f"{r['seconds']:.1f}")
                 for r in result.extra.get("friction_sphere", []))
    head = ("kinematics", "loading", "method", "spacing (um)", "R_r (N)", "energy (N)", "R_r^F (N)", "stick fraction",
            "xi (-)", "d (mm)", "nodes", "peak memory (GB)", "s")
    return [Table("Every kinematics, loading, method and level (nodes: the BEM's in contact, the FEM's "
                  "candidates on the half layer)", head, rows)] if rows else []


def figures(result: CaseResult, folder) -> list[str]:
    return []
