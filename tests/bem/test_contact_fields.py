"""bem.contact.solve_normal: the returned fields, record and messages recomputed from their
definitions.

Each solve's outputs are checked against quantities recomputed here from the returned
forces with the operator (``u = C F``, ``h = s - d + u``, the complementarity residual,
``R_r = sum F arm``, the pressure centroid), and the bordered linear system against its
stated matrix. Small grids (21 x 21, dense).
"""

import math

import numpy as np
import pytest

from bem.contact import ContactAtEdge, ContactNotConverged, NormalSystem, grid_summary, solve_normal
from bem.grid import Grid
from bem.indenters import Sphere
from bem.operator import ComplianceOperator
from bem.result import ROLLING_SCALARS, SHARED_SCALARS


SMALL = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5e-3, 5e-3))  # 21 x 21

SPHERE = Sphere(0.02)


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
    assert set(summary) == set(SHARED_SCALARS) | set(ROLLING_SCALARS) | {"grid", "solver"}
    assert all(summary[k] == getattr(r, k) for k in SHARED_SCALARS)
    # a solve on a prepared operator knows neither the speed nor the layer: no rolling figures
    assert all(math.isnan(summary[k]) and math.isnan(getattr(r, k)) for k in ROLLING_SCALARS)
    assert rec.times == {}
    assert summary["grid"] == grid_summary(SMALL) == {
        "nodes": [21, 21], "spacing": [0.5e-3, 0.5e-3], "period": [0.2, 0.2], "truncation": [200, 200]}
    assert summary["solver"] == {"iterations": rec.iterations, "residual": rec.residual,
                                 "history": list(rec.history), "linear_solver": "dense",
                                 "linear_iterations": 0}


def test_without_an_arm_the_rolling_resistance_is_nan(rolling_small):
    s, _, _ = _profile(SMALL)
    assert math.isnan(solve_normal(rolling_small, s, load=2.0).rolling_resistance)


def test_displacement_control_gives_the_load_controlled_contact(rolling_small):
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
def test_bad_loading_is_refused_with_the_rule(rolling_small, kw, message):
    s, _, _ = _profile(SMALL)
    with pytest.raises(ValueError, match=message):
        solve_normal(rolling_small, s, **kw)


def test_bad_profile_is_refused_with_the_rule(rolling_small):
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


def test_the_iteration_limit_is_exact(rolling_small):
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


def test_gmres_without_the_circulant_preconditioner_reaches_the_dense_solution(rolling_small):
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
