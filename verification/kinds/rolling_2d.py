"""Steady viscoelastic rolling in plane strain over a speed sweep: a rigid cylinder on a
layer (per unit length), each method at every speed, against Hunter's (1961) half-space
solution and against each other; optionally repeated for several layer thicknesses.

Speeds are given as ``V tau / b0`` (``[speeds] scaled``, tau the material's creep time,
b0 = sqrt(P R / (pi G0)) the 2D Hertz half-width with the relaxed modulus) or in m/s
(``[speeds] values``), with ``[speeds] quick`` the subset ``verify --quick`` runs;
thicknesses as ``H / b0`` (``[layers] scaled``).

How errors are measured (one gate = the largest error over the speeds):

- ``rolling_resistance``: ``|R_r - R_r,ref|`` over the largest ``|R_r,ref|`` of the sweep
  (near zero at both ends of the sweep, a relative error there would measure round-off);
- ``leading_edge``, ``trailing_edge``: the distance over the reference's contact length;
- ``indentation``, ``peak_pressure``: relative;
- ``pressure_rms_interior``: RMS of ``p - p_ref`` over the inner 90% of the reference's
  contact (as ``r < 0.9 r_c`` at rest: at the edges the pressure's steep fall makes any
  interpolation between two discretizations differ by more than either's error), over
  the reference's peak;
- ``rolling_resistance`` against ``dissipation``: the method's own energy balance,
  ``|W - D / V|`` over the largest ``D / V`` (D the dissipated power per unit length),
  ``W = int p s'(x) dx`` the pressure's work rate over V when the method gives it
  (``rolling_resistance_slope``), else its ``R_r``: the paper's ``x / R`` arm is the
  small-slope form of ``s'(x)``, ``~ b^2 / 2 R^2`` below it.
"""

from __future__ import annotations

import copy
import math
import time

import numpy as np

from ..formatting import fmt, new_figure
from ..results import CaseResult, Gate, Run, Table
from ..schema import CaseError, Field, check_table
from .gates import check_gate, check_methods, used_methods

__all__ = ["errors", "scales"]

ADDS_METHODS = True
SECTIONS = ("analytic", "bem", "fem", "methods", "speeds", "layers")
QUANTITIES = ("rolling_resistance", "leading_edge", "trailing_edge", "indentation", "peak_pressure", "pressure_rms_interior")
SPEEDS = {"scaled": Field("numbers", positive=True, doc="V tau / b0 (-)"),
          "values": Field("numbers", positive=True, doc="V (m/s)"),
          "quick": Field("numbers", positive=True, doc="the speeds verify --quick runs, in the list's unit")}
LAYERS = {"scaled": Field("numbers", True, positive=True, doc="H / b0 (-)"),
          "fem_elements_across": Field("number", positive=True,
                                       doc="the FEM's element size is at most H / this, on every layer")}
ANALYTIC = {"reference": Field("string", True, choices=("hunter",), doc="Hunter (1961), the half-space")}


def scales(problem: dict) -> tuple[float, float]:
    """(b0, tau): the relaxed 2D Hertz half-width (m) and the material's creep time (s)."""
    m = problem["material"]
    G0 = m.get("G0", m.get("G_inf", m.get("shear_modulus")))
    if m["model"] == "prony":
        tau = max(m["tau"])
    else:
        tau = m.get("tau", math.nan)
    b0 = math.sqrt(problem["loading"]["load"] * problem["indenter"]["radius"] / (math.pi * G0))
    return b0, tau


def _speeds(case: dict, quick: bool = False) -> list[float]:
    """The speeds (m/s); with ``quick``, only those of ``[speeds] quick`` if it is given."""
    b0, tau = scales(case["problem"])
    s = case["speeds"]
    given = s["scaled"] if "scaled" in s else s["values"]
    if quick and "quick" in s:
        given = [x for x in given if x in s["quick"]]
    return [x * b0 / tau for x in given] if "scaled" in s else list(given)


def _parts(case: dict):
    """(label, case with its thickness) for each layer of ``[layers]``, or the one layer."""
    if "layers" not in case:
        yield "", case
        return
    b0, _ = scales(case["problem"])
    across = case["layers"].get("fem_elements_across")
    for x in case["layers"]["scaled"]:
        sub = copy.deepcopy(case)
        sub["problem"]["layer"]["thickness"] = x * b0
        if across and "fem" in sub:
            sub["fem"]["element_sizes"] = [min(h, x * b0 / across) for h in sub["fem"]["element_sizes"]]
        yield f"H/b0={x:g}", sub


