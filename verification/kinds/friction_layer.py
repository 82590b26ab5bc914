"""Frictional steady rolling of a cylinder on thin viscoelastic layers in plane strain:
the BEM's line solver (``bem.solve`` on a :class:`bem.plane.LineGrid` with a
:class:`bem.frictional.Friction`) against the frictional FEM reference
(:mod:`fem_reference.frictional`: the moving-frame FEM layer condensed to its normal and
tangential surface compliance, and its own dense Coulomb solver). They share the
material law and Coulomb's law, nothing else: the BEM sums the layer's Fourier modes on
a periodic line, the FEM transports the viscous strains through a truncated section.

On a layer about as thick as the contact and thinner, the bonded incompressible layer
couples the normal and tangential problems, so friction shifts the pressure, the
rolling resistance and the creepage. Each layer of ``[friction_layer] thicknesses`` (m)
is solved for each loading of ``loadings`` ("pushed_at_top", "towed", or "omega" with
the creepage ``creepage``), by the BEM at each spacing of ``bem_spacings`` (m) and by the
FEM at each element size of ``fem_element_sizes`` (m); both take the candidate region
|x| <= ``half_width`` (m) and Coulomb's ``mu`` with ``kinematics``; the BEM's period is
``period`` (m). The tables show every level (the convergence of each method).

Gates (each the largest over the layers and loadings, at the finest levels):
``methods = ["bem"], against = "fem"``: ``rolling_resistance`` (R_r', relative),
``rolling_resistance_friction`` (R_r^F' = sum S w / V, relative to the FEM's),
``driving_force`` (|Q'_bem - Q'_fem| / (mu P')), ``creepage`` (xi of the loadings that
solve for it, relative), ``stick_edge`` (the trailing end of the stick zone, over the
FEM's contact length); ``against = "energy"`` with ``methods`` ["bem"] and/or ["fem"]:
``energy_balance``, |R_r' - (P_visc' + P_fric') / V| / R_r', each method's own.
"""

from __future__ import annotations

import copy
import math
import time

from ..formatting import fmt
from ..results import CaseResult, Gate, Table
from ..schema import CaseError, Field, check_table, close

ADDS_METHODS = False
SECTIONS = ("friction_layer",)
COMPARED = ("rolling_resistance", "rolling_resistance_friction", "driving_force", "creepage", "stick_edge")
QUANTITIES = (*COMPARED, "energy_balance")
#: the gates' value and reference in the Runs tables' units: per unit length (N/m), the
#: stick zone's trailing end in mm
UNITS = {"rolling_resistance": ("N/m", 1.0), "rolling_resistance_friction": ("N/m", 1.0),
         "driving_force": ("N/m", 1.0), "creepage": ("-", 1.0), "stick_edge": ("mm", 1e3),
         "energy_balance": ("N/m", 1.0)}
LOADINGS = ("pushed_at_top", "towed", "omega")
SECTION = {
    "mu": Field("number", True, positive=True, doc="Coulomb coefficient (-)"),
    "kinematics": Field("string", choices=("small_slope", "exact"), doc="rolling geometry (default small_slope)"),
    "thicknesses": Field("numbers", True, positive=True, doc="layer thicknesses H (m), one run each"),
    "loadings": Field("strings", True, choices=LOADINGS, doc="loading modes, one run each"),
    "creepage": Field("number", doc="xi = (V - Omega R) / V (-) of the omega loading"),
    "bem_spacings": Field("numbers", True, positive=True, doc="BEM node spacings (m), coarse to fine"),
    "period": Field("number", True, positive=True, doc="the BEM's period (m)"),
    "half_width": Field("number", True, positive=True, doc="candidate region |x| <= half_width (m), both methods"),
    "fem_element_sizes": Field("numbers", True, positive=True, doc="FEM element sizes (m), coarse to fine"),
}

def check(case: dict, path, methods: dict) -> None:
    problem = case["problem"]
    if problem["indenter"].get("shape") != "line":
        raise CaseError(f"{path} [problem] indenter: a friction-layer case needs shape = \"line\" (plane strain)")
    if not problem["loading"].get("speed", 0.0) > 0 or "load" not in problem["loading"]:
        raise CaseError(f"{path} [problem] loading: a friction-layer case needs speed > 0 (m/s) and the load (N/m)")
    if "friction_layer" not in case:
        raise CaseError(f"{path}: a friction-layer case needs a [friction_layer] section")
    s = check_table(case["friction_layer"], SECTION, f"{path} [friction_layer]")
    if ("omega" in s["loadings"]) != ("creepage" in s):
        raise CaseError(f"{path} [friction_layer] creepage: given with loadings containing \"omega\" and only "
                        f"then, got loadings = {s['loadings']!r}, creepage = {s.get('creepage')!r}")
    check_levels_and_gates(case, s, path, "friction_layer", QUANTITIES)
    for i, gate in enumerate(case["gates"]):
        if gate["quantity"] == "creepage" and set(s["loadings"]) == {"omega"}:
            raise CaseError(f"{path} gates[{i}] (creepage): the creepage is given in every loading (\"omega\"); add "
                            "\"pushed_at_top\" or \"towed\" to loadings, or remove the gate")


