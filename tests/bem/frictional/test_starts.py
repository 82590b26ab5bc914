"""bem.frictional.starts: the start states against their definitions (frictionless, Carter's
saturation creepage, the coarse grid's sets and forces, prolongation), the continuation's
ladder of mu, its starts, history and messages (run_active_set replaced by a recorder).
"""

import math
import types

import numpy as np
import pytest

from bem.frictional import Friction
from bem.frictional import Friction, FrictionNotConverged


def _fake_setup():
    from bem.frictional.system import RollingSetup

    return RollingSetup(ops=None, profile=np.zeros(4), arm=np.zeros(4), ell=np.array([1.0, 1.0, 2.0, 0.5]),
                        radius=0.02, speed=1.0, mu=0.0, load=1.0, indentation=None, omega=None, constraint=None)


def test_frictionless_start_all_stick_without_omega():
    from bem.frictional.starts import frictionless_start

    N0 = np.array([0.0, 1.0, 2.0, -1.0, 3.0])
    st = frictionless_start(N0, np.ones(5), 1.0, Friction(0.3, "towed"))
    np.testing.assert_array_equal(st.contact, N0 > 0)
    np.testing.assert_array_equal(st.stick, N0 > 0)
    assert st.direction.shape == (5, 2) and not st.direction.any() and not st.slope.any()


def test_frictionless_start_slips_where_the_rigid_creep_exceeds_one_percent():
    """creep = V - Omega l; |creep| > 1e-2 V slips along (sign creep, 0) with
    k = |creep| / (mu N0); exactly 1 % sticks (V = 100 m/s: the tie is exact)."""
    from bem.frictional.starts import frictionless_start

    V_, om = 100.0, 1.0
    ell = np.array([99.0, 101.0, 97.0, 102.5, 100.0, 90.0])  # creep 1, -1, 3, -2.5, 0, 10
    N0 = np.array([1.0, 2.0, 4.0, 5.0, 3.0, 0.0])
    st = frictionless_start(N0, ell, V_, Friction(0.5, "omega", omega=om))
    np.testing.assert_array_equal(st.contact, [1, 1, 1, 1, 1, 0])
    np.testing.assert_array_equal(st.stick, [1, 1, 0, 0, 1, 0])
    np.testing.assert_array_equal(st.direction, [[0, 0], [0, 0], [1, 0], [-1, 0], [0, 0], [0, 0]])
    np.testing.assert_allclose(st.slope, [0, 0, 3.0 / (0.5 * 4.0), 2.5 / (0.5 * 5.0), 0, 0], rtol=1e-15)


def test_frictionless_start_sticks_below_the_saturation_creepage():
    """With ``saturation`` a node slips only where |creep| exceeds max(1 %, saturation) V."""
    from bem.frictional.starts import frictionless_start

    V_, om = 100.0, 1.0
    ell = np.array([99.0, 97.0, 97.0, 95.0, 104.0, 90.0])  # creep 1, 3, 3, 5, -4, 10
    N0 = np.array([1.0, 2.0, 4.0, 5.0, 3.0, 0.0])
    sat = np.array([0.0, 0.029, 0.03, 0.04, 0.05, 0.0])
    st = frictionless_start(N0, ell, V_, Friction(0.5, "omega", omega=om), sat)
    np.testing.assert_array_equal(st.stick, [1, 0, 1, 0, 1, 0])
    np.testing.assert_array_equal(st.direction, [[0, 0], [1, 0], [0, 0], [1, 0], [0, 0], [0, 0]])
    np.testing.assert_allclose(st.slope, [0, 3.0 / (0.5 * 2.0), 0, 5.0 / (0.5 * 5.0), 0, 0], rtol=1e-15)
    # a scalar saturation, and none below 1 %
    st = frictionless_start(N0, ell, V_, Friction(0.5, "omega", omega=om), 0.045)
    np.testing.assert_array_equal(st.stick, [1, 1, 1, 0, 1, 0])
    assert np.array_equal(frictionless_start(N0, ell, V_, Friction(0.5, "omega", omega=om), 0.001).stick,
                          frictionless_start(N0, ell, V_, Friction(0.5, "omega", omega=om)).stick)


