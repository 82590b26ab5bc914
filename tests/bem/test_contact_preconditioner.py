"""The frictionless solver's preconditioner: the inverse of the kernel's wrapped circulant,
applied on the contact set's bounding box (bem.operator, bem.contact).

The case: the standard linear solid (G0 = 3 MPa, tau = 0.25 s, f = 1) on a layer thick
enough for a half-space (H = 0.2 m), a paraboloid R = 20 mm rolling at 0.05 m/s under
150 N, on 39 x 39 nodes (a = 0.36 mm) - the small grid of
benchmarks/bem_viscoelastic_rolling.py's case - and the elastic layer (G = 3 MPa) on the
same grid.
"""

import math

import numpy as np
import pytest

from bem.contact import NormalSystem, solve_normal
from bem.grid import Grid
from bem.indenters import Paraboloid
from bem.layer import Layer
from bem.materials import Elastic, ThreeParameterSolid
from bem.operator import BLOCKS_KEPT, ComplianceOperator, periodic_size
from bem.spectral import influence_kernels

A = 0.36e-3
GRID = Grid.centred((A, A), (0.6, 0.6), (math.ceil(0.6 / (2 * A) - 1e-9),) * 2, (7e-3, 7e-3))  # 39 x 39


@pytest.fixture(scope="module")
def half_space():
    """Compliance operators of the viscoelastic and the elastic thick layer, and the profile."""
    ops = {name: ComplianceOperator(GRID, influence_kernels(GRID, Layer(0.2, material, 0.0), 0.05)["ww"])
           for name, material in (("sls", ThreeParameterSolid(G0=3e6, tau=0.25, f=1.0)), ("elastic", Elastic(3e6)))}
    X, Y = GRID.coordinates()
    return ops, Paraboloid(0.02).profile(X, Y)


def test_viscoelastic_rolling_takes_about_the_elastic_gmres_iterations(half_space):
    """Fine-grid GMRES iterations of the whole solve (deterministic): viscoelastic 48 and
    elastic 34 with the wrapped circulant, against 127 and 51 with the inverse of the
    zero-padded embedding; 55, 40 and 1.5 times the elastic count allowed (about 15 %
    above the measured counts, far below the old ones). The GMRES answer is the dense
    LU answer on the same set: contacts equal, forces within 1e-9 of the largest (the
    GMRES tolerance is 1e-11 of the right-hand side; measured 2.8e-10 and 2.4e-10)."""
    ops, s = half_space
    res = {name: solve_normal(op, s, load=150.0) for name, op in ops.items()}
    visco, elastic = res["sls"].record, res["elastic"].record
    assert visco.linear_solver == elastic.linear_solver == "gmres"
    assert visco.linear_iterations <= 55 and elastic.linear_iterations <= 40
    assert visco.linear_iterations <= 1.5 * elastic.linear_iterations
    for name, op in ops.items():
        dense = solve_normal(op, s, load=150.0, dense_limit=10**6)
        assert dense.record.linear_solver == "dense"
        np.testing.assert_array_equal(res[name].contact, dense.contact)
        np.testing.assert_allclose(res[name].force, dense.force, rtol=0, atol=1e-9 * dense.force.max())


def test_the_wrapped_circulant_is_dissipative_where_the_zero_padded_embedding_is_not(half_space, rolling_small):
    """The compliance symbol of a passive layer has a positive real part (``G' > 0``):
    the wrapped kernel keeps it (measured at least 1.5e-3 of the largest on the thick
    layers, 2.3e-2 on the section 11 layer), while the zero-padded embedding of the thick
    layers' kernels, cut off at the table's border, has real parts down to -4.6e-3
    (viscoelastic, 13 of them) and -6.0e-4 (elastic, 3): the eigenvalues whose inverse
    the old preconditioner amplified."""
    ops, _ = half_space
    for op in (*ops.values(), rolling_small):
        w = op.periodic_spectrum
        assert w.real.min() > 0
        assert w.shape == (periodic_size(op.grid.nodes_y), periodic_size(op.grid.nodes_x) // 2 + 1)
    for op in ops.values():
        assert op.spectrum.real.min() < 0


def test_the_period_is_the_longest_fast_length_the_kernel_table_holds():
    """``periodic_size``: at most ``2 K - 2`` (every offset within half a period is in the
    table), at least ``K`` (the grid fits), factors 2, 3 and 5 only, and no such length
    between it and ``2 K - 2``; 1 for a single node."""
    def smooth(n):
        for p in (2, 3, 5):
            while n % p == 0:
                n //= p
        return n == 1

    assert periodic_size(1) == 1
    for k in range(2, 400):
        p = periodic_size(k)
        assert k <= p <= 2 * k - 2 and smooth(p)
        assert not any(smooth(q) for q in range(p + 1, 2 * k - 1))


def test_a_block_operator_is_the_grids_on_any_block_of_that_shape(half_space):
    """Entries depend on the node offset only: the product of a block's operator is the
    grid's product read on that block, wherever the block sits (to rounding); the whole
    grid's shape gives the operator itself, a block larger than the grid an error, and the
    last ``BLOCKS_KEPT`` shapes are kept."""
    op = half_space[0]["sls"]
    rng = np.random.default_rng(3)
    block = op.block((16, 24))
    assert block is op.block((16, 24)) and op.block(GRID.shape) is op
    f = rng.standard_normal((16, 24))
    scale = np.abs(op.apply(np.pad(f, ((0, 23), (0, 15))))).max()
    for j0, i0 in ((0, 0), (23, 15), (5, 9)):
        full = np.zeros(GRID.shape)
        full[j0:j0 + 16, i0:i0 + 24] = f
        want = op.apply(full)[j0:j0 + 16, i0:i0 + 24]
        np.testing.assert_allclose(block.apply(f), want, rtol=0, atol=1e-13 * scale)
    with pytest.raises(ValueError, match=r"a block of \(40, 8\) nodes does not fit in the grid's \(39, 39\)"):
        op.block((40, 8))
    for n in range(1, BLOCKS_KEPT + 2):
        op.block((n, n))
    assert block is not op.block((16, 24))  # pushed out by the newer shapes, built again


def test_the_systems_product_on_its_box_is_the_dense_product(half_space):
    """NormalSystem's product on the set's bounding box equals the dense bordered matrix
    times the vector, for a set touching the grid's corner and one in its middle."""
    op, s = half_space[0]["sls"], half_space[1]
    rng = np.random.default_rng(5)
    Ky, Kx = GRID.shape
    for rows, cols in ((slice(0, 7), slice(0, 11)), (slice(12, 30), slice(9, 20))):
        mask = np.zeros(GRID.shape, bool)
        mask[rows, cols] = True
        idx = np.flatnonzero(mask.ravel() & (rng.random(Ky * Kx) < 0.8))
        system = NormalSystem(op, idx, s.ravel()[idx], 150.0, None)
        v = rng.standard_normal(system.n)
        want = system.dense() @ v
        np.testing.assert_allclose(system.matvec(v), want, rtol=0, atol=1e-13 * np.abs(want).max())
