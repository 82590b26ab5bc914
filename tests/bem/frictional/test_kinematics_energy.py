"""The two rolling-resistance figures of a frictional solve, equilibrium (eqs. 1, 63) and
energy ((P_visc + P_fric) / V), on the paper's section 11 example for each
``[friction] kinematics`` (docs/derivations.md, "Rolling kinematics").

``exact`` and ``small_slope`` close the energy balance exactly in the continuum, so the
figures differ by the discretisation only. Measured (N_t = 2000, Rr / energy - 1) at
a = 0.5 / 0.25 / 0.125 / 0.0625 mm: exact +0.046 / +0.232 / +0.128 / +0.058 %,
small_slope +0.053 / +0.138 / +0.070 / +0.035 %: gate 0.3 %. ``paper`` (arm x / R on the
exact sphere) misses the energy figure by the slope term sum N x (1/zeta - 1/R):
-1.38 / -1.27 / -1.42 / -1.52 %; with that term added back the figures differ by
+0.21 / +0.33 / +0.17 % (the same discretisation error): gate 0.4 %.
"""

from pathlib import Path
import tomllib

import numpy as np
import pytest

from bem.case import friction_from_config, problem_from_config
from bem.frictional import solve_friction

CASE = Path(__file__).resolve().parents[3] / "examples" / "paper-section11-friction.toml"
R = 0.02
CONSISTENT = 0.003  # largest measured |Rr / energy - 1| is 0.23 % (exact at 0.25 mm)
PAPER_RESIDUE = 0.004  # largest measured after the slope term: 0.33 % (0.25 mm)


def _solve(spacing, kinematics):
    with open(CASE, "rb") as fh:
        cfg = tomllib.load(fh)
    cfg["grid"]["spacing"] = spacing
    cfg["friction"]["kinematics"] = kinematics
    p, _ = problem_from_config(cfg)
    res, _ = solve_friction(p, friction_from_config(cfg))
    return p, res


def _check_consistent(spacing, kinematics):
    _, res = _solve(spacing, kinematics)
    assert abs(res.rolling_resistance / res.rolling_resistance_energy - 1) < CONSISTENT
    return res


def _check_paper(spacing):
    p, res = _solve(spacing, "paper")
    X, Y = p.grid.coordinates()
    zeta = np.sqrt(np.maximum(R * R - X * X - Y * Y, 0.0))
    with np.errstate(divide="ignore"):
        slope = float(np.where(res.force > 0, res.force * X * (1 / zeta - 1 / R), 0.0).sum())
    gap = 1 - res.rolling_resistance / res.rolling_resistance_energy
    assert 0.012 < gap < 0.016  # the slope term, about r^2 / 2R^2 of R_r
    assert abs((res.rolling_resistance + slope) / res.rolling_resistance_energy - 1) < PAPER_RESIDUE


@pytest.mark.parametrize("kinematics", ["exact", "small_slope"])
def test_consistent_kinematics_close_the_energy_balance_at_half_a_millimetre(kinematics):
    res = _check_consistent(0.5e-3, kinematics)
    assert res.rolling_resistance_friction >= 0


@pytest.mark.slow
@pytest.mark.parametrize("spacing", [0.25e-3, 0.125e-3])
@pytest.mark.parametrize("kinematics", ["exact", "small_slope"])
def test_consistent_kinematics_close_the_energy_balance_on_finer_grids(kinematics, spacing):
    _check_consistent(spacing, kinematics)


@pytest.mark.slow
@pytest.mark.parametrize("spacing", [0.5e-3, 0.25e-3, 0.125e-3])
def test_paper_kinematics_miss_the_energy_figure_by_the_slope_term(spacing):
    _check_paper(spacing)
