"""The stationary comparison: every method the gates name, on its levels, against an
analytic limit and against each other (scalars, pressure fields, convergence)."""

from __future__ import annotations

import math
import time

import numpy as np

from ..methods import references
from ..formatting import fmt, new_figure, scalars_line
from ..metrics import pressure_difference, richardson
from ..results import CaseResult, Gate, Run, Table
from ..schema import PRESSURE, SCALARS, CaseError
from .gates import check_gate, check_methods, used_methods

ADDS_METHODS = True  # verify --method NAME holds NAME to every gate the BEM is held to
QUANTITIES = SCALARS + PRESSURE
SHOWN = ("contact_radius", "indentation", "peak_pressure", "rolling_resistance")  # in the progress lines
SECTIONS = ("analytic", "bem", "fem", "methods")


def _used(case: dict) -> list[str]:
    return used_methods(case, ("analytic",))


def check(case: dict, path, methods: dict) -> None:
    """Gates name known quantities, methods with levels in the case, a reference that
    exists and provides the quantity; ``extrapolated`` needs three levels."""
    problem = case["problem"]
    if "analytic" in case:
        references.check(case["analytic"], problem, f"{path} [analytic]")
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        check_gate(gate, where, QUANTITIES, methods, ("analytic",))
        q, against = gate["quantity"], gate["against"]
        if against == "analytic":
            if "analytic" not in case:
                raise CaseError(f"{where}: against = 'analytic' needs an [analytic] reference")
            ref = case["analytic"]["reference"]
            if q in SCALARS and q not in references.REFERENCES[ref][1]:
                raise CaseError(f"{where}: the {ref!r} solution gives no {q!r}; it gives "
                                f"{', '.join(references.REFERENCES[ref][1])}")
        if "extrapolated" in gate.get("levels", []) and q not in SCALARS:
            raise CaseError(f"{where}: only scalars are extrapolated, not {q!r}")
    check_methods(case, path, _used(case), methods)


def _check_run(run, method: str) -> Run:
    if not isinstance(run, Run):
        raise TypeError(f"method {method!r} returned {type(run).__name__}, not verification.results.Run")
    run.r, run.pressure = np.asarray(run.r, float).ravel(), np.asarray(run.pressure, float).ravel()
    if run.r.shape != run.pressure.shape:
        raise ValueError(f"method {method!r}: r and pressure differ in length ({run.r.size} and {run.pressure.size})")
    run.scalars = {k: float(v) for k, v in run.scalars.items()}
    return run


def solve_methods(case: dict, result: CaseResult, ctx, problem: dict | None = None,
                  names: list[str] | None = None) -> None:
    """Every method the gates use (or ``names``), on its levels; a method that fails is
    recorded in ``result.extra["failed"]`` and its gates fail with the error; the
    Richardson estimate of every scalar of a method with three levels or more goes to
    ``result.convergence``."""
    problem = case["problem"] if problem is None else problem
    failed = result.extra.setdefault("failed", {})
    moving = problem.get("loading", {}).get("speed", 0.0) > 0  # a rolling resistance only when rolling
    shown = SHOWN if moving else tuple(q for q in SHOWN if q != "rolling_resistance")
    for name in _used(case) if names is None else names:
        method = ctx.methods[name]
        runs = []
        try:
            for level in method.levels(case):
                run = _check_run(method.solve(problem, level), name)
                size = "" if run.size is None else f"h = {run.size * 1e3:.4g} mm: "
                ctx.progress(f"  {case['name']}: {name} {size}{scalars_line(run.scalars, shown)} "
                             f"({run.seconds:.1f} s)")
                runs.append(run)
        except Exception as exc:  # one failing method fails its gates, not the suite
            failed[name] = f"{type(exc).__name__}: {exc}"
            ctx.progress(f"  {case['name']}: {name} FAILED: {failed[name]}")
            continue
        result.runs[name] = runs
        sizes = [r.size for r in runs]
        if len(runs) >= 3 and None not in sizes[-3:]:
            ratio = sizes[-2] / sizes[-1]
            common = set.intersection(*(set(r.scalars) for r in runs[-3:]))
            for q in sorted(common):
                result.convergence[(name, q)] = richardson([r.scalars[q] for r in runs[-3:]], ratio)


