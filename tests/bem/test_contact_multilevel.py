"""bem.contact's multilevel start: the coarse grid (every other node), the edge mask, the
first trial set from the coarse contact and :func:`bem.contact.coarse_solution`, each
against its documented definition (45 x 45 nodes and their 23 x 23 coarse level).
"""

import numpy as np
import pytest
from scipy.ndimage import binary_dilation

from bem.contact import coarse_grid, edge_nodes, solve_normal
from bem.grid import Grid
from bem.indenters import Sphere
from bem.layer import Layer
from bem.materials import Elastic
from bem.operator import ComplianceOperator
from bem.spectral import influence_kernels


SMALL = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5e-3, 5e-3))  # 21 x 21

MID = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5.5e-3, 5.5e-3))  # 45 x 45

SPHERE = Sphere(0.02)


def _profile(grid):
    X, Y = grid.coordinates()
    return SPHERE.profile(X, Y), SPHERE.rolling_arm(X, Y), X


@pytest.mark.parametrize("shape, coarse", [
    ((25, 25), (13, 13)),   # 625 nodes: the smallest grid with a coarse level
    ((23, 27), None),       # 621 < 625 nodes
    ((9, 71), (5, 36)),     # 9 a side is enough
    ((7, 101), None),       # fewer than 9 a side
    ((25, 26), None),       # even
    ((26, 25), None),
])
def test_coarse_grid_is_every_other_node(shape, coarse):
    Ky, Kx = shape
    g = Grid(1e-3, 2e-3, 1.0, 1.0, 600, 300, Kx, Ky)
    c = coarse_grid(g)
    if coarse is None:
        assert c is None
        return
    assert c.shape == coarse
    assert (c.spacing_x, c.spacing_y, c.period_x, c.period_y, c.truncation_x, c.truncation_y) == (
        2e-3, 4e-3, 1.0, 1.0, 600, 300)
    np.testing.assert_allclose(c.x, g.x[::2], rtol=0, atol=1e-15)
    np.testing.assert_allclose(c.y, g.y[::2], rtol=0, atol=1e-15)


def test_edge_nodes_are_the_border_and_a_line_s_two_ends():
    e = edge_nodes((4, 5)).reshape(4, 5)
    expected = np.ones((4, 5), bool)
    expected[1:-1, 1:-1] = False
    np.testing.assert_array_equal(e, expected)
    np.testing.assert_array_equal(edge_nodes((1, 5)), [True, False, False, False, True])  # a line: its ends


def test_both_rows_of_a_two_row_grid_are_its_border():
    np.testing.assert_array_equal(edge_nodes((2, 4)), np.ones(8, bool))  # both rows are borders


def _first_set(coarse, s):
    """The first trial set on 45 x 45 nodes by its definition: the coarse contact on the fine
    nodes it stands for, and every node where the fine profile ``s`` less the coarse
    indentation plus the coarse deflection, interpolated linearly between coarse nodes, is
    at most 0."""
    up = np.zeros(MID.shape, bool)
    up[::2, ::2] = coarse.contact
    u = np.zeros(MID.shape)
    u[::2, ::2] = coarse.deflection
    u[1::2, ::2] = (u[:-2:2, ::2] + u[2::2, ::2]) / 2
    u[:, 1::2] = (u[:, :-2:2] + u[:, 2::2]) / 2
    return up | (s - coarse.indentation + u <= 0)


def test_multilevel_start_is_the_coarse_contact_and_its_predicted_gap(elastic_mid):
    """On 45 x 45 nodes the first trial set is the contact of the same problem on every
    other node, upsampled, with the nodes whose gap the coarse solution predicts at most 0;
    from there the set converges in a few iterations to the same contact as a start from
    every reachable node would."""
    op = elastic_mid
    s, _, _ = _profile(MID)
    r = solve_normal(op, s, load=1.0)
    coarse = solve_normal(ComplianceOperator(coarse_grid(MID), op.kernel[::2, ::2]), s[::2, ::2], load=1.0)
    start = _first_set(coarse, s)
    assert r.record.history[0] == int(start.sum()) < MID.nodes_x * MID.nodes_y
    # every contact node, and under half the extra nodes of a start widened by one node
    # around the coarse contact (measured 8 against 44 of 61 contact nodes)
    up = np.zeros(MID.shape, bool)
    up[::2, ::2] = coarse.contact
    widened = binary_dilation(up, structure=np.ones((3, 3), bool))
    assert not (r.contact & ~start).any()
    assert (start & ~r.contact).sum() < 0.5 * (widened & ~r.contact).sum()
    assert r.record.iterations <= 3  # measured 2: the extra nodes dropped, then confirmed
    # the result carries that coarse solution (and it carries its own: none below 625 nodes)
    assert r.coarse.grid == coarse_grid(MID) and r.coarse.coarse is None
    np.testing.assert_array_equal(r.coarse.force, coarse.force)
    assert r.coarse.indentation == coarse.indentation
    # under displacement control, the coarse problem at the same d
    rd = solve_normal(op, s, indentation=r.indentation)
    cd = solve_normal(ComplianceOperator(coarse_grid(MID), op.kernel[::2, ::2]), s[::2, ::2],
                      indentation=r.indentation)
    assert rd.record.history[0] == int(_first_set(cd, s).sum())
    np.testing.assert_array_equal(rd.contact, r.contact)


