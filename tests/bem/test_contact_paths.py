"""bem.contact.solve_normal on paths no layer reaches cheaply, forced in milliseconds.

A hand-made compliance on one grid row of 9 nodes (a line: its two end nodes are the
edge) whose neighbours pull each other down (C_ii = 1, C_i,i+1 = -2 m/N: not a layer's,
which is positive definite) makes the active set empty and cycle; the flexible GMRES
replaced by one that fails.
"""

import numpy as np
import pytest

from bem.contact import LOOSE_RTOL, ContactAtEdge, ContactNotConverged, NormalSystem, solve_normal
from bem.grid import Grid
from bem.indenters import Sphere
from bem.operator import ComplianceOperator


SMALL = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5e-3, 5e-3))  # 21 x 21

SPHERE = Sphere(0.02)


def _profile(grid):
    X, Y = grid.coordinates()
    return SPHERE.profile(X, Y), SPHERE.rolling_arm(X, Y), X


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
    after 7 iterations: the error names the set and what to change. The solver asks the
    first set (every reachable node: no coarse level below 625 nodes) for the residual
    ``LOOSE_RTOL |b|`` of the bordered system in one restart cycle (a loose first step),
    then, that failing (no dense fallback with ``dense_limit=0``), ``rtol |b|`` with restart
    and maxiter 100 and 100; the circulant preconditioner, its Krylov vectors in double."""
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
    assert len(calls) == 2 and m == SMALL.nodes_x * SMALL.nodes_y
    assert calls[0][0] == pytest.approx(LOOSE_RTOL, rel=1e-12) and calls[0][1:] == (100, 1, True, None, np.float64)
    assert calls[1][0] == pytest.approx(1e-9, rel=1e-12) and calls[1][1:] == (100, 100, True, None, np.float64)
