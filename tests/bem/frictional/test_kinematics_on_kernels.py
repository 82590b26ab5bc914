"""bem.kinematics on the viscoelastic layer's kernels (as the frictional solver uses it): the
upwind table of a kernel applied is the upwind difference of the applied kernel, and a
sphere's rolling radius is the distance to its axis.
"""

import math

import numpy as np
import pytest

from bem import Grid, Layer, Sphere, ThreeParameterSolid, influence_kernels
from bem.kinematics import rolling_radius, upwind_field, upwind_table
from bem.operator import ComplianceOperator
from bem.spectral import BLOCKS


LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5.5e-3, 5.5e-3))


@pytest.fixture(scope="module")
def kernels():
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)


def test_upwind_table_is_the_upwind_difference_of_the_field(kernels):
    """Kd * F equals (u_{i+1} - u_i) / a_x of u = K * F on every column but the last."""
    rng = np.random.default_rng(1)
    F = rng.normal(size=GRID.shape)
    u = ComplianceOperator(GRID, kernels["uu"]).apply(F)
    du = ComplianceOperator(GRID, upwind_table(kernels["uu"], GRID.spacing_x)).apply(F)
    ref = upwind_field(u, GRID.spacing_x)
    np.testing.assert_allclose(du[:, :-1], ref[:, :-1], rtol=0, atol=1e-12 * np.abs(ref).max())


def test_rolling_radius_of_a_sphere_is_the_distance_to_its_axis():
    Y = np.array([0.0, 0.01])
    np.testing.assert_allclose(rolling_radius(Sphere(0.02), Y), [0.02, math.sqrt(0.02**2 - 0.01**2)])
