"""Other people's methods through the same cases and gates: a plugin function (the Hertz
"solver" of examples/hertz_method.py), an installed entry point, and results files
computed elsewhere, all through the command line."""

import importlib.metadata
import json
from pathlib import Path

import numpy as np

import verification.methods as methods
from tests.verification.small_cases import THICK_LAYER_CASE
from verification.cli import main as verify_main

ROOT = Path(__file__).resolve().parents[3]
HERTZ = f"hertz={ROOT / 'examples' / 'hertz_method.py'}:solve"

# the shared thick-layer case with a second gate: the pressure inside the contact
HALFSPACE = THICK_LAYER_CASE + """[[gates]]
quantity = "pressure_rms_interior"
methods = ["bem"]
against = "analytic"
tolerance = 0.01
reason = "test"
"""

THIN = """
name = "thin"
title = "A thin layer: Hertz does not hold"
kind = "stationary"
[problem]
layer = { thickness = 1.0e-4 }
material = { model = "elastic", shear_modulus = 3.0e6 }
indenter = { shape = "paraboloid", radius = 80.0 }
loading = { load = 10.0 }
[bem]
spacings = [0.1e-3]  # = H: coarse, the BEM's radius is 6.5% from Jaffar's (measured)
half_width = 4.4e-3
[analytic]
reference = "jaffar_thin"
[[gates]]
quantity = "contact_radius"
methods = ["bem"]
against = "analytic"
tolerance = 0.1
reason = "the coarse BEM: 6.5% measured; Hertz is off by a factor of ten"
"""


def _cases(tmp_path, *texts, extra=""):
    folder = tmp_path / "cases"
    folder.mkdir()
    for text in texts:
        name = text.split('name = "')[1].split('"')[0]
        (folder / f"{name}.toml").write_text(text + extra)
    return folder


def _gates(out: Path, method: str) -> dict:
    metrics = json.loads((out / "metrics.json").read_text())
    return {(c["name"], g["quantity"], g["against"]): g for c in metrics["cases"] for g in c["gates"]
            if g["method"] == method and g["verdict"] != "REPORTED"}


def test_hertz_plugin_passes_on_the_half_space_and_is_caught_on_the_thin_layer(tmp_path):
    cases = _cases(tmp_path, HALFSPACE, THIN)
    out = tmp_path / "out"
    code = verify_main(["--cases-dir", str(cases), "--out", str(out), "--method", HERTZ])
    assert code == 1
    g = _gates(out, "hertz")
    assert g[("hs", "contact_radius", "analytic")]["passed"]
    assert g[("hs", "pressure_rms_interior", "analytic")]["passed"]
    wrong = g[("thin", "contact_radius", "analytic")]
    assert not wrong["passed"] and wrong["error"] > 5  # Hertz's radius is ten times Jaffar's here
    bem = _gates(out, "bem")
    assert all(x["passed"] for x in bem.values())  # the BEM passes the same gates
    assert "hertz" in (out / "report.md").read_text()


def test_a_case_can_hold_a_plugin_to_a_gate_against_the_bem(tmp_path):
    gate = ('\n[methods.hertz]\nentry = "hertz_method:solve"\n[[gates]]\nquantity = "contact_radius"\n'
            'methods = ["hertz"]\nagainst = "bem"\ntolerance = 0.01\nreason = "test"\n')
    cases = _cases(tmp_path, HALFSPACE, extra=gate)
    import sys

    sys.path.insert(0, str(ROOT / "examples"))
    try:
        assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "out")]) == 0
    finally:
        sys.path.remove(str(ROOT / "examples"))
    g = _gates(tmp_path / "out", "hertz")[("hs", "contact_radius", "bem")]
    assert g["passed"] and g["error"] < 0.01


def test_an_installed_entry_point_is_a_method_by_name(tmp_path, monkeypatch):
    monkeypatch.syspath_prepend(str(ROOT / "examples"))
    ep = importlib.metadata.EntryPoint(name="hertz", value="hertz_method:solve", group=methods.ENTRY_POINT_GROUP)
    real = importlib.metadata.entry_points
    monkeypatch.setattr(importlib.metadata, "entry_points",
                        lambda **kw: [ep] if kw.get("group") == methods.ENTRY_POINT_GROUP else real(**kw))
    text = HALFSPACE.replace('methods = ["bem"]', 'methods = ["bem", "hertz"]')
    cases = _cases(tmp_path, text)
    assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "out")]) == 0
    assert _gates(tmp_path / "out", "hertz")[("hs", "contact_radius", "analytic")]["passed"]