def test_multilevel_start_keeps_out_unreachable_nodes(elastic_mid):
    """Nodes the indenter cannot reach (inf profile) are never in a trial set: here every
    node of a column through the contact."""
    op = elastic_mid
    s, _, _ = _profile(MID)
    s[:, 23] = np.inf
    r = solve_normal(op, s, load=1.0)
    assert not r.contact[:, 23].any() and np.isposinf(r.gap[:, 23]).all()
    assert r.record.residual < 1e-12
    assert r.record.history[0] < MID.nodes_x * MID.nodes_y - MID.nodes_y


def test_an_indentation_below_every_coarse_node_falls_back_to_the_overlap(elastic_mid):
    """An indentation that reaches fine nodes but no coarse node (every other node): the
    first set is the geometric overlap {s < d}."""
    op = elastic_mid
    s, _, _ = _profile(MID)
    s[::2, ::2] += 1e-3  # lift the coarse nodes out of reach of d
    d = 2e-6
    r = solve_normal(op, s, indentation=d)
    assert r.record.history[0] == int((s < d).sum())
    assert r.indentation == d and r.load > 0 and r.coarse is None


def test_coarse_solution_is_the_problem_on_every_other_node(elastic_mid, rolling_small, monkeypatch):
    """``coarse_solution``: ``solve_normal`` on the coarse grid with the caller's load,
    dense limit and tolerance (the defaults: solve_normal's), passed on to every level;
    ``None`` below 625 nodes and when the indentation reaches no coarse node (a coarse
    node exactly at ``d`` is not reached); ``solve_normal(coarse=)`` starts from a given
    coarse solution instead of solving it again, and ignores one of another grid."""
    import bem.contact as contact

    op = elastic_mid
    s, _, _ = _profile(MID)
    sub = ComplianceOperator(coarse_grid(MID), op.kernel[::2, ::2])
    want = solve_normal(sub, s[::2, ::2], load=1.0)
    got = contact.coarse_solution(op, s, load=1.0)
    np.testing.assert_array_equal(got.force, want.force)
    assert got.record == want.record and got.grid == coarse_grid(MID)
    assert contact.coarse_solution(rolling_small, _profile(SMALL)[0], load=1.0) is None  # 441 nodes
    import inspect

    mine, theirs = (inspect.signature(f).parameters for f in (contact.coarse_solution, solve_normal))
    assert all(mine[k].default == theirs[k].default for k in ("load", "indentation", "dense_limit", "rtol"))
    # the caller's dense limit and tolerance reach the coarse level
    seen = []
    real = contact.solve_normal
    monkeypatch.setattr(contact, "solve_normal", lambda o, p, **kw: seen.append(
        (o.grid.shape, kw["dense_limit"], kw["rtol"])) or real(o, p, **kw))
    contact.coarse_solution(op, s, load=1.0, dense_limit=7, rtol=1e-9)
    assert seen == [((23, 23), 7, 1e-9)]
    seen.clear()
    real(op, s, load=1.0, dense_limit=7, rtol=1e-9)
    assert seen == [((23, 23), 7, 1e-9)]
    # a given coarse solution: no coarse solve, the same result; one of another grid ignored
    seen.clear()
    r = real(op, s, load=1.0, coarse=want)
    assert seen == [] and r.coarse is want
    ref = real(op, s, load=1.0)
    np.testing.assert_array_equal(r.force, ref.force)
    seen.clear()
    real(op, s, load=1.0, coarse=ref)
    assert seen == [((23, 23), contact.DENSE_LIMIT, 1e-11)]
    # an indentation exactly at the lowest coarse node reaches none (27 x 27: the centre
    # node is not a coarse node): no coarse level, and the fine solve goes on
    g = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (6.5e-3, 6.5e-3))
    sg, _, _ = _profile(g)
    assert g.shape == (27, 27) and coarse_grid(g) is not None and sg[13, 13] == 0
    lowest = float(sg[::2, ::2].min())
    og = ComplianceOperator(g, influence_kernels(g, Layer(5e-3, Elastic(3e6)), 0.0)["ww"])
    assert contact.coarse_solution(og, sg, indentation=lowest) is None
    rg = real(og, sg, indentation=lowest)
    assert rg.coarse is None and rg.load > 0
