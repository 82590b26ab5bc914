"""bem.frictional.loading: each loading mode's equilibrium row against its definition, and
the reachability check at its limits (exact arithmetic on small vectors, milliseconds)."""

import os

import numpy as np
import pytest

from bem.friction import LoadingUnreachable
from bem.frictional import toeplitz
from bem.frictional.loading import check_reachable, constraint

RNG = np.random.default_rng(7)
ARM, ELL = RNG.normal(size=6) * 0.1, RNG.normal(size=6) * 1e-3
N, SX = RNG.uniform(0.1, 2.0, size=6), RNG.normal(size=6) * 0.3
R = 0.02


@pytest.mark.parametrize("mode, row", [
    # pushed at the top: Q R + sum l S_x = 0 with the horizontal force Q = sum N arm + sum S_x
    ("pushed_at_top", lambda: (N @ ARM + SX.sum()) * R + ELL @ SX),
    # towed at the axle: no torque, T = -sum l S_x = 0
    ("towed", lambda: ELL @ SX),
    # driven by a torque: no horizontal force, Q = sum N arm + sum S_x = 0
    ("torque", lambda: N @ ARM + SX.sum()),
])
def test_each_mode_row_is_its_equilibrium(mode, row):
    cN, cx = constraint(mode, ARM, ELL, R)
    assert cN.shape == cx.shape == ARM.shape
    assert cN @ N + cx @ SX == pytest.approx(row(), rel=1e-14, abs=1e-18)


def test_omega_mode_has_no_row():
    assert constraint("omega", ARM, ELL, R) is None


def test_reachability_at_its_limit():
    """Full slip can give mu sum |c_x| N0 against the |c_N . N0| the mode needs: equal is
    enough, a hair less raises with the numbers; towed and omega are always reachable."""
    N0 = np.array([1.0, 2.0, 3.0])
    cons = (np.array([0.5, 0.25, 0.0]), np.array([1.0, -1.0, 2.0]))  # need 1.0, sum |c_x| N0 = 9
    check_reachable("torque", 1.0 / 9.0, cons, N0)  # can = need exactly
    with pytest.raises(LoadingUnreachable, match=(
            r"^mode 'torque' needs tangential forces beyond the friction limit: mu = 0\.11 can give a "
            r"moment/force of 0\.99, the rolling resistance asks for 1 \(in units of N\); raise mu or use "
            r"mode 'towed' or 'omega'$")):
        check_reachable("torque", 0.11, cons, N0)
    with pytest.raises(LoadingUnreachable, match=r"asks for 1 \(in units of N m\); raise mu"):
        check_reachable("pushed_at_top", 0.11, (-cons[0], cons[1]), N0)  # |need| whatever its sign
    check_reachable("towed", 0.0, cons, N0)
    check_reachable("omega", 0.0, None, N0)


# --------------------------------------------------------------------------------------
# bem.frictional.operators: every block and product against a dense matrix assembled
# column by column from ComplianceOperator's FFT product of unit forces (a different
# algorithm from the direct table reads and the batched one-axis-at-a-time transforms),
# on random, nonsymmetric kernel tables of a small grid with K_x != K_y and a_x != a_y.

import math  # noqa: E402
import types  # noqa: E402

from bem.grid import Grid  # noqa: E402
from bem.kinematics import upwind_table  # noqa: E402
from bem.operator import ComplianceOperator  # noqa: E402
from bem.spectral import BLOCKS  # noqa: E402

SMALL = Grid(1.0e-3, 2.0e-3, 0.02, 0.04, 10, 10, 7, 5)  # 7 x 5 nodes


def _random_kernels(grid, seed=3):
    rng = np.random.default_rng(seed)
    Ky, Kx = grid.shape
    return {b: rng.normal(size=(2 * Ky - 1, 2 * Kx - 1)) * 10.0**-(i % 3) for i, b in enumerate(BLOCKS)}


def _dense_of(grid, table):
    """The matrix of the convolution with ``table``: column q is the FFT product of the
    unit force on node q."""
    n = grid.nodes_x * grid.nodes_y
    op = ComplianceOperator(grid, table)
    M = np.empty((n, n))
    for q in range(n):
        e = np.zeros(n)
        e[q] = 1.0
        M[:, q] = op.apply(e.reshape(grid.shape)).ravel()
    return M


def _close(got, want, rel=1e-13):
    """Equal to FFT round-off: ``rel`` of the largest entry (measured a few 1e-15)."""
    want = np.asarray(want)
    np.testing.assert_allclose(got, want, rtol=0, atol=rel * np.abs(want).max())


def test_operator_tables_and_dense_blocks_against_fft_products():
    """``ops.dense(name)`` between any nodes is the FFT product's matrix; the ``d`` blocks
    are the upwind x-differences ``(K(dx + 1) - K(dx)) / a_x`` of the ``u, v`` rows (a_x,
    not a_y), ``ww, wu, wv`` are read undifferenced; ``diagonal`` is ``C_ww`` of a node on
    itself; ``op`` serves kernels and differenced tables alike, built once."""
    from bem.frictional.operators import DIFFERENCED, RollingOperators

    kern = _random_kernels(SMALL)
    ops = RollingOperators(SMALL, kern)
    n = SMALL.nodes_x * SMALL.nodes_y
    rng = np.random.default_rng(5)
    rows, cols = rng.choice(n, 11, replace=False), rng.choice(n, 9, replace=False)
    everything = np.arange(n)
    assert set(ops.tables) == {"ww", "wu", "wv"} | {"d" + b for b in DIFFERENCED}
    for name, table in ([(b, kern[b]) for b in ("ww", "wu", "wv")]
                        + [("d" + b, upwind_table(kern[b], SMALL.spacing_x)) for b in DIFFERENCED]):
        M = _dense_of(SMALL, table)
        _close(ops.dense(name, everything, everything), M)
        _close(ops.dense(name, rows, cols), M[np.ix_(rows, cols)])
        # rows on one grid row and columns on one (the same or another): the one-row read
        Kx = SMALL.nodes_x
        for jr, jc in ((2, 2), (1, 3)):
            r, c = jr * Kx + rng.choice(Kx, 5, replace=False), jc * Kx + rng.choice(Kx, 4, replace=False)
            _close(ops.dense(name, r, c), M[np.ix_(r, c)])
            # one side on one grid row, the other on several: the general read
            _close(ops.dense(name, r, cols), M[np.ix_(r, cols)])
            _close(ops.dense(name, rows, c), M[np.ix_(rows, c)])
        assert ops.dense(name, rows[:0], cols).shape == (0, cols.size)
        F = rng.normal(size=SMALL.shape)
        _close(ops.op(name).apply(F).ravel(), M @ F.ravel())
    for b in BLOCKS:  # raw kernels through op() as well
        F = rng.normal(size=SMALL.shape)
        _close(ops.op(b).apply(F).ravel(), _dense_of(SMALL, kern[b]) @ F.ravel())
    assert ops.op("duu") is ops.op("duu") and ops.op("uu") is not ops.op("duu")
    # the upwind difference written out on the grid: (u_{i+1} - u_i) / a_x of u = C_uu F
    F = rng.normal(size=SMALL.shape)
    u = (_dense_of(SMALL, kern["uu"]) @ F.ravel()).reshape(SMALL.shape)
    du = (ops.dense("duu", everything, everything) @ F.ravel()).reshape(SMALL.shape)
    np.testing.assert_allclose(du[:, :-1], (u[:, 1:] - u[:, :-1]) / SMALL.spacing_x, rtol=0,
                               atol=1e-9 * np.abs(du).max())
    q = 17
    assert ops.diagonal == pytest.approx(_dense_of(SMALL, kern["ww"])[q, q], rel=1e-14)
    assert ops.diagonal == kern["ww"][SMALL.nodes_y - 1, SMALL.nodes_x - 1]  # offset (0, 0)
    assert isinstance(ops.diagonal, float)


