"""bem.frictional.system: the set system's single-precision product against the double one,
and the residual of a known guess against the product's.
"""

import numpy as np
import pytest

from bem import Layer, Sphere, ThreeParameterSolid, influence_kernels
from bem.frictional.loading import constraint
from bem.grid import Grid
from bem.spectral import BLOCKS


LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (5.5e-3, 5.5e-3))  # 23 x 23, 529 nodes


@pytest.fixture(scope="module")
def kernels():
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)


def _system(kernels, load=None, indentation=1e-4, omega=2.4, seed=0, flip=None, hole=None, turn=0.0, ops=None):
    """A synthetic set state on the frictionless contact of 20 N: random stick/slip
    split, slip directions (turned by ``turn`` rad) and slopes; ``hole``: a node left out
    of the contact (splitting its grid row's run in two); ``ops``: the operators of
    another such system (new ones otherwise)."""
    from bem.contact import solve_normal
    from bem.frictional import RollingOperators, RollingSetup, SetState, SetSystem
    from bem.kinematics import rolling_radius

    ops = RollingOperators(GRID, kernels) if ops is None else ops
    X, Y = GRID.coordinates()
    s = Sphere(0.02).profile(X, Y).ravel()
    N0 = solve_normal(ops.op("ww"), s.reshape(GRID.shape), load=20.0).force.ravel()
    rng = np.random.default_rng(seed)
    contact = N0 > 0
    if hole is not None:
        contact[hole] = False
    stick = contact & (rng.random(N0.size) < 0.6)
    if flip is not None:
        stick[flip] = ~stick[flip]
    ang = rng.uniform(0, 2 * np.pi, N0.size) + turn
    e = np.stack([np.cos(ang), np.sin(ang)], 1)
    k = rng.uniform(0.1, 2.0, N0.size) * V / N0.max()
    ell = rolling_radius(Sphere(0.02), Y).ravel()
    arm = Sphere(0.02).rolling_arm(X, Y).ravel()
    cons = None
    if omega is None:
        from bem.frictional.loading import constraint
        cons = constraint("pushed_at_top", arm, ell, 0.02)
    setup = RollingSetup(ops=ops, profile=s, arm=arm, ell=ell, radius=0.02, speed=V, mu=0.3, load=load,
                         indentation=indentation, omega=omega, constraint=cons)
    return SetSystem(setup, SetState(contact=contact, stick=stick & contact, direction=e, slope=k))


def test_the_single_precision_product_is_single_and_close(kernels):
    """``SetSystem.matvec_single`` rounds the convolution in single precision: it differs
    from ``matvec`` (by more than double rounding) and agrees with it within single
    rounding (measured 8.4e-9 of the largest entry: the rows mix the fields with the
    forces, which stay in double)."""
    system = _system(kernels)
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

    system = _system(kernels, load=load, indentation=indentation, omega=omega)
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
