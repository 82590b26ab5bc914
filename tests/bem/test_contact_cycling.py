"""bem.contact.solve_normal on a strongly lagging layer: the active set reaches the
complementarity solution in a few steps, whatever the region.

The case: a short roll (R = 66.5 mm, L = 50 mm, ends rounded with r_e = 3 mm) rolling at
V = 2 m/s under P = 230 N on a 4 mm three-parameter solid (G0 = 1 MPa, f = 30, tau = 5 ms:
V tau = 10 mm, about two contact lengths), nodes 0.25 mm x 1.25 mm. The coarse-grid
start holds a row on the rounded end, hundreds of micrometres above the indentation; a
node there needs tens of newtons of tension to close its gap, which lifts its trailing
neighbour into penetration. Adding that neighbour while dropping the node makes the set
creep one node a step towards the region's edge (16 mm half-width: 93 steps; 24 mm:
no convergence in 100); :func:`bem.contact._lifted` keeps such nodes out (8 steps).

The discrete problem has one solution (checked below): every Fourier mode of the kernel
has a compliance of positive real part, so ``x^T C x > 0`` for every nodal vector ``x``.
"""

import numpy as np
import pytest

from bem.contact import NormalSystem, solve_normal
from bem.grid import Grid
from bem.indenters import Cylinder
from bem.layer import Layer
from bem.materials import ThreeParameterSolid
from bem.operator import ComplianceOperator
from bem.spectral import influence_kernels, mode_symbols

LOAD = 230.0  # N
ROLL = Cylinder(0.0665, 0.05, edge_radius=3e-3)
LAYER = Layer(4e-3, ThreeParameterSolid(G0=1e6, tau=5e-3, f=30.0), 1150.0)


def _solve(half_width_x):
    """The case on |x| <= half_width_x (m), |y| <= 27.5 mm; its operator, profile, result."""
    grid = Grid.centred((2.5e-4, 1.25e-3), (0.1, 0.2), (200, 80), (half_width_x, 0.0275))
    op = ComplianceOperator(grid, influence_kernels(grid, LAYER, 2.0)["ww"])
    X, Y = grid.coordinates()
    s = ROLL.profile(X, Y)
    return op, s, solve_normal(op, s, load=LOAD, arm=ROLL.rolling_arm(X, Y))


@pytest.fixture(scope="module")
def wide():
    return _solve(24e-3)  # 45 x 193 nodes


def test_lagging_layer_converges_to_the_complementarity_solution(wide):
    """Contact conditions on the result, and the same state from dense LU on its set.

    Measured: 8 steps; smallest force on the set 2.6e-3 of the largest, smallest gap off it
    6.0e-4 d (so the set is decided by clear margins, not by rounding); |h| on the set
    5.8e-11 d (GMRES to 1e-11); dense LU on the set: forces within 9.7e-10 of the largest,
    d within 3.8e-12. The bounds below leave a factor of 10 or more."""
    op, s, res = wide
    assert res.record.iterations <= 20  # one step a node of creep would be about 90
    F, h, d = res.force.ravel(), res.gap.ravel(), res.indentation
    on = F > 0
    reach = np.isfinite(s.ravel())
    assert F.min() == 0.0 and F[on].min() > 1e-4 * F.max()
    assert np.abs(h[on]).max() < 1e-9 * d
    assert h[reach & ~on].min() > 5e-5 * d
    assert F.sum() == pytest.approx(LOAD, rel=1e-12)

    idx = np.flatnonzero(on)
    system = NormalSystem(op, idx, s.ravel()[idx], LOAD, None)
    x = np.linalg.solve(system.dense(), system.b)
    f_lu, d_lu = system.split(x)
    F_lu = np.zeros_like(F)
    F_lu[idx] = f_lu
    h_lu = s.ravel() - d_lu + op.apply(F_lu.reshape(op.grid.shape)).ravel()
    assert np.abs(F_lu - F).max() < 1e-8 * F.max()
    assert d_lu == pytest.approx(d, rel=1e-10)
    assert f_lu.min() > 1e-4 * f_lu.max() and h_lu[reach & ~on].min() > 5e-5 * d_lu


