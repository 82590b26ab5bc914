"""bem.linear.LinearSolver's dense fallback: a GMRES solve that fails on a system of at
most ``dense_fallback`` unknowns is solved by dense LU, and so is every later call up to
that size; bem.contact.solve_normal uses it up to DENSE_FALLBACK nodes.

GMRES is made to fail by giving it two iterations (restart 2, one cycle) on a system
that needs about its size; the answers are checked against ``numpy.linalg.solve``
(rounding of a well-conditioned system of 60 unknowns: ~1e-15 relative).
"""

from types import SimpleNamespace

import numpy as np
import pytest

from bem.contact import ContactNotConverged, solve_normal
from bem.grid import Grid
from bem.indenters import Sphere
from bem.layer import Layer
from bem.linear import LinearSolver
from bem.materials import ThreeParameterSolid
from bem.operator import ComplianceOperator
from bem.spectral import influence_kernels


def _system(n=60, seed=5):
    rng = np.random.default_rng(seed)
    A = np.eye(n) + 0.5 * rng.normal(size=(n, n)) / np.sqrt(n)
    b = rng.normal(size=n)
    calls = []

    def matvec(x):
        calls.append(1)
        return A @ x

    return SimpleNamespace(n=n, b=b, dense=lambda: A, matvec=matvec, calls=calls), np.linalg.solve(A, b)


def test_a_failed_gmres_is_solved_by_dense_lu_up_to_the_fallback_size():
    system, exact = _system()
    solver = LinearSolver(0, 1e-12, restart=2, maxiter=1, error=ContactNotConverged, dense_fallback=60)
    x = solver(system)
    assert np.abs(x - exact).max() < 1e-13 * np.abs(exact).max()
    assert solver.fallbacks == 1 and solver.used_gmres
    # later calls up to that size go to dense LU straight away: no product
    system.calls.clear()
    assert np.abs(solver(system) - exact).max() < 1e-13 * np.abs(exact).max()
    assert not system.calls and solver.fallbacks == 1


@pytest.mark.parametrize("fallback", [0, 59])
def test_a_failed_gmres_above_the_fallback_size_raises(fallback):
    system, _ = _system()
    solver = LinearSolver(0, 1e-12, restart=2, maxiter=1, error=ContactNotConverged, dense_fallback=fallback)
    with pytest.raises(ContactNotConverged, match=r"^GMRES did not reduce the residual by 1\.0e-12 on 60 unknowns"):
        solver(system)
    assert solver.fallbacks == 0


def test_solve_normal_ends_on_the_dense_state_when_every_gmres_fails(rolling_small, monkeypatch):
    """The section 11 layer rolling on 21 x 21 nodes, every set through GMRES
    (``dense_limit`` 1) and GMRES replaced by one that fails: the solve ends on the state
    that dense LU on every set gives (the same sets; forces to rounding)."""
    import bem.linear as linear

    X, Y = rolling_small.grid.coordinates()
    s = (X ** 2 + Y ** 2) / (2 * 0.02)  # paraboloid R = 20 mm (m)
    dense = solve_normal(rolling_small, s, load=20.0, dense_limit=10 ** 4)
    monkeypatch.setattr(linear, "fgmres", lambda matvec, b, *args, **kw: (np.zeros_like(b), False, 3))
    res = solve_normal(rolling_small, s, load=20.0, dense_limit=1)
    assert res.record.linear_solver == "gmres" and res.record.linear_iterations == 3  # one failed run
    assert np.array_equal(res.force > 0, dense.force > 0)
    assert np.abs(res.force - dense.force).max() < 1e-12 * dense.force.max()
    assert res.indentation == pytest.approx(dense.indentation, rel=1e-12)


@pytest.mark.slow
def test_a_sphere_on_a_thick_lagging_layer_ends_on_the_dense_state():
    """A sphere (R = 20 mm, 59 N, 2.7 m/s) on a 10 mm three-parameter solid (G0 = 0.53 MPa,
    f = 85, tau = 3.2 ms), 97 x 97 nodes of 0.25 mm: GMRES with the wrapped circulant does
    not reach the first fine set's loose tolerance (1267 nodes) in its one restart cycle
    (100 iterations; to 1e-11 it fails after 10000); the dense fallback ends on the state
    of dense LU on every set. Measured: 11 sets, 0.46 s CPU (0.55 s all dense, 3.5 s after a
    failed tight run); the same sets and forces; smallest force 1.3e-3 of the largest,
    smallest gap off the set 1.0e-5 d."""
    grid = Grid.centred((2.5e-4, 2.5e-4), (0.1, 0.1), (200, 200), (12e-3, 12e-3))
    layer = Layer(10e-3, ThreeParameterSolid(G0=5.29e5, tau=3.2e-3, f=85.1), 1150.0)
    op = ComplianceOperator(grid, influence_kernels(grid, layer, 2.7)["ww"])
    X, Y = grid.coordinates()
    s = Sphere(0.02).profile(X, Y)
    res = solve_normal(op, s, load=59.0)
    dense = solve_normal(op, s, load=59.0, dense_limit=4000)
    assert res.record.linear_iterations == 100  # one failed GMRES cycle, then dense LU
    assert np.array_equal(res.force > 0, dense.force > 0)
    assert np.abs(res.force - dense.force).max() < 1e-12 * dense.force.max()
    F, h = dense.force.ravel(), dense.gap.ravel()
    on = F > 0
    assert F[on].min() > 1e-4 * F.max() and h[np.isfinite(h) & ~on].min() > 1e-6 * dense.indentation