@pytest.mark.parametrize("shape_in", ["grid", "flat"])
def test_fields_and_displacements_are_the_signed_block_sums(shape_in):
    """eq. 51 with F_W = -N: delta = C_ww N - C_wu S_x - C_wv S_y,
    u = -C_uw N + C_uu S_x + C_uv S_y, v = -C_vw N + C_vu S_x + C_vv S_y, and the strains
    du/dx, dv/dx their upwind differences; computed twice (cached spectra) with new forces."""
    from bem.frictional.operators import RollingOperators

    kern = _random_kernels(SMALL, seed=4)
    ops = RollingOperators(SMALL, kern)
    ax = SMALL.spacing_x
    M = {b: _dense_of(SMALL, kern[b]) for b in BLOCKS}
    D = {b: _dense_of(SMALL, upwind_table(kern[b], ax)) for b in ("uw", "uu", "uv", "vw", "vu", "vv")}
    rng = np.random.default_rng(9)
    for _ in range(2):
        N, Sx, Sy = (rng.normal(size=SMALL.shape) for _ in range(3))
        args = (N, Sx, Sy) if shape_in == "grid" else (N.ravel(), Sx.ravel(), Sy.ravel())
        n, x, y = N.ravel(), Sx.ravel(), Sy.ravel()
        fields = ops.fields(*args)
        disp = ops.displacements(*args)
        assert fields.shape == (3,) + SMALL.shape and disp.shape == (2,) + SMALL.shape
        expect = [M["ww"] @ n - M["wu"] @ x - M["wv"] @ y,
                  -D["uw"] @ n + D["uu"] @ x + D["uv"] @ y,
                  -D["vw"] @ n + D["vu"] @ x + D["vv"] @ y]
        for got, want in zip(fields, expect):
            _close(got.ravel(), want)
        expect = [-M["uw"] @ n + M["uu"] @ x + M["uv"] @ y, -M["vw"] @ n + M["vu"] @ x + M["vv"] @ y]
        for got, want in zip(disp, expect):
            _close(got.ravel(), want)
    # on a node subset: the forces there (0 elsewhere), the fields read there
    nodes = rng.choice(SMALL.nodes_x * SMALL.nodes_y, 13, replace=False)
    forces = rng.normal(size=(3, 13))
    N, Sx, Sy = (np.zeros(SMALL.nodes_x * SMALL.nodes_y) for _ in range(3))
    N[nodes], Sx[nodes], Sy[nodes] = forces
    want = ops.fields(N, Sx, Sy).reshape(3, -1)[:, nodes]
    _close(ops.fields_on(nodes, forces), want)
    # on every core or on one (THREADED_FROM): the same numbers, bit for bit
    from bem import operator as op_module

    kept, got = op_module.THREADED_FROM, []
    try:
        for threshold, workers in ((0, -1), (10**12, 1)):
            op_module.THREADED_FROM = threshold
            assert ops._workers() == workers
            got.append(ops.fields_on(nodes, forces))
    finally:
        op_module.THREADED_FROM = kept
    np.testing.assert_array_equal(got[0], got[1])
    # increasing nodes (a system's contact) take the boolean-mask scatter: the same product
    order = np.argsort(nodes)
    assert ops._placed(nodes)[1] is None and ops._placed(nodes[order])[1] is not None
    _close(ops.fields_on(nodes[order], forces[:, order]), want[:, order])
    # in single precision: within its rounding (measured 1e-7 of the largest), not exact
    single = ops.fields_on(nodes, forces, np.float32)
    assert single.dtype == np.float32
    err = np.abs(single - want).max() / np.abs(want).max()
    assert 1e-12 < err < 1e-6, err


@pytest.mark.parametrize("box, at", [((3, 4), (1, 2)), ((1, 7), (4, 0)), ((5, 1), (0, 6)), ((2, 2), (0, 0))])
def test_a_window_is_the_whole_grid_s_product_inside_a_box(box, at):
    """fields and displacements of forces inside a box (shape ``box``, corner ``at``),
    read inside it, equal the whole grid's; the window is kept per shape, the whole
    grid's shape is the operators themselves, and a box larger than the grid is an error."""
    from bem.frictional.operators import RollingOperators

    kern = _random_kernels(SMALL, seed=12)
    ops = RollingOperators(SMALL, kern)
    w = ops.window(box)
    assert w.grid.shape == box and w.grid.spacing_x == SMALL.spacing_x and ops.window(box) is w
    rng = np.random.default_rng(13)
    N, Sx, Sy = (np.zeros(SMALL.shape) for _ in range(3))
    inside = (slice(at[0], at[0] + box[0]), slice(at[1], at[1] + box[1]))
    for f in (N, Sx, Sy):
        f[inside] = rng.normal(size=box)
    full, part = ops.fields(N, Sx, Sy), w.fields(N[inside], Sx[inside], Sy[inside])
    _close(part, full[(slice(None),) + inside])
    _close(w.displacements(N[inside], Sx[inside], Sy[inside]), ops.displacements(N, Sx, Sy)[(slice(None),) + inside])
    assert w.diagonal == ops.diagonal
    assert ops.window(SMALL.shape) is ops
    for bad in ((0, 3), (3, SMALL.nodes_x + 1)):  # SMALL: 5 x 7
        with pytest.raises(ValueError, match=r"^a window of \(.*\) nodes must fit in the grid's \(5, 7\)$"):
            ops.window(bad)


