"""bem.contact's coarse level of any grid and its loose active-set steps: the coarse nodes, kernel and interpolation against the
fine grid's, and the loose steps against every step solved to ``rtol`` (the same
converged set)."""

import numpy as np
import pytest

import bem.contact as contact
from bem.coarse_levels import coarse_grid, coarse_kernel, coarse_level, prolonged
from bem.contact import solve_normal
from bem.grid import Grid
from bem.indenters import Sphere
from bem.layer import Layer
from bem.materials import Elastic
from bem.operator import ComplianceOperator
from bem.spectral import influence_kernels


@pytest.mark.parametrize("shape", [(26, 25), (25, 26), (26, 26), (25, 25)])
def test_coarse_level_of_any_grid(shape):
    """Odd-sized axes keep every other node, even-sized ones a node in the middle of each
    pair; the frictional solver's ``coarse_grid`` stays odd-only."""
    Ky, Kx = shape
    g = Grid(1e-3, 2e-3, 1.0, 1.0, 600, 300, Kx, Ky)
    c = coarse_level(g)
    assert c.shape == ((Ky + 1) // 2, (Kx + 1) // 2)
    assert (c.spacing_x, c.spacing_y, c.truncation_x, c.truncation_y) == (2e-3, 4e-3, 600, 300)
    for fine, coarse, n in ((g.x, c.x, Kx), (g.y, c.y, Ky)):
        want = fine[::2] if n % 2 else 0.5 * (fine[0::2] + fine[1::2])
        np.testing.assert_allclose(coarse, want, rtol=0, atol=1e-15)
    assert (coarse_grid(g) is None) == (Kx % 2 == 0 or Ky % 2 == 0)
    assert coarse_level(Grid(1e-3, 1e-3, 1.0, 1.0, 600, 600, 24, 26)) is None  # 624 nodes


@pytest.mark.parametrize("shape", [(10, 11), (11, 10), (12, 12)])
def test_coarse_kernel_is_the_compliance_between_the_coarse_nodes(shape):
    """Offsets between coarse nodes are even numbers of fine spacings: the coarse operator
    is the fine one between nodes ``0, 2, 4, ...`` exactly."""
    Ky, Kx = shape
    rng = np.random.default_rng(1)
    kernel = rng.random((2 * Ky - 1, 2 * Kx - 1))
    fine = ComplianceOperator(Grid(1e-3, 1e-3, 1.0, 1.0, 600, 600, Kx, Ky), kernel)
    cy, cx = (Ky + 1) // 2, (Kx + 1) // 2
    sub = ComplianceOperator(Grid(2e-3, 2e-3, 1.0, 1.0, 600, 600, cx, cy), coarse_kernel(kernel))
    nodes = (2 * np.arange(cy)[:, None] * Kx + 2 * np.arange(cx)[None, :]).ravel()
    np.testing.assert_array_equal(sub.dense(), fine.dense(nodes))


@pytest.mark.parametrize("shape", [(9, 10), (10, 9), (1, 10)])
def test_prolonged_is_linear_interpolation(shape):
    """A field linear in position on the coarse nodes comes back linear on the fine nodes
    between the outermost coarse ones, and constant along the axis beyond them."""
    Ky, Kx = shape
    g = Grid(1e-3, 1e-3, 1.0, 1.0, 600, 600, Kx, Ky)
    fine_x = g.x
    coarse_x = fine_x[::2] if Kx % 2 else 0.5 * (fine_x[0::2] + fine_x[1::2])
    coarse_y = g.y[::2] if Ky % 2 else 0.5 * (g.y[0::2] + g.y[1::2])
    field = 3.0 + 2.0 * coarse_x[None, :] - 5.0 * coarse_y[:, None]
    out = prolonged(field, shape)
    X = np.clip(fine_x, coarse_x[0], coarse_x[-1])
    Y = np.clip(g.y, coarse_y[0], coarse_y[-1])
    np.testing.assert_allclose(out, 3.0 + 2.0 * X[None, :] - 5.0 * Y[:, None], rtol=0, atol=1e-13)


def _sphere_case(nodes):
    g = Grid(0.25e-3, 0.25e-3, 0.2, 0.2, 500, 500, nodes, nodes)
    X, Y = g.coordinates()
    op = ComplianceOperator(g, influence_kernels(g, Layer(5e-3, Elastic(3e6)), 0.0)["ww"])
    return op, Sphere(0.02).profile(X, Y)


@pytest.mark.parametrize("nodes", [44, 45])
def test_loose_steps_end_on_the_set_of_tight_ones(nodes, monkeypatch):
    """GMRES on every set (``dense_limit=0``): the loose steps (``LOOSE_RTOL``) and every
    step to ``rtol`` end on the same contact, forces within 1e-9 of the largest (the GMRES
    accuracy at rtol 1e-11: measured 5e-13 and 9e-11 here), the last solve to ``rtol``, in
    fewer GMRES iterations; the even-sized grid has its coarse level too."""
    op, s = _sphere_case(nodes)
    rtols = []
    real = contact.LinearSolver.__call__

    def recording(self, system, guess=None, *, rtol=None, **kw):
        rtols.append(self.rtol if rtol is None else rtol)
        return real(self, system, guess, rtol=rtol, **kw)

    monkeypatch.setattr(contact.LinearSolver, "__call__", recording)
    loose = solve_normal(op, s, load=1.0, dense_limit=0)
    steps = list(rtols)
    monkeypatch.setattr(contact, "LOOSE_RTOL", 0.0)
    tight = solve_normal(op, s, load=1.0, dense_limit=0)
    np.testing.assert_array_equal(loose.contact, tight.contact)
    assert np.abs(loose.force - tight.force).max() <= 1e-9 * tight.force.max()
    assert loose.coarse is not None and loose.coarse.grid.shape == ((nodes + 1) // 2,) * 2
    assert steps[-1] == 1e-11 and max(steps) > 1e-11
    assert loose.record.linear_iterations < tight.record.linear_iterations
