"""Viscoelastic rolling at very low and very high speed against the elastic contact with
the relaxed and the glassy modulus (the BEM only)."""

from __future__ import annotations

import copy
import time
from pathlib import Path

import numpy as np

from ..formatting import fmt, new_figure
from ..methods import bem
from ..results import CaseResult, Gate, Table
from ..schema import CaseError, Field, check_table, close

ADDS_METHODS = False
SECTIONS = ("bem", "limits")
QUANTITIES = ("indentation", "rolling_resistance", "pressure_max", "peak_pressure", "contact_radius", "load")
LIMIT = {
    "name": Field("string", True, doc="the limit's name, referred to by its gates"),
    "speed": Field("number", True, positive=True, doc="the extreme speed (m/s)"),
    "modulus": Field("string", True, choices=("relaxed", "glassy"), doc="the elastic modulus of the limit"),
    "reference_speed": Field("number", True, positive=True, doc="speed of the R_r the limit is measured against"),
    "period": Field("number", positive=True, doc="period L of this limit's grid (m)"),
}
BEM = {**bem.FIELDS}


def check(case: dict, path, methods: dict) -> None:
    if "bem" not in case or "limits" not in case:
        raise CaseError(f"{path}: a rolling-limits case needs [bem] and [[limits]]")
    check_table(case["bem"], BEM, f"{path} [bem]")
    if not isinstance(case["limits"], list) or not case["limits"]:
        raise CaseError(f"{path}: [[limits]] must be a non-empty array of tables")
    names = []
    for i, limit in enumerate(case["limits"]):
        check_table(limit, LIMIT, f"{path} limits[{i}]")
        names.append(limit["name"])
    if case["problem"]["material"]["model"] == "elastic":
        raise CaseError(f"{path} [problem] material: the limits of an elastic material are the material itself")
    used = set()
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        for key in ("methods", "against", "levels"):
            if key in gate:
                raise CaseError(f"{where}: {key!r} does not apply (the BEM against the elastic limit)")
        if gate.get("limit") not in names:
            raise CaseError(f"{where} limit: {gate.get('limit')!r} is not a limit of the case; known: "
                            f"{', '.join(names)}{close(gate.get('limit', ''), names)}")
        if gate["quantity"] not in QUANTITIES:
            raise CaseError(f"{where}: unknown quantity {gate['quantity']!r}; known: {', '.join(QUANTITIES)}"
                            f"{close(gate['quantity'], QUANTITIES)}")
        used.add(gate["limit"])
    for name in names:
        if name not in used:
            raise CaseError(f"{path}: limit {name!r} has no gate")


def _with(cfg: dict, speed: float) -> dict:
    out = copy.deepcopy(cfg)
    out["loading"]["speed"] = speed
    return out


def run(case: dict, ctx) -> CaseResult:
    from bem.case import material_from_config  # the limiting moduli

    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    base = case["problem"]
    material = material_from_config(base["material"], Path("."))
    spacing = case["bem"]["spacings"][-1]
    rows = []
    for limit in case["limits"]:
        modulus = material.relaxed_modulus if limit["modulus"] == "relaxed" else material.glassy_modulus
        elastic = _with(base, 0.0)
        elastic["material"] = {"model": "elastic", "shear_modulus": modulus}
        settings = dict(case["bem"], period=limit.get("period", case["bem"].get("period", 0.2)))
        visco = bem.run(_with(base, limit["speed"]), settings, spacing)
        still = bem.run(elastic, settings, spacing)
        mid = bem.run(_with(base, limit["reference_speed"]), settings, spacing)
        ctx.progress(f"  {case['name']}: V = {limit['speed']:g} m/s: d = {visco.scalars['indentation'] * 1e3:.6g} mm "
                     f"(elastic {limit['modulus']}: {still.scalars['indentation'] * 1e3:.6g} mm), "
                     f"R_r = {visco.scalars['rolling_resistance']:.3e} N")
        rows.append((limit, visco, still, mid))
        for spec in case["gates"]:
            if spec["limit"] != limit["name"]:
                continue
            q = spec["quantity"]
            if q == "rolling_resistance":  # relative to the rolling resistance at a middle speed
                value, ref = visco.scalars[q], mid.scalars[q]
                error = abs(value) / abs(ref)
            elif q == "pressure_max":
                value = float(np.abs(visco.field - still.field).max())
                ref = float(still.field.max())
                error = value / ref
            else:
                value, ref = visco.scalars[q], still.scalars[q]
                error = abs(value - ref) / abs(ref)
            result.gates.append(Gate(case=result.name, quantity=f"{q}[{limit['name']}]", method="bem",
                                     against=f"elastic G({limit['modulus']})", level="finest", value=value,
                                     reference=ref, error=error, tolerance=float(spec["tolerance"]),
                                     reason=spec["reason"], report_only=bool(spec.get("report_only", False))))
    result.extra["limits"] = rows
    result.seconds = time.perf_counter() - t0
    return result


def tables(result: CaseResult) -> list[Table]:
    rows = tuple((limit["name"], f"{limit['speed']:g}", limit["modulus"], fmt(v.scalars["indentation"] * 1e3),
                  fmt(e.scalars["indentation"] * 1e3), fmt(v.scalars["rolling_resistance"]),
                  fmt(m.scalars["rolling_resistance"])) for limit, v, e, m in result.extra.get("limits", []))
    head = ("limit", "V (m/s)", "elastic modulus", "d (mm)", "d elastic (mm)", "R_r (N)", "R_r at reference speed (N)")
    return [Table("Limits", head, rows)] if rows else []


def figures(result: CaseResult, folder) -> list[str]:
    rows = result.extra.get("limits", [])
    if not rows:
        return []
    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    for limit, visco, still, _ in rows:
        g = visco.grid
        j = g.y.size // 2
        ax.plot(g.x * 1e3, visco.field[j] / 1e6, "-", label=f"V = {limit['speed']:g} m/s")
        ax.plot(g.x * 1e3, still.field[j] / 1e6, "k:", lw=1)
    ax.set_xlabel("x (mm), y = 0")
    ax.set_ylabel("contact pressure (MPa)")
    ax.set_title("dotted: elastic contact with the limiting modulus", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    name = f"{result.name}-limits.png"
    fig.savefig(folder / name, dpi=110)
    return [name]
