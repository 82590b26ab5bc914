"""The ``friction-layer`` kind: bad cases are refused before anything is solved, a coarse
copy of the case runs end to end, and (slow) the case passes its gates."""

import math
from pathlib import Path

import pytest

from tests.verification.small_cases import assert_refused
from verification.runner import load_case, run_case

CASE = Path(__file__).resolve().parents[3] / "verification" / "cases" / "friction-layer-2d.toml"


def test_bad_cases_are_refused():
    assert_refused("friction-layer", load_case(CASE), [
        (lambda c: c["gates"][0].update(quantity="rolling_resistanse"), "unknown quantity 'rolling_resistanse'"),
        (lambda c: c["gates"][0].update(against="analytic"), r"methods = \[\"bem\"\] and against = \"fem\""),
        (lambda c: c["gates"][-1].update(against="fem"), "against = \"energy\""),
        (lambda c: c["friction_layer"].pop("creepage"), "creepage: given with loadings containing \"omega\""),
        (lambda c: c["friction_layer"].update(loadings=["sliding"]), "loadings"),
        (lambda c: c["friction_layer"].update(fem_element_sizes=[2.5e-5, 5e-5]), "fem_element_sizes: coarse to fine"),
        (lambda c: c["friction_layer"].update(mu=-0.3), "mu"),
        (lambda c: c["problem"]["indenter"].update(shape="sphere"), "shape = \"line\""),
        (lambda c: c["friction_layer"].update(spacing=1e-4), "spacing"),
    ])


def test_a_coarse_copy_runs_end_to_end():
    """One layer, the coarsest level of each method: every gate gets a finite error."""
    case = load_case(CASE)
    s = case["friction_layer"]
    s["thicknesses"], s["bem_spacings"], s["fem_element_sizes"] = [1e-3], [1e-4], [1e-4]
    result = run_case(case, progress=lambda m: None)
    assert "error" not in result.extra
    assert all(math.isfinite(g.error) for g in result.gates), [(g.quantity, g.error) for g in result.gates]
    assert {(r["method"], r["mode"]) for r in result.extra["friction_layer"]} == \
        {(m, l) for m in ("bem", "fem") for l in s["loadings"]}


@pytest.mark.slow
def test_case_passes_its_gates():
    result = run_case(load_case(CASE), progress=lambda m: None)
    assert "error" not in result.extra
    assert all(g.passed for g in result.gates), [(g.quantity, g.method, g.error) for g in result.gates]
