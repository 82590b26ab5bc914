"""bem.contact: the returned fields, record and messages recomputed from their definitions.

Each solve's outputs are checked against quantities recomputed here from the returned
forces with the operator (``u = C F``, ``h = s - d + u``, the complementarity residual,
``R_r = sum F arm``, the pressure centroid), and the solver's parts (bordered system,
coarse grid, edge mask, multilevel start) against their documented definitions. Small
grids (21 x 21 dense; 45 x 45 for the multilevel start): about 2 s for the file.
"""

import math

import numpy as np
import pytest
from scipy.ndimage import binary_dilation

from bem.contact import (SHARED_SCALARS, ContactAtEdge, ContactNotConverged, NormalSystem, coarse_grid,
                         edge_nodes, grid_summary, solve_normal)
from bem.grid import Grid
from bem.indenters import Sphere
from bem.layer import Layer
from bem.materials import Elastic, ThreeParameterSolid
from bem.operator import ComplianceOperator
from bem.spectral import influence_kernels

SMALL = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5e-3, 5e-3))  # 21 x 21
MID = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5.5e-3, 5.5e-3))  # 45 x 45
SPHERE = Sphere(0.02)


@pytest.fixture(scope="module")
def rolling_small():
    """The section 11 layer rolling at 0.05 m/s: a non-symmetric operator."""
    layer = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
    return ComplianceOperator(SMALL, influence_kernels(SMALL, layer, 0.05)["ww"])


@pytest.fixture(scope="module")
def elastic_mid():
    return ComplianceOperator(MID, influence_kernels(MID, Layer(5e-3, Elastic(3e6)), 0.0)["ww"])


def _profile(grid):
    X, Y = grid.coordinates()
    return SPHERE.profile(X, Y), SPHERE.rolling_arm(X, Y), X


def _residual(F, h, d):
    """max(|h| on the contact, penetration elsewhere) / d, from the returned fields."""
    on = F > 0
    reach = np.isfinite(h)
    return max(np.abs(h[on]).max(initial=0.0), (-h[reach & ~on]).max(initial=0.0)) / d


def test_returned_fields_and_scalars_are_what_they_say(rolling_small):
    """u = C F, h = s - d + u (inf where the indenter cannot touch), F >= 0, F h = 0,
    P = sum F, R_r = sum F x / R, the record (one history entry per iteration, the last
    the contact), the residual, the derived properties and the summary, all recomputed."""
    op = rolling_small
    s, arm, X = _profile(SMALL)
    s[0, 0] = np.inf  # a corner the indenter cannot reach
    lines = []
    r = solve_normal(op, s, load=2.0, arm=arm, progress=lines.append, dense_limit=3000)  # the dense path
    F, a = r.force, SMALL.cell_area
    np.testing.assert_allclose(r.deflection, op.apply(F), rtol=0, atol=1e-14 * np.abs(r.deflection).max())
    assert np.isposinf(r.gap[0, 0])
    h = np.where(np.isfinite(s), s - r.indentation + r.deflection, np.inf)
    np.testing.assert_allclose(r.gap, h, rtol=0, atol=1e-15)
    assert F.min() >= 0 and np.all(F[F > 0] * 0 == 0)
    assert abs(r.load - 2.0) <= 1e-13 * 2.0 and r.load == float(F.sum())
    assert r.rolling_resistance == pytest.approx(float((F * X).sum()) / 0.02, rel=1e-13)
    assert r.rolling_resistance > 0  # passive material, rolling in +x
    rec = r.record
    assert rec.iterations == len(rec.history) == len(lines) >= 2
    assert rec.history[-1] == int((F > 0).sum())
    assert rec.linear_solver == "dense" and rec.linear_iterations == 0
    assert rec.residual == _residual(F, r.gap, r.indentation) < 1e-12
    # the progress lines: iteration, set size, indentation, nodes dropped and added
    for it, (line, n) in enumerate(zip(lines, rec.history), start=1):
        assert line.startswith(f"active set {it}: {n} nodes, d = ")
    assert lines[-1] == f"active set {rec.iterations}: {rec.history[-1]} nodes, d = {r.indentation:.6e} m, -0 +0"
    # properties
    np.testing.assert_array_equal(r.pressure, F / a)
    np.testing.assert_array_equal(r.contact, F > 0)
    assert r.contact_area == (F > 0).sum() * a
    assert r.contact_radius == pytest.approx(math.sqrt((F > 0).sum() * a / math.pi), rel=1e-15)
    assert r.peak_pressure == F.max() / a
    assert r.pressure_centroid_x == pytest.approx(float((F * X).sum() / F.sum()), rel=1e-13)
    summary = r.summary()
    assert set(summary) == set(SHARED_SCALARS) | {"grid", "solver"}
    assert all(summary[k] == getattr(r, k) for k in SHARED_SCALARS)
    assert summary["grid"] == grid_summary(SMALL) == {
        "nodes": [21, 21], "spacing": [0.5e-3, 0.5e-3], "period": [0.2, 0.2], "truncation": [200, 200]}
    assert summary["solver"] == {"iterations": rec.iterations, "residual": rec.residual,
                                 "history": list(rec.history), "linear_solver": "dense",
                                 "linear_iterations": 0}