def _profile(run: Run):
    order = np.argsort(run.r)
    r, p = run.r[order], run.pressure[order]
    return lambda x: np.interp(x, r, p, right=0.0)


def _gate(result, spec, method, level, value, reference, error, **kw) -> Gate:
    report_only = kw.pop("report_only", bool(spec.get("report_only", False)))
    alongside = kw.pop("alongside", False)  # shown beside a gated metric: no tolerance of its own
    return Gate(case=result.name, quantity=kw.pop("quantity", spec["quantity"]), method=method,
                against=spec["against"], level=level, value=float(value), reference=float(reference),
                error=float(error), tolerance=math.inf if alongside else float(spec["tolerance"]),
                reason=kw.pop("reason", spec["reason"]), report_only=report_only or alongside)


def _reference(result: CaseResult, against: str, quantity: str, level: str):
    """(value, pressure profile, contact radius) of the reference of a comparison."""
    if against == "analytic":
        ref = result.reference
        return references.reference_value(ref, quantity), ref.pressure, ref.contact_radius
    run = result.runs[against][-1]
    if level == "extrapolated" and (against, quantity) in result.convergence:
        value = result.convergence[(against, quantity)].extrapolated
    else:
        value = run.scalars.get(quantity, math.nan)
    return value, _profile(run), run.scalars.get("contact_radius", math.nan)


def evaluate(case: dict, result: CaseResult) -> None:
    """Every gate of the case, for every method and level it names."""
    failed = result.extra.get("failed", {})
    for spec in case["gates"]:
        quantity, against = spec["quantity"], spec["against"]
        for method in spec["methods"]:
            for level in spec.get("levels", ["finest"]):
                broken = failed.get(method) or (failed.get(against) if against != "analytic" else None)
                if broken:
                    result.gates.append(_gate(result, spec, method, level, math.nan, math.nan, math.nan,
                                              reason=f"no result: {broken}", report_only=False))
                    continue
                run = result.runs[method][-1]
                ref_value, ref_profile, ref_radius = _reference(result, against, quantity, level)
                if quantity in PRESSURE:
                    if run.r.size == 0 or not math.isfinite(ref_radius):
                        result.gates.append(_gate(result, spec, method, level, math.nan, 0.0, math.nan,
                                                  reason=f"{method!r} or {against!r} gave no pressure samples"))
                        continue
                    diff = pressure_difference(run.r, run.pressure, ref_profile, ref_radius)
                    value = getattr(diff, quantity.replace("pressure_", ""))
                    result.gates.append(_gate(result, spec, method, level, value, 0.0, value))
                    for other in PRESSURE:  # the other three metrics, shown alongside
                        if other != quantity:
                            v = float(getattr(diff, other.replace("pressure_", "")))
                            result.gates.append(_gate(result, spec, method, level, v, 0.0, v, quantity=other,
                                                      reason="Reported alongside the gated pressure metric.",
                                                      alongside=True))
                    continue
                if quantity not in run.scalars:
                    result.gates.append(_gate(result, spec, method, level, math.nan, ref_value, math.nan,
                                              reason=f"method {method!r} returned no {quantity!r}"))
                    continue
                value = run.scalars[quantity]
                if level == "extrapolated":
                    value = result.convergence[(method, quantity)].extrapolated
                error = abs(value - ref_value) / abs(ref_value) if ref_value else math.nan
                result.gates.append(_gate(result, spec, method, level, value, ref_value, error))


def run(case: dict, ctx) -> CaseResult:
    """The methods on their levels, the analytic limit, convergence and the gates."""
    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    if "analytic" in case:
        result.reference = references.reference(case["analytic"], case["problem"])
    solve_methods(case, result, ctx)
    evaluate(case, result)
    result.seconds = time.perf_counter() - t0
    return result


# --- the report -------------------------------------------------------------------


