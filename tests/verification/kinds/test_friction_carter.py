"""The ``friction-carter`` kind: the case runs and passes its gates, and bad cases are
refused before anything is solved."""

from pathlib import Path

import pytest

from tests.verification.small_cases import assert_refused
from verification.runner import load_case, run_case

CASE = Path(__file__).resolve().parents[3] / "verification" / "cases" / "friction-carter-2d.toml"


def test_case_passes_its_gates_over_the_creepages():
    result = run_case(load_case(CASE), progress=lambda m: None)
    assert "error" not in result.extra
    assert {g.quantity for g in result.gates} == {"creep_force", "stick_edge", "traction_rms", "plane_creep_force",
                                                  "plane_stick_edge", "plane_traction_rms"}
    assert all(g.passed for g in result.gates), [(g.quantity, g.error) for g in result.gates]
    rows = result.extra["carter"]
    assert rows[0]["frac"] == 1e-3 and rows[-1]["frac"] == 1.5
    assert rows[-1]["Q"] == pytest.approx(0.3 * rows[-1]["load"], rel=1e-9)  # full slip: mu P'


def test_bad_cases_are_refused():
    assert_refused("friction-carter", load_case(CASE), [
        (lambda c: c["gates"][0].update(quantity="creep_forse"), "unknown quantity 'creep_forse'"),
        (lambda c: c["carter"].update(creepages=[0.1, -0.2]), r"creepages: each must be > 0 .* got -0.2"),
        (lambda c: c["problem"].update(material={"model": "three_parameter", "G0": 3e6, "tau": 0.25, "f": 1.0}),
         "material model = \"elastic\""),
        (lambda c: c["carter"].pop("plane_depth"), "plane_spacing_x: plane_spacing_x and plane_depth go together"),
    ])
