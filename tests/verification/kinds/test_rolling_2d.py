"""The rolling-2d kind's own rules: the quick subset of speeds, and the energy balance on
the pressure's work rate (int p s'(x) dx) rather than on the small-slope x / R moment."""

import tomllib

import numpy as np
import pytest

from verification.kinds import rolling_2d
from verification.results import Run
from verification.runner import load_case, run_case
from verification.schema import CaseError

CASE = """
name = "r2d"
title = "A cylinder on a layer, coarse"
kind = "rolling-2d"
[problem]
layer = { thickness = 1.4567e-3, density = 0.0 }
material = { model = "three_parameter", G0 = 3.0e6, tau = 0.25, f = 1.0 }
indenter = { shape = "line", radius = 0.02 }
loading = { speed = 0.01, load = 1000.0 }
[speeds]
scaled = [0.1, 1.0, 10.0]
quick = [1.0]
[bem]
spacings = [1.4567e-4]
period = 0.03
half_width = 3.64e-3
[[gates]]
quantity = "rolling_resistance"
methods = ["bem"]
against = "dissipation"
tolerance = 0.05
reason = "coarse"
"""


def _write(tmp_path, text=CASE):
    path = tmp_path / "r2d.toml"
    path.write_text(text)
    return path


def test_quick_runs_the_quick_speeds_only(tmp_path):
    case = load_case(_write(tmp_path))
    b0, tau = rolling_2d.scales(case["problem"])
    quick = run_case(case, progress=lambda s: None, quick=True)
    assert quick.extra["speeds"] == pytest.approx([1.0 * b0 / tau])
    assert len(quick.extra["parts"][0][2]["bem"]) == 1


def test_quick_speeds_must_be_listed(tmp_path):
    with pytest.raises(CaseError, match=r"quick: \[3.0\] not in scaled"):
        load_case(_write(tmp_path, CASE.replace("quick = [1.0]", "quick = [3.0]")))


def _run(R_r, slope, dissipation):
    return Run("m", None, {"rolling_resistance": R_r, "rolling_resistance_slope": slope,
                           "dissipation": dissipation}, np.zeros(0), np.zeros(0))


def test_energy_balance_holds_the_work_rate_not_the_small_slope_moment():
    speeds = [0.5, 2.0]
    # the work rate equals D / V exactly; the x / R moment is 1% and 2% below it
    runs = [_run(0.99 * 3.0, 3.0, 3.0 * 0.5), _run(0.98 * 1.5, 1.5, 1.5 * 2.0)]
    assert rolling_2d._energy_errors(runs, speeds) == pytest.approx([0.0, 0.0], abs=1e-15)
    # a method that gives no work rate is held by its R_r, over the largest D / V
    bare = [Run("m", None, {k: v for k, v in r.scalars.items() if k != "rolling_resistance_slope"},
                r.r, r.pressure) for r in runs]
    assert rolling_2d._energy_errors(bare, speeds) == pytest.approx([0.01, 0.01])