PSEUDO = ("analytic", "dissipation")  # references that are not methods


def _used(case: dict) -> list[str]:
    return used_methods(case, PSEUDO)


def check(case: dict, path, methods: dict) -> None:
    problem = case["problem"]
    if problem["indenter"].get("shape") != "line":
        raise CaseError(f"{path} [problem] indenter: a rolling-2d case is a line contact (shape = \"line\")")
    if "load" not in problem["loading"]:
        raise CaseError(f"{path} [problem] loading: give the load per unit length (N/m)")
    if "speeds" not in case:
        raise CaseError(f"{path}: a rolling-2d case needs [speeds] scaled (V tau / b0) or values (m/s)")
    check_table(case["speeds"], SPEEDS, f"{path} [speeds]")
    listed = [k for k in ("scaled", "values") if k in case["speeds"]]
    if len(listed) != 1:
        raise CaseError(f"{path} [speeds]: give exactly one of scaled and values")
    extra = [x for x in case["speeds"].get("quick", []) if x not in case["speeds"][listed[0]]]
    if extra:
        raise CaseError(f"{path} [speeds] quick: {extra} not in {listed[0]} (the quick speeds are a subset)")
    if "scaled" in case["speeds"] or "layers" in case:
        if problem["material"]["model"] not in ("three_parameter", "prony"):
            raise CaseError(f"{path}: scaled speeds need a material with a time scale (three_parameter, prony)")
    if "layers" in case:
        check_table(case["layers"], LAYERS, f"{path} [layers]")
    if "analytic" in case:
        check_table(case["analytic"], ANALYTIC, f"{path} [analytic]")
        if problem["material"]["model"] != "three_parameter":
            raise CaseError(f"{path} [analytic]: Hunter's solution is for the three-parameter solid")
        if problem["layer"].get("density", 0.0) != 0:
            raise CaseError(f"{path} [analytic]: Hunter's solution has no inertia; set density = 0")
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        check_gate(gate, where, QUANTITIES, methods, PSEUDO, levels=None, kind="rolling-2d")
        q, against = gate["quantity"], gate["against"]
        if against == "analytic" and "analytic" not in case:
            raise CaseError(f"{where}: against = 'analytic' needs [analytic] reference = \"hunter\"")
        if against == "analytic" and q == "indentation":
            raise CaseError(f"{where}: a half-space in plane strain has no finite indentation")
        if against == "dissipation" and q != "rolling_resistance":
            raise CaseError(f"{where}: the energy balance checks rolling_resistance")
    check_methods(case, path, _used(case), methods)


def _hunter(problem: dict, speed: float):
    from ..analytic import hunter_rolling_contact

    m = problem["material"]
    return hunter_rolling_contact(problem["loading"]["load"], problem["indenter"]["radius"], m["G0"], m["tau"],
                                  m["f"], speed)


class _Reference:
    """The analytic solution shaped like a run: scalars and a pressure profile."""

    def __init__(self, h):
        self.scalars = {q: getattr(h, q) for q in ("rolling_resistance", "leading_edge", "trailing_edge",
                                                   "peak_pressure")}
        self.pressure_of = h.pressure


def _solve_part(case: dict, ctx, label: str, result: CaseResult) -> dict:
    """Every method at every speed (finest level last); returns {method: [runs per speed]}."""
    speeds = _speeds(case, ctx.quick)
    failed = result.extra.setdefault("failed", {})
    out = {}
    for name in _used(case):
        method = ctx.methods[name]
        finest = method.levels(case)[-1]  # the gated level; coarser ones would be solved for nothing
        runs = []
        try:
            for V in speeds:
                problem = copy.deepcopy(case["problem"])
                problem["loading"]["speed"] = V
                run = method.solve(problem, finest)
                if not isinstance(run, Run):
                    raise TypeError(f"method {name!r} returned {type(run).__name__}, not verification.results.Run")
                ctx.progress(f"  {case['name']}{label and ' ' + label}: {name} V = {V:.4g} m/s: R_r = "
                             f"{run.scalars.get('rolling_resistance', math.nan):.6g} N/m, edges "
                             f"{run.scalars.get('trailing_edge', math.nan) * 1e3:.4f}.."
                             f"{run.scalars.get('leading_edge', math.nan) * 1e3:.4f} mm ({run.seconds:.1f} s)")
                runs.append(run)
        except Exception as exc:  # one failing method fails its gates, not the suite
            failed[(label, name)] = f"{type(exc).__name__}: {exc}"
            ctx.progress(f"  {case['name']}{label and ' ' + label}: {name} FAILED: {failed[(label, name)]}")
            continue
        out[name] = runs
    if "analytic" in case:
        out["analytic"] = [_Reference(_hunter(case["problem"], V)) for V in speeds]
    return out