def test_no_arm_no_rolling_resistance(rolling_small):
    s, _, _ = _profile(SMALL)
    assert math.isnan(solve_normal(rolling_small, s, load=2.0).rolling_resistance)


def test_displacement_control_fields(rolling_small):
    """Under displacement control d is the given value and P = sum F follows; the same
    contact as load control at that P (the same discrete problem)."""
    s, _, _ = _profile(SMALL)
    by_load = solve_normal(rolling_small, s, load=2.0)
    r = solve_normal(rolling_small, s, indentation=by_load.indentation)
    assert r.indentation == by_load.indentation
    assert r.load == pytest.approx(2.0, rel=1e-12)
    np.testing.assert_array_equal(r.contact, by_load.contact)
    assert r.record.residual == _residual(r.force, r.gap, r.indentation) < 1e-12


def test_bordered_system_is_the_stated_matrix(rolling_small):
    """Load control: [[C_AA, -1], [c 1^T, 0]] with c = C_ii (the self-compliance, a
    scale for the load row) and right side [-s_A, c P]; displacement control: C_AA and
    d - s_A. The FFT product equals the dense matrix, and under load control the
    preconditioner is the exact inverse of the force preconditioner's own inverse
    bordered the same way (d eliminated by its Schur complement)."""
    op = rolling_small
    idx = np.array([0, 5, 100, 220, 221, 440])
    s_A = np.linspace(1e-6, 3e-6, idx.size)
    K = op.dense(idx)
    c = K[0, 0]
    assert np.allclose(np.diag(K), c, rtol=1e-13)  # a translation-invariant operator
    sys_p = NormalSystem(op, idx, s_A, 2.0, None)
    M = np.block([[K, -np.ones((6, 1))], [np.full((1, 6), c), np.zeros((1, 1))]])
    assert (sys_p.m, sys_p.n) == (6, 7)
    np.testing.assert_allclose(sys_p.dense(), M, rtol=1e-14, atol=0)
    np.testing.assert_allclose(sys_p.b, np.concatenate([-s_A, [c * 2.0]]), rtol=1e-15)
    v = np.linspace(-1.0, 2.0, 7)
    np.testing.assert_allclose(sys_p.matvec(v), M @ v, rtol=1e-12, atol=1e-12 * np.abs(M @ v).max())
    assert sys_p.split(v) == (pytest.approx(v[:6]), v[6]) and isinstance(sys_p.split(v)[1], float)
    pre = sys_p.precondition(v)
    P = np.column_stack([sys_p._forces(e) for e in np.eye(6)])  # the circulant inverse on the set
    bordered = np.block([[np.linalg.inv(P), -np.ones((6, 1))], [np.full((1, 6), c), np.zeros((1, 1))]])
    assert pre.shape == (7,)
    np.testing.assert_allclose(bordered @ pre, v, rtol=0, atol=1e-10 * np.abs(v).max())
    sys_d = NormalSystem(op, idx, s_A, None, 4e-6)
    assert (sys_d.m, sys_d.n) == (6, 6)
    np.testing.assert_allclose(sys_d.dense(), K, rtol=1e-15)
    np.testing.assert_allclose(sys_d.b, 4e-6 - s_A, rtol=1e-15)
    np.testing.assert_allclose(sys_d.matvec(v[:6]), K @ v[:6], rtol=1e-12, atol=1e-12 * np.abs(K @ v[:6]).max())
    f, d = sys_d.split(v[:6])
    assert d == 4e-6 and np.array_equal(f, v[:6])


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


