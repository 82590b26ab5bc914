"""The harness itself: its metrics on exact data, and its gates catching wrong results."""

import copy

import numpy as np
import pytest

from verification import analytic
from verification.cli import main as verify_main
from verification.metrics import fit_contact_radius, pressure_difference, richardson
from verification.runner import CASES_DIR, CaseResult, evaluate_gates, list_cases, load_case, run_bem


def test_richardson_recovers_order_and_limit():
    q = [1.0 + 0.3 * h**1.7 for h in (0.4, 0.2, 0.1)]
    c = richardson(q)
    assert abs(c.order - 1.7) < 1e-12
    assert abs(c.extrapolated - 1.0) < 1e-12 and c.asymptotic
    stagnant = richardson([4.5011, 4.5077, 4.5139])  # observed order 0.09: no extrapolation
    assert not stagnant.asymptotic and stagnant.extrapolated == 4.5139
    assert abs(stagnant.error_finest - 3 * 0.0062) < 1e-12
    assert not richardson([1.0, 1.2, 1.1]).asymptotic  # non-monotone


def test_radius_fit_is_exact_for_the_hertz_edge():
    """g = c (r - r_c)^(3/2) outside the contact: the g^(2/3) line gives r_c exactly, from
    scattered 2D samples as from a line of samples."""
    rc = 2.3456e-3
    x = np.arange(-40, 41) * 0.1e-3
    X, Y = np.meshgrid(x, x)
    r = np.hypot(X, Y)
    gap = np.where(r > rc, 0.7 * np.clip(r - rc, 0, None) ** 1.5, 0.0)
    assert abs(fit_contact_radius(r, gap, r <= rc, 0.1e-3) - rc) < 1e-15
    line = np.linspace(0, 4e-3, 33)
    g = np.where(line > rc, 0.7 * np.clip(line - rc, 0, None) ** 1.5, 0.0)
    assert abs(fit_contact_radius(line, g, line <= rc, line[1]) - rc) < 1e-15


def test_pressure_difference_of_a_field_with_itself_is_zero():
    h = analytic.hertz_contact(10.0, 0.02, 12e6)
    r = np.linspace(0, h.contact_radius, 50)
    d = pressure_difference(r, h.pressure(r), h.pressure, h.contact_radius)
    assert d.max_interior == 0 and d.rms_edge == 0


@pytest.fixture(scope="module")
def hertz_case_result():
    """The half-space case with one BEM level (0.1 mm) against Hertz."""
    case = load_case(CASES_DIR / "halfspace-hertz.toml")
    case["bem"]["spacings"] = [0.1e-3]
    case.pop("fem")
    case["gates"] = [g for g in case["gates"] if g["against"] == "analytic"]
    for g in case["gates"]:
        g["methods"] = ["bem"]
    result = CaseResult(case["name"], case["title"], "", "stationary")
    result.reference = analytic.hertz_contact(10.0, 0.02, 4 * 3.0e6)
    result.runs["bem"] = [run_bem(case["problem"], case["bem"], 0.1e-3)]
    return case, result


def _gates(case, result):
    result = copy.copy(result)
    result.gates = []
    evaluate_gates(case, result)
    return {g.quantity: g for g in result.gates}


def test_correct_solution_passes(hertz_case_result):
    case, result = hertz_case_result
    gates = _gates(case, result)
    assert all(g.passed for g in gates.values()), {q: g.error for q, g in gates.items()}


def test_pressure_scaled_by_2_percent_fails_the_pressure_gates(hertz_case_result):
    case, result = hertz_case_result
    wrong = copy.copy(result)
    run = copy.copy(result.runs["bem"][0])
    run.pressure = run.pressure * 1.02
    run.scalars = dict(run.scalars, peak_pressure=run.scalars["peak_pressure"] * 1.02)
    wrong.runs = {"bem": [run]}
    gates = _gates(case, wrong)
    assert not gates["pressure_rms_interior"].passed
    assert not gates["peak_pressure"].passed
    assert gates["contact_radius"].passed  # untouched quantity still passes


def test_radius_off_by_one_percent_fails_the_radius_gate(hertz_case_result):
    case, result = hertz_case_result
    wrong = copy.copy(result)
    run = copy.copy(result.runs["bem"][0])
    run.scalars = dict(run.scalars, contact_radius=run.scalars["contact_radius"] * 1.01)
    wrong.runs = {"bem": [run]}
    assert not _gates(case, wrong)["contact_radius"].passed


def test_default_suite_has_the_issue_cases():
    names = {p.stem for p in list_cases()}
    assert {"halfspace-hertz", "thick-layer", "thin-layer", "thickness-sweep", "table1", "rolling-limits"} <= names
    sweep = load_case(CASES_DIR / "thickness-sweep.toml")
    assert len(sweep["sweep"]["thicknesses"]) >= 5
    for path in list_cases():
        case = load_case(path)
        for gate in case["gates"]:
            assert gate["reason"].strip() and gate["tolerance"] > 0


def test_verify_cli_writes_report_and_fails_on_a_failing_gate(tmp_path):
    out = tmp_path / "ok"
    assert verify_main(["--case", "table1", "--quick", "--out", str(out)]) == 0
    for name in ("report.md", "report.html", "metrics.json", "table1-table1.png"):
        assert (out / name).exists()
    strict = tmp_path / "cases"
    strict.mkdir()
    text = (CASES_DIR / "table1.toml").read_text().replace("tolerance = 1e-4", "tolerance = 1e-9")
    (strict / "table1.toml").write_text(text)
    assert verify_main(["--cases-dir", str(strict), "--quick", "--out", str(tmp_path / "bad")]) == 1
    assert "FAIL" in (tmp_path / "bad" / "report.md").read_text()
