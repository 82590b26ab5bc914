"""Steady viscoelastic rolling of a round indenter (3D): every method on its levels, the
Richardson estimate of each, compared on the line ``y = 0`` and on the scalars.

A method's :class:`~verification.results.Run` for this kind holds the signed ``x`` (m,
``x > 0`` ahead) of its pressure samples on the line ``y = 0`` in ``r``, and among its
scalars any of ``rolling_resistance`` (N, the paper's ``sum F x / R``), ``indentation``
(m), ``trailing_edge`` and ``leading_edge`` (m, on ``y = 0``), ``peak_pressure`` (Pa),
``pressure_centroid_x`` (m), and for the energy balance ``dissipation`` (W) with
``rolling_resistance_slope`` (N, the pressure's work rate over ``V``: ``sum F ds/dx``).

How errors are measured (as in the plane-strain kind, :mod:`.rolling_2d`):

- ``rolling_resistance``, ``rolling_resistance_energy`` (D / V, N), ``indentation``,
  ``peak_pressure``: relative;
- ``leading_edge``, ``trailing_edge``, ``pressure_centroid_x``: the distance over the
  reference's contact length on ``y = 0``;
- ``pressure_rms_interior``: RMS of ``p - p_ref`` on ``y = 0`` over the inner 90% of the
  reference's contact length, over the reference's peak;
- against ``dissipation``: the method's own energy balance, ``|sum F ds/dx - D / V|``
  over ``D / V``. On a sphere the work rate uses the exact slope ``x / sqrt(R^2 - r^2)``;
  the paper's ``x / R`` differs from it by ``~ r^2 / 2 R^2`` (1.6% in section 11).

A gate's ``levels`` is ``["finest"]`` (default) or ``["extrapolated"]`` (the Richardson
value of the method's three finest levels, for scalars).
"""

from __future__ import annotations

import copy
import math
import time

import numpy as np

from ..formatting import fmt, new_figure
from ..results import CaseResult, Gate, Run, Table
from ..schema import LEVELS, CaseError
from . import rolling_2d, stationary
from .gates import check_gate, check_methods, used_methods

ADDS_METHODS = True
SECTIONS = ("bem", "fem", "methods")
QUANTITIES = ("rolling_resistance", "rolling_resistance_energy", "indentation", "leading_edge", "trailing_edge", "peak_pressure",
              "pressure_centroid_x", "pressure_rms_interior")


def _used(case: dict) -> list[str]:
    return used_methods(case, ("dissipation",))


def check(case: dict, path, methods: dict) -> None:
    problem = case["problem"]
    if problem["indenter"].get("shape") == "line":
        raise CaseError(f"{path} [problem] indenter: a line contact is a rolling-2d case")
    if not problem["loading"].get("speed", 0.0) > 0:
        raise CaseError(f"{path} [problem] loading: a rolling-3d case needs speed > 0 (m/s)")
    if "load" not in problem["loading"]:
        raise CaseError(f"{path} [problem] loading: give the load (N)")
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        check_gate(gate, where, QUANTITIES, methods, ("dissipation",), levels=LEVELS)
        q = gate["quantity"]
        if gate["against"] == "dissipation" and q != "rolling_resistance":
            raise CaseError(f"{where}: the energy balance checks rolling_resistance")
        if "extrapolated" in gate.get("levels", []) and q == "pressure_rms_interior":
            raise CaseError(f"{where}: only scalars are extrapolated, not {q!r}")
    check_methods(case, path, _used(case), methods)


def _at(result: CaseResult, method: str, level: str) -> Run:
    """The method's finest run, its scalars replaced by their Richardson values when
    ``level`` is ``extrapolated`` (the pressure samples stay the finest)."""
    run = result.runs[method][-1]
    if level != "extrapolated":
        return run
    out = copy.copy(run)
    out.scalars = {q: (result.convergence[(method, q)].extrapolated if (method, q) in result.convergence else v)
                   for q, v in run.scalars.items()}
    return out


def _sorted(run: Run) -> Run:
    order = np.argsort(run.r, kind="stable")
    out = copy.copy(run)
    out.r, out.pressure = run.r[order], run.pressure[order]
    return out


def _compare(q: str, run: Run, ref: Run) -> tuple[float, float, float]:
    """(value, reference value, error) of one gate."""
    if q == "pressure_rms_interior":
        err = rolling_2d.errors(q, [run], [_sorted(ref)])[0]
        return err, 0.0, err
    if q == "pressure_centroid_x":
        length = ref.scalars["leading_edge"] - ref.scalars["trailing_edge"]
        return run.scalars[q], ref.scalars[q], abs(run.scalars[q] - ref.scalars[q]) / length
    return run.scalars[q], ref.scalars[q], rolling_2d.errors(q, [run], [ref])[0]


def _energy(run: Run, speed: float) -> tuple[float, float, float]:
    work = run.scalars["rolling_resistance_slope"]
    energy = run.scalars["dissipation"] / speed
    return work, energy, abs(work - energy) / abs(energy)


