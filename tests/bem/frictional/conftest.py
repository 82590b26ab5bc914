"""Fixtures of the frictional solve tests (tests/bem/frictional/solve_checks.py holds their
setting and the result check)."""

import pytest

from bem import influence_kernels
from bem.spectral import BLOCKS
from tests.bem.frictional.solve_checks import GRID, LAYER, V


@pytest.fixture(scope="module")
def kernels():
    """The nine influence kernels of the shared 23 x 23 grid (m/N)."""
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)
