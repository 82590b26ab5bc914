"""bem.frictional.preconditioner: the line preconditioner is the exact inverse of its own run
blocks (the system's dense matrix restricted to one run of contact nodes along a grid row,
without the normal-tangential coupling blocks, keeping the slip rows' -mu N), whatever the
layout, precision, threads and options; what it keeps between attaches (run inverses,
Woodbury columns, Schur parts) and the global unknowns' elimination.
"""

import os
from dataclasses import replace

import numpy as np
import pytest

from bem.frictional import FrictionNotConverged
from bem.frictional import SolverOptions
from bem.frictional import toeplitz
from tests.bem.frictional.solve_checks import GRID, V, synthetic_system


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


def _slip_columns(system):
    """The distinct (run length, place in the run) of the slip nodes: the Toeplitz inverse
    columns the line preconditioner needs (one per pair, whichever runs ask)."""
    r = _runs(system)
    lens = np.bincount(r)
    starts = np.r_[0, np.flatnonzero(np.diff(r)) + 1]
    place = np.arange(r.size) - starts[r - 1]
    return set(zip(lens[r][system.B].tolist(), place[system.B].tolist()))


def _two_threads_in_child(system, x, want, pipe, options):
    import bem.frictional.preconditioner as P

    pre = P.LinePreconditioner(options=options)
    pre.attach(system)
    pipe.send(bool(np.array_equal(system.precondition(x), want)))


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


