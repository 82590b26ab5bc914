"""The harness itself: its metrics on exact data, and its gates catching wrong results."""

import copy
import math

import numpy as np
import pytest

from verification import analytic
from verification.cli import main as verify_main
from verification.kinds import stationary
from verification.methods import bem
from verification.metrics import fit_contact_radius, pressure_difference, richardson
from verification.results import CaseResult
from verification.runner import CASES_DIR, list_cases, load_case


@pytest.mark.parametrize("ratio", [2.0, 3.0, 1.5])
def test_richardson_recovers_order_and_limit_for_any_ratio(ratio):
    h = [0.4, 0.4 / ratio, 0.4 / ratio**2]
    q = [1.0 + 0.3 * x**1.7 for x in h]
    c = richardson(q, ratio)
    assert abs(c.order - 1.7) < 1e-9
    assert abs(c.extrapolated - 1.0) < 1e-12 and c.asymptotic
    assert abs(c.error_finest - 0.3 * h[-1] ** 1.7) < 1e-12  # the finest level's true error


def test_richardson_refuses_to_extrapolate_stagnant_or_oscillating_sequences():
    stagnant = richardson([4.5011, 4.5077, 4.5139])  # observed order 0.09
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


def test_pressure_difference_of_a_scaled_field_is_known_exactly():
    """p = (1 + eps) p_Hertz: the difference over the peak is eps sqrt(1 - r^2/a^2), so its
    largest interior value is eps at the centre and its edge RMS is the RMS of that
    function over the edge samples."""
    eps = 0.013
    h = analytic.hertz_contact(10.0, 0.02, 12e6)
    a = h.contact_radius
    r = np.linspace(0, a, 201)
    d = pressure_difference(r, (1 + eps) * h.pressure(r), h.pressure, a)
    assert abs(d.max_interior - eps) < 1e-14
    edge = (r >= 0.9 * a) & (r < a)
    expect = eps * np.sqrt(np.mean(1 - (r[edge] / a) ** 2))
    assert abs(d.rms_edge - expect) < 1e-14
    assert abs(d.peak_reference - h.peak_pressure) < 1e-9 * h.peak_pressure


@pytest.fixture(scope="module")
def hertz_case_result():
    """The half-space case with one BEM level (0.1 mm) against Hertz."""
    case = load_case(CASES_DIR / "halfspace-hertz.toml")
    case["gates"] = [g for g in case["gates"] if g["against"] == "analytic"]
    for g in case["gates"]:
        g["methods"] = ["bem"]
    result = CaseResult(case["name"], case["title"], "", "stationary")
    result.reference = analytic.hertz_contact(10.0, 0.02, 4 * 3.0e6)
    result.runs["bem"] = [bem.run(case["problem"], case["bem"], 0.1e-3)]
    return case, result


def _gates(case, result):
    result = copy.copy(result)
    result.gates = []
    stationary.evaluate(case, result)
    return {g.quantity: g for g in result.gates if not g.report_only}


def test_correct_solution_passes(hertz_case_result):
    case, result = hertz_case_result
    gates = _gates(case, result)
    assert set(gates) == {"contact_radius", "peak_pressure", "pressure_rms_interior"}
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
    g = _gates(case, wrong)["contact_radius"]
    assert not g.passed and abs(g.error - 0.01) < 2e-3


def test_a_method_without_a_quantity_fails_that_gate_and_says_why(hertz_case_result):
    case, result = hertz_case_result
    wrong = copy.copy(result)
    run = copy.copy(result.runs["bem"][0])
    run.scalars = {k: v for k, v in run.scalars.items() if k != "peak_pressure"}
    wrong.runs = {"bem": [run]}
    g = _gates(case, wrong)["peak_pressure"]
    assert not g.passed and math.isnan(g.error) and "returned no 'peak_pressure'" in g.reason


def test_default_suite_has_the_issue_cases():
    names = {p.stem for p in list_cases()}
    assert {"halfspace-hertz", "thick-layer", "thin-layer", "thickness-sweep", "table1", "rolling-limits"} <= names
    sweep = load_case(CASES_DIR / "thickness-sweep.toml")
    assert len(sweep["sweep"]["thicknesses"]) >= 5


def test_verify_cli_writes_report_and_fails_on_a_failing_gate(tmp_path):
    out = tmp_path / "ok"
    assert verify_main(["--case", "table1", "--quick", "--out", str(out)]) == 0
    for name in ("summary.md", "report.md", "report.html", "metrics.json", "table1-table1.png"):
        assert (out / name).exists()
    strict = tmp_path / "cases"
    strict.mkdir()
    text = (CASES_DIR / "table1.toml").read_text().replace("tolerance = 1e-4", "tolerance = 1e-9")
    (strict / "table1.toml").write_text(text)
    assert verify_main(["--cases-dir", str(strict), "--quick", "--out", str(tmp_path / "bad")]) == 1
    assert "FAIL" in (tmp_path / "bad" / "summary.md").read_text()