def test_edge_nodes():
    e = edge_nodes((4, 5)).reshape(4, 5)
    expected = np.ones((4, 5), bool)
    expected[1:-1, 1:-1] = False
    np.testing.assert_array_equal(e, expected)
    np.testing.assert_array_equal(edge_nodes((1, 5)), [True, False, False, False, True])  # a line: its ends


def test_multilevel_start_is_the_widened_coarse_contact(elastic_mid):
    """On 45 x 45 nodes the first trial set is the contact of the same problem on every
    other node, upsampled and widened by one node; from there the set converges in a few
    iterations to the same contact as a start from every reachable node would."""
    op = elastic_mid
    s, _, _ = _profile(MID)
    r = solve_normal(op, s, load=1.0)
    coarse = solve_normal(ComplianceOperator(coarse_grid(MID), op.kernel[::2, ::2]), s[::2, ::2], load=1.0)
    up = np.zeros(MID.shape, bool)
    up[::2, ::2] = coarse.contact
    start = binary_dilation(up, structure=np.ones((3, 3), bool))
    assert r.record.history[0] == int(start.sum()) < MID.nodes_x * MID.nodes_y
    assert r.record.iterations <= 4  # measured 2-3: the start is within one node of the answer
    # the result carries that coarse solution (and it carries its own: none below 625 nodes)
    assert r.coarse.grid == coarse_grid(MID) and r.coarse.coarse is None
    np.testing.assert_array_equal(r.coarse.force, coarse.force)
    assert r.coarse.indentation == coarse.indentation
    # under displacement control, the coarse problem at the same d
    rd = solve_normal(op, s, indentation=r.indentation)
    cd = solve_normal(ComplianceOperator(coarse_grid(MID), op.kernel[::2, ::2]), s[::2, ::2],
                      indentation=r.indentation)
    up[:] = False
    up[::2, ::2] = cd.contact
    assert rd.record.history[0] == int(binary_dilation(up, structure=np.ones((3, 3), bool)).sum())
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


@pytest.mark.parametrize("kw, message", [
    ({}, r"^give exactly one of load \(N\) and indentation \(m\)$"),
    ({"load": 1.0, "indentation": 1e-5}, r"^give exactly one of load \(N\) and indentation \(m\)$"),
    ({"load": 0.0}, r"^load must be > 0 N, got 0\.0$"),
    ({"load": -1.0}, r"^load must be > 0 N, got -1\.0$"),
    ({"load": math.nan}, r"^load must be > 0 N, got nan$"),
    ({"load": math.inf}, r"^load must be > 0 N, got inf$"),
    ({"indentation": 0.0}, r"^indentation must be > 0 m, got 0\.0$"),
    ({"indentation": math.inf}, r"^indentation must be > 0 m, got inf$"),
    ({"indentation": math.nan}, r"^indentation must be > 0 m, got nan$"),
])
def test_bad_loading_messages(rolling_small, kw, message):
    s, _, _ = _profile(SMALL)
    with pytest.raises(ValueError, match=message):
        solve_normal(rolling_small, s, **kw)