def test_the_problem_has_one_solution():
    """``C`` sums the kernel's Fourier modes ``g(m, n)`` (:func:`bem.spectral.mode_symbols`,
    ``g(-m, -n)`` the conjugate), so ``x^T C x = sum Re g |x_hat|^2``: with ``Re g > 0`` on
    every mode but the uniform one (``g(0, 0) = 0``, the incompressible layer on its rigid
    base; a region shorter than the period has no uniform nodal vector) ``C`` is positive
    definite in its symmetric part. Two solutions ``(F1, d1)``, ``(F2, d2)`` would give
    ``(F1 - F2)^T C (F1 - F2) = -F1^T h2 - F2^T h1 <= 0`` (equal loads), so ``F1 = F2``.
    Measured: smallest ``Re g`` 6.4e-12 m/N, 2.0e-4 of the largest."""
    grid = Grid.centred((2.5e-4, 1.25e-3), (0.1, 0.2), (200, 80), (24e-3, 0.0275))
    g = mode_symbols(grid, LAYER, 2.0)["ww"]
    assert g[0, 0] == 0
    assert np.delete(g.real.ravel(), 0).min() > 0


def test_the_state_does_not_depend_on_the_region(wide):
    """The contact lies well inside both regions, so |x| <= 16 mm and 24 mm pose the same
    problem on the nodes that matter (same kernel at every offset, same profile): the
    same contact nodes and forces (plain primal-dual updates, without the lifted-node
    test, take 93 steps on the narrower region and do not converge in 100 on the wider).
    Measured: forces within 5e-13 of the largest, d within 3e-15; the bounds are the
    solve's own accuracy (the first test)."""
    _, _, big = wide
    _, _, small = _solve(16e-3)  # 45 x 129 nodes
    shift = (big.force.shape[1] - small.force.shape[1]) // 2
    inner = big.force[:, shift:shift + small.force.shape[1]]
    assert big.force.sum() == pytest.approx(inner.sum(), rel=1e-14)  # nothing outside
    assert np.array_equal(inner > 0, small.force > 0)
    assert np.abs(inner - small.force).max() < 1e-8 * small.force.max()
    assert small.indentation == pytest.approx(big.indentation, rel=1e-10)


def test_a_node_lifted_only_by_the_dropped_tension_does_not_join():
    """One row of 9 nodes (nodes 0 and 8 the edge), d = 1 m; C_ii = 1, a node pressed
    down by its leading neighbour (C_i,i-1 = 1) and by the node two behind
    (C_i,i+2 = 1 m/N). Nodes 4 and 5 (s = 0, 0.5 m) start: F_4 = 1, F_5 = -0.5 N; the
    tension lifts node 3 (s = 1.2 m) to h_3 = 1.2 - 1 - 0.5 = -0.3 m, without it
    h_3 = 0.2 m. Node 5 leaves and node 3 stays out: {4} is the solution (h_5 = 0.5,
    h_3 = 0.2 m)."""
    kernel = np.zeros((1, 17))
    kernel[0, 8] = 1.0  # offset 0
    kernel[0, 9] = 1.0  # C_i,i-1
    kernel[0, 6] = 1.0  # C_i,i+2
    op = ComplianceOperator(Grid(1e-3, 1e-3, 0.02, 0.02, 10, 10, 9, 1), kernel)
    s = np.full((1, 9), np.inf)
    s[0, 3], s[0, 4], s[0, 5] = 1.2, 0.0, 0.5
    lines = []
    res = solve_normal(op, s, indentation=1.0, progress=lines.append)
    assert lines == ["active set 1: 2 nodes, d = 1.000000e+00 m, -1 +0",
                     "active set 2: 1 nodes, d = 1.000000e+00 m, -0 +0"]
    assert res.force.ravel()[4] == pytest.approx(1.0, rel=1e-14) and np.count_nonzero(res.force) == 1
    assert res.gap.ravel()[[3, 5]] == pytest.approx([0.2, 0.5], rel=1e-12)
