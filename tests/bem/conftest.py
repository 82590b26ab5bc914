"""Shared fixtures of the bem tests: compliance operators of small grids."""

import pytest

from bem.grid import Grid
from bem.layer import Layer
from bem.materials import Elastic, ThreeParameterSolid
from bem.operator import ComplianceOperator
from bem.spectral import influence_kernels


@pytest.fixture(scope="session")
def rolling_small():
    """The section 11 layer rolling at 0.05 m/s on 21 x 21 nodes (a = 0.5 mm): a
    non-symmetric operator."""
    grid = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5e-3, 5e-3))
    layer = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
    return ComplianceOperator(grid, influence_kernels(grid, layer, 0.05)["ww"])


@pytest.fixture(scope="session")
def elastic_mid():
    """An elastic layer at rest on 45 x 45 nodes (a = 0.25 mm): grids with a coarse level."""
    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5.5e-3, 5.5e-3))
    return ComplianceOperator(grid, influence_kernels(grid, Layer(5e-3, Elastic(3e6)), 0.0)["ww"])