def test_window_around_widens_to_the_same_transform_and_shares_it():
    """The box around a node set: each side widened to ``(E + 1) // 2`` nodes for the
    transform length ``E`` of the tight side (never a longer transform), moved back inside
    the grid at its far edge, the whole grid's side where that is shorter; node sets whose
    tight boxes differ by a node share one window; the products on it, placed by the
    returned corner, are the whole grid's at the nodes."""
    import scipy.fft as sfft

    from bem.frictional.operators import RollingOperators

    grid = Grid(1.0e-3, 1.0e-3, 0.06, 0.06, 60, 60, 41, 33)  # 41 x 33 nodes
    ops = RollingOperators(grid, _random_kernels(grid, seed=21))
    Ky, Kx = grid.shape

    def widened(n, K):
        return min(K, (sfft.next_fast_len(2 * n - 1, real=True) + 1) // 2)

    rng = np.random.default_rng(22)
    for (j0, j1), (i0, i1) in (((3, 12), (5, 17)), ((20, 32), (30, 40)), ((0, 32), (0, 40)), ((7, 7), (9, 9))):
        rows, cols = np.array([j0, j1, (j0 + j1) // 2]), np.array([i1, i0, (i0 + i1) // 2])
        w, b0, a0 = ops.window_around(rows, cols)
        By, Bx = widened(j1 - j0 + 1, Ky), widened(i1 - i0 + 1, Kx)
        assert w.grid.shape == (By, Bx) and w is ops.window((By, Bx))
        assert 0 <= b0 <= j0 and j1 < b0 + By <= Ky and 0 <= a0 <= i0 and i1 < a0 + Bx <= Kx
        assert b0 == min(j0, Ky - By) and a0 == min(i0, Kx - Bx)
        tight = ops.window((j1 - j0 + 1, i1 - i0 + 1))
        assert all(e <= t for e, t in zip(w.op("ww").embedding, tight.op("ww").embedding))
        nodes = np.unique(rng.integers(j0, j1 + 1, 20) * Kx + rng.integers(i0, i1 + 1, 20))
        forces = rng.normal(size=(3, nodes.size))
        jn, in_ = np.divmod(nodes, Kx)
        got = w.fields_on((jn - b0) * Bx + (in_ - a0), forces)
        full = [np.zeros(Ky * Kx) for _ in range(3)]
        for f, vals in zip(full, forces):
            f[nodes] = vals
        want = ops.fields(*(f.reshape(Ky, Kx) for f in full)).reshape(3, -1)[:, nodes]
        _close(got, want)
    # tight sides of 11 and 12 nodes both take a transform of 24: one window of 12 x 12
    assert widened(11, Ky) == widened(12, Ky) == 12
    w12 = ops.window_around(np.array([3, 14]), np.array([5, 16]))[0]
    assert w12.grid.shape == (12, 12) and ops.window_around(np.array([4, 14]), np.array([5, 15]))[0] is w12
    # the whole grid when the widened sides reach it
    w, b0, a0 = ops.window_around(np.array([0, Ky - 1]), np.array([0, Kx - 1]))
    assert w is ops and (b0, a0) == (0, 0)


def test_coarse_operators_are_every_other_node():
    """The coarse level (bem.contact.coarse_grid, 25 x 25 -> 13 x 13) reads the kernels at
    even offsets: its dense blocks between coarse nodes are the fine ones between the
    same nodes, and its differences are over 2 a_x."""
    from bem.contact import coarse_grid
    from bem.frictional.operators import RollingOperators

    fine = Grid(0.5e-3, 0.5e-3, 0.1, 0.1, 100, 100, 25, 25)
    kern = _random_kernels(fine, seed=6)
    ops = RollingOperators(fine, kern)
    cg = coarse_grid(fine)
    co = ops.coarse(cg)
    assert co.grid is cg and co.grid.shape == (13, 13)
    nodes = np.arange(13 * 13)
    j, i = np.divmod(nodes, 13)
    under = 2 * j * 25 + 2 * i  # the fine node under each coarse node
    for b in ("ww", "wu", "wv"):
        np.testing.assert_array_equal(co.dense(b, nodes, nodes), ops.dense(b, under, under))
    # the coarse differences: (K(dx + 2) - K(dx)) / (2 a_x) read on the fine table, for
    # coarse offsets below K_x - 1 (the last column repeats its neighbour)
    uu = kern["uu"]
    dj, di = j[:, None] - j[None, :], i[:, None] - i[None, :]
    ok = di < 12
    want = (uu[2 * dj[ok] + 24, 2 * di[ok] + 26] - uu[2 * dj[ok] + 24, 2 * di[ok] + 24]) / (2 * 0.5e-3)
    np.testing.assert_allclose(co.dense("duu", nodes, nodes)[ok], want, rtol=1e-13, atol=0)
    assert co.diagonal == kern["ww"][24, 24]


# --------------------------------------------------------------------------------------
# bem.frictional.preconditioner: the result is the exact inverse of its own run blocks
# (the system's dense matrix restricted to one run of contact nodes along a grid row,
# without the normal-tangential coupling blocks, keeping the slip rows' -mu N), whatever
# the layout; its Toeplitz pieces against numpy's dense inverses.

from bem import Layer, Sphere, ThreeParameterSolid  # noqa: E402

LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (5.5e-3, 5.5e-3))  # 23 x 23


@pytest.fixture(scope="module")
def kernels():
    from bem import influence_kernels

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


def _runs(system):
    """Each contact node's run: its grid row, split where a node's right-hand neighbour is
    out of contact."""
    return np.cumsum(np.r_[True, (np.diff(system.Cj) != 0) | (np.diff(system.Ci) != 1)])


def _line_blocks(system):
    """The system's dense matrix (force unknowns) with every entry between different runs,
    the gap rows' S_x, S_y columns and the x, y rows' N columns set to 0, except the slip
    nodes' own -mu diag N in their magnitude rows."""
    nC = system.nC
    A = system.dense()[:3 * nC, :3 * nC].copy()
    line = np.tile(_runs(system), 3)
    A[line[:, None] != line[None, :]] = 0.0
    keep = np.zeros(nC, bool)
    keep[system.B] = True
    coup = np.diag(A[nC:2 * nC, :nC]).copy()
    A[:nC, nC:] = 0.0
    A[nC:, :nC] = 0.0
    A[nC + np.arange(nC), np.arange(nC)] = np.where(keep, coup, 0.0)
    np.testing.assert_allclose(coup[keep], -0.3 * system.diag, rtol=1e-14)
    return A


def _slip_runs(system):
    return np.unique(_runs(system)[system.B]).size


def _slip_columns(system):
    """The distinct (run length, place in the run) of the slip nodes: the Toeplitz inverse
    columns the line preconditioner needs (one per pair, whichever runs ask)."""
    r = _runs(system)
    lens = np.bincount(r)
    starts = np.r_[0, np.flatnonzero(np.diff(r)) + 1]
    place = np.arange(r.size) - starts[r - 1]
    return set(zip(lens[r][system.B].tolist(), place[system.B].tolist()))


def _toeplitz(t, n):
    """``T_n[i, j] = t[M - 1 + i - j]`` for ``t`` of ``2 M - 1`` values."""
    c = (t.size - 1) // 2
    i = np.arange(n)
    return t[c + i[:, None] - i[None, :]]


def test_levinson_gives_the_first_and_last_columns_for_every_length(kernels):
    """The columns of ``T_n^{-1}`` for ``n = 1 ... M`` against numpy's inverse, for a
    random nonsymmetric Toeplitz matrix (diagonally dominant) and the grid row of each
    of the layer's three blocks (``C_ww`` and the upwind-differenced ``C_uu``, ``C_vv``;
    nonsymmetric in a moving frame): measured 1e-15 relative, 1e-12 allowed; a singular
    leading block is an error naming its size."""
    from bem.frictional import RollingOperators
    from bem.frictional.toeplitz import levinson

    ops = RollingOperators(GRID, kernels)
    Ky, Kx = GRID.shape
    M = 12
    rng = np.random.default_rng(3)
    rows = [rng.normal(size=2 * M - 1) + 8.0 * (np.arange(2 * M - 1) == M - 1)]
    rows += [ops.tables[b][Ky - 1, Kx - M:Kx - 1 + M] for b in ("ww", "duu", "dvv")]
    for t in rows:
        assert not np.allclose(t, t[::-1])  # nonsymmetric
        first, last = levinson(t, M)
        assert first.shape == last.shape == (M, M)
        for n in range(1, M + 1):
            ref = np.linalg.inv(_toeplitz(t, n))
            scale = np.abs(ref).max()
            assert np.abs(first[n - 1, :n] - ref[:, 0]).max() < 1e-12 * scale
            assert np.abs(last[n - 1, :n] - ref[:, -1]).max() < 1e-12 * scale
            assert not first[n - 1, n:].any() and not last[n - 1, n:].any()
    # all four in one recursion: the same columns, to rounding
    both = levinson(np.stack(rows), M)
    assert both[0].shape == both[1].shape == (len(rows), M, M)
    for k, t in enumerate(rows):
        for got, want in zip(both, levinson(t, M)):
            assert np.abs(got[k] - want).max() <= 1e-14 * np.abs(want).max()
    t = np.ones(2 * M - 1)  # every leading block of size 2 or more is singular
    with pytest.raises(np.linalg.LinAlgError, match=r"^Levinson's recursion: the leading 2 x 2 block is singular$"):
        levinson(t, M)
    with pytest.raises(np.linalg.LinAlgError) as info:  # in a batch: which system
        levinson(np.stack([rows[0], t, t]), M)
    assert info.value.system == 1
    with pytest.raises(np.linalg.LinAlgError, match=r"^Levinson's recursion: zero diagonal$"):
        levinson(np.r_[np.ones(M - 1), 0.0, np.ones(M - 1)], M)


@pytest.mark.parametrize("M", [16, 13])
@pytest.mark.parametrize("dense", [False, True])
@pytest.mark.parametrize("threads", [False, True])
def test_row_inverses_solve_the_runs_toeplitz_systems(kernels, threads, dense, M):
    """:class:`RowInverses` on the layer's grid, by transforms or by the inverses
    themselves: for runs of 1 to ``M`` nodes, batched with others of different lengths and
    zero beyond their own, ``solve`` equals numpy's solve with the run's Toeplitz block
    (``C_ww``, ``a_x`` times the differenced ``C_uu``, ``C_vv``) to 1e-12 (measured 1e-15),
    ``columns`` gives the inverse's columns, and the dense inverses are numpy's, built
    for the lengths asked for only; the transform is at least ``2 M - 1`` long (no wrap),
    and two threads give the same bits as one; an odd transform length (``M = 13``: 25) as
    an even one; the dense inverses batched (padded to ``M x M``) or grouped by length."""
    from bem.frictional import RollingOperators
    from bem.frictional.toeplitz import DENSE_UPTO, GroupedRuns, RowInverses

    ops = RollingOperators(GRID, kernels)
    Ky, Kx = GRID.shape
    inv = RowInverses(ops, M, dense=dense)
    assert inv.M == M and inv.F == {16: 32, 13: 25}[M] and inv.dense == dense
    if dense:  # the transforms' spectra are not built: the inverses are applied themselves
        assert inv.spectra is None and inv.units is None
    else:
        assert inv.spectra.shape == (3, 4, M, inv.F // 2 + 1) and inv.units.shape == (M, inv.F // 2 + 1)
    assert RowInverses(ops, 99).M == Kx  # no run is longer than a grid row
    assert RowInverses(ops, 16).dense == (16 <= DENSE_UPTO)
    with pytest.MonkeyPatch.context() as m:  # dense up to DENSE_UPTO nodes inclusive
        m.setattr(toeplitz, "DENSE_UPTO", M)
        assert RowInverses(ops, M).dense and not RowInverses(ops, M + 1).dense
    with pytest.raises(ValueError, match=rf"^a run of {M + 1} nodes: the inverses are for 1 to {M}$"):
        inv.inverse(M + 1)
    lens = np.array([1, 2, 7, M, 9, M])
    pos = np.array([[0, 0], [1, 0], [6, 2], [M - 1, 3], [4, 8], [0, 9]])
    rng = np.random.default_rng(8)
    v = rng.normal(size=(lens.size, M)) * (np.arange(M) < lens[:, None])
    if dense:
        assert sorted(inv._inverses) == []  # none built before asked for
    for b, (name, scale) in enumerate((("ww", 1.0), ("duu", GRID.spacing_x), ("dvv", GRID.spacing_x))):
        t = scale * ops.tables[name][Ky - 1, Kx - M:Kx - 1 + M]
        got = inv.solve(inv.operand(b, lens, np.float64), v, threads=threads)
        if dense:
            assert sorted(inv._inverses) == sorted(set(lens))  # the lengths present only
            with pytest.MonkeyPatch.context() as m:  # grouped by length: the same values
                m.setattr(toeplitz, "BATCHED_UPTO", M - 1)
                grouped = GroupedRuns(inv, (b,), lens, np.float64)
                assert grouped.stack is None and len(grouped.groups) == len(set(lens))
                other = inv.solve(grouped, v, threads=threads)
                np.testing.assert_array_equal(other, inv.solve(grouped, v))
            assert np.abs(other - got).max() < 1e-13 * np.abs(got).max()
            # both blocks of the tangential rows in one operand: each block's rows as alone
            two = inv.solve(inv.operand((b, 2), lens, np.float64), np.concatenate([v, v]), threads=threads)
            assert np.abs(two[:lens.size] - got).max() < 1e-13 * np.abs(got).max()
        cols = inv.columns(b, lens, pos, np.float64, threads=threads)
        np.testing.assert_array_equal(got, inv.solve(inv.operand(b, lens, np.float64), v))
        assert cols.shape == (lens.size, 2, M)
        assert inv.columns(b, lens, pos, np.float32, threads=threads).dtype == np.float32
        single = inv.solve(inv.operand(b, lens, np.float32), v.astype(np.float32))
        assert single.dtype == np.float32
        for row, n in enumerate(lens):
            T = _toeplitz(t, n)
            ref = np.linalg.solve(T, v[row, :n])
            assert np.abs(got[row, :n] - ref).max() < 1e-12 * np.abs(ref).max()
            assert np.abs(single[row, :n] - ref).max() < 1e-5 * np.abs(ref).max()
            Ti = np.linalg.inv(T)
            for k in range(2):
                if pos[row, k] < n:
                    col = Ti[:, pos[row, k]]
                    assert np.abs(cols[row, k, :n] - col).max() < 1e-12 * np.abs(col).max()
            if dense:
                assert inv.inverse(n).shape == (3, n, n)
                assert np.abs(inv.inverse(n)[b] - Ti).max() < 1e-12 * np.abs(Ti).max()
                assert not got[row, n:].any() and not cols[row, :, n:].any()  # 0 beyond the run


@pytest.mark.parametrize("dtype, tol", [(np.float64, 1e-10), (np.float32, 2e-5)])
@pytest.mark.parametrize("hole", [False, True])
@pytest.mark.parametrize("dense_upto", [0, 96])
def test_line_preconditioner_is_the_inverse_of_its_run_blocks(kernels, monkeypatch, dtype, tol, hole, dense_upto):
    """M (B x) = x for the run blocks B of a contact of 67 nodes on 9 grid rows (runs of 3
    to 9 nodes, stick and slip mixed; with a hole, one row in two runs), in double and
    single precision, by transforms or by the dense inverses; measured 2e-15 (double) and
    3e-7 (single) relative. The slip-slip columns are computed once for every run with
    slip nodes."""
    from bem.frictional import preconditioner
    from bem.frictional.preconditioner import LinePreconditioner

    monkeypatch.setattr(toeplitz, "DENSE_UPTO", dense_upto)

    system = _system(kernels)
    if hole:
        system = _system(kernels, hole=system.C[system.nC // 2])
    runs = _runs(system)
    assert runs.max() == len(set(system.Cj)) + hole
    assert 0 < system.A.size < system.nC and system.n == 3 * system.nC
    B = _line_blocks(system)
    x = np.random.default_rng(1).normal(size=system.n)
    pre = LinePreconditioner(dtype=dtype, filter_power=0)
    pre.attach(system)
    assert pre.inverses.dense == (dense_upto > 0)
    got = system.precondition(B @ x)
    assert got.shape == (system.n,) and got.dtype == np.float64
    assert np.abs(got - x).max() < tol * np.abs(x).max()
    assert pre.factorised == len(_slip_columns(system)) > 3
    assert len(_slip_columns(system)) < system.B.size  # runs of one length share columns


@pytest.mark.parametrize("block", ["ww", "duu", "dvv"])
def test_a_singular_row_block_ends_the_solve_with_what_to_change(kernels, block):
    """A row block whose own diagonal vanishes (the layer's table edited at offset 0) has
    no Levinson recursion: attaching the line preconditioner raises FrictionNotConverged
    naming the block and the way out (dense LU, another spacing), not numpy's error."""
    from bem.friction import FrictionNotConverged
    from bem.frictional.preconditioner import LinePreconditioner

    system = _system(kernels)
    Ky, Kx = GRID.shape
    table = system.ops.tables[block].copy()
    table[Ky - 1, Kx - 1] = 0.0
    system.ops.tables[block] = table
    with pytest.raises(FrictionNotConverged) as info:
        LinePreconditioner().attach(system)
    assert str(info.value) == (
        f"the line preconditioner cannot be built on this grid: Levinson's recursion: zero diagonal "
        f"(block {block[-2:]} on a grid row); solve by dense LU (raise friction.dense_limit above the "
        "system's unknowns) or change the grid spacing")
    assert isinstance(info.value.__cause__, np.linalg.LinAlgError)


def _two_threads_in_child(system, x, want, pipe):
    import bem.frictional.preconditioner as P

    pre = P.LinePreconditioner()
    pre.attach(system)
    pipe.send(bool(np.array_equal(system.precondition(x), want)))


@pytest.mark.parametrize("dense_upto", [0, 96])
def test_line_preconditioner_on_two_threads_gives_the_same_result(kernels, monkeypatch, dense_upto):
    """With THREAD_FROM lowered to 0 the application's solves and Woodbury terms and the
    build's columns and inversions run on two threads: the result is bit-identical to one
    thread's (by transforms and by the dense inverses); from THREAD_FROM = the bytes of
    the runs' operands (the three blocks' inverses or spectra, single precision) the
    application goes to two threads, below it, with threads=False, or on a single core
    it stays on one."""
    import bem.frictional.preconditioner as P

    monkeypatch.setattr(toeplitz, "DENSE_UPTO", dense_upto)
    system = _system(kernels)
    x = np.random.default_rng(3).normal(size=system.n)
    one = P.LinePreconditioner(threads=False)
    with monkeypatch.context() as m:
        m.setattr(toeplitz, "second_thread", lambda: pytest.fail("a second thread with threads=False"))
        one.attach(system)
        want = system.precondition(x)
    used = []
    real = toeplitz.second_thread
    monkeypatch.setattr(toeplitz, "second_thread", lambda: used.append(1) or real())
    monkeypatch.setattr(P, "THREAD_FROM", 0)
    P.LinePreconditioner().attach(system)
    built = len(used)
    np.testing.assert_array_equal(system.precondition(x), want)
    assert built > 0 and len(used) > built
    runs = _runs(system)
    lens = np.bincount(runs)[1:]
    inv = one.inverses
    size = sum(inv.operand(b, lens, np.float32).nbytes for b in range(3))
    assert size == (3 * lens.size * inv.M ** 2 * 4 if dense_upto else 12 * lens.size * (inv.F // 2 + 1) * 8)
    for threshold, cores, applied in ((size, 2, True), (size + 1, 2, False), (0, 1, False), (0, None, False)):
        monkeypatch.setattr(P, "THREAD_FROM", threshold)
        monkeypatch.setattr(P.os, "cpu_count", lambda: cores)
        P.LinePreconditioner().attach(system)
        used.clear()
        np.testing.assert_array_equal(system.precondition(x), want)
        assert bool(used) == applied, (threshold, cores)


def test_a_forked_child_builds_and_applies_on_its_own_second_thread(kernels, monkeypatch):
    """After the parent used its second thread, a forked child (multiprocessing's fork, as
    in process pools) attaches and applies on two threads too: it starts its own thread
    instead of handing work to the parent's, which does not exist in the child and would
    never answer."""
    import multiprocessing

    import bem.frictional.preconditioner as P

    if (os.cpu_count() or 1) < 2 or "fork" not in multiprocessing.get_all_start_methods():
        pytest.skip("needs two cores and fork")
    system = _system(kernels)
    x = np.random.default_rng(4).normal(size=system.n)
    one = P.LinePreconditioner(threads=False)
    one.attach(system)
    want = system.precondition(x)
    monkeypatch.setattr(P, "THREAD_FROM", 0)
    parent = P.LinePreconditioner()
    parent.attach(system)
    np.testing.assert_array_equal(system.precondition(x), want)
    assert toeplitz._POOL is not None  # the parent's thread is running
    ctx = multiprocessing.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)
    child = ctx.Process(target=_two_threads_in_child, args=(system, x, want, send))
    child.start()
    child.join(60)
    alive = child.is_alive()
    if alive:
        child.kill()
    assert not alive, "the child hung on the parent's thread"
    assert child.exitcode == 0 and receive.poll(1) and receive.recv() is True


def test_line_preconditioner_keeps_unchanged_runs_and_rebuilds_changed_ones(kernels):
    """A second attach with the same sets computes no columns; with every slip direction
    turned (the same sets) none either, and the result is the exact inverse of the new
    run blocks (the Woodbury matrices hold the slip law and are built every time), not
    of the old ones; flipping nodes between stick and slip computes only the columns of
    (run length, place) pairs not asked for before; new operators compute every one."""
    from bem.frictional.preconditioner import LinePreconditioner

    pre = LinePreconditioner(dtype=np.float64, filter_power=0)
    first = _system(kernels)
    cols = _slip_columns(first)
    pre.attach(first)
    x = np.random.default_rng(2).normal(size=first.n)
    for again in (_system(kernels, ops=first.ops), _system(kernels, turn=0.7, ops=first.ops)):
        pre.attach(again)
        assert pre.factorised == len(cols)
        assert np.abs(again.precondition(_line_blocks(again) @ x) - x).max() < 1e-10 * np.abs(x).max()
    assert np.abs(again.precondition(_line_blocks(first) @ x) - x).max() > 1e-3 * np.abs(x).max()
    nodes = first.C[first.A[::7]]  # stick nodes turned to slip, some at places already asked for
    changed = _system(kernels, flip=nodes, ops=first.ops)
    new = _slip_columns(changed) - cols
    assert 0 < len(new) < nodes.size
    pre.attach(changed)
    assert pre.factorised == len(cols) + len(new)
    assert np.abs(changed.precondition(_line_blocks(changed) @ x) - x).max() < 1e-10 * np.abs(x).max()
    assert np.abs(changed.precondition(_line_blocks(first) @ x) - x).max() > 1e-6
    other = _system(kernels, seed=5)  # new operators: every column again
    pre.attach(other)
    assert pre.factorised == len(cols) + len(new) + len(_slip_columns(other))


def test_line_preconditioner_keeps_its_row_inverses_while_they_fit(kernels, monkeypatch):
    """The :class:`RowInverses` of a grid's operators are kept for runs up to their
    ``M`` (the longest run rounded up to 16 nodes, at most a grid row) and built again
    for a longer run or other operators; a single-precision preconditioner solves with
    single-precision operands (real or complex) on single-precision runs and filters in
    complex64."""
    from bem.frictional import preconditioner as P

    system = _system(kernels)
    pre = P.LinePreconditioner()
    longest = int(np.bincount(_runs(system)).max())
    pre.attach(system)
    first = pre.inverses
    assert first.M == min(-(-longest // 16) * 16, GRID.nodes_x) == 16
    assert pre._row_inverses(system.ops, 16) is first
    wider = pre._row_inverses(system.ops, 17)
    assert wider is not first and wider.M == GRID.nodes_x == 23
    assert pre._row_inverses(system.ops, 23) is wider
    assert pre._row_inverses(_system(kernels).ops, 5) is not wider
    seen = []
    solve = toeplitz.RowInverses.solve
    monkeypatch.setattr(toeplitz.RowInverses, "solve", lambda self, op, v, threads=False: seen.append(
        (op.dtype, v.dtype)) or solve(self, op, v, threads))
    box = system.box
    row_filter = box.row_filter
    blends = []
    monkeypatch.setattr(box, "row_filter", lambda power, dtype, **blend: blends.append(blend) or seen.append(
        np.dtype(dtype)) or row_filter(power, dtype, **blend))
    for dense_upto in (0, 96):
        monkeypatch.setattr(toeplitz, "DENSE_UPTO", dense_upto)
        seen.clear()
        P.LinePreconditioner().attach(system)
        system.precondition(np.ones(system.n))
        real = np.complex64 if dense_upto == 0 else np.float32
        assert seen == [np.dtype(np.complex64), (real, np.float32), (real, np.float32)], seen
    # the filter blended as the module says, its width read when attaching
    assert blends[-1] == {"long": P.FILTER_LONG, "waves": P.FILTER_WAVES}
    monkeypatch.setattr(P, "FILTER_WAVES", 3.0)
    P.LinePreconditioner(filter_long=0.9).attach(system)
    assert blends[-1] == {"long": 0.9, "waves": 3.0}
    monkeypatch.setattr(P, "FILTER_LONG", 0.6)  # read at construction, as FILTER_POWER
    P.LinePreconditioner().attach(system)
    assert blends[-1] == {"long": 0.6, "waves": 3.0}


def _bordered_line_blocks(system):
    """The run blocks of :func:`_line_blocks` bordered by the global unknowns' columns
    (from the system's rows with no forces) and rows (``SetSystem.global_rows``)."""
    nC, n = system.nC, system.n
    k = n - 3 * nC
    unit = np.zeros((n, k))
    unit[3 * nC:] = np.eye(k)
    out = np.zeros((n, n))
    out[:3 * nC, :3 * nC] = _line_blocks(system)
    out[:3 * nC, 3 * nC:] = system.rows(np.zeros((nC, k)), np.zeros((nC, k)), np.zeros((nC, k)), unit)[:3 * nC]
    out[3 * nC:, :3 * nC] = system.global_rows(np.eye(3 * nC))
    return out


def test_line_preconditioner_with_global_unknowns(kernels):
    """Load control and a free Omega add two unknowns (``d`` in every gap row, ``Omega`` in
    the ``x`` stick rows and the slip rows across ``e``; the rows of the load and the loading
    mode): M r is the exact inverse of the run blocks bordered by those columns and rows
    (block elimination with the Schur complement of the two), checked on the bordered
    matrix assembled here from the system's own rows."""
    from bem.frictional.preconditioner import LinePreconditioner

    system = _system(kernels, load=20.0, indentation=None, omega=None)
    nC, n = system.nC, system.n
    assert n == 3 * nC + 2
    bordered = _bordered_line_blocks(system)
    F = bordered[:3 * nC, 3 * nC:]
    assert np.count_nonzero(F[:nC, 0]) == nC and not F[nC:, 0].any()  # d: every gap row, only them
    assert not F[:nC, 1].any() and np.count_nonzero(F[nC:, 1]) > 0  # Omega: tangential rows only
    r = np.random.default_rng(4).normal(size=n)
    LinePreconditioner(dtype=np.float64, filter_power=0).attach(system)
    got = system.precondition(r)
    assert got.shape == (n,) and np.isfinite(got).all()
    np.testing.assert_allclose(bordered @ got, r, rtol=0, atol=1e-9 * np.abs(r).max())
    # the global rows' residuals reach the forces (the former preconditioner passed them on)
    r2 = r.copy()
    r2[3 * nC:] *= 7.0
    assert not np.allclose(system.precondition(r2)[:3 * nC], got[:3 * nC])


def test_line_preconditioner_keeps_the_schur_parts_while_the_contact_set_repeats(kernels, monkeypatch):
    """The complement of d and Omega is computed once per contact set: a second attach
    with the same contact, turned slip directions or a node flipped between stick and
    slip reuses it (no new ``eliminate``; the result is then not the new blocks' exact
    bordered inverse, but the first attach's parts applied with the new lines); another
    contact set, another ``mu`` or new operators compute it again."""
    from dataclasses import replace

    from bem.frictional import SetState, SetSystem
    from bem.frictional import preconditioner as P

    calls = []
    eliminate = P.eliminate
    monkeypatch.setattr(P, "eliminate", lambda *a: calls.append(1) or eliminate(*a))
    pre = P.LinePreconditioner(dtype=np.float64, filter_power=0)
    first = _system(kernels, load=20.0, indentation=None, omega=None)
    pre.attach(first)
    turned = _system(kernels, load=20.0, indentation=None, omega=None, turn=0.4, ops=first.ops)
    assert np.array_equal(turned.C, first.C) and np.array_equal(turned.stick, first.stick)
    parts = pre._schur[1]
    pre.attach(turned)
    assert len(calls) == 1 and pre._schur[1] is parts
    r = np.random.default_rng(6).normal(size=turned.n)
    residual = _bordered_line_blocks(turned) @ turned.precondition(r) - r
    assert np.abs(residual[:3 * turned.nC]).max() > 1e-6 * np.abs(r).max()  # inexact: the old parts
    flipped = _system(kernels, load=20.0, indentation=None, omega=None, flip=first.C[first.B[:1]], ops=first.ops)
    assert not np.array_equal(flipped.stick, first.stick)
    pre.attach(flipped)
    assert len(calls) == 1 and pre._schur[1] is parts
    holed = _system(kernels, load=20.0, indentation=None, omega=None, hole=first.C[first.nC // 2], ops=first.ops)
    pre.attach(holed)
    assert len(calls) == 2
    pre.attach(flipped)
    assert len(calls) == 3
    size = GRID.nodes_x * GRID.nodes_y
    contact, stick = np.zeros(size, bool), np.zeros(size, bool)
    contact[flipped.C], stick[flipped.C[flipped.A]] = True, True
    direction, slope = np.zeros((size, 2)), np.zeros(size)
    direction[flipped.C[flipped.B]] = np.stack([flipped.dir_x, flipped.dir_y], 1)
    slope[flipped.C[flipped.B]] = flipped.slope * V / GRID.spacing_x
    other_mu = SetSystem(replace(flipped.setup, mu=0.2),
                         SetState(contact=contact, stick=stick, direction=direction, slope=slope))
    pre.attach(other_mu)
    assert len(calls) == 4
    pre.attach(_system(kernels, load=20.0, indentation=None, omega=None, flip=first.C[first.B[:1]]))
    assert len(calls) == 5


@pytest.mark.parametrize("omega", [None, 2.4])
def test_line_preconditioner_singular_complement_scales_the_globals(kernels, monkeypatch, omega):
    """When the Schur complement of the global unknowns is singular (here: global rows
    that read nothing), the forces get the lines alone and the global rows are passed on:
    ``d`` as it is, a free ``Omega`` scaled by the inverse of its stick-row coefficient
    ``1 / a_x``."""
    from bem.frictional.preconditioner import LinePreconditioner

    system = _system(kernels, load=20.0, indentation=None, omega=omega)
    nC, k = system.nC, system.n - 3 * system.nC
    assert k == (2 if omega is None else 1)
    monkeypatch.setattr(system, "global_rows", lambda X: np.zeros((k, X.shape[1])))
    r = np.random.default_rng(5).normal(size=system.n)
    LinePreconditioner(dtype=np.float64, filter_power=0).attach(system)
    got = system.precondition(r)
    np.testing.assert_allclose(_line_blocks(system) @ got[:3 * nC], r[:3 * nC], rtol=0, atol=1e-10 * np.abs(r).max())
    assert got[system.iD] == r[system.iD]
    if omega is None:
        assert got[system.iO] == r[system.iO] / system.ax


def test_line_preconditioner_columns_in_many_batches(kernels, monkeypatch):
    """With one run length a batch (``CHUNK`` 1) the missing columns come in many
    batches: every one computed once and the result still the exact inverse of the run
    blocks (a batch counter that does not advance never ends)."""
    from bem.frictional import preconditioner as P

    monkeypatch.setattr(P, "CHUNK", 1)
    system = _system(kernels)
    pre = P.LinePreconditioner(dtype=np.float64, filter_power=0)
    pre.attach(system)
    lengths = {n for n, _ in _slip_columns(system)}
    assert len(lengths) > 2 and pre.factorised == len(_slip_columns(system))
    x = np.random.default_rng(9).normal(size=system.n)
    assert np.abs(system.precondition(_line_blocks(system) @ x) - x).max() < 1e-10 * np.abs(x).max()


@pytest.mark.parametrize("keep", [0, 1])
def test_no_or_one_slip_node(kernels, keep):
    """Every slip node but ``keep`` flipped to stick: with none the runs' blocks are
    Toeplitz and no columns are computed; with one, one run has a 2 x 2 Woodbury matrix.
    Either way the result is the exact inverse of the run blocks."""
    from bem.frictional.preconditioner import LinePreconditioner

    system = _system(kernels, seed=2)
    state = _system(kernels, seed=2, flip=system.C[system.B[keep:]])
    assert state.B.size == keep
    pre = LinePreconditioner(dtype=np.float64, filter_power=0)
    pre.attach(state)
    assert pre.factorised == keep
    x = np.random.default_rng(7).normal(size=state.n)
    assert np.abs(state.precondition(_line_blocks(state) @ x) - x).max() < 1e-10 * np.abs(x).max()


# --------------------------------------------------------------------------------------
# bem.frictional.starts: the start states against their definitions, the continuation's
# ladder of mu, its starts, history and messages (run_active_set replaced by a recorder).

from bem.friction import Friction, FrictionNotConverged  # noqa: E402


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


def _fake_setup():
    from bem.frictional.system import RollingSetup

    return RollingSetup(ops=None, profile=np.zeros(4), arm=np.zeros(4), ell=np.array([1.0, 1.0, 2.0, 0.5]),
                        radius=0.02, speed=1.0, mu=0.0, load=1.0, indentation=None, omega=None, constraint=None)


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

    def fake(setup, friction, state, solves, progress):
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


def test_continuation_failure_names_where_it_stopped(monkeypatch):
    from bem.frictional import starts
    from bem.frictional.active_set import ActiveSetResult

    def fake(setup, friction, state, solves, progress):
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


# --------------------------------------------------------------------------------------
# bem.friction: validation messages whole, defaults as the case-file schema documents
# them, the record's residual, the result's derived fields recomputed by hand.

@pytest.mark.parametrize("kwargs, message", [
    ({"mu": -0.1}, "mu must be >= 0, got -0.1"),
    ({"mu": math.nan}, "mu must be >= 0, got nan"),
    ({"mu": math.inf}, "mu must be >= 0, got inf"),
    ({"mu": "0.2"}, "mu must be >= 0, got '0.2'"),
    ({"mu": 0.2, "mode": "pulled"}, "mode must be one of pushed_at_top, towed, torque, omega, got 'pulled'"),
    ({"mu": 0.2, "mode": "omega"},
     "omega (rad/s) must be given with mode = 'omega' and only then, got mode = 'omega', omega = None"),
    ({"mu": 0.2, "omega": 1.0},
     "omega (rad/s) must be given with mode = 'omega' and only then, got mode = 'pushed_at_top', omega = 1.0"),
    ({"mu": 0.2, "mode": "omega", "omega": math.inf}, "omega must be finite (rad/s), got inf"),
    ({"mu": 0.2, "mode": "omega", "omega": math.nan}, "omega must be finite (rad/s), got nan"),
    ({"mu": 0.2, "radius": -1.0}, "radius must be > 0 m, got -1.0"),
    ({"mu": 0.2, "radius": 0.0}, "radius must be > 0 m, got 0.0"),
    ({"mu": 0.2, "radius": math.inf}, "radius must be > 0 m, got inf"),
    ({"mu": 0.2, "radius": math.nan}, "radius must be > 0 m, got nan"),
    ({"mu": 0.2, "max_iter": 0}, "max_iter must be an integer > 0, got 0"),
    ({"mu": 0.2, "max_iter": 2.0}, "max_iter must be an integer > 0, got 2.0"),
    ({"mu": 0.2, "direction_tol": 0.0}, "direction_tol must be > 0, got 0.0"),
    ({"mu": 0.2, "direction_tol": math.nan}, "direction_tol must be > 0, got nan"),
    ({"mu": 0.2, "dense_limit": -1}, "dense_limit must be an integer >= 0, got -1"),
    ({"mu": 0.2, "dense_limit": 10.0}, "dense_limit must be an integer >= 0, got 10.0"),
    ({"mu": 0.2, "set_tol": -1e-9}, "set_tol must be >= 0, got -1e-09"),
    ({"mu": 0.2, "set_tol": math.nan}, "set_tol must be >= 0, got nan"),
])
def test_friction_validation_messages_whole(kwargs, message):
    with pytest.raises(ValueError) as info:
        Friction(**kwargs)
    assert str(info.value) == message


def test_friction_limits_accepted_and_defaults_as_documented():
    """The limits themselves are accepted (mu = 0, omega = 0, max_iter = 1, dense_limit = 0,
    set_tol = 0, a tiny radius and direction_tol); the defaults are the case-file schema's."""
    from casefile.schema import section

    Friction(0, "omega", omega=0.0, radius=1e-12, max_iter=1, direction_tol=1e-300, dense_limit=0, set_tol=0.0)
    Friction(0.0, "omega", omega=-3.0)
    f = Friction(0.2)
    keys = {k.name: k.default for k in section("friction").keys}
    for name in ("mode", "max_iter", "direction_tol", "set_tol", "dense_limit"):
        assert getattr(f, name) == keys[name], name
    assert f.omega is None and f.radius is None


def test_friction_errors_are_contact_errors():
    from bem.contact import ContactError, ContactNotConverged
    from bem.friction import LoadingUnreachable

    assert issubclass(FrictionNotConverged, ContactNotConverged)
    assert issubclass(LoadingUnreachable, ContactError) and not issubclass(LoadingUnreachable, ContactNotConverged)


def _contact_result(**over):
    from bem.friction import FrictionalContact, FrictionRecord

    g = Grid(1.0e-3, 2.0e-3, 0.02, 0.04, 10, 10, 4, 3)
    N = np.array([[0.0, 1.0, 2.0, 0.0], [3.0, 0.0, 5.0, -1.0], [0.0, 0.5, 0.0, 0.0]])
    Sx = np.array([[0.0, 0.1, -0.2, 0.0], [0.3, 0.0, 0.4, 0.0], [0.0, -0.05, 0.0, 0.0]])
    Sy = np.array([[0.0, 0.2, 0.1, 0.0], [-0.1, 0.0, 0.2, 0.0], [0.0, 0.05, 0.0, 0.0]])
    wx = np.array([[0.0, 0.0, -2.0, 0.0], [1.5, 0.0, 0.0, 0.0], [0.0, -1.0, 0.0, 0.0]])
    wy = np.array([[0.0, 0.0, 1.0, 0.0], [-0.5, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]])
    stick = np.array([[0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 0]], bool)
    rec = FrictionRecord(3, ((5, 2, 0.5, 1.0), (5, 2, 1e-3, 1.1), (5, 2, 1e-9, 1.2)), "gmres", 42,
                         1e-11, 2e-12, 3e-8)
    fields = dict(grid=g, force=N, force_x=Sx, force_y=Sy, deflection=N * 1e-6, displacement_x=Sx * 1e-6,
                  displacement_y=Sy * 1e-6, gap=N * 0.0, slip_x=wx, slip_y=wy, stick=stick, indentation=1e-4,
                  load=11.5, omega=1.2, driving_force=0.7, driving_torque=0.014, rolling_resistance=0.9,
                  rolling_resistance_friction=0.25, rolling_resistance_viscous=0.65, speed=0.05, mu=0.3,
                  mode="towed", record=rec)
    fields.update(over)
    return FrictionalContact(**fields)


def test_frictional_contact_derived_fields_by_hand():
    from bem.contact import SHARED_SCALARS

    r = _contact_result()
    assert r.record.residual == 3e-8
    assert type(r).__dataclass_fields__["rolling_resistance_energy"].default is not None
    assert math.isnan(r.rolling_resistance_energy)
    contact = r.force > 0
    np.testing.assert_array_equal(r.contact, contact)
    np.testing.assert_array_equal(r.slip, contact & ~r.stick)
    assert r.slip.sum() == 3
    area = 1e-3 * 2e-3
    np.testing.assert_allclose(r.pressure, r.force / area, rtol=1e-15)
    np.testing.assert_allclose(r.traction_x, r.force_x / area, rtol=1e-15)
    np.testing.assert_allclose(r.traction_y, r.force_y / area, rtol=1e-15)
    assert r.stick_fraction == 2 / 5
    assert r.contact_area == pytest.approx(5 * area, rel=1e-15)
    assert r.contact_radius == pytest.approx(math.sqrt(5 * area / math.pi), rel=1e-15)
    assert r.peak_pressure == pytest.approx(5.0 / area, rel=1e-15) and isinstance(r.peak_pressure, float)
    x = (np.arange(4) - 1.5) * 1e-3
    assert r.pressure_centroid_x == pytest.approx(float((r.force * x).sum() / r.force.sum()), rel=1e-14)
    # S . w over the contact: (-0.2)(-2) + 0.1 * 1 + 0.3 * 1.5 + (-0.1)(-0.5) + (-0.05)(-1) + 0.05 * 1
    assert r.friction_power == pytest.approx(0.4 + 0.1 + 0.45 + 0.05 + 0.05 + 0.05, rel=1e-14)
    empty = _contact_result(force=np.zeros((3, 4)))
    assert math.isnan(empty.stick_fraction)
    s = r.summary()
    for name in SHARED_SCALARS:
        assert s[name] == getattr(r, name) or (math.isnan(s[name]) and math.isnan(getattr(r, name))), name
    for name in ("rolling_resistance_friction", "rolling_resistance_viscous", "omega", "driving_force",
                 "driving_torque", "stick_fraction", "mu", "mode", "speed"):
        assert s[name] == getattr(r, name), name
    assert math.isnan(s["rolling_resistance_energy"])
    assert s["grid"] == {"nodes": [4, 3], "spacing": [1e-3, 2e-3], "period": [0.02, 0.04], "truncation": [10, 10]}
    assert s["solver"] == {"iterations": 3, "residual": 3e-8,
                           "history": [[5, 2, 0.5, 1.0], [5, 2, 1e-3, 1.1], [5, 2, 1e-9, 1.2]],
                           "gap_residual": 1e-11, "stick_residual": 2e-12, "coulomb_residual": 3e-8,
                           "linear_solver": "gmres", "linear_iterations": 42}
    assert _contact_result(rolling_resistance_energy=1.5).summary()["rolling_resistance_energy"] == 1.5
    rec = r.record
    assert type(rec)(1, (), "dense", 0, 0.3, 0.2, 0.1).residual == 0.3
    assert type(rec)(1, (), "dense", 0, 0.1, 0.3, 0.2).residual == 0.3


def test_transforms_go_threaded_from_the_threshold():
    """``fft_workers``: one thread below ``THREADED_FROM`` embedding points, every core from
    there on, one inside ``one_worker`` (nested, and after an error, restored on leaving);
    a ComplianceOperator asks at each product, and its product is the same bit for bit
    either way."""
    from bem import operator as op_module
    from bem.operator import THREADED_FROM, ComplianceOperator, fft_workers, one_worker

    assert THREADED_FROM == 100_000
    assert fft_workers((100, 1000)) == -1 and fft_workers((100, 999)) == 1 and fft_workers((1, 1)) == 1
    with one_worker():
        assert fft_workers((100, 1000)) == 1
        with one_worker():
            assert fft_workers((1000, 1000)) == 1
        assert fft_workers((100, 1000)) == 1
    with pytest.raises(KeyError):
        with one_worker():
            raise KeyError
    assert fft_workers((100, 1000)) == -1
    kern = _random_kernels(SMALL, seed=21)["ww"]
    F = np.random.default_rng(22).normal(size=SMALL.shape)
    op = ComplianceOperator(SMALL, kern)
    assert op._workers == 1
    one = op.apply(F)
    kept = op_module.THREADED_FROM
    try:
        op_module.THREADED_FROM = 0
        assert op._workers == -1
        every = op.apply(F)
        with one_worker():
            assert op._workers == 1
    finally:
        op_module.THREADED_FROM = kept
    np.testing.assert_array_equal(one, every)


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
