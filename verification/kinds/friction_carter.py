"""Frictional steady rolling of a long roller against Carter's plane-strain solution
(:mod:`verification.analytic.carter`), on the roller's mid-plane ``y = 0``.

``bem`` solves frictional rolling in 3D only, so the line contact is the mid-plane of a
roller much longer than its contact (``[problem] indenter shape = "cylinder"``) on an
elastic layer much thicker than the contact (a bonded layer of finite thickness couples
the normal and tangential problems; the half-space of Carter's theory does not). The
rotational speed is prescribed (``mode = "omega"``) from each creepage ``xi = (V - Omega
R) / V``, the kinematics are ``small_slope`` (Carter's theory, rolling radius ``R``), and
Carter's solution is taken at the mid-plane's own load per unit length (N/m: the
pressure on ``y = 0`` summed over ``x`` times the spacing).

``[carter]``: ``mu`` (-), ``spacing_x``, ``spacing_y``, ``period``, ``half_width_x``
(m) and ``creepages``: the creepages as fractions of the full-slip creepage ``mu a / R``
(``a`` of the nominal load per unit length, ``load / length``).

Gates (``methods = ["bem"]``, ``against = "analytic"``), each the largest over the
creepages: ``creep_force`` (``|Q' - Q_Carter| / (mu P')``, the mid-plane tangential force
per unit length), ``stick_edge`` (the trailing end of the stick zone, ``|x_bem -
x_Carter| / a``, creepages with a stick zone wider than two nodes), ``traction_rms`` (RMS
of ``q_bem - q_Carter`` over the contact nodes of ``y = 0``, over ``mu p0``).
"""

from __future__ import annotations

import copy
import math
import time

import numpy as np

from ..formatting import fmt
from ..results import CaseResult, Gate, Table
from ..schema import CaseError, Field, check_table, close

ADDS_METHODS = False
SECTIONS = ("carter",)
QUANTITIES = ("creep_force", "stick_edge", "traction_rms")
CARTER = {
    "mu": Field("number", True, positive=True, doc="Coulomb coefficient (-)"),
    "spacing_x": Field("number", True, positive=True, doc="node spacing along the rolling direction (m)"),
    "spacing_y": Field("number", True, positive=True, doc="node spacing along the roller's axis (m)"),
    "period": Field("number", True, positive=True, doc="period L_x = L_y (m)"),
    "half_width_x": Field("number", True, positive=True, doc="candidate region |x| <= half_width_x (m)"),
    "creepages": Field("numbers", True, doc="creepages over the full-slip creepage mu a / R (-), each > 0"),
}


def check(case: dict, path, methods: dict) -> None:
    problem = case["problem"]
    if problem["indenter"].get("shape") != "cylinder" or problem["material"].get("model") != "elastic":
        raise CaseError(f"{path} [problem]: a friction-carter case needs indenter shape = \"cylinder\" and "
                        "material model = \"elastic\"")
    if not problem["loading"].get("speed", 0.0) > 0 or "load" not in problem["loading"]:
        raise CaseError(f"{path} [problem] loading: a friction-carter case needs speed > 0 (m/s) and the load (N)")
    if "carter" not in case:
        raise CaseError(f"{path}: a friction-carter case needs a [carter] section")
    check_table(case["carter"], CARTER, f"{path} [carter]")
    bad = [c for c in case["carter"]["creepages"] if not c > 0]
    if bad:
        raise CaseError(f"{path} [carter] creepages: each must be > 0 (a fraction of mu a / R), got {bad[0]!r}")
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        if gate["quantity"] not in QUANTITIES:
            raise CaseError(f"{where}: unknown quantity {gate['quantity']!r}; known: {', '.join(QUANTITIES)}"
                            f"{close(gate['quantity'], QUANTITIES)}")
        if gate.get("methods") != ["bem"] or gate.get("against") != "analytic" or "levels" in gate:
            raise CaseError(f"{where}: takes methods = [\"bem\"], against = \"analytic\" and no levels")


def _problem(case: dict):
    from bem.case import problem_from_config

    s = case["carter"]
    cfg = copy.deepcopy(case["problem"])
    length = cfg["indenter"]["length"]
    cfg["grid"] = {
        "spacing_x": s["spacing_x"], "spacing_y": s["spacing_y"], "period": s["period"],
        "truncation_x": math.ceil(s["period"] / (2 * s["spacing_x"])) + 1,
        "truncation_y": math.ceil(s["period"] / (2 * s["spacing_y"])) + 1,
        "half_width_x": s["half_width_x"], "half_width_y": length / 2 + s["spacing_y"],
    }
    return problem_from_config(cfg)[0]


