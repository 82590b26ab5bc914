"""The condensed surface compliance of the plane-strain FEM layer: reciprocity at rest,
the moving frame's reversal identity, and its normal block against the frictionless
FEM's own compliance (fem_reference/frictional/compliance.py, module docstring)."""

import numpy as np

from fem_reference.rolling.solve import compliance
from tests.fem_reference.frictional.layers import elastic, viscous


def test_elastic_layer_at_rest_is_reciprocal():
    """Betti: at V = 0 the elastic layer's operator is symmetric (measured 1.6e-14)."""
    _, comp = elastic(0.01, 2e-4, speed=0.0)
    assert comp.asymmetry() < 1e-12
    for a in "xz":
        assert np.all(np.diag(comp.block(a, a)) > 0)


def test_rolling_layer_obeys_the_reversal_identity():
    """C(V) = C(-V)^T, with the mirror image C(-V) = P C(V) P: the viscoelastic rolling
    operator is far from symmetric (||C - C^T|| / ||C|| measured 0.485) but C - P C^T P is
    the truncation and transport error only (measured 1.6e-5 at h = 0.2 mm, 1.2e-5 at 0.1
    mm); 1e-4 leaves a 6x margin and stays 3000 times below the asymmetry."""
    _, comp = viscous(2e-4)
    assert comp.asymmetry() > 0.3
    assert comp.reversal_defect() < 1e-4


def test_normal_block_is_the_frictionless_compliance():
    """C_zz = M^-1 W M^-1 with W the frictionless solve's own compliance (rounding:
    measured 1.2e-14)."""
    _, comp = viscous(2e-4)
    W = compliance(comp.system, comp.solver, 64, lambda _: None)
    m = comp.weights
    Czz = comp.block("z", "z")
    assert np.abs(W / np.outer(m, m) - Czz).max() <= 1e-12 * np.abs(Czz).max()
