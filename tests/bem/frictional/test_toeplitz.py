"""bem.frictional.toeplitz: Levinson's columns for every run length and the run inverses (by
transforms, by the inverses themselves, batched or grouped, on one or two threads) against
numpy's dense solves and inverses of the runs' Toeplitz blocks.
"""

import numpy as np
import pytest

from bem import Layer, ThreeParameterSolid, influence_kernels
from bem.frictional import SolverOptions
from bem.grid import Grid
from bem.spectral import BLOCKS


LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (5.5e-3, 5.5e-3))  # 23 x 23, 529 nodes


@pytest.fixture(scope="module")
def kernels():
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)


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
    from bem.frictional import SolverOptions
    from bem.frictional.toeplitz import GroupedRuns, RowInverses

    ops = RollingOperators(GRID, kernels)
    Ky, Kx = GRID.shape
    inv = RowInverses(ops, M, dense=dense)
    assert inv.M == M and inv.F == {16: 32, 13: 25}[M] and inv.dense == dense
    if dense:  # the transforms' spectra are not built: the inverses are applied themselves
        assert inv.spectra is None and inv.units is None
    else:
        assert inv.spectra.shape == (3, 4, M, inv.F // 2 + 1) and inv.units.shape == (M, inv.F // 2 + 1)
    assert RowInverses(ops, 99).M == Kx  # no run is longer than a grid row
    assert RowInverses(ops, 16).dense == (16 <= SolverOptions().dense_upto)
    # dense up to dense_upto nodes inclusive
    assert RowInverses(ops, M, dense_upto=M).dense and not RowInverses(ops, M + 1, dense_upto=M).dense
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
            # grouped by length: the same values
            grouped = GroupedRuns(RowInverses(ops, M, dense=dense, batched_upto=M - 1), (b,), lens, np.float64)
            assert grouped.stack is None and len(grouped.groups) == len(set(lens))
            other = inv.solve(grouped, v, threads=threads)
            np.testing.assert_array_equal(other, inv.solve(grouped, v))
            assert np.abs(other - got).max() < 1e-13 * np.abs(got).max()
            # both blocks of the tangential rows in one operand: each block's rows as alone
            two = inv.solve(inv.operand((b, 2), lens, np.float64), np.concatenate([v, v]), threads=threads)
            assert np.abs(two[:lens.size] - got).max() < 1e-13 * np.abs(got).max()
        cols = inv.columns(b, lens, pos, np.float64)
        np.testing.assert_array_equal(got, inv.solve(inv.operand(b, lens, np.float64), v))
        assert cols.shape == (lens.size, 2, M)
        assert inv.columns(b, lens, pos, np.float32).dtype == np.float32
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


def test_dense_columns_at_a_run_s_end_are_zero_and_grouped_runs_count_their_bytes(kernels):
    """``columns`` by the dense inverses gives 0 for a place at or beyond the run's end (a
    place equal to the run's length included); a :class:`GroupedRuns` counts the bytes of
    what it applies: the padded stack when batched, the groups' inverses when grouped."""
    from bem.frictional import RollingOperators
    from bem.frictional.toeplitz import GroupedRuns, RowInverses

    ops = RollingOperators(GRID, kernels)
    lens = np.array([3, 5, 5, 8])
    pos = np.array([[3, 0], [5, 4], [6, 1], [7, 8]])
    inv = RowInverses(ops, 16, dense=True)
    for b in range(3):
        cols = inv.columns(b, lens, pos, np.float64)
        assert not cols[0, 0].any() and not cols[1, 0].any() and not cols[2, 0].any() and not cols[3, 1].any()
        assert cols[0, 1].any() and cols[1, 1].any() and cols[2, 1].any() and cols[3, 0].any()
    grouped = GroupedRuns(RowInverses(ops, 16, dense=True, batched_upto=8), (0, 1), lens, np.float32)
    assert grouped.stack is None and grouped.nbytes == 4 * 2 * (3 * 3 + 5 * 5 + 8 * 8)
    batched = GroupedRuns(inv, (0, 1), lens, np.float32)
    assert batched.nbytes == batched.stack.nbytes == 4 * 2 * 4 * 16 * 16