def check_levels_and_gates(case: dict, s: dict, path, section: str, quantities) -> None:
    """What a BEM-against-FEM frictional kind's case must say of its levels and gates:
    ``bem_spacings`` and ``fem_element_sizes`` coarse to fine; each gate a known quantity at
    the finest level, ``bem`` against ``fem``, or ``energy_balance`` of either method
    against its energy figure. ``section``: the kind's section, ``[friction_layer]`` say."""
    for key in ("bem_spacings", "fem_element_sizes"):
        if list(s[key]) != sorted(s[key], reverse=True):
            raise CaseError(f"{path} [{section}] {key}: coarse to fine (decreasing), got {s[key]!r}")
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        q = gate["quantity"]
        if q not in quantities:
            raise CaseError(f"{where}: unknown quantity {q!r}; known: {', '.join(quantities)}{close(q, quantities)}")
        if "levels" in gate:
            raise CaseError(f"{where}: 'levels' does not apply to this kind (the finest level is gated)")
        if q == "energy_balance":
            ok = gate.get("against") == "energy" and gate.get("methods") and set(gate["methods"]) <= {"bem", "fem"}
            if not ok:
                raise CaseError(f"{where}: takes against = \"energy\" and methods among \"bem\", \"fem\"")
        elif gate.get("methods") != ["bem"] or gate.get("against") != "fem":
            raise CaseError(f"{where}: takes methods = [\"bem\"] and against = \"fem\"")

def _fem_runs(cfg: dict, s: dict, H: float, ctx) -> list[dict]:
    from fem_reference.case import problem_from_dict
    from fem_reference.frictional import RollingFriction, solve_frictional, surface_compliance

    rows = []
    for h in s["fem_element_sizes"]:
        c = copy.deepcopy(cfg)
        c["layer"]["thickness"] = H
        c["fem"] = {"element_size": h, "contact_zone": s["half_width"]}
        problem = problem_from_dict(c)
        t0 = time.perf_counter()
        comp = surface_compliance(problem)
        t_comp = time.perf_counter() - t0
        for mode in s["loadings"]:
            t1 = time.perf_counter()
            fr = RollingFriction(s["mu"], "omega" if mode == "omega" else mode,
                                 creepage=s.get("creepage") if mode == "omega" else None,
                                 kinematics=s.get("kinematics", "small_slope"))
            r = solve_frictional(problem, fr, compliance=comp)
            trail, lead = r.contact_edges
            rows.append(dict(H=H, mode=mode, method="fem", level=h, Rr=r.rolling_resistance,
                             E=r.rolling_resistance_energy, RrF=r.rolling_resistance_friction, Q=r.driving_force,
                             xi=r.creepage, stick=r.stick_zone[0], trail=trail, lead=lead, load=r.load,
                             nodes=int(comp.n), seconds=t_comp / len(s["loadings"]) + time.perf_counter() - t1))
            ctx.progress(f"  H = {H * 1e3:g} mm, {mode}, FEM h = {h:g} m: R_r' {r.rolling_resistance:.5f} N/m, "
                         f"R_r^F' {r.rolling_resistance_friction:.5f} N/m, Q' {r.driving_force:.5f} N/m")
    return rows

def _bem_runs(cfg: dict, s: dict, H: float, ctx) -> list[dict]:
    from bem import solve
    from bem.case import problem_from_config
    from bem.frictional import Friction

    rows = []
    V, R = cfg["loading"]["speed"], cfg["indenter"]["radius"]
    for a in s["bem_spacings"]:
        c = copy.deepcopy(cfg)
        c["layer"]["thickness"] = H
        c["grid"] = {"spacing": a, "period": s["period"], "truncation": math.ceil(s["period"] / (2 * a) - 1e-9),
                     "half_width": s["half_width"]}
        problem = problem_from_config(c)[0]
        for mode in s["loadings"]:
            t1 = time.perf_counter()
            omega = V * (1 - s["creepage"]) / R if mode == "omega" else None
            res = solve(problem, Friction(s["mu"], mode, omega=omega, kinematics=s.get("kinematics", "small_slope")))
            x, st, ct = res.grid.x, res.stick[0], res.contact[0]
            rows.append(dict(H=H, mode=mode, method="bem", level=a, Rr=float(res.rolling_resistance),
                             E=float(res.rolling_resistance_energy), RrF=float(res.rolling_resistance_friction),
                             Q=float(res.driving_force), xi=float(1 - res.omega * R / V),
                             stick=float(x[st].min()) if st.any() else math.nan, trail=float(x[ct].min()),
                             lead=float(x[ct].max()), load=float(res.load), nodes=int(len(x)),
                             seconds=time.perf_counter() - t1))
            ctx.progress(f"  H = {H * 1e3:g} mm, {mode}, BEM a = {a:g} m: R_r' {res.rolling_resistance:.5f} N/m, "
                         f"R_r^F' {res.rolling_resistance_friction:.5f} N/m, Q' {res.driving_force:.5f} N/m")
    return rows