def tables(result: CaseResult) -> list[Table]:
    rows = []
    for method, runs in result.runs.items():
        for r in runs:
            s = r.scalars
            rows.append((method, "-" if r.size is None else f"{r.size * 1e3:g}",
                         fmt(s.get("contact_radius", math.nan) * 1e3), fmt(s.get("indentation", math.nan) * 1e3),
                         fmt(s.get("peak_pressure", math.nan) / 1e6), f"{r.seconds:.1f}", ""))
        for q in ("contact_radius", "indentation"):
            c = result.convergence.get((method, q))
            if c is not None:
                value = fmt(c.extrapolated * 1e3)
                rows.append((method, f"Richardson {q}", value if q == "contact_radius" else "",
                             value if q == "indentation" else "", "", "", order_note(c)))
    head = ("method", "h or a (mm)", "r_c (mm)", "d (mm)", "p_max (MPa)", "time (s)", "note")
    return [Table("Runs", head, tuple(rows))] if rows else []


def order_note(c) -> str:
    """The Richardson row's note: the observed order, or why there is none."""
    if not math.isfinite(c.order):
        return "no order (the levels do not converge monotonically): finest kept"
    return f"order {c.order:.2f}" + ("" if c.asymptotic else " (not asymptotic: finest kept)")


def _reference_profile(result):
    if "fem" in result.runs:
        return "FEM", _profile(result.runs["fem"][-1])
    if result.reference is not None:
        return "analytic", result.reference.pressure
    return None, None


def figures(result: CaseResult, folder) -> list[str]:
    """Pressure profiles of every method, the BEM's difference map, convergence."""
    files = []
    if not result.runs:
        return files
    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    for method, runs in result.runs.items():
        run = runs[-1]
        if run.r.size == 0:
            continue
        size = "" if run.size is None else f", h = {run.size * 1e3:g} mm"
        if method == "bem":
            ax.plot(run.r * 1e3, run.pressure / 1e6, ".", ms=2, alpha=0.4, label=f"BEM nodes{size}")
        else:
            o = np.argsort(run.r)
            ax.plot(run.r[o] * 1e3, run.pressure[o] / 1e6, "-", lw=1.5, label=f"{method}{size}")
    if result.reference is not None:
        rr = np.linspace(0, 1.05 * result.reference.contact_radius, 300)
        ax.plot(rr * 1e3, result.reference.pressure(rr) / 1e6, "k--", lw=1, label="analytic")
    ax.set_xlabel("r (mm)")
    ax.set_ylabel("contact pressure (MPa)")
    ax.legend()
    ax.grid(alpha=0.3)
    files.append(f"{result.name}-profiles.png")
    fig.savefig(folder / files[-1], dpi=110)

    name, ref = _reference_profile(result)
    if "bem" in result.runs and ref is not None and result.runs["bem"][-1].grid is not None:
        b = result.runs["bem"][-1]
        X, Y = b.grid.coordinates()
        peak = float(np.max(ref(np.linspace(0, b.r.max(), 500))))
        diff = (b.field - ref(np.hypot(X, Y))) / peak * 100
        lim = max(float(np.abs(diff).max()), 1e-6)
        fig = new_figure((5.6, 4.6))
        ax = fig.subplots()
        m = ax.pcolormesh(b.grid.x * 1e3, b.grid.y * 1e3, diff, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="nearest")
        fig.colorbar(m, ax=ax, label=f"(BEM - {name}) / peak (%)")
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        files.append(f"{result.name}-difference.png")
        fig.savefig(folder / files[-1], dpi=110)

    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    for method, runs in result.runs.items():
        if len(runs) < 3 or any(r.size is None for r in runs):
            continue
        h = np.array([r.size for r in runs[-3:]]) * 1e3
        for q, marker in (("contact_radius", "o"), ("indentation", "s")):
            conv = result.convergence.get((method, q))
            if conv is None or not math.isfinite(conv.extrapolated):
                continue
            err = np.abs(np.array(conv.values) - conv.extrapolated) / abs(conv.extrapolated)
            ok = err > 0
            if ok.any():
                order = f"p = {conv.order:.2f}" if math.isfinite(conv.order) else "no order"
                ax.loglog(h[ok], err[ok], marker + "-", label=f"{method} {q} ({order})")
    ax.set_xlabel("element size / node spacing (mm)")
    ax.set_ylabel("|q - q_Richardson| / |q|")
    ax.grid(alpha=0.3, which="both")
    if ax.lines:
        ax.legend(fontsize=8)
        files.append(f"{result.name}-convergence.png")
        fig.savefig(folder / files[-1], dpi=110)
    return files
