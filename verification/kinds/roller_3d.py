"""Steady rolling of a roller of finite length (``[indenter] shape = "cylinder"``): every
method on its levels, compared as in :mod:`.rolling_3d`, and the BEM's mid-plane against
the plane-strain line contact.

Method gates take the quantities of :mod:`.rolling_3d` and two more, read from each run:
``contact_length`` (m, ``leading_edge - trailing_edge`` on ``y = 0``, relative error) and
``peak_pressure_midplane`` (Pa, the largest pressure on ``y = 0``, relative; the whole
contact's ``peak_pressure`` sits where the rounded ends begin, the profile's curvature
jump, which each method resolves differently).

The mid-plane gate (``quantity = "midplane_pressure_rms_interior"``, ``methods =
["bem"]``, ``against = "plane_strain"``): for each roller length of ``[midplane]
lengths`` (m; the load per unit length of ``[problem]`` kept), the BEM's 3D pressure on
``y = 0`` against the plane-strain BEM (:class:`bem.indenters.LineCylinder` on a
:class:`bem.plane.LineGrid`, same layer, speed, node spacing and period) at the mid-plane's
own load per unit length (N/m, the 3D pressure on ``y = 0`` summed over ``x`` times the
spacing). The error is the RMS difference over the inner 90% of the line contact, over its
peak. The longest length is gated; the shorter ones are reported beside it, to show how
the ends' influence decays.
"""

from __future__ import annotations

import copy
import math
import time

import numpy as np

from ..formatting import fmt
from ..results import CaseResult, Gate, Table
from ..schema import CaseError, Field, check_table
from . import rolling_3d
from .gates import check_gate, check_methods

ADDS_METHODS = True
SECTIONS = ("bem", "fem", "methods", "midplane")
QUANTITIES = rolling_3d.QUANTITIES + ("contact_length", "peak_pressure_midplane")
MIDPLANE_QUANTITY = "midplane_pressure_rms_interior"
PLANE_STRAIN = "plane_strain"
MIDPLANE = {
    "lengths": Field("numbers", True, positive=True, doc="roller lengths L (m), short to long; the longest is gated"),
    "spacing": Field("number", True, positive=True, doc="node spacing a (m) of both BEM solves"),
    "period": Field("number", positive=True, doc="period (m) of both BEM solves, default 0.2"),
    "half_width": Field("number", True, positive=True, doc="candidate region |x| <= half_width (m)"),
}


def _split(case: dict) -> tuple[list, list]:
    mid = [g for g in case["gates"] if g["quantity"] == MIDPLANE_QUANTITY]
    return [g for g in case["gates"] if g["quantity"] != MIDPLANE_QUANTITY], mid


def check(case: dict, path, methods: dict) -> None:
    problem = case["problem"]
    if problem["indenter"].get("shape") != "cylinder":
        raise CaseError(f"{path} [problem] indenter: a roller-3d case needs shape = \"cylinder\"")
    from bem.indenters import Cylinder

    ind = problem["indenter"]
    try:  # the rules between the roller's keys, before anything is solved
        Cylinder(ind["radius"], ind["length"], ind.get("edge_radius", 0.0), ind.get("crown_radius"))
    except ValueError as exc:
        raise CaseError(f"{path} [problem] indenter: {exc}") from None
    if not problem["loading"].get("speed", 0.0) > 0 or "load" not in problem["loading"]:
        raise CaseError(f"{path} [problem] loading: a roller-3d case needs speed > 0 (m/s) and the load (N)")
    gates, mid = _split(case)
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        if gate in mid:
            if gate.get("methods") != ["bem"] or gate.get("against") != PLANE_STRAIN or "levels" in gate:
                raise CaseError(f"{where}: the mid-plane gate takes methods = [\"bem\"], against = "
                                f"\"{PLANE_STRAIN}\" and no levels")
            if "midplane" not in case:
                raise CaseError(f"{where}: needs a [midplane] section (lengths, spacing, half_width)")
            continue
        check_gate(gate, where, QUANTITIES, methods, ("dissipation",))
        if gate["against"] == "dissipation" and gate["quantity"] != "rolling_resistance":
            raise CaseError(f"{where}: the energy balance checks rolling_resistance")
        if "extrapolated" in gate.get("levels", []) and gate["quantity"] == "pressure_rms_interior":
            raise CaseError(f"{where}: only scalars are extrapolated, not 'pressure_rms_interior'")
    if "midplane" in case:
        check_table(case["midplane"], MIDPLANE, f"{path} [midplane]")
        lengths = case["midplane"]["lengths"]
        if lengths != sorted(lengths):
            raise CaseError(f"{path} [midplane] lengths must increase (short to long), got {lengths!r}")
    check_methods({**case, "gates": gates}, path, rolling_3d._used({**case, "gates": gates}), methods)


def _derive(run) -> None:
    """The roller's two extra scalars of a method's run (module docstring)."""
    s = run.scalars
    if "leading_edge" in s and "trailing_edge" in s:
        s["contact_length"] = s["leading_edge"] - s["trailing_edge"]
    if np.size(run.pressure):
        s["peak_pressure_midplane"] = float(np.max(run.pressure))


