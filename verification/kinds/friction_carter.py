"""Frictional steady rolling against Carter's plane-strain solution
(:mod:`verification.analytic.carter`): the mid-plane ``y = 0`` of a long 3D roller, and
the plane-strain BEM (a line contact per unit length, :class:`bem.plane.LineGrid`).

The 3D line contact is the mid-plane of a roller much longer than its contact
(``[problem] indenter shape = "cylinder"``) on an elastic layer much thicker than the
contact (a bonded layer of finite thickness couples the normal and tangential problems;
the half-space of Carter's theory does not). The rotational speed is prescribed (``mode =
"omega"``) from each creepage ``xi = (V - Omega R) / V``, the kinematics are
``small_slope`` (Carter's theory, rolling radius ``R``), and Carter's solution is taken
at the mid-plane's own load per unit length (N/m: the pressure on ``y = 0`` summed over
``x`` times the spacing).

The plane-strain BEM solves the same cylinder (``[indenter] shape = "line"``, radius
``R``) under the nominal load per unit length ``load / length`` with the same creepages,
kinematics and material, on a layer ``plane_depth`` thick with the period
``plane_depth``: in plane strain the coupling of a bonded layer decays slowly with its
thickness (at 75 a it leaves 0.018 mu P' in the creep force), and a layer as thick as its
period, 1000 a, is Carter's half-space to 1e-5 mu P' (docs/derivations.md, section 8).

``[carter]``: ``mu`` (-), ``spacing_x``, ``spacing_y``, ``period``, ``half_width_x``
(m) and ``creepages``: the creepages as fractions of the full-slip creepage ``mu a / R``
(``a`` of the nominal load per unit length, ``load / length``); for the plane-strain BEM
``plane_spacing_x`` and ``plane_depth`` (m), given together.

Gates (``methods = ["bem"]``, ``against = "analytic"``), each the largest over the
creepages: ``creep_force`` (``|Q' - Q_Carter| / (mu P')``, the mid-plane tangential force
per unit length), ``stick_edge`` (the trailing end of the stick zone, ``|x_bem -
x_Carter| / a``, creepages with a stick zone wider than two nodes), ``traction_rms`` (RMS
of ``q_bem - q_Carter`` over the contact nodes of ``y = 0``, over ``mu p0``); and the same
three of the plane-strain BEM, ``plane_creep_force``, ``plane_stick_edge`` and
``plane_traction_rms``.
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
QUANTITIES = ("creep_force", "stick_edge", "traction_rms", "plane_creep_force", "plane_stick_edge",
              "plane_traction_rms")
#: the gates' value and reference as the Runs tables show them: forces per unit length,
#: the stick zone's trailing end in mm, the traction RMS in units of mu p0
UNITS = {q: u for base, u in (("creep_force", ("N/m", 1.0)), ("stick_edge", ("mm", 1e3)),
                              ("traction_rms", ("of mu p0", 1.0))) for q in (base, f"plane_{base}")}
CARTER = {
    "mu": Field("number", True, positive=True, doc="Coulomb coefficient (-)"),
    "spacing_x": Field("number", True, positive=True, doc="node spacing along the rolling direction (m)"),
    "spacing_y": Field("number", True, positive=True, doc="node spacing along the roller's axis (m)"),
    "period": Field("number", True, positive=True, doc="period L_x = L_y (m)"),
    "half_width_x": Field("number", True, positive=True, doc="candidate region |x| <= half_width_x (m)"),
    "creepages": Field("numbers", True, doc="creepages over the full-slip creepage mu a / R (-), each > 0"),
    "plane_spacing_x": Field("number", positive=True, doc="node spacing of the plane-strain BEM (m)"),
    "plane_depth": Field("number", positive=True, doc="layer thickness and period of the plane-strain BEM (m)"),
}
PLANE = ("plane_spacing_x", "plane_depth")


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
    given = [k for k in PLANE if k in case["carter"]]
    if len(given) == 1:
        raise CaseError(f"{path} [carter] {given[0]}: plane_spacing_x and plane_depth go together (the "
                        "plane-strain BEM's spacing and layer); give both or neither")
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        if gate["quantity"].startswith("plane_") and not given:
            raise CaseError(f"{where}: a plane-strain gate needs [carter] plane_spacing_x and plane_depth (m)")
        if gate["quantity"] not in QUANTITIES:
            raise CaseError(f"{where}: unknown quantity {gate['quantity']!r}; known: {', '.join(QUANTITIES)}"
                            f"{close(gate['quantity'], QUANTITIES)}")
        if gate.get("methods") != ["bem"] or gate.get("against") != "analytic" or "levels" in gate:
            raise CaseError(f"{where}: takes methods = [\"bem\"], against = \"analytic\" and no levels")


def _truncation(period: float, spacing: float) -> int:
    """``N_t = L / (2 a)`` (rounded up): with ``L`` a multiple of ``a`` its end modes alias onto
    the lattice's Nyquist frequency at half weight (:func:`bem.spectral.end_weights`), so
    every lattice frequency takes one mode; one mode more would double three of them."""
    return math.ceil(period / (2 * spacing) - 1e-9)


def _problem(case: dict):
    from bem.case import problem_from_config

    s = case["carter"]
    cfg = copy.deepcopy(case["problem"])
    length = cfg["indenter"]["length"]
    cfg["grid"] = {
        "spacing_x": s["spacing_x"], "spacing_y": s["spacing_y"], "period": s["period"],
        "truncation_x": _truncation(s["period"], s["spacing_x"]),
        "truncation_y": _truncation(s["period"], s["spacing_y"]),
        "half_width_x": s["half_width_x"], "half_width_y": length / 2 + s["spacing_y"],
    }
    return problem_from_config(cfg)[0]


def _plane_problem(case: dict):
    """The plane-strain problem: the roller's radius and material as a line contact under
    ``load / length`` (N/m) on a layer ``plane_depth`` thick, period ``plane_depth``."""
    from bem.case import problem_from_config

    s, pr = case["carter"], case["problem"]
    depth, ax = s["plane_depth"], s["plane_spacing_x"]
    cfg = {"layer": {**pr["layer"], "thickness": depth}, "material": copy.deepcopy(pr["material"]),
           "indenter": {"shape": "line", "radius": pr["indenter"]["radius"]},
           "loading": {"speed": pr["loading"]["speed"], "load": pr["loading"]["load"] / pr["indenter"]["length"]},
           "grid": {"spacing": ax, "period": depth, "truncation": _truncation(depth, ax),
                    "half_width": s["half_width_x"]}}
    return problem_from_config(cfg)[0]


def _row(frac, xi, x, ax, pn, q, stick, mu, R, G) -> dict:
    """One creepage's figures from the pressure ``pn`` and traction ``q`` (Pa) and the stick
    nodes along the row ``x`` (m, spacing ``ax``), against Carter at the row's own load."""
    from verification.analytic.carter import carter_rolling_from_creepage

    load = float(pn.sum() * ax)
    ref = carter_rolling_from_creepage(load, R, G, mu, xi)
    contact = pn > 0
    force_err = abs(float(q.sum() * ax) - ref.tangential_force) / (mu * load)
    rms = float(np.sqrt(np.mean((q - ref.traction(x))[contact] ** 2)) / (mu * ref.peak_pressure))
    edge = float(x[stick].min()) if stick.any() else math.nan
    edge_ref = ref.stick_centre - ref.stick_half_width
    edge_err = abs(edge - edge_ref) / ref.half_width if ref.stick_half_width > 2 * ax else math.nan
    return dict(frac=frac, xi=xi, load=load, Q=float(q.sum() * ax), Q_ref=ref.tangential_force, edge=edge,
                edge_ref=edge_ref if ref.stick_half_width > 0 else math.nan, force_err=force_err,
                edge_err=edge_err, rms=rms)


