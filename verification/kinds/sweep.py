"""The stationary comparison repeated for each layer thickness of ``[sweep]``."""

from __future__ import annotations

import copy
import math
import time

import numpy as np

from ..formatting import fmt, new_figure
from ..results import CaseResult, Table
from ..schema import CaseError, Field, check_table
from . import stationary

ADDS_METHODS = True
SECTIONS = stationary.SECTIONS + ("sweep",)
FIELDS = {"thicknesses": Field("numbers", True, positive=True, doc="layer thicknesses H (m)")}


def _parts(case: dict):
    for H in case["sweep"]["thicknesses"]:
        sub = copy.deepcopy(case)
        sub["problem"]["layer"]["thickness"] = H
        sub["name"] = f"{case['name']}[H={H * 1e3:g}mm]"
        yield H, sub


def check(case: dict, path, methods: dict) -> None:
    if "sweep" not in case:
        raise CaseError(f"{path}: a sweep case needs [sweep] thicknesses")
    check_table(case["sweep"], FIELDS, f"{path} [sweep]")
    for _, sub in _parts(case):
        stationary.check(sub, path, methods)


def run(case: dict, ctx) -> CaseResult:
    t0 = time.perf_counter()
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    rows = []
    for H, sub in _parts(case):
        part = stationary.run(sub, ctx)
        result.gates.extend(part.gates)
        rows.append((H, part))
    result.extra["sweep"] = rows
    result.seconds = time.perf_counter() - t0
    return result


def _scalar(part, method, q):
    runs = part.runs.get(method)
    return runs[-1].scalars.get(q, math.nan) * 1e3 if runs else math.nan


def tables(result: CaseResult) -> list[Table]:
    rows = result.extra.get("sweep", [])
    methods = sorted({m for _, part in rows for m in part.runs})
    head = ("H (mm)", *(f"{q} {m} (mm)" for q in ("r_c", "d") for m in methods))
    body = tuple((f"{H * 1e3:g}", *(fmt(_scalar(part, m, q)) for q in ("contact_radius", "indentation")
                                    for m in methods)) for H, part in rows)
    return [Table("Thickness sweep", head, body)] if rows else []


def figures(result: CaseResult, folder) -> list[str]:
    """Contact radius and indentation against H, one figure each (legible at page width)."""
    rows = result.extra.get("sweep", [])
    if not rows:
        return []
    H = np.array([h for h, _ in rows]) * 1e3
    methods = sorted({m for _, part in rows for m in part.runs})
    names = []
    for q, label in (("contact_radius", "contact radius r_c (mm)"), ("indentation", "indentation d (mm)")):
        fig = new_figure((6.4, 4.2))
        ax = fig.subplots()
        for i, method in enumerate(methods):
            ax.semilogx(H, [_scalar(part, method, q) for _, part in rows], "os^v"[i % 4] + "-", mfc="none",
                        ms=9 if i == 0 else 6, label=method)
        ax.set_xlabel("layer thickness H (mm)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3, which="both")
        ax.legend()
        names.append(f"{result.name}-sweep-{q.replace('_', '-')}.png")
        fig.savefig(folder / names[-1], dpi=110)
    return names