def _hertz_results(folder: Path, length_unit="mm", scale=1e3, scalar="contact_radius"):
    """What an external FEM model would export for the half-space case, in mm and MPa."""
    G, P, R = 3e6, 10.0, 0.02
    a = (3 * P * R / (16 * G)) ** (1 / 3)
    p0 = 3 * P / (2 * np.pi * a**2)
    x = np.linspace(-1.5 * a, 1.5 * a, 41)
    X, Y = np.meshgrid(x, x)
    p = p0 * np.sqrt(np.clip(1 - (X**2 + Y**2) / a**2, 0, None))
    folder.mkdir(exist_ok=True)
    lines = ["x,y,pressure"] + [f"{xx * scale:.17g},{yy * scale:.17g},{pp / 1e6:.17g}" for xx, yy, pp in
                                zip(X.ravel(), Y.ravel(), p.ravel())]
    (folder / "hs-p.csv").write_text("\n".join(lines) + "\n")
    doc = {"units": {"length": length_unit, "pressure": "MPa", "force": "N"},
           "levels": [{"size": 0.1, "scalars": {scalar: a * scale, "peak_pressure": p0 / 1e6, "load": P},
                       "pressure": "hs-p.csv"}]}
    (folder / "hs.json").write_text(json.dumps(doc))


def test_external_results_pass_and_wrong_units_are_caught(tmp_path):
    cases = _cases(tmp_path, HALFSPACE)
    _hertz_results(tmp_path / "abaqus")
    assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "ok"),
                        "--method", f"abaqus={tmp_path / 'abaqus'}"]) == 0
    g = _gates(tmp_path / "ok", "abaqus")
    assert g[("hs", "contact_radius", "analytic")]["error"] < 1e-12
    assert g[("hs", "pressure_rms_interior", "analytic")]["error"] < 1e-12

    _hertz_results(tmp_path / "wrong", length_unit="m")  # mm numbers declared as metres
    assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "bad"),
                        "--method", f"abaqus={tmp_path / 'wrong'}"]) == 1
    assert not _gates(tmp_path / "bad", "abaqus")[("hs", "contact_radius", "analytic")]["passed"]


def test_a_malformed_results_file_is_an_input_error(tmp_path, capsys):
    cases = _cases(tmp_path, HALFSPACE)
    _hertz_results(tmp_path / "typo", scalar="contact_raduis")
    assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "o"),
                        "--method", f"abaqus={tmp_path / 'typo'}"]) == 2
    err = capsys.readouterr().err
    assert "hs.json: levels[0]: unknown scalar 'contact_raduis'" in err and "did you mean 'contact_radius'" in err


def test_a_plugin_that_raises_fails_its_gates_not_the_suite(tmp_path):
    bad = tmp_path / "bad_method.py"
    bad.write_text("def solve(problem, level):\n    raise RuntimeError('diverged')\n")
    cases = _cases(tmp_path, HALFSPACE)
    out = tmp_path / "out"
    assert verify_main(["--cases-dir", str(cases), "--out", str(out), "--method", f"bad={bad}:solve"]) == 1
    g = _gates(out, "bad")[("hs", "contact_radius", "analytic")]
    assert not g["passed"] and g["error"] is None and "RuntimeError: diverged" in g["reason"]
    assert all(x["passed"] for x in _gates(out, "bem").values())


def test_a_case_that_raises_is_a_failed_case_and_the_others_run(tmp_path, monkeypatch):
    from verification.kinds import stationary

    real = stationary.run

    def run(case, ctx):
        if case["name"] == "thin":
            raise RuntimeError("mesh exploded")
        return real(case, ctx)

    monkeypatch.setattr(stationary, "run", run)
    cases = _cases(tmp_path, HALFSPACE, THIN)
    out = tmp_path / "out"
    assert verify_main(["--cases-dir", str(cases), "--out", str(out)]) == 1
    metrics = json.loads((out / "metrics.json").read_text())
    by_name = {c["name"]: c for c in metrics["cases"]}
    assert by_name["hs"]["passed"] and not by_name["thin"]["passed"]
    assert "RuntimeError: mesh exploded" in by_name["thin"]["gates"][0]["reason"]
    assert "| thin | FAIL |" in (out / "summary.md").read_text()
    assert "the case did not run: RuntimeError: mesh exploded" in (out / "report.md").read_text()