def test_bad_profile_messages(rolling_small):
    s, _, _ = _profile(SMALL)
    with pytest.raises(ValueError, match=r"^profile must have the grid's shape \(21, 21\), got \(21, 20\)$"):
        solve_normal(rolling_small, s[:, :20], load=1.0)
    with pytest.raises(ValueError, match=r"^the indenter reaches no node of the grid$"):
        solve_normal(rolling_small, np.full(SMALL.shape, np.inf), load=1.0)
    with pytest.raises(ValueError, match=r"^indentation = 1e-06 m reaches no node: the indenter's lowest node "
                       r"is 2e-06 m above its lowest point; increase loading.indentation or refine the grid$"):
        solve_normal(rolling_small, s + 2e-6, indentation=1e-6)


def test_contact_at_the_edge_names_the_region(rolling_small):
    s, _, _ = _profile(SMALL)
    with pytest.raises(ContactAtEdge, match=r"^the contact reaches the edge of the candidate region "
                       r"\(\|x\| <= 0\.005 m, \|y\| <= 0\.005 m\): increase grid.half_width$"):
        solve_normal(rolling_small, s, load=1000.0)


def test_iteration_limit(rolling_small):
    s, _, _ = _profile(SMALL)
    full = solve_normal(rolling_small, s, load=2.0)
    assert full.record.iterations >= 3
    with pytest.raises(ContactNotConverged, match=r"^no converged contact set in 1 active-set iterations$"):
        solve_normal(rolling_small, s, load=2.0, max_iter=1)
    n = full.record.iterations
    with pytest.raises(ContactNotConverged, match=rf"^no converged contact set in {n - 1} active-set iterations$"):
        solve_normal(rolling_small, s, load=2.0, max_iter=n - 1)  # one short
    same = solve_normal(rolling_small, s, load=2.0, max_iter=n)  # exactly enough
    np.testing.assert_array_equal(same.force, full.force)


def test_edge_nodes_of_two_rows():
    np.testing.assert_array_equal(edge_nodes((2, 4)), np.ones(8, bool))  # both rows are borders


def test_gmres_without_the_circulant_preconditioner(rolling_small):
    """An operator whose circulant embedding is not invertible gives no preconditioner;
    plain GMRES then reaches the dense solution (measured 3e-15 of the largest force in
    331 iterations; 1e-9 allowed, the GMRES tolerance being 1e-11 relative)."""
    class NoInverse(ComplianceOperator):
        has_circulant_inverse = False

    op = NoInverse(SMALL, rolling_small.kernel)
    s, _, _ = _profile(SMALL)
    dense = solve_normal(rolling_small, s, load=2.0)
    it = solve_normal(op, s, load=2.0, dense_limit=5)
    assert it.record.linear_solver == "gmres" and it.record.linear_iterations > 0
    np.testing.assert_array_equal(it.contact, dense.contact)
    np.testing.assert_allclose(it.force, dense.force, rtol=0, atol=1e-9 * dense.force.max())


def test_single_precision_profile_is_solved_in_double(rolling_small):
    """A float32 profile gives the float64 answer for the same (float32) values, under
    load and displacement control (float32 arithmetic in the right side would err by
    ~1e-8 relative)."""
    s, _, _ = _profile(SMALL)
    s32 = s.astype(np.float32)
    for kw in ({"load": 2.0}, {"indentation": 3e-5}):
        a = solve_normal(rolling_small, s32, **kw)
        b = solve_normal(rolling_small, s32.astype(float), **kw)
        np.testing.assert_array_equal(a.contact, b.contact)
        np.testing.assert_allclose(a.force, b.force, rtol=0, atol=1e-13 * b.force.max())
        assert a.indentation == pytest.approx(b.indentation, rel=1e-13)


