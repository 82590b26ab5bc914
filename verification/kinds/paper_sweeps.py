"""The paper's parametric studies (sections 11.4-11.7) reproduced by sweeps on Dask and
held to its published findings: the fitted laws of Tables 2 and 3, friction's share of
the rolling resistance, where that share peaks (fig. 9) and where R_r peaks in speed
(fig. 10). The sweeps are sweep files (:mod:`sweeps`), run on a local Dask cluster.

Errors: ``table2`` and ``table3`` the largest relative difference between our fitted law
and the paper's over the fitted range (Table 3 from ``table3_thickness_min``; the full
range as ``table3_full_range``); ``friction_share_max`` the largest share itself (its
tolerance is the paper's bound); ``share_peak_thickness`` the distance of our peak from
the paper's 6-8 mm, in units of that range's width; ``share_rise`` the friction share at
H = 5 mm in units of the share at 1 mm (:func:`sweeps.paper.share_rise`: small when the
share rises towards thin layers, as it does under every kinematics and grid; its
reference 1 is a share that does not change with H).
"""

from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

from ..formatting import fmt, new_figure
from ..results import CaseResult, Gate, Table
from ..schema import CaseError, Field, check_table, close

ADDS_METHODS = False
NEEDS_PROBLEM = False
#: its sweeps run on Dask: under ``verify --workers``/``--scheduler`` the case runs in
#: verify's process (it reads its sweep files there) and submits to verify's cluster
USES_DASK = True
SECTIONS = ("sweeps",)
QUANTITIES = ("table2", "table3", "table3_full_range", "friction_share_max", "share_peak_thickness", "share_rise")
FIELDS = {
    "loads": Field("string", True, doc="sweep file: H x P, with friction (Table 2, fig. 7)"),
    "thickness": Field("string", True, doc="sweep file: P x H, with friction (Table 3, figs. 8-9)"),
    "speed": Field("string", True, doc="sweep file: H x V, with friction (fig. 10)"),
    "y": Field("string", choices=("rolling_resistance", "rolling_resistance_energy"),
               doc="the rolling-resistance figure the laws are fitted to (default the energy one)"),
    "table3_thickness_min": Field("number", positive=True, doc="Table 3 gated from this H (m)"),
}


def _files(case: dict, path: Path) -> dict:
    return {k: (Path(path).parent / case["sweeps"][k]).resolve() for k in ("loads", "thickness", "speed")}


def check(case: dict, path, methods: dict) -> None:
    if "sweeps" not in case:
        raise CaseError(f"{path}: a paper-sweeps case needs [sweeps] loads, thickness and speed")
    check_table(case["sweeps"], FIELDS, f"{path} [sweeps]")
    try:
        from sweeps.spec import SweepError, read_sweep
    except ImportError as exc:  # pragma: no cover - dask is a dependency
        raise CaseError(f"{path}: the sweeps package cannot be imported: {exc}") from None
    for key, file in _files(case, path).items():
        if not file.is_file():
            raise CaseError(f"{path} [sweeps] {key}: no sweep file {str(file)!r}")
        try:
            read_sweep(file)
        except SweepError as exc:
            raise CaseError(f"{path} [sweeps] {key}: {exc}") from None
    case["_files"] = {k: str(v) for k, v in _files(case, path).items()}
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}] ({gate['quantity']})"
        for key in ("methods", "against", "levels", "limit"):
            if key in gate:
                raise CaseError(f"{where}: {key!r} does not apply (the BEM's sweeps against the paper)")
        if gate["quantity"] not in QUANTITIES:
            raise CaseError(f"{where}: unknown quantity {gate['quantity']!r}; known: {', '.join(QUANTITIES)}"
                            f"{close(gate['quantity'], QUANTITIES)}")


