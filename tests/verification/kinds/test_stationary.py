"""The stationary kind's gates (:mod:`verification.kinds.stationary`): the BEM's
half-space run against Hertz passes its gates, and the same run made wrong by known
amounts (pressure up 2 %, contact radius up 1 %, a quantity missing) fails exactly the
gates of what was changed, saying why."""

import copy
import math

import pytest

from verification import analytic
from verification.kinds import stationary
from verification.methods import bem
from verification.results import CaseResult
from verification.runner import CASES_DIR, load_case


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


def test_the_bem_half_space_run_passes_its_hertz_gates(hertz_case_result):
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