def run(case: dict, ctx) -> CaseResult:
    from bem.frictional import Friction, solve_friction
    from bem.problem import compute_kernels
    from bem.spectral import BLOCKS
    from verification.analytic.carter import carter_rolling_from_creepage

    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    s, pr = case["carter"], case["problem"]
    p = _problem(case)
    g, mu, V = p.grid, s["mu"], p.loading.speed
    R, G = p.indenter.radius, p.layer.material.shear_modulus
    nominal = carter_rolling_from_creepage(pr["loading"]["load"] / pr["indenter"]["length"], R, G, mu, 1e-9)
    kernels, _ = compute_kernels(p, BLOCKS, None)
    j, ax, cell = g.nodes_y // 2, g.spacing_x, g.cell_area
    x = g.x
    rows = []
    for frac in s["creepages"]:
        xi = frac * nominal.full_slip_creepage
        res, _ = solve_friction(p, Friction(mu, "omega", omega=V * (1 - xi) / R, kinematics="small_slope"),
                                kernels=kernels, energy=False)
        pn, q = res.force[j] / cell, res.force_x[j] / cell
        load = float(pn.sum() * ax)
        ref = carter_rolling_from_creepage(load, R, G, mu, xi)
        contact = pn > 0
        force_err = abs(float(q.sum() * ax) - ref.tangential_force) / (mu * load)
        rms = float(np.sqrt(np.mean((q - ref.traction(x))[contact] ** 2)) / (mu * ref.peak_pressure))
        stick = res.stick[j]
        edge = float(x[stick].min()) if stick.any() else math.nan
        edge_ref = ref.stick_centre - ref.stick_half_width
        edge_err = abs(edge - edge_ref) / ref.half_width if ref.stick_half_width > 2 * ax else math.nan
        rows.append(dict(frac=frac, xi=xi, load=load, Q=float(q.sum() * ax), Q_ref=ref.tangential_force, edge=edge,
                         edge_ref=edge_ref if ref.stick_half_width > 0 else math.nan, force_err=force_err,
                         edge_err=edge_err, rms=rms))
        ctx.progress(f"  {case['name']}: xi = {xi:.3e}: Q'/(mu P') = {q.sum() * ax / (mu * load):.4f} "
                     f"(Carter {ref.tangential_force / (mu * load):.4f}), traction RMS {rms:.4f} mu p0")
    worst = {"creep_force": max(rows, key=lambda r: r["force_err"]),
             "stick_edge": max((r for r in rows if math.isfinite(r["edge_err"])), key=lambda r: r["edge_err"],
                               default=None),
             "traction_rms": max(rows, key=lambda r: r["rms"])}
    key = {"creep_force": ("force_err", "Q", "Q_ref"), "stick_edge": ("edge_err", "edge", "edge_ref"),
           "traction_rms": ("rms", "rms", "rms")}
    for spec in case["gates"]:
        qty = spec["quantity"]
        row = worst[qty]
        err, val, ref = (math.nan,) * 3 if row is None else (row[k] for k in key[qty])
        result.gates.append(Gate(case=result.name, quantity=qty, method="bem", against="analytic (Carter)",
                                 level="finest", value=val, reference=0.0 if qty == "traction_rms" else ref,
                                 error=err, tolerance=float(spec["tolerance"]), reason=spec["reason"],
                                 report_only=bool(spec.get("report_only", False))))
    result.extra["carter"] = rows
    result.seconds = time.perf_counter() - t0
    return result


def tables(result: CaseResult) -> list[Table]:
    rows = tuple((fmt(r["frac"]), f"{r['xi']:.3e}", fmt(r["load"]), fmt(r["Q"]), fmt(r["Q_ref"]),
                  fmt(r["edge"] * 1e3), fmt(r["edge_ref"] * 1e3), fmt(r["rms"]))
                 for r in result.extra.get("carter", []))
    head = ("xi / xi_full", "xi (-)", "P' (N/m)", "Q' BEM (N/m)", "Q' Carter (N/m)", "stick from (mm)",
            "Carter (mm)", "traction RMS / mu p0")
    return [Table("Mid-plane against Carter", head, rows)] if rows else []


def figures(result: CaseResult, folder) -> list[str]:
    return []