def midplane(problem: dict, length: float, settings: dict) -> dict:
    """The BEM's 3D roller of ``length`` (m) at the problem's load per unit length and the
    plane-strain BEM at the mid-plane's load per unit length: their pressures on ``y = 0``
    (Pa), the load per unit length (N/m), the RMS error (-) and the seconds."""
    import bem
    from bem.case import problem_from_config

    t0 = time.perf_counter()
    a, period = settings["spacing"], settings.get("period", 0.2)
    nt = math.ceil(period / (2 * a) - 1e-9)
    cfg = copy.deepcopy(problem)
    per_length = cfg["loading"]["load"] / cfg["indenter"]["length"]
    cfg["indenter"]["length"] = length
    cfg["loading"]["load"] = per_length * length
    cfg["grid"] = {"spacing": a, "period": period, "truncation": nt,
                   "half_width_x": settings["half_width"], "half_width_y": length / 2 + 2 * a}
    p3, _ = problem_from_config(cfg)
    r3 = bem.solve(p3, energy=False)
    row = p3.grid.shape[0] // 2  # a centred grid: a row on y = 0
    pressure = r3.pressure[row]
    line_load = float(pressure.sum() * a)
    line = copy.deepcopy(problem)
    line["indenter"] = {"shape": "line", "radius": problem["indenter"]["radius"]}
    line["loading"]["load"] = line_load
    line["grid"] = {"spacing": a, "period": period, "truncation": nt, "half_width": settings["half_width"]}
    p2, _ = problem_from_config(line)
    r2 = bem.solve(p2, energy=False)
    p_line = r2.pressure_profile
    centre, half = r2.contact_centre, 0.45 * (r2.leading_edge - r2.trailing_edge)
    inner = np.abs(p3.grid.x - centre) <= half
    error = float(np.sqrt(np.mean((pressure - p_line)[inner] ** 2)) / p_line.max())
    return {"length": length, "x": np.asarray(p3.grid.x), "pressure": pressure, "line_pressure": p_line,
            "line_load": line_load, "half_width": r2.half_width, "error": error,
            "seconds": time.perf_counter() - t0}


def run(case: dict, ctx) -> CaseResult:
    t0 = time.perf_counter()
    gates, mid = _split(case)
    result = rolling_3d.run({**case, "gates": gates}, ctx, derive=_derive)
    rows = result.extra["midplane"] = []
    if mid:
        for length in case["midplane"]["lengths"]:
            try:
                rows.append(midplane(case["problem"], length, case["midplane"]))
                m = rows[-1]
                ctx.progress(f"  {case['name']}: mid-plane L = {length * 1e3:g} mm: {m['line_load']:.6g} N/m, L / 2b = "
                             f"{length / m['half_width'] / 2:.3g}, RMS {m['error']:.3e} ({m['seconds']:.1f} s)")
            except Exception as exc:  # a failing solve fails the gate, not the suite
                rows.append({"length": length, "error": math.nan, "reason": f"{type(exc).__name__}: {exc}"})
    for spec in mid:
        for k, m in enumerate(rows):
            last = k == len(rows) - 1
            reason = spec["reason"] if last else f"L = {m['length'] * 1e3:g} mm, shown beside the gated longest length."
            result.gates.append(Gate(
                case=result.name,
                quantity=MIDPLANE_QUANTITY if last else f"{MIDPLANE_QUANTITY}[L={m['length'] * 1e3:g}mm]",
                method="bem", against=PLANE_STRAIN, level="finest", value=m["error"], reference=0.0,
                error=m["error"], tolerance=float(spec["tolerance"]) if last else math.inf,
                reason=m.get("reason", reason), report_only=bool(spec.get("report_only", False)) or not last))
    result.seconds = time.perf_counter() - t0
    return result


def tables(result: CaseResult) -> list[Table]:
    out = rolling_3d.tables(result)
    rows = tuple((fmt(m["length"] * 1e3), fmt(m.get("line_load", math.nan)),
                  fmt(m["length"] / (2 * m["half_width"])) if "half_width" in m else "-", fmt(m["error"]),
                  f"{m.get('seconds', math.nan):.1f}") for m in result.extra.get("midplane", []))
    if rows:
        out.append(Table("The BEM's mid-plane y = 0 against the plane-strain line contact",
                         ("L (mm)", "mid-plane load (N/m)", "L / 2b", "RMS / peak (inner 90%)", "time (s)"), rows))
    return out


def figures(result: CaseResult, folder) -> list[str]:
    files = rolling_3d.figures(result, folder)
    rows = [m for m in result.extra.get("midplane", []) if "pressure" in m]
    if rows:
        from ..formatting import new_figure

        fig = new_figure((6.4, 4.2))
        ax = fig.subplots()
        for k, m in enumerate(rows):
            ax.plot(m["x"] * 1e3, m["pressure"] / 1e6, "-", color=f"C{k}", lw=1.2,
                    label=f"3D, y = 0, L = {m['length'] * 1e3:g} mm")
        m = rows[-1]
        ax.plot(m["x"] * 1e3, m["line_pressure"] / 1e6, "k--", lw=1, label="plane strain (longest L's load)")
        ax.set_xlabel("x (mm), rolling towards +x")
        ax.set_ylabel("contact pressure (MPa)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        files.append(f"{result.name}-midplane.png")
        fig.savefig(folder / files[-1], dpi=110)
    return files