def errors(quantity: str, runs, refs) -> list[float]:
    """Errors of ``runs`` against ``refs`` (same length), as the module's docstring says."""
    if quantity == "rolling_resistance":
        scale = max(abs(r.scalars["rolling_resistance"]) for r in refs)
        return [abs(a.scalars[quantity] - b.scalars[quantity]) / scale for a, b in zip(runs, refs)]
    if quantity in ("leading_edge", "trailing_edge"):
        return [abs(a.scalars[quantity] - b.scalars[quantity]) / (b.scalars["leading_edge"] - b.scalars["trailing_edge"])
                for a, b in zip(runs, refs)]
    if quantity == "pressure_rms_interior":
        out = []
        for a, b in zip(runs, refs):
            lo, hi = b.scalars["trailing_edge"], b.scalars["leading_edge"]
            centre, half = 0.5 * (lo + hi), 0.45 * (hi - lo)
            inside = (a.r > centre - half) & (a.r < centre + half)
            ref = b.pressure_of(a.r[inside]) if hasattr(b, "pressure_of") else \
                np.interp(a.r[inside], b.r, b.pressure, left=0.0, right=0.0)
            out.append(float(np.sqrt(np.mean((a.pressure[inside] - ref) ** 2)) / b.scalars["peak_pressure"]))
        return out
    return [abs(a.scalars[quantity] - b.scalars[quantity]) / abs(b.scalars[quantity]) for a, b in zip(runs, refs)]


def _energy_errors(runs, speeds) -> list[float]:
    energy = [r.scalars["dissipation"] / V for r, V in zip(runs, speeds)]
    scale = max(abs(e) for e in energy)
    work = [r.scalars.get("rolling_resistance_slope", r.scalars["rolling_resistance"]) for r in runs]
    return [abs(w - e) / scale for w, e in zip(work, energy)]


def run(case: dict, ctx) -> CaseResult:
    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    speeds = _speeds(case, ctx.quick)
    result.extra["speeds"] = speeds
    result.extra["scales"] = scales(case["problem"])
    parts = []
    for label, sub in _parts(case):
        solved = _solve_part(sub, ctx, label, result)
        parts.append((label, sub["problem"]["layer"]["thickness"], solved))
        for spec in case["gates"]:
            q, against = spec["quantity"], spec["against"]
            for method in spec["methods"]:
                broken = result.extra["failed"].get((label, method)) or result.extra["failed"].get((label, against))
                name = f"{q}[{label}]" if label else q
                common = dict(case=result.name, quantity=name, method=method, against=against, level="finest",
                              tolerance=float(spec["tolerance"]), reason=spec["reason"],
                              report_only=bool(spec.get("report_only", False)))
                if broken:
                    result.gates.append(Gate(value=math.nan, reference=math.nan, error=math.nan,
                                             **{**common, "reason": f"no result: {broken}"}))
                    continue
                runs = solved[method]
                try:
                    if against == "dissipation":
                        errs = _energy_errors(runs, speeds)
                        refs = [r.scalars["dissipation"] / V for r, V in zip(runs, speeds)]
                        values = [r.scalars.get("rolling_resistance_slope", r.scalars["rolling_resistance"])
                                  for r in runs]
                    else:
                        ref_runs = solved[against]
                        errs = errors(q, runs, ref_runs)
                        key = "peak_pressure" if q == "pressure_rms_interior" else q
                        refs = [r.scalars[key] for r in ref_runs]
                        values = [r.scalars[key] for r in runs]
                except KeyError as exc:
                    result.gates.append(Gate(value=math.nan, reference=math.nan, error=math.nan,
                                             **{**common, "reason": f"method {method!r} or {against!r} gave no {exc}"}))
                    continue
                worst = int(np.nanargmax(errs)) if np.isfinite(errs).any() else 0
                result.gates.append(Gate(value=float(values[worst]), reference=float(refs[worst]),
                                         error=float(errs[worst]) if np.isfinite(errs).all() else math.nan,
                                         **{**common, "reason": f"{spec['reason']} (worst at V = {speeds[worst]:.4g} m/s)"}))
    result.extra["parts"] = parts
    if "analytic" in case:  # Hunter between the swept speeds too, for the R_r(V) plot
        dense = np.geomspace(min(speeds), max(speeds), 41)
        result.extra["hunter_curve"] = (dense, [_hunter(case["problem"], V).rolling_resistance for V in dense])
    result.seconds = time.perf_counter() - t0
    return result


