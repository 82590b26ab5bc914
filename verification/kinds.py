"""Case kinds beyond the stationary comparison: a thickness sweep, the paper's Table 1,
and the slow and fast limits of viscoelastic rolling."""

from __future__ import annotations

import copy
import csv
from pathlib import Path

import numpy as np

from .runner import CaseResult, Gate, run_bem, run_stationary

DATA = Path(__file__).resolve().parent / "data"


def run_sweep(case: dict, result: CaseResult, progress, quick: bool) -> None:
    """The stationary comparison repeated for each layer thickness of ``[sweep]``."""
    rows = []
    for H in case["sweep"]["thicknesses"]:
        sub = copy.deepcopy(case)
        sub["problem"]["layer"]["thickness"] = H
        sub["name"] = f"{case['name']}[H={H * 1e3:g}mm]"
        part = CaseResult(sub["name"], case["title"], "", "stationary")
        run_stationary(sub, part, progress, quick)
        result.gates.extend(part.gates)
        rows.append((H, part))
    result.extra["sweep"] = rows


def run_table1(case: dict, result: CaseResult, progress, quick: bool) -> None:
    """Every printed cell of the paper's Table 1 (or the case's quick subset)."""
    table = DATA / case["table1"]["file"]
    rows = list(csv.reader(line for line in table.open() if not line.startswith("#")))
    nts = [int(v) for v in rows[0][1:]]
    subset = {tuple(c) for c in case["table1"].get("quick_cells", [])} if quick else None
    cells = []
    for row in rows[1:]:
        a_mm = float(row[0])
        for nt, value in zip(nts, row[1:]):
            if not value or (subset is not None and (a_mm, nt) not in subset):
                continue
            spacing = a_mm * 1e-3
            cfg = copy.deepcopy(case["problem"])
            bem_cfg = {"period": 0.2, "half_width": case["bem"]["half_width"],
                       "truncation_factor": nt / (0.2 / (2 * spacing))}
            run = run_bem(cfg, bem_cfg, spacing)
            rr, ref = run.scalars["rolling_resistance"], float(value)
            progress(f"  {case['name']}: a = {a_mm:g} mm, Nt = {nt}: R_r = {rr:.5f} N (paper {ref:.4f}) ({run.seconds:.1f} s)")
            cells.append((a_mm, nt, rr, ref))
            gate = case["gates"][0]
            result.gates.append(Gate(result.name, f"rolling_resistance[a={a_mm:g}mm,Nt={nt}]", "bem", "published",
                                     "finest", rr, ref, abs(rr - ref), gate["tolerance"], gate["reason"]))
    result.extra["table1"] = cells


def _with(cfg: dict, **changes) -> dict:
    out = copy.deepcopy(cfg)
    for dotted, value in changes.items():
        section, key = dotted.split("__")
        out[section][key] = value
    return out


def run_rolling_limits(case: dict, result: CaseResult, progress, quick: bool) -> None:
    """Viscoelastic rolling at very low and very high speed against the elastic contact
    with the relaxed and the glassy modulus."""
    from bem.materials import material_from_config

    base = case["problem"]
    material = material_from_config(base["material"], Path("."))
    bem_cfg = case["bem"]
    spacing = bem_cfg["spacings"][-1]
    rows = []
    for limit in case["limits"]:
        cfg = _with(base, loading__speed=limit["speed"])
        modulus = material.relaxed_modulus if limit["modulus"] == "relaxed" else material.glassy_modulus
        elastic = _with(base, loading__speed=0.0)
        elastic["material"] = {"model": "elastic", "shear_modulus": modulus}
        grid_cfg = dict(bem_cfg, period=limit.get("period", bem_cfg.get("period", 0.2)))
        visco_run = run_bem(cfg, grid_cfg, spacing)
        elastic_run = run_bem(elastic, grid_cfg, spacing)
        mid = run_bem(_with(base, loading__speed=limit["reference_speed"]), grid_cfg, spacing)
        progress(f"  {case['name']}: V = {limit['speed']:g} m/s: d = {visco_run.scalars['indentation']:.6e} m "
                 f"(elastic {limit['modulus']}: {elastic_run.scalars['indentation']:.6e} m), "
                 f"R_r = {visco_run.scalars['rolling_resistance']:.3e} N")
        rows.append((limit, visco_run, elastic_run, mid))
        for spec in case["gates"]:
            if spec.get("limit") != limit["name"]:
                continue
            q = spec["quantity"]
            if q == "rolling_resistance":  # relative to the rolling resistance at a middle speed
                value, ref = visco_run.scalars[q], mid.scalars[q]
                error = abs(value) / abs(ref)
            elif q == "pressure_max":
                value = float(np.abs(visco_run.field - elastic_run.field).max())
                ref = float(elastic_run.field.max())
                error = value / ref
            else:
                value, ref = visco_run.scalars[q], elastic_run.scalars[q]
                error = abs(value - ref) / abs(ref)
            result.gates.append(Gate(result.name, f"{q}[{limit['name']}]", "bem", f"elastic G({limit['modulus']})",
                                     "finest", value, ref, error, spec["tolerance"], spec["reason"]))
    result.extra["limits"] = rows


HANDLERS = {
    "stationary": run_stationary,
    "sweep": run_sweep,
    "table1": run_table1,
    "rolling-limits": run_rolling_limits,
}