def run(case: dict, ctx) -> CaseResult:
    from sweeps import paper
    from sweeps.engine import connect, run_sweep
    from sweeps.spec import read_sweep

    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    y = case["sweeps"].get("y", "rolling_resistance_energy")
    rows = {}
    client = ctx.client if ctx.client is not None else connect()
    try:
        with tempfile.TemporaryDirectory(prefix="verify-sweeps-") as out:
            for key, file in case["_files"].items():
                sweep = read_sweep(file)
                ctx.progress(f"  {case['name']}: sweep {Path(file).name} on Dask")
                report = run_sweep(sweep, Path(out) / key, client=client, stream=None)
                failed = [r for r in report.rows if r.get("status") != "ok"]
                ctx.progress(f"  {case['name']}: {len(report.rows)} points, {len(failed)} failed")
                rows[key] = report.rows
    finally:
        if client is not ctx.client:  # the local cluster it started
            cluster = getattr(client, "cluster", None)
            client.close()
            if cluster is not None:
                cluster.close()
    found = paper.findings(rows["loads"], rows["thickness"], rows["speed"], y)
    h_min = case["sweeps"].get("table3_thickness_min", 0.0)
    measured = {}
    for H, item in found["table2"].items():
        measured[f"table2[H={H * 1e3:g}mm]"] = ("table2", item["ours"].values[1], item["paper"].values[1], item["gap"])
    for P, item in found["table3"].items():
        ours, theirs = item["ours"], item["paper"]
        lo = max(ours.x_min, h_min)
        measured[f"table3[P={P:g}N]"] = ("table3", ours(lo), theirs(lo), paper.law_gap(ours, theirs, lo, ours.x_max))
        measured[f"table3_full_range[P={P:g}N]"] = ("table3_full_range", ours(ours.x_min), theirs(ours.x_min),
                                                    item["gap"])
    share = found["friction_share_max"]
    measured["friction_share_max[P<=150N]"] = ("friction_share_max", share, paper.FRICTION_SHARE_LIMIT, share)
    lo, hi = paper.SHARE_PEAK_RANGE
    for P, H in found["share_peak_thickness"].items():
        outside = max(lo - H, H - hi, 0.0) / (hi - lo)
        measured[f"share_peak_thickness[P={P:g}N]"] = ("share_peak_thickness", H, 0.5 * (lo + hi), outside)
    for P, rise in found["share_rise"].items():
        measured[f"share_rise[P={P:g}N]"] = ("share_rise", rise, 1.0, rise)  # 1: a share flat in H
    for spec in case["gates"]:
        hits = [(name, m) for name, m in measured.items() if m[0] == spec["quantity"]]
        if not hits:
            result.gates.append(Gate(case=result.name, quantity=spec["quantity"], method="bem", against="paper",
                                     level="-", value=math.nan, reference=math.nan, error=math.nan,
                                     tolerance=float(spec["tolerance"]), reason=f"no data: {spec['reason']}"))
        for name, (_, value, ref, error) in hits:
            result.gates.append(Gate(case=result.name, quantity=name, method="bem", against="paper", level="-",
                                     value=float(value), reference=float(ref), error=float(error),
                                     tolerance=float(spec["tolerance"]), reason=spec["reason"],
                                     report_only=bool(spec.get("report_only", False))))
    result.extra.update(found=found, rows=rows, y=y)
    result.seconds = time.perf_counter() - t0
    return result


def tables(result: CaseResult) -> list[Table]:
    found = result.extra.get("found")
    if not found:
        return []
    fits = []
    for label, table in (("Table 2, H", "table2"), ("Table 3, P", "table3")):
        for key, item in found[table].items():
            ours, theirs = item["ours"], item["paper"]
            fits.append((f"{label} = {key * 1e3:g} mm" if table == "table2" else f"{label} = {key:g} N",
                         ", ".join(f"{n} = {v:.4g} [{lo:.4g}, {hi:.4g}]" for n, v, lo, hi in
                                   zip(ours.names, ours.values, ours.lower, ours.upper)),
                         ", ".join(f"{n} in [{lo:.4g}, {hi:.4g}]" for n, lo, hi in
                                   zip(theirs.names, theirs.lower, theirs.upper)),
                         f"{item['gap']:.2%}"))
    out = [Table(f"Fitted laws of {result.extra['y']} (95% intervals)", ("law", "ours", "paper", "largest gap"),
                 tuple(fits))]
    peaks = tuple((", ".join(f"{k} = {v}" for k, v in combo), fmt(V * 1e3)) for combo, V in found["peak_speed"].items())
    if peaks:
        out.append(Table("Speed of the R_r peak (fig. 10; the paper prints no number)", ("sweep", "V_peak (mm/s)"),
                         peaks))
    return out


def figures(result: CaseResult, folder) -> list[str]:
    """Our points against the paper's laws: against the load (Table 2) and against the
    thickness (Table 3), one figure each (legible at page width)."""
    found = result.extra.get("found")
    if not found:
        return []
    from sweeps.paper import curve

    y = result.extra["y"]
    names = []
    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    for H, item in found["table2"].items():
        P, R = curve(result.extra["rows"]["loads"], "loading.load", y, **{"layer.thickness": H})
        line, = ax.plot(P, R, "o", label=f"ours, H = {H * 1e3:g} mm")
        ax.plot(P, item["paper"](P), "-", color=line.get_color(), lw=1, label="paper's law (Table 2)")
    ax.set_xlabel("load P (N)")
    ax.set_ylabel(f"{y} (N)")
    names.append(f"{result.name}-laws-load.png")
    _finish(fig, ax, folder / names[-1])
    fig = new_figure((6.4, 4.2))
    ax = fig.subplots()
    for P, item in found["table3"].items():
        H, R = curve(result.extra["rows"]["thickness"], "layer.thickness", y, **{"loading.load": P})
        line, = ax.plot(H * 1e3, R, "o", label=f"ours, P = {P:g} N")
        ax.plot(H * 1e3, item["paper"](H), "-", color=line.get_color(), lw=1, label="paper's law (Table 3)")
    ax.set_xlabel("layer thickness H (mm)")
    ax.set_ylabel(f"{y} (N)")
    names.append(f"{result.name}-laws-thickness.png")
    _finish(fig, ax, folder / names[-1])
    return names


def _finish(fig, ax, path) -> None:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=110)