def run(case: dict, ctx) -> CaseResult:
    from bem import solve
    from bem.frictional import Friction, solve_friction
    from bem.plane import line_kernels as bem_line_kernels
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
    line = _plane_problem(case) if "plane_depth" in s else None
    line_kernels = None if line is None else bem_line_kernels(line.grid, line.layer, V)
    rows, plane = [], []
    for frac in s["creepages"]:
        xi = frac * nominal.full_slip_creepage
        friction = Friction(mu, "omega", omega=V * (1 - xi) / R, kinematics="small_slope")
        res, _ = solve_friction(p, friction, kernels=kernels, energy=False)
        rows.append(r := _row(frac, xi, g.x, ax, res.force[j] / cell, res.force_x[j] / cell, res.stick[j], mu, R, G))
        text = f"mid-plane Q'/(mu P') = {r['Q'] / (mu * r['load']):.4f} (Carter {r['Q_ref'] / (mu * r['load']):.4f})"
        if line is not None:
            lr = solve(line, friction, energy=False, kernels=line_kernels)
            plane.append(r2 := _row(frac, xi, line.grid.x, line.grid.spacing, lr.pressure[0], lr.traction_x[0],
                                    lr.stick[0], mu, R, G))
            text += f", plane strain {r2['Q'] / (mu * r2['load']):.4f} (Carter {r2['Q_ref'] / (mu * r2['load']):.4f})"
        ctx.progress(f"  {case['name']}: xi = {xi:.3e}: {text}")
    key = {"creep_force": ("force_err", "Q", "Q_ref"), "stick_edge": ("edge_err", "edge", "edge_ref"),
           "traction_rms": ("rms", "rms", "rms")}
    for spec in case["gates"]:
        qty = spec["quantity"]
        base = qty.removeprefix("plane_")
        pick = [r for r in (plane if qty.startswith("plane_") else rows) if math.isfinite(r[key[base][0]])]
        row = max(pick, key=lambda r: r[key[base][0]], default=None)
        err, val, ref = (math.nan,) * 3 if row is None else (row[k] for k in key[base])
        result.gates.append(Gate(case=result.name, quantity=qty, method="bem", against="analytic (Carter)",
                                 level="finest", value=val, reference=0.0 if base == "traction_rms" else ref,
                                 error=err, tolerance=float(spec["tolerance"]), reason=spec["reason"],
                                 report_only=bool(spec.get("report_only", False))))
    result.extra["carter"] = rows
    if plane:
        result.extra["plane"] = plane
    result.seconds = time.perf_counter() - t0
    return result


def tables(result: CaseResult) -> list[Table]:
    head = ("xi / xi_full", "xi (-)", "P' (N/m)", "Q' BEM (N/m)", "Q' Carter (N/m)", "stick from (mm)",
            "Carter (mm)", "traction RMS / mu p0")
    out = []
    for name, title in (("carter", "Mid-plane against Carter"), ("plane", "Plane strain against Carter")):
        rows = tuple((fmt(r["frac"]), f"{r['xi']:.3e}", fmt(r["load"]), fmt(r["Q"]), fmt(r["Q_ref"]),
                      fmt(r["edge"] * 1e3), fmt(r["edge_ref"] * 1e3), fmt(r["rms"]))
                     for r in result.extra.get(name, []))
        if rows:
            out.append(Table(title, head, rows))
    return out


def figures(result: CaseResult, folder) -> list[str]:
    return []
