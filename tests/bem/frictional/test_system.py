"""bem.frictional.system: the set system's single-precision product against the double one,
and the residual of a known guess against the product's.
"""

import numpy as np
import pytest

from tests.bem.frictional.solve_checks import GRID, synthetic_system


def test_the_single_precision_product_is_single_and_close(kernels):
    """``SetSystem.matvec_single`` rounds the convolution in single precision: it differs
    from ``matvec`` (by more than double rounding) and agrees with it within single
    rounding (measured 8.4e-9 of the largest entry: the rows mix the fields with the
    forces, which stay in double)."""
    system = synthetic_system(kernels)
    x = np.random.default_rng(8).normal(size=system.n)
    exact, single = system.matvec(x), system.matvec_single(x)
    assert single.dtype == np.float64
    err = np.abs(single - exact).max() / np.abs(exact).max()
    assert 1e-12 < err < 1e-7, err


@pytest.mark.parametrize("load, indentation, omega", [(20.0, None, None), (None, 1e-4, 2.4)])
def test_a_known_residual_is_the_product_s(kernels, load, indentation, omega):
    """``SetSystem.residual`` of the array whose fields were recorded (``know``) equals
    ``b - A x`` by the FFT product to rounding, without a product; of any other array
    (an equal copy too) it takes the product; ``LinearSolver`` starts from it."""
    from bem.linear import LinearSolver

    system = synthetic_system(kernels, load=load, indentation=indentation, omega=omega)
    rng = np.random.default_rng(31)
    x = rng.normal(size=system.n)
    want = system.b - system.matvec(x)
    ops, C, nC = system.ops, system.C, system.nC
    size = GRID.nodes_x * GRID.nodes_y
    full = [np.zeros(size) for _ in range(3)]
    for k, f in enumerate(full):
        f[C] = x[k * nC:(k + 1) * nC]
    fields = ops.fields(*(f.reshape(GRID.shape) for f in full)).reshape(3, -1)[:, C]
    system.know(x, list(fields))
    products = []
    real = system.matvec
    system.matvec = lambda v, dtype=np.float64: products.append(1) or real(v, dtype)
    np.testing.assert_allclose(system.residual(x), want, rtol=0, atol=1e-12 * np.abs(want).max())
    assert products == []
    np.testing.assert_allclose(system.residual(x.copy()), want, rtol=0, atol=1e-12 * np.abs(want).max())
    assert products == [1]
    seen = []
    system.residual = lambda v: seen.append(v) or want
    system.precondition = None
    with pytest.raises(RuntimeError, match="GMRES did not reduce"):  # one step cannot reach 1e-30
        LinearSolver(0, 1e-30, maxiter=1, restart=1)._fgmres(system, None, x, 1e-30, "", "")
    assert len(seen) == 1 and seen[0] is x