# --------------------------------------------------------------------------------------
# Paths no layer reaches cheaply, forced in milliseconds: a hand-made compliance on one
# grid row of 9 nodes (a line: its two end nodes are the edge) whose neighbours pull each
# other down (C_ii = 1, C_i,i+1 = -2 m/N: not a layer's, which is positive definite) makes
# the active set empty and cycle; scipy's GMRES replaced by one that fails.

ROW = Grid(1e-3, 1e-3, 0.02, 0.02, 10, 10, 9, 1)


def _row_operator(neighbour=-2.0, far=0.0):
    kernel = np.zeros((1, 17))
    kernel[0, 8] = 1.0  # offset 0
    kernel[0, 7] = kernel[0, 9] = neighbour  # offsets -1, +1
    kernel[0, 6] = kernel[0, 10] = far  # offsets -2, +2
    return ComplianceOperator(ROW, kernel)


def _row_profile(**nodes):
    s = np.full((1, 9), np.inf)
    for k, v in nodes.items():
        s[0, int(k[1:])] = v
    return s


class _Spy:
    """NormalSystem recording each trial set (flat indices)."""

    sets: list = []

    def __init__(self, *args):
        self.__class__.sets.append(np.asarray(args[1]).tolist())
        self._s = NormalSystem(*args)

    def __getattr__(self, name):
        return getattr(self._s, name)


def test_emptied_set_restarts_at_the_deepest_node_then_cycles_one_node_at_a_time(monkeypatch):
    """d = 1 m, nodes 4 and 5 at s = 0 and 0.5 m: together their forces come out tensile
    (F = -2/3, -5/6 N), the set empties and restarts at node 4 (the deepest), where
    F_4 = 1 N pulls node 5 into penetration (h_5 = 0.5 - 1 - 2 = -2.5 m); {4, 5} again: a
    cycle; one-node updates add the deepest penetrating node (5), {4, 5} a third time:
    the cycle error, after 4 iterations."""
    import bem.contact as contact

    _Spy.sets = []
    monkeypatch.setattr(contact, "NormalSystem", _Spy)
    lines = []
    with pytest.raises(ContactNotConverged) as info:
        solve_normal(_row_operator(), _row_profile(n4=0.0, n5=0.5), indentation=1.0, progress=lines.append)
    assert str(info.value) == "the active set cycles after 4 iterations even with one-node updates"
    assert _Spy.sets == [[4, 5], [4], [4, 5], [4]]
    assert lines == ["active set 1: 2 nodes, d = 1.000000e+00 m, -2 +0",
                     "active set 2: 1 nodes, d = 1.000000e+00 m, -0 +1",
                     "active set 3: 2 nodes, d = 1.000000e+00 m, -2 +0",
                     "active set 4: 1 nodes, d = 1.000000e+00 m, -0 +1"]


def test_one_node_updates_drop_the_most_tensile_node_first(monkeypatch):
    """Three nodes 3, 4, 5 (s = 0, 0, 0.1 m, d = 1 m) with C_i,i+1 = -2, C_i,i+2 = 0.5:
    after the first cycle each step changes one node, the most tensile dropped first,
    else the deepest penetrating one added (recomputed here from the same rules)."""
    import bem.contact as contact

    op = _row_operator(far=0.5)
    s = _row_profile(n3=0.0, n4=0.0, n5=0.1)
    _Spy.sets = []
    monkeypatch.setattr(contact, "NormalSystem", _Spy)
    with pytest.raises(ContactNotConverged, match=r"^the active set cycles after \d+ iterations even with "
                                                  r"one-node updates$"):
        solve_normal(op, s, indentation=1.0)
    sets = _Spy.sets
    C = op.dense()
    flat = s.ravel()
    reach = np.isfinite(flat)
    # replay the rules: all at once until a set recurs, then one node at a time
    seen, careful, replay = set(), False, []
    active = reach & (flat < 1.0)
    for _ in range(len(sets)):
        idx = np.flatnonzero(active)
        replay.append(idx.tolist())
        F = np.zeros(9)
        F[idx] = np.linalg.solve(C[np.ix_(idx, idx)], 1.0 - flat[idx])
        h = np.where(reach, flat - 1.0 + C @ F, np.inf)
        drop, add = active & (F <= 0), ~active & (h < -1e-12)
        if careful:
            new = active.copy()
            if drop.any():
                new[np.argmin(np.where(drop, F, np.inf))] = False
            else:
                new[np.argmin(np.where(add, h, np.inf))] = True
        else:
            new = (active & ~drop) | add
        if not new.any():
            new[np.argmin(np.where(reach, flat, np.inf))] = True
        key = new.tobytes()
        if key in seen:
            careful = True
        seen.add(key)
        active = new
    assert sets == replay
    one_node = [(a, b) for a, b in zip(sets, sets[1:]) if len(set(a) ^ set(b)) == 1]
    assert any(len(b) < len(a) for a, b in one_node) and any(len(b) > len(a) for a, b in one_node)


