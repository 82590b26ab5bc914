"""bem.frictional.operators: every block and product against a dense matrix assembled column
by column from ComplianceOperator's FFT product of unit forces (a different algorithm from
the direct table reads and the batched one-axis-at-a-time transforms), on random,
nonsymmetric kernel tables of a small grid with K_x != K_y and a_x != a_y; windows, coarse
operators and the threaded transforms.
"""

import numpy as np
import pytest

from bem.grid import Grid
from bem.kinematics import upwind_table
from bem.operator import ComplianceOperator
from bem.spectral import BLOCKS


RNG = np.random.default_rng(7)
N, SX = RNG.uniform(0.1, 2.0, size=6), RNG.normal(size=6) * 0.3
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
    # on every core or on one (THREADED_FROM): the same numbers to rounding (scipy.fft and
    # numpy.fft, bem.fft)
    from bem import operator as op_module
    from bem.threads import cores

    kept, got = (op_module.THREADED_FROM, op_module.IMPORT_PAYS_FROM), []
    try:
        for threshold, workers in ((0, cores()), (10**12, 1)):
            op_module.THREADED_FROM = op_module.IMPORT_PAYS_FROM = threshold
            assert ops._workers() == workers
            got.append(ops.fields_on(nodes, forces))
    finally:
        op_module.THREADED_FROM, op_module.IMPORT_PAYS_FROM = kept
    assert np.abs(got[0] - got[1]).max() <= 1e-14 * np.abs(got[1]).max()
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


def test_transforms_go_threaded_from_the_threshold(monkeypatch):
    """``fft_workers``: every usable core from ``THREADED_FROM`` embedding points on once
    scipy.fft (which runs the threads) is loaded, from ``IMPORT_PAYS_FROM`` on before (its
    import, 0.135 s, pays only there), one thread below; one inside ``one_worker`` (nested,
    and after an error, restored on leaving); a ComplianceOperator asks at each product,
    and its product is the same to rounding either way (one thread runs in numpy.fft, more
    in scipy.fft: :mod:`bem.fft`)."""
    import sys
    import types

    from bem import operator as op_module
    from bem.operator import IMPORT_PAYS_FROM, THREADED_FROM, ComplianceOperator, fft_workers, one_worker
    from bem.threads import cores

    assert (THREADED_FROM, IMPORT_PAYS_FROM) == (100_000, 1_000_000)
    monkeypatch.delitem(sys.modules, "scipy.fft", raising=False)
    assert fft_workers((1000, 1000)) == cores() and fft_workers((1000, 999)) == 1
    assert fft_workers((100, 1000)) == 1 and fft_workers((1, 1)) == 1
    monkeypatch.setitem(sys.modules, "scipy.fft", types.ModuleType("scipy.fft"))
    assert fft_workers((100, 1000)) == cores() and fft_workers((100, 999)) == 1 and fft_workers((1, 1)) == 1
    with one_worker():
        assert fft_workers((100, 1000)) == 1
        with one_worker():
            assert fft_workers((1000, 1000)) == 1
        assert fft_workers((100, 1000)) == 1
    with pytest.raises(KeyError):
        with one_worker():
            raise KeyError
    assert fft_workers((100, 1000)) == cores()
    monkeypatch.undo()
    kern = _random_kernels(SMALL, seed=21)["ww"]
    F = np.random.default_rng(22).normal(size=SMALL.shape)
    op = ComplianceOperator(SMALL, kern)
    assert op._workers == 1
    one = op.apply(F)
    monkeypatch.setattr(op_module, "THREADED_FROM", 0)
    monkeypatch.setattr(op_module, "IMPORT_PAYS_FROM", 0)
    assert op._workers == cores()
    every = op.apply(F)
    with one_worker():
        assert op._workers == 1
    assert np.abs(one - every).max() <= 1e-14 * np.abs(every).max()
