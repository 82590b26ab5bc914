"""The ``friction-sphere`` kind: bad cases are refused before anything is solved, a coarse
copy of the case runs end to end, and (slow) the case passes its gates."""

import math
from pathlib import Path

import pytest

from tests.verification.small_cases import assert_refused
from verification.runner import load_case, run_case

CASE = Path(__file__).resolve().parents[3] / "verification" / "cases" / "friction-sphere-3d.toml"


def test_bad_cases_are_refused():
    assert_refused("friction-sphere", load_case(CASE), [
        (lambda c: c["friction_sphere"].update(kinematics=["paper"]),
         "kinematics: 'paper' is not one the 3D FEM reference represents; give small_slope or exact"),
        (lambda c: c["problem"]["indenter"].update(shape="paraboloid"),
         "indenter.shape = 'paraboloid': a friction-sphere case needs shape = \"sphere\""),
        (lambda c: c["problem"]["loading"].pop("speed"), "speed > 0"),
        (lambda c: c["gates"][0].update(quantity="stick_fractoin"), "unknown quantity 'stick_fractoin'"),
        (lambda c: c["gates"][0].update(against="analytic"), r"methods = \[\"bem\"\] and against = \"fem\""),
        (lambda c: c["gates"][-1].update(against="fem"), "against = \"energy\""),
        (lambda c: c["gates"][0].update(levels=["extrapolated"]), "'levels' does not apply"),
        (lambda c: c["friction_sphere"].update(loadings=["omega"]), "loadings"),
        (lambda c: c["friction_sphere"].update(fem_element_sizes=[5e-4, 1e-3]), "fem_element_sizes: coarse to fine"),
        (lambda c: c["friction_sphere"].update(mu=0.0), "mu"),
        (lambda c: c.pop("friction_sphere"), r"needs a \[friction_sphere\] section"),
    ])


def test_a_coarse_copy_runs_end_to_end():
    """One coarse level of each method, one kinematics: every gate gets a finite error."""
    case = load_case(CASE)
    s = case["friction_sphere"]
    s.update(kinematics=["small_slope"], bem_spacings=[5e-4], fem_element_sizes=[2e-3], fem_grading=0.5,
             fem_far_size=1e-2)
    result = run_case(case, progress=lambda m: None)
    assert "error" not in result.extra, result.extra.get("error")
    assert all(math.isfinite(g.error) for g in result.gates), [(g.quantity, g.error) for g in result.gates]
    assert {r["method"] for r in result.extra["friction_sphere"]} == {"bem", "fem"}


@pytest.mark.slow
def test_case_passes_its_gates():
    """76 s and 2.2 GB peak measured (loaded 2-core machine)."""
    result = run_case(load_case(CASE), progress=lambda m: None)
    assert "error" not in result.extra, result.extra.get("error")
    assert all(g.passed for g in result.gates), [(g.quantity, g.method, g.error) for g in result.gates]


def test_the_full_case_is_the_default_one_a_level_finer():
    default = load_case(CASE)
    full = load_case(CASE.with_name("friction-sphere-3d-full.toml"))
    assert full.get("full") and not default.get("full") and not default.get("quick")
    fs, ds = full["friction_sphere"], default["friction_sphere"]
    assert fs["fem_element_sizes"][:-1] == ds["fem_element_sizes"]
    assert {k: v for k, v in fs.items() if k != "fem_element_sizes"} == \
        {k: v for k, v in ds.items() if k != "fem_element_sizes"}
    assert full["problem"] == default["problem"]