@pytest.mark.parametrize("dtype, tol", [(np.float64, 1e-10), (np.float32, 2e-5)])
@pytest.mark.parametrize("hole", [False, True])
@pytest.mark.parametrize("dense_upto", [0, 96])
def test_line_preconditioner_is_the_inverse_of_its_run_blocks(kernels, dtype, tol, hole, dense_upto):
    """M (B x) = x for the run blocks B of a contact of 67 nodes on 9 grid rows (runs of 3
    to 9 nodes, stick and slip mixed; with a hole, one row in two runs), in double and
    single precision, by transforms or by the dense inverses; measured 2e-15 (double) and
    3e-7 (single) relative. The slip-slip columns are computed once for every run with
    slip nodes."""
    from bem.frictional import SolverOptions
    from bem.frictional.preconditioner import LinePreconditioner

    system = synthetic_system(kernels)
    if hole:
        system = synthetic_system(kernels, hole=system.C[system.nC // 2])
    runs = _runs(system)
    assert runs.max() == len(set(system.Cj)) + hole
    assert 0 < system.A.size < system.nC and system.n == 3 * system.nC
    B = _line_blocks(system)
    x = np.random.default_rng(1).normal(size=system.n)
    pre = LinePreconditioner(dtype=dtype, options=SolverOptions(filter_power=0, dense_upto=dense_upto))
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
    from bem.frictional import FrictionNotConverged
    from bem.frictional.preconditioner import LinePreconditioner

    system = synthetic_system(kernels)
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


@pytest.mark.parametrize("dense_upto", [0, 96])
def test_line_preconditioner_on_two_threads_gives_the_same_result(kernels, monkeypatch, dense_upto):
    """With ``thread_from`` lowered to 0 the application's solves and Woodbury terms run on
    two threads, the build on one: the result is bit-identical to one thread's (by
    transforms and by the dense inverses); from ``thread_from`` = the bytes of the runs'
    operands (the three blocks' inverses or spectra, single precision) the application
    goes to two threads, below it, with threads=False, or on a single core it stays on
    one."""
    import bem.frictional.preconditioner as P
    from bem.frictional import SolverOptions

    options = SolverOptions(dense_upto=dense_upto)
    system = synthetic_system(kernels)
    x = np.random.default_rng(3).normal(size=system.n)
    one = P.LinePreconditioner(threads=False, options=options)
    with monkeypatch.context() as m:
        m.setattr(toeplitz, "second_thread", lambda: pytest.fail("a second thread with threads=False"))
        one.attach(system)
        want = system.precondition(x)
    used = []
    real = toeplitz.second_thread
    monkeypatch.setattr(toeplitz, "second_thread", lambda: used.append(1) or real())
    P.LinePreconditioner(options=replace(options, thread_from=0)).attach(system)
    built = len(used)
    np.testing.assert_array_equal(system.precondition(x), want)
    assert built == 0 and len(used) > built
    runs = _runs(system)
    lens = np.bincount(runs)[1:]
    inv = one.inverses
    size = sum(inv.operand(b, lens, np.float32).nbytes for b in range(3))
    assert size == (3 * lens.size * inv.M ** 2 * 4 if dense_upto else 12 * lens.size * (inv.F // 2 + 1) * 8)
    for threshold, cores, applied in ((size, 2, True), (size + 1, 2, False), (0, 1, False), (0, None, False)):
        monkeypatch.setattr(P, "cores", lambda: cores or 1)
        P.LinePreconditioner(options=replace(options, thread_from=threshold)).attach(system)
        used.clear()
        np.testing.assert_array_equal(system.precondition(x), want)
        assert bool(used) == applied, (threshold, cores)


def test_a_forked_child_builds_and_applies_on_its_own_second_thread(kernels, monkeypatch):
    """After the parent used its second thread, a forked child (multiprocessing's fork, as
    in process pools) attaches and then applies on two threads too: it starts its own thread
    instead of handing work to the parent's, which does not exist in the child and would
    never answer."""
    import multiprocessing

    import bem.frictional.preconditioner as P
    from bem.frictional import SolverOptions

    if (os.cpu_count() or 1) < 2 or "fork" not in multiprocessing.get_all_start_methods():
        pytest.skip("needs two cores and fork")
    system = synthetic_system(kernels)
    x = np.random.default_rng(4).normal(size=system.n)
    one = P.LinePreconditioner(threads=False)
    one.attach(system)
    want = system.precondition(x)
    two = SolverOptions(thread_from=0)
    parent = P.LinePreconditioner(options=two)
    parent.attach(system)
    np.testing.assert_array_equal(system.precondition(x), want)
    assert toeplitz._POOL is not None  # the parent's thread is running
    ctx = multiprocessing.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)
    child = ctx.Process(target=_two_threads_in_child, args=(system, x, want, send, two))
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

    pre = LinePreconditioner(dtype=np.float64, options=SolverOptions(filter_power=0))
    first = synthetic_system(kernels)
    cols = _slip_columns(first)
    pre.attach(first)
    x = np.random.default_rng(2).normal(size=first.n)
    for again in (synthetic_system(kernels, ops=first.ops), synthetic_system(kernels, turn=0.7, ops=first.ops)):
        pre.attach(again)
        assert pre.factorised == len(cols)
        assert np.abs(again.precondition(_line_blocks(again) @ x) - x).max() < 1e-10 * np.abs(x).max()
    assert np.abs(again.precondition(_line_blocks(first) @ x) - x).max() > 1e-3 * np.abs(x).max()
    nodes = first.C[first.A[::7]]  # stick nodes turned to slip, some at places already asked for
    changed = synthetic_system(kernels, flip=nodes, ops=first.ops)
    new = _slip_columns(changed) - cols
    assert 0 < len(new) < nodes.size
    pre.attach(changed)
    assert pre.factorised == len(cols) + len(new)
    assert np.abs(changed.precondition(_line_blocks(changed) @ x) - x).max() < 1e-10 * np.abs(x).max()
    assert np.abs(changed.precondition(_line_blocks(first) @ x) - x).max() > 1e-6
    other = synthetic_system(kernels, seed=5)  # new operators: every column again
    pre.attach(other)
    assert pre.factorised == len(cols) + len(new) + len(_slip_columns(other))


def test_line_preconditioner_keeps_its_row_inverses_while_they_fit(kernels, monkeypatch):
    """The :class:`RowInverses` of a grid's operators are kept for runs up to their
    ``M`` (the longest run rounded up to 16 nodes, at most a grid row) and built again
    for a longer run or other operators; a single-precision preconditioner solves with
    single-precision operands (real or complex) on single-precision runs and filters in
    complex64."""
    from bem.frictional import SolverOptions
    from bem.frictional import preconditioner as P

    system = synthetic_system(kernels)
    pre = P.LinePreconditioner()
    longest = int(np.bincount(_runs(system)).max())
    pre.attach(system)
    first = pre.inverses
    assert first.M == min(-(-longest // 16) * 16, GRID.nodes_x) == 16
    assert pre._row_inverses(system.ops, 16) is first
    wider = pre._row_inverses(system.ops, 17)
    assert wider is not first and wider.M == GRID.nodes_x == 23
    assert pre._row_inverses(system.ops, 23) is wider
    assert pre._row_inverses(synthetic_system(kernels).ops, 5) is not wider
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
        seen.clear()
        P.LinePreconditioner(options=SolverOptions(dense_upto=dense_upto)).attach(system)
        system.precondition(np.ones(system.n))
        real = np.complex64 if dense_upto == 0 else np.float32
        assert seen == [np.dtype(np.complex64), (real, np.float32), (real, np.float32)], seen
    # the filter blended as the options say
    assert blends[-1] == {"long": SolverOptions().filter_long, "waves": SolverOptions().filter_waves}
    P.LinePreconditioner(options=SolverOptions(filter_long=0.9, filter_waves=3.0)).attach(system)
    assert blends[-1] == {"long": 0.9, "waves": 3.0}
    P.LinePreconditioner(options=SolverOptions(filter_long=0.6, filter_waves=3.0)).attach(system)
    assert blends[-1] == {"long": 0.6, "waves": 3.0}


def test_line_preconditioner_with_global_unknowns(kernels):
    """Load control and a free Omega add two unknowns (``d`` in every gap row, ``Omega`` in
    the ``x`` stick rows and the slip rows across ``e``; the rows of the load and the loading
    mode): M r is the exact inverse of the run blocks bordered by those columns and rows
    (block elimination with the Schur complement of the two), checked on the bordered
    matrix assembled here from the system's own rows."""
    from bem.frictional.preconditioner import LinePreconditioner

    system = synthetic_system(kernels, load=20.0, indentation=None, omega=None)
    nC, n = system.nC, system.n
    assert n == 3 * nC + 2
    bordered = _bordered_line_blocks(system)
    F = bordered[:3 * nC, 3 * nC:]
    assert np.count_nonzero(F[:nC, 0]) == nC and not F[nC:, 0].any()  # d: every gap row, only them
    assert not F[:nC, 1].any() and np.count_nonzero(F[nC:, 1]) > 0  # Omega: tangential rows only
    r = np.random.default_rng(4).normal(size=n)
    LinePreconditioner(dtype=np.float64, options=SolverOptions(filter_power=0)).attach(system)
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
    pre = P.LinePreconditioner(dtype=np.float64, options=SolverOptions(filter_power=0))
    first = synthetic_system(kernels, load=20.0, indentation=None, omega=None)
    pre.attach(first)
    turned = synthetic_system(kernels, load=20.0, indentation=None, omega=None, turn=0.4, ops=first.ops)
    assert np.array_equal(turned.C, first.C) and np.array_equal(turned.stick, first.stick)
    parts = pre._schur[1]
    pre.attach(turned)
    assert len(calls) == 1 and pre._schur[1] is parts
    r = np.random.default_rng(6).normal(size=turned.n)
    residual = _bordered_line_blocks(turned) @ turned.precondition(r) - r
    assert np.abs(residual[:3 * turned.nC]).max() > 1e-6 * np.abs(r).max()  # inexact: the old parts
    flipped = synthetic_system(kernels, load=20.0, indentation=None, omega=None, flip=first.C[first.B[:1]], ops=first.ops)
    assert not np.array_equal(flipped.stick, first.stick)
    pre.attach(flipped)
    assert len(calls) == 1 and pre._schur[1] is parts
    holed = synthetic_system(kernels, load=20.0, indentation=None, omega=None, hole=first.C[first.nC // 2], ops=first.ops)
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
    pre.attach(synthetic_system(kernels, load=20.0, indentation=None, omega=None, flip=first.C[first.B[:1]]))
    assert len(calls) == 5


@pytest.mark.parametrize("omega", [None, 2.4])
def test_line_preconditioner_singular_complement_scales_the_globals(kernels, monkeypatch, omega):
    """When the Schur complement of the global unknowns is singular (here: global rows
    that read nothing), the forces get the lines alone and the global rows are passed on:
    ``d`` as it is, a free ``Omega`` scaled by the inverse of its stick-row coefficient
    ``1 / a_x``."""
    from bem.frictional.preconditioner import LinePreconditioner

    system = synthetic_system(kernels, load=20.0, indentation=None, omega=omega)
    nC, k = system.nC, system.n - 3 * system.nC
    assert k == (2 if omega is None else 1)
    monkeypatch.setattr(system, "global_rows", lambda X: np.zeros((k, X.shape[1])))
    r = np.random.default_rng(5).normal(size=system.n)
    LinePreconditioner(dtype=np.float64, options=SolverOptions(filter_power=0)).attach(system)
    got = system.precondition(r)
    np.testing.assert_allclose(_line_blocks(system) @ got[:3 * nC], r[:3 * nC], rtol=0, atol=1e-10 * np.abs(r).max())
    assert got[system.iD] == r[system.iD]
    if omega is None:
        assert got[system.iO] == r[system.iO] / system.ax


def test_line_preconditioner_columns_in_many_batches(kernels):
    """With one run length a batch (``chunk`` 1) the missing columns come in many
    batches: every one computed once and the result still the exact inverse of the run
    blocks (a batch counter that does not advance never ends)."""
    from bem.frictional import SolverOptions
    from bem.frictional import preconditioner as P

    system = synthetic_system(kernels)
    pre = P.LinePreconditioner(dtype=np.float64, options=SolverOptions(chunk=1, filter_power=0))
    pre.attach(system)
    lengths = {n for n, _ in _slip_columns(system)}
    assert len(lengths) > 2 and pre.factorised == len(_slip_columns(system))
    x = np.random.default_rng(9).normal(size=system.n)
    assert np.abs(system.precondition(_line_blocks(system) @ x) - x).max() < 1e-10 * np.abs(x).max()


@pytest.mark.parametrize("keep", [0, 1])
def test_line_preconditioner_is_exact_with_no_or_one_slip_node(kernels, keep):
    """Every slip node but ``keep`` flipped to stick: with none the runs' blocks are
    Toeplitz and no columns are computed; with one, one run has a 2 x 2 Woodbury matrix.
    Either way the result is the exact inverse of the run blocks."""
    from bem.frictional.preconditioner import LinePreconditioner

    system = synthetic_system(kernels, seed=2)
    state = synthetic_system(kernels, seed=2, flip=system.C[system.B[keep:]])
    assert state.B.size == keep
    pre = LinePreconditioner(dtype=np.float64, options=SolverOptions(filter_power=0))
    pre.attach(state)
    assert pre.factorised == keep
    x = np.random.default_rng(7).normal(size=state.n)
    assert np.abs(state.precondition(_line_blocks(state) @ x) - x).max() < 1e-10 * np.abs(x).max()