def test_add_threshold_is_a_relative_penetration_of_1e_12():
    """d = 1e-4 m on node 4 (s = 0; C_ii = 1, C_i,i+2 = -1e-6 m/N, no other coupling):
    F_4 = d pulls node 2 (s = d) down by 1e-10 m = 1e-6 d, a penetration that joins the
    set; node 7 (s = d, uncoupled: h = 0) and node 1 (s = d + 1e-17 m: h = 1e-13 d) do not."""
    d = 1e-4
    op = _row_operator(neighbour=0.0, far=-1e-6)
    res = solve_normal(op, _row_profile(n4=0.0, n2=d, n7=d, n1=d + 1e-17, n6=d + 2e-10), indentation=d)
    F = res.force.ravel()
    assert F[4] == pytest.approx(d, rel=1e-11) and F[2] == pytest.approx(1e-6 * d, rel=1e-6)
    assert not F[[1, 6, 7]].any()
    assert res.record.history == (1, 2) and res.record.iterations == 2


def test_a_tiny_force_on_the_edge_node_is_contact_at_the_edge():
    """Node 0 (the row's end) penetrates by 1e-9 m and carries 1e-9 N: still contact at
    the edge, with the region in the message."""
    op = _row_operator(neighbour=0.0)
    with pytest.raises(ContactAtEdge) as info:
        solve_normal(op, _row_profile(n4=0.0, n0=1.0 - 1e-9), indentation=1.0)
    assert str(info.value) == ("the contact reaches the edge of the candidate region (|x| <= 0.004 m, "
                               "|y| <= 0 m): increase grid.half_width")


def test_gmres_that_fails_says_what_to_change(rolling_small, monkeypatch):
    """The flexible GMRES (as bem.linear calls it) replaced by one that reports failure
    after 7 iterations: the error names the set and what to change; the solver asks for
    the residual ``rtol |b|`` of the bordered system, with restart and maxiter 100 and 100
    and the circulant preconditioner, its Krylov vectors in double."""
    import bem.linear as linear

    calls = []

    def failing(matvec, b, precondition=None, *, tol, restart, maxiter, callback=None, inner=None,
                basis=np.float64):
        calls.append((tol / np.linalg.norm(b), restart, maxiter, precondition is not None, inner, np.dtype(basis)))
        return np.zeros_like(b), False, 7

    monkeypatch.setattr(linear, "fgmres", failing)
    s, _, _ = _profile(SMALL)
    with pytest.raises(ContactNotConverged) as info:
        solve_normal(rolling_small, s, load=20.0, dense_limit=0, rtol=1e-9)
    assert type(info.value) is ContactNotConverged
    m = int(str(info.value).split(" on ")[1].split()[0])
    assert str(info.value) == (f"GMRES did not reduce the residual by 1.0e-09 on {m} contact nodes in 7 "
                               "iterations; refine less, or raise dense_limit if memory allows")
    assert len(calls) == 1
    assert calls[0][0] == pytest.approx(1e-9, rel=1e-12) and calls[0][1:] == (100, 100, True, None, np.float64)
