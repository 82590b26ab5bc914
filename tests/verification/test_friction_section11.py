"""Paper section 11 with friction (mu = 0.2, pushed at the top): R_r = 3.07 N, < 0.05 N
from slipping friction (sec. 11.2)."""

import pytest

from bem import Grid, Layer, Loading, Problem, Sphere, ThreeParameterSolid
from bem.friction import Friction
from bem.rolling import solve_friction


@pytest.mark.slow
def test_section11_rolling_resistance_and_friction_share():
    layer = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5e-3, 5e-3))
    res, _ = solve_friction(Problem(layer, Sphere(0.02), grid, Loading(0.05, load=150.0)), Friction(0.2))
    assert res.rolling_resistance_friction < 0.05
    # force-based R_r (eq. 4) of the small-slope theory; the paper prints 3.07 N, and the
    # theory's arm x/R against the sphere's slope x/zeta leaves O(r^2 / 2R^2) ~ 1.3 %
    assert abs(res.rolling_resistance - 3.07) < 0.05
    assert res.rolling_resistance_friction / res.rolling_resistance < 0.0155  # sec. 11.6