# --- the report -------------------------------------------------------------------


def tables(result: CaseResult) -> list[Table]:
    out = []
    speeds = result.extra.get("speeds", [])
    b0, tau = result.extra.get("scales", (math.nan, math.nan))
    for label, H, solved in result.extra.get("parts", []):
        names = list(solved)
        head = ("V (m/s)", "V tau / b0", *(f"R_r {m} (N/m)" for m in names),
                *(f"edges {m} (mm)" for m in names))
        rows = []
        for i, V in enumerate(speeds):
            rows.append((f"{V:.4g}", f"{V * tau / b0:.3g}",
                         *(fmt(solved[m][i].scalars["rolling_resistance"]) for m in names),
                         *(f"{solved[m][i].scalars['trailing_edge'] * 1e3:.4f} .. "
                           f"{solved[m][i].scalars['leading_edge'] * 1e3:.4f}" for m in names)))
        out.append(Table(f"Rolling resistance and contact edges{', ' + label if label else ''} "
                         f"(H = {H * 1e3:.4g} mm, b0 = {b0 * 1e3:.4g} mm)", head, tuple(rows)))
    return out


def figures(result: CaseResult, folder) -> list[str]:
    parts = result.extra.get("parts", [])
    if not parts:
        return []
    speeds = np.array(result.extra["speeds"])
    b0, tau = result.extra["scales"]
    files = []
    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    markers = {"bem": "o", "fem": "s"}
    for k, (label, H, solved) in enumerate(parts):
        colour = f"C{k}"
        for m, runs in solved.items():
            y = [r.scalars["rolling_resistance"] for r in runs]
            name = f"{'Hunter' if m == 'analytic' else m}{' ' + label if label else ''}"
            if m == "analytic":
                dense, curve = result.extra.get("hunter_curve", (speeds, y))
                ax.semilogx(np.asarray(dense) * tau / b0, curve, "-", color="k", lw=1, label=name)
            else:
                ax.semilogx(speeds * tau / b0, y, markers.get(m, "^") + ":", color=colour, mfc="none", lw=0.8,
                            ms=7 if m == "bem" else 9, label=name)
    ax.set_xlabel("V tau / b0")
    ax.set_ylabel("rolling resistance R_r (N/m)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    files.append(f"{result.name}-rolling-resistance.png")
    fig.savefig(folder / files[-1], dpi=110)

    # pressure profiles at the speed of the largest rolling resistance
    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    label, H, solved = parts[len(parts) // 2]
    ref = solved.get("analytic") or next(iter(solved.values()))
    i = int(np.argmax([r.scalars["rolling_resistance"] for r in ref]))
    for m, runs in solved.items():
        r = runs[i]
        if m == "analytic":
            x = np.linspace(r.scalars["trailing_edge"] - 0.2 * b0, r.scalars["leading_edge"] + 0.2 * b0, 400)
            ax.plot(x / b0, r.pressure_of(x) / 1e6, "k-", lw=1, label="Hunter")
        else:
            ax.plot(r.r / b0, r.pressure / 1e6, ".-" if m == "bem" else "-", ms=2, label=m)
    ax.set_xlabel("x / b0 (x > 0 ahead)")
    ax.set_ylabel("contact pressure (MPa)")
    ax.set_title(f"V tau / b0 = {speeds[i] * tau / b0:.3g}{', ' + label if label else ''}", fontsize=9)
    ax.set_xlim(-1.6, 1.6)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    files.append(f"{result.name}-pressure.png")
    fig.savefig(folder / files[-1], dpi=110)
    return files
