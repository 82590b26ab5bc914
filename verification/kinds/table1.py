"""Every printed cell of the paper's Table 1 (or the case's quick subset): the BEM's
frictionless rolling resistance against the published value."""

from __future__ import annotations

import copy
import csv
import time
from pathlib import Path

from ..methods import bem
from ..formatting import new_figure
from ..results import CaseResult, Gate, Table
from ..schema import CaseError, Field, check_table

ADDS_METHODS = False
SECTIONS = ("bem", "table1")
DATA = Path(__file__).resolve().parent.parent / "data"
FIELDS = {
    "file": Field("string", True, doc="the table's CSV in verification/data"),
    "quick_cells": Field("cells", doc="[[a (mm), Nt], ...] run by --quick"),
}
BEM = {"half_width": Field("number", True, positive=True, doc="candidate region (m)")}


def _cells(case: dict):
    rows = list(csv.reader(line for line in (DATA / case["table1"]["file"]).open() if not line.startswith("#")))
    nts = [int(v) for v in rows[0][1:]]
    return [(float(row[0]), nt, float(v)) for row in rows[1:] for nt, v in zip(nts, row[1:]) if v]


def check(case: dict, path, methods: dict) -> None:
    for section, fields in (("table1", FIELDS), ("bem", BEM)):
        if section not in case:
            raise CaseError(f"{path}: a table1 case needs [{section}]")
        check_table(case[section], fields, f"{path} [{section}]")
    if not (DATA / case["table1"]["file"]).is_file():
        raise CaseError(f"{path} [table1] file: {case['table1']['file']!r} is not in {DATA}")
    printed = {(a, nt) for a, nt, _ in _cells(case)}
    for cell in case["table1"].get("quick_cells", []):
        if (float(cell[0]), int(cell[1])) not in printed:
            raise CaseError(f"{path} [table1] quick_cells: {cell} is not a printed cell of the table")
    for i, gate in enumerate(case["gates"]):
        where = f"{path} gates[{i}]"
        if gate["quantity"] != "rolling_resistance":
            raise CaseError(f"{where}: Table 1 gives 'rolling_resistance' only, not {gate['quantity']!r}")
        if gate.get("methods", ["bem"]) != ["bem"] or gate.get("against", "published") != "published":
            raise CaseError(f"{where}: Table 1 holds methods = ['bem'] against 'published'")
        for key in ("levels", "limit"):
            if key in gate:
                raise CaseError(f"{where}: {key!r} does not apply to Table 1")
    if len(case["gates"]) != 1:
        raise CaseError(f"{path}: a table1 case has exactly one gate (the absolute tolerance of every cell)")


def run(case: dict, ctx) -> CaseResult:
    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    subset = {(float(a), int(nt)) for a, nt in case["table1"].get("quick_cells", [])} if ctx.quick else None
    gate = case["gates"][0]
    cells = []
    for a_mm, nt, ref in _cells(case):
        if subset is not None and (a_mm, nt) not in subset:
            continue
        spacing = a_mm * 1e-3
        settings = {"period": 0.2, "half_width": case["bem"]["half_width"],
                    "truncation_factor": nt / (0.2 / (2 * spacing))}
        r = bem.run(copy.deepcopy(case["problem"]), settings, spacing)
        rr = r.scalars["rolling_resistance"]
        ctx.progress(f"  {case['name']}: a = {a_mm:g} mm, Nt = {nt}: R_r = {rr:.5f} N (paper {ref:.4f}) ({r.seconds:.1f} s)")
        cells.append((a_mm, nt, rr, ref))
        result.gates.append(Gate(case=result.name, quantity=f"rolling_resistance[a={a_mm:g}mm,Nt={nt}]",
                                 method="bem", against="published", level="finest", value=rr, reference=ref,
                                 error=abs(rr - ref), tolerance=float(gate["tolerance"]), reason=gate["reason"]))
    result.extra["table1"] = cells
    result.seconds = time.perf_counter() - t0
    return result


def tables(result: CaseResult) -> list[Table]:
    return []  # every cell is a gate row


def figures(result: CaseResult, folder) -> list[str]:
    cells = result.extra.get("table1", [])
    if not cells:
        return []
    fig = new_figure((6.4, 4))
    ax = fig.subplots()
    tol = result.gates[0].tolerance if result.gates else 1e-4
    for a in sorted({c[0] for c in cells}, reverse=True):
        sel = [c for c in cells if c[0] == a]
        ax.plot([c[1] for c in sel], [(c[2] - c[3]) / tol for c in sel], "o-", label=f"a = {a:g} mm")
    ax.axhspan(-1, 1, color="g", alpha=0.1, label=f"gate +/- {tol:g} N")
    ax.set_xlabel("truncation order Nt")
    ax.set_ylabel("(R_r ours - R_r paper) / tolerance")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    name = f"{result.name}-table1.png"
    fig.savefig(folder / name, dpi=110)
    return [name]
