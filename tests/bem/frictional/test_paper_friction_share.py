"""Paper section 11.6: with mu = 0.2 (pushed at the top) the slipping friction's share of
the rolling resistance stays below 1.55 % for P up to 150 N, and R_r grows with P
(figs. 7a, 9; section 11 layer, a = 0.25 mm, Nt = 500 as the paper's figures)."""

import pytest

from bem import Grid, Layer, Loading, Problem, Sphere, ThreeParameterSolid, influence_kernels
from bem.frictional import Friction
from bem.frictional import solve_friction
from bem.spectral import BLOCKS

LOADS = (25.0, 50.0, 100.0, 150.0)


@pytest.mark.slow
def test_friction_share_below_1_55_percent_up_to_150_n():
    """Measured shares R_r^F / R_r: 0.37 % (25 N), 0.58 % (50 N), 0.86 % (100 N),
    1.05 % (150 N); R_r 0.245, 0.660, 1.739, 3.035 N (9 s in all)."""
    layer = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5e-3, 5e-3))
    kernels = influence_kernels(grid, layer, 0.05, blocks=BLOCKS)
    rr = []
    for P in LOADS:
        res, _ = solve_friction(Problem(layer, Sphere(0.02), grid, Loading(0.05, load=P)), Friction(0.2),
                                kernels=kernels, energy=False)
        assert res.rolling_resistance_friction > 0
        assert res.rolling_resistance_friction / res.rolling_resistance < 0.0155, P
        rr.append(res.rolling_resistance)
    assert all(b > a for a, b in zip(rr, rr[1:]))