def test_saturation_creepage_is_carters_mu_a_over_r_by_grid_row():
    from bem.frictional.starts import saturation_creepage

    contact = np.zeros((3, 5), bool)
    contact[0, 1:4] = True  # 3 nodes: a = 1.5 spacing
    contact[1, [0, 2]] = True  # 2 nodes (not contiguous): a = 1 spacing
    sat = saturation_creepage(contact.ravel(), (3, 5), 2e-4, 0.3, 0.02)
    want = 0.3 * np.array([3e-4, 2e-4, 0.0]) / 0.02
    np.testing.assert_allclose(sat.reshape(3, 5), np.repeat(want[:, None], 5, 1), rtol=1e-14)


def test_coarse_start_slips_where_any_coarse_neighbour_slips():
    """Fine node (j, i) reads the coarse nodes (floor or ceil of j/2, floor or ceil of i/2):
    one, two or four of them. It slips when it is in the fine contact and the sum ``S`` of
    the slipping ones' forces and the largest of their slip speeds ``|w|`` are > 0, along
    S/|S| with k = |w| / (mu N0); otherwise it sticks (in contact)."""
    from bem.frictional.starts import coarse_start

    rng = np.random.default_rng(8)
    cy, cx = 4, 5
    shape = (2 * cy - 1, 2 * cx - 1)
    cc = rng.random((cy, cx)) < 0.8
    cs = cc & (rng.random((cy, cx)) < 0.6)
    fx, fy = rng.normal(size=(cy, cx)), rng.normal(size=(cy, cx))
    wx, wy = rng.normal(size=(cy, cx)), rng.normal(size=(cy, cx))
    cc[0, 0] = cc[0, 1] = cc[1, 1] = True
    cs[0, 0] = cs[0, 1] = cs[1, 1] = False
    fx[0, 1] = fy[0, 1] = 0.0  # slipping with no force
    wx[1, 1] = wy[1, 1] = 0.0  # slipping at rest
    fx[0, 0], fy[0, 0] = 0.0, 0.0  # fine (0, 0) reads only coarse (0, 0): sticks
    res = types.SimpleNamespace(force_x=fx, force_y=fy, slip_x=wx, slip_y=wy, contact=cc, stick=cs)
    N0 = np.where(rng.random(shape) < 0.85, rng.uniform(0.5, 2.0, shape), 0.0).ravel()
    N0[0] = 1.0
    mu = 0.4
    st = coarse_start(res, shape, N0, mu)
    kinds = set()
    for j in range(shape[0]):
        for i in range(shape[1]):
            p = j * shape[1] + i
            near = {(a, b) for a in (j // 2, math.ceil(j / 2)) for b in (i // 2, math.ceil(i / 2))}
            slipping = [c for c in near if cc[c] and not cs[c]]
            S = sum((np.array([fx[c], fy[c]]) for c in slipping), np.zeros(2))
            w = max((math.hypot(wx[c], wy[c]) for c in slipping), default=0.0)
            slips = N0[p] > 0 and np.hypot(*S) > 0 and w > 0
            kinds.add((len(near), slips))
            assert st.contact[p] == (N0[p] > 0)
            assert st.stick[p] == (N0[p] > 0 and not slips), (j, i)
            if slips:
                np.testing.assert_allclose(st.direction[p], S / np.hypot(*S), rtol=1e-14)
                assert st.slope[p] == pytest.approx(w / (mu * N0[p]), rel=1e-15)
            else:
                assert not st.direction[p].any() and st.slope[p] == 0.0
    assert st.stick[0]
    # one, two and four neighbours, each both slipping and sticking
    assert {(1, True), (2, True), (4, True), (2, False), (4, False)} <= kinds
    assert (~st.stick & st.contact).sum() >= 5


@pytest.mark.parametrize("mu, ladder", [
    (1e-3, [0.256, 0.128, 0.064, 0.032, 0.016, 0.008, 0.004, 0.002, 0.001]),
    (0.03, [0.24, 0.12, 0.06, 0.03]),
    (0.15, [0.3, 0.15]),
    (0.2, [0.4, 0.2]),
    (0.7, [1.4, 0.7]),
])
def test_continuation_ladder_starts_and_history(monkeypatch, mu, ladder):
    """mu 2^K (K >= 1 the smallest with mu 2^K >= 0.2) halved down to mu; the first solve
    starts from the frictionless start, each next one from the previous sets; the setup
    and friction carry the ladder's mu; histories are concatenated; the progress line."""
    from bem.frictional import starts
    from bem.frictional.active_set import ActiveSetResult

    calls, progresses = [], []

    def fake(setup, friction, state, solves, progress, options=None):
        calls.append((setup.mu, friction.mu, friction.mode, state, solves))
        progresses.append(progress)
        marker = types.SimpleNamespace(mu=friction.mu)
        return ActiveSetResult(N=np.full(4, friction.mu), Sx=None, Sy=None, indentation=0.0, omega=0.0,
                               state=marker, history=[(len(calls), friction.mu)], gap=None, scale=1.0, fields=())

    monkeypatch.setattr(starts, "run_active_set", fake)
    N0 = np.array([1.0, 0.0, 2.0, 3.0])
    lines = []
    solves = object()
    out = starts.continuation(_fake_setup(), Friction(mu, "towed"), N0, solves, lines.append, RuntimeError("x"))
    assert [c[0] for c in calls] == pytest.approx(ladder, rel=1e-12)
    assert [c[1] for c in calls] == pytest.approx(ladder, rel=1e-12)
    assert all(c[2] == "towed" and c[4] is solves for c in calls)
    first = calls[0][3]
    ref = starts.frictionless_start(N0, _fake_setup().ell, 1.0, Friction(mu, "towed"))
    np.testing.assert_array_equal(first.contact, ref.contact)
    np.testing.assert_array_equal(first.stick, ref.stick)
    for prev, (_, _, _, state, _) in zip(calls, calls[1:]):
        assert state.mu == prev[1]
    assert out.history == [(i + 1, m) for i, m in enumerate(c[1] for c in calls)]
    assert out.N[0] == calls[-1][1] and out.state.mu == calls[-1][1]
    assert lines == [f"friction: direct solve failed (x); continuation in mu from {ladder[0]:.4g}"]
    assert progresses == [lines.append] * len(ladder)  # each rung reports its iterations
    starts.continuation(_fake_setup(), Friction(mu, "towed"), N0, solves, None, RuntimeError("x"))  # quiet


def test_continuation_starts_at_its_option_and_passes_the_options_to_each_solve(monkeypatch):
    """With ``continuation_mu`` 0.5 the ladder from mu = 0.1 is 0.8, 0.4, 0.2, 0.1 (the
    smallest mu 2^K >= 0.5, K >= 1), and every rung's active set gets the options given;
    without options, the defaults."""
    from bem.frictional import SolverOptions, starts
    from bem.frictional.active_set import ActiveSetResult

    seen = []

    def fake(setup, friction, state, solves, progress, options=None):
        seen.append((friction.mu, options))
        return ActiveSetResult(N=np.zeros(4), Sx=None, Sy=None, indentation=0.0, omega=0.0, state=state,
                               history=[], gap=None, scale=1.0, fields=())

    monkeypatch.setattr(starts, "run_active_set", fake)
    N0 = np.array([1.0, 0.0, 2.0, 3.0])
    options = SolverOptions(continuation_mu=0.5)
    starts.continuation(_fake_setup(), Friction(0.1, "towed"), N0, object(), None, RuntimeError("x"), options)
    assert [m for m, _ in seen] == pytest.approx([0.8, 0.4, 0.2, 0.1], rel=1e-12)
    assert all(o is options for _, o in seen)
    seen.clear()
    starts.continuation(_fake_setup(), Friction(0.1, "towed"), N0, object(), None, RuntimeError("x"))
    assert [m for m, _ in seen] == pytest.approx([0.2, 0.1], rel=1e-12)
    assert all(o == SolverOptions() for _, o in seen)


def test_continuation_failure_names_where_it_stopped(monkeypatch):
    from bem.frictional import starts
    from bem.frictional.active_set import ActiveSetResult

    def fake(setup, friction, state, solves, progress, options=None):
        if friction.mu < 0.1:
            raise FrictionNotConverged("cycled")
        return ActiveSetResult(N=None, Sx=None, Sy=None, indentation=0.0, omega=0.0, state=state,
                               history=[], gap=None, scale=1.0, fields=())

    monkeypatch.setattr(starts, "run_active_set", fake)
    with pytest.raises(FrictionNotConverged) as info:
        starts.continuation(_fake_setup(), Friction(0.03, "torque"), np.ones(4), None, None, RuntimeError("boom"))
    assert str(info.value) == (
        "mode 'torque', mu = 0.03: the direct solve failed (boom) and the continuation in mu stopped at "
        "mu = 0.06 (cycled); try mode 'omega' with a prescribed Omega, or a finer grid")
    assert isinstance(info.value.__cause__, FrictionNotConverged)


def test_prolonged_is_exact_on_bilinear_fields_and_coarse_forces_scale_by_the_node_area():
    """:func:`bem.coarse_levels.prolonged` reproduces ``a + b x + c y + e x y`` sampled on
    every other node at every node of the fine grid (the mean of two neighbours is exact
    along an edge, of four at a cell's centre); :func:`coarse_forces` hands on the fine
    frictionless forces, a quarter of the prolonged coarse tangential forces on their
    contact (a fine node's area is a quarter of a coarse node's) and nothing off it, the
    fine indentation plus what friction added on the coarse grid, and the coarse Omega."""
    from types import SimpleNamespace

    from bem.coarse_levels import prolonged
    from bem.frictional.starts import coarse_forces

    Ky, Kx = 9, 13
    y, x = np.mgrid[0:Ky, 0:Kx].astype(float)
    f = 0.3 + 1.7 * x - 0.4 * y + 0.05 * x * y
    np.testing.assert_allclose(prolonged(f[::2, ::2], (Ky, Kx)), f, rtol=0, atol=1e-13)
    rng = np.random.default_rng(3)
    N0 = np.where(rng.random(Ky * Kx) < 0.6, rng.uniform(0.1, 1.0, Ky * Kx), 0.0)
    coarse = SimpleNamespace(force_x=np.full((5, 7), 0.8), force_y=f[::2, ::2], indentation=2.5e-4, omega=3.1)
    below = SimpleNamespace(indentation=2.0e-4)
    N, Sx, Sy, d, om = coarse_forces(coarse, (Ky, Kx), N0, 1.1e-4, below)
    assert N is N0 and om == 3.1 and d == pytest.approx(1.1e-4 + 0.5e-4, rel=1e-12)
    np.testing.assert_allclose(Sx, np.where(N0 > 0, 0.2, 0.0), rtol=1e-14)
    np.testing.assert_allclose(Sy, np.where(N0 > 0, f.ravel() / 4, 0.0), rtol=0, atol=1e-13)
    assert coarse_forces(coarse, (Ky, Kx), N0, 1.1e-4)[3] == 1.1e-4  # no coarse frictionless solution


def test_nodes_within_finds_the_grid_error_levels_on_the_case_grid_and_nothing_else():
    """The levels coarsened by 2 and 4 (``coarsened_grid``) sit on every second node and on
    every fourth from the third (61 nodes at 0.2 mm: 31 at 0.4 mm, 15 at 0.8 mm from
    -5.6 mm); an even count at twice the spacing sits between the axis's neighbours. A
    spacing 1.5 times the case's, or a region wider than the case's, has nodes off it."""
    from bem import Grid
    from bem.frictional.grid_error import coarsened_grid
    from bem.frictional.starts import nodes_within

    fine = Grid.centred((0.2e-3, 0.2e-3), (0.6, 0.6), (1500, 1500), (6e-3, 6e-3))
    rows, cols = nodes_within(fine, coarsened_grid(fine, 2))
    np.testing.assert_array_equal(cols.ravel(), np.arange(0, 61, 2))
    np.testing.assert_array_equal(rows.ravel(), np.arange(0, 61, 2))
    rows, cols = nodes_within(fine, coarsened_grid(fine, 4))
    np.testing.assert_array_equal(cols.ravel(), np.arange(2, 59, 4))
    X, Y = fine.coordinates()
    Xc, Yc = coarsened_grid(fine, 4).coordinates()
    np.testing.assert_allclose(X[rows, cols], Xc, rtol=0, atol=1e-15)
    np.testing.assert_allclose(Y[rows, cols], Yc, rtol=0, atol=1e-15)
    assert nodes_within(fine, fine) is not None
    even = Grid(0.4e-3, 0.4e-3, 0.6, 0.6, 750, 750, 30, 31)
    np.testing.assert_array_equal(nodes_within(fine, even)[1].ravel(), np.arange(1, 60, 2))
    assert nodes_within(fine, Grid.centred((0.3e-3, 0.4e-3), (0.6, 0.6), (1000, 750), (6e-3, 6e-3))) is None
    assert nodes_within(fine, Grid(0.4e-3, 0.4e-3, 0.6, 0.6, 750, 750, 32, 31)) is None  # wider than the case
    assert nodes_within(coarsened_grid(fine, 2), fine) is None  # finer than the solved grid