def errors(bem: dict, fem: dict, mu: float) -> dict:
    """The compared quantities' errors of one BEM run against one FEM run (module
    docstring); nan where a quantity does not apply (the creepage where it is given, the
    stick edge without a stick zone)."""
    given = bem["mode"] == "omega"
    return {
        "rolling_resistance": abs(bem["Rr"] - fem["Rr"]) / abs(fem["Rr"]),
        "rolling_resistance_friction": abs(bem["RrF"] - fem["RrF"]) / abs(fem["RrF"]),
        "driving_force": abs(bem["Q"] - fem["Q"]) / (mu * fem["load"]),
        "creepage": math.nan if given else abs(bem["xi"] - fem["xi"]) / abs(fem["xi"]),
        "stick_edge": abs(bem["stick"] - fem["stick"]) / (fem["lead"] - fem["trail"]),
    }


def run(case: dict, ctx) -> CaseResult:
    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    s, cfg = case["friction_layer"], case["problem"]
    rows = []
    for H in s["thicknesses"]:
        rows += _bem_runs(cfg, s, H, ctx) + _fem_runs(cfg, s, H, ctx)
    finest = {(r["H"], r["mode"], r["method"]): r for r in rows
              if r["level"] == min(s["bem_spacings"] if r["method"] == "bem" else s["fem_element_sizes"])}
    runs = [(H, m) for H in s["thicknesses"] for m in s["loadings"]]
    compared = [(finest[(*r, "bem")], finest[(*r, "fem")]) for r in runs]
    compared = [(b, f, errors(b, f, s["mu"])) for b, f in compared]
    key = {"rolling_resistance": "Rr", "rolling_resistance_friction": "RrF", "driving_force": "Q", "creepage": "xi",
           "stick_edge": "stick"}
    bem_fem_gates(result, case["gates"], finest, runs, compared, key, "energy (P_visc' + P_fric') / V")
    result.extra["friction_layer"] = rows
    result.seconds = time.perf_counter() - t0
    return result


def bem_fem_gates(result: CaseResult, specs, finest: dict, runs, compared, key: dict, energy_against: str) -> None:
    """Append one gate per spec to ``result``, each the worst over ``runs`` (the ``(case
    parameter, loading)`` pairs of the ``finest`` levels, keyed ``(parameter, loading,
    method)``): ``energy_balance`` of each named method, ``R_r`` against its energy figure
    ``E``; any other quantity, the BEM against the FEM over ``compared`` (``(bem, fem,
    errors)`` triples; ``key`` names each quantity's row field), NaN where none applies."""
    for spec in specs:
        q = spec["quantity"]
        common = dict(case=result.name, quantity=q, level="finest", tolerance=float(spec["tolerance"]),
                      reason=spec["reason"], report_only=bool(spec.get("report_only", False)))
        if q == "energy_balance":
            for method in spec["methods"]:
                worst = max((finest[(*r, method)] for r in runs), key=lambda r: abs(r["Rr"] - r["E"]) / abs(r["Rr"]))
                result.gates.append(Gate(method=method, against=energy_against, value=worst["Rr"],
                                         reference=worst["E"], error=abs(worst["Rr"] - worst["E"]) / abs(worst["Rr"]),
                                         **common))
            continue
        valid = [c for c in compared if math.isfinite(c[2][q])]
        if not valid:
            result.gates.append(Gate(method="bem", against="fem", value=math.nan, reference=math.nan, error=math.nan,
                                     **common))
            continue
        b, f, e = max(valid, key=lambda c: c[2][q])
        result.gates.append(Gate(method="bem", against="fem", value=b[key[q]], reference=f[key[q]], error=e[q],
                                 **common))


def tables(result: CaseResult) -> list[Table]:
    rows = tuple((fmt(r["H"] * 1e3), r["mode"], r["method"], fmt(r["level"] * 1e6), fmt(r["Rr"]), fmt(r["E"]),
                  fmt(r["RrF"]), fmt(r["Q"]), f"{r['xi']:.4e}", fmt(r["stick"] * 1e3), fmt(r["trail"] * 1e3),
                  fmt(r["lead"] * 1e3), f"{r['seconds']:.1f}")
                 for r in result.extra.get("friction_layer", []))
    head = ("H (mm)", "loading", "method", "spacing (um)", "R_r' (N/m)", "energy (N/m)", "R_r^F' (N/m)", "Q' (N/m)",
            "xi (-)", "stick from (mm)", "contact from (mm)", "to (mm)", "s")
    return [Table("Every layer, loading, method and level", head, rows)] if rows else []

def figures(result: CaseResult, folder) -> list[str]:
    return []