def run(case: dict, ctx, derive=None) -> CaseResult:
    """The methods on their levels, then the gates; ``derive(run)``, if given, adds
    scalars to each method's runs before the gates read them (:mod:`.roller_3d`)."""
    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    speed = result.extra["speed"] = case["problem"]["loading"]["speed"]
    stationary.solve_methods(case, result, ctx, names=_used(case))
    for runs in result.runs.values() if derive is not None else ():
        for r in runs:
            derive(r)
    failed = result.extra["failed"]
    for spec in case["gates"]:
        q, against = spec["quantity"], spec["against"]
        for method in spec["methods"]:
            for level in spec.get("levels", ["finest"]):
                common = dict(case=result.name, quantity=q, method=method, against=against, level=level,
                              tolerance=float(spec["tolerance"]), reason=spec["reason"],
                              report_only=bool(spec.get("report_only", False)))
                broken = failed.get(method) or failed.get(against)
                try:
                    if broken:
                        raise LookupError(f"no result: {broken}")
                    if against == "dissipation":
                        value, reference, error = _energy(_at(result, method, level), speed)
                    else:
                        value, reference, error = _compare(q, _at(result, method, level), _at(result, against, level))
                except KeyError as exc:
                    result.gates.append(Gate(value=math.nan, reference=math.nan, error=math.nan,
                                             **{**common, "reason": f"{method!r} or {against!r} gave no {exc}"}))
                    continue
                except LookupError as exc:
                    result.gates.append(Gate(value=math.nan, reference=math.nan, error=math.nan,
                                             **{**common, "reason": str(exc)}))
                    continue
                result.gates.append(Gate(value=float(value), reference=float(reference), error=float(error), **common))
    result.seconds = time.perf_counter() - t0
    return result


# --- the report -------------------------------------------------------------------

_COLUMNS = (("rolling_resistance", "R_r (N)", 1.0), ("rolling_resistance_slope", "sum F ds/dx (N)", 1.0),
            ("dissipation", "D / V (N)", None), ("indentation", "d (mm)", 1e3),
            ("trailing_edge", "x_t (mm)", 1e3), ("leading_edge", "x_l (mm)", 1e3),
            ("peak_pressure", "p_max (MPa)", 1e-6))


def tables(result: CaseResult) -> list[Table]:
    speed = result.extra.get("speed", math.nan)
    rows = []
    for method, runs in result.runs.items():
        for r in runs:
            cells = []
            for q, _, scale in _COLUMNS:
                v = r.scalars.get(q, math.nan)
                cells.append(fmt(v / speed if scale is None else v * scale))
            rows.append((method, "-" if r.size is None else f"{r.size * 1e3:g}", *cells, f"{r.seconds:.1f}"))
        for q, _, scale in _COLUMNS:
            c = result.convergence.get((method, q))
            if c is None or q != "rolling_resistance":
                continue
            note = f"Richardson, {stationary.order_note(c)}"
            rows.append((method, note, fmt(c.extrapolated), *[""] * len(_COLUMNS)))
    head = ("method", "h or a (mm)", *(label for _, label, _ in _COLUMNS), "time (s)")
    return [Table("Runs (scalars on the whole contact; edges on y = 0)", head, tuple(rows))] if rows else []


def figures(result: CaseResult, folder) -> list[str]:
    files = []
    if not result.runs:
        return files
    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    for method, runs in result.runs.items():
        r = _sorted(runs[-1])
        size = "" if r.size is None else f", h = {r.size * 1e3:g} mm"
        ax.plot(r.r * 1e3, r.pressure / 1e6, ".-" if method == "bem" else "-", ms=3, lw=1.2, label=f"{method}{size}")
    ax.set_xlabel("x (mm) on y = 0 (x > 0 ahead)")
    ax.set_ylabel("contact pressure (MPa)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    files.append(f"{result.name}-pressure.png")
    fig.savefig(folder / files[-1], dpi=110)

    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    for k, (method, runs) in enumerate(result.runs.items()):
        sizes = [r.size for r in runs]
        if None in sizes:
            continue
        h = np.array(sizes) * 1e3
        ax.semilogx(h, [r.scalars.get("rolling_resistance", math.nan) for r in runs], "os"[k % 2] + "-",
                    color=f"C{k}", label=f"{method}")
        c = result.convergence.get((method, "rolling_resistance"))
        if c is not None and math.isfinite(c.extrapolated):
            ax.axhline(c.extrapolated, color=f"C{k}", ls="--", lw=0.8,
                       label=f"{method} Richardson {c.extrapolated:.5g} N ("
                             f"{f'p = {c.order:.2f}' if math.isfinite(c.order) else 'no order'})")
    ax.set_xlabel("node spacing / element size at the contact (mm)")
    ax.set_ylabel("rolling resistance R_r (N)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    files.append(f"{result.name}-convergence.png")
    fig.savefig(folder / files[-1], dpi=110)

    bem = result.runs.get("bem")
    if bem and bem[-1].grid is not None:
        b = bem[-1]
        fig = new_figure((5.6, 4.6))
        ax = fig.subplots()
        m = ax.contourf(b.grid.x * 1e3, b.grid.y * 1e3, b.field / 1e6, levels=16, cmap="viridis")
        fig.colorbar(m, ax=ax, label="BEM contact pressure (MPa)")
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm), rolling towards +x")
        ax.set_ylabel("y (mm)")
        files.append(f"{result.name}-pressure-map.png")
        fig.savefig(folder / files[-1], dpi=110)
    return files
