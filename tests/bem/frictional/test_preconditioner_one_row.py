"""bem.frictional.preconditioner and bem.frictional.system on a sphere's contact: the
matrix-free product against the dense system, the line preconditioner exact on a contact
on one grid row (both Woodbury forms, its kept inverses told apart by run length and slip
places), and the row-coupling block it leaves out.
"""

import numpy as np
import pytest

from bem import influence_kernels
from bem.spectral import BLOCKS
from tests.bem.frictional.row_states import GRID, LAYER, V, synthetic_row_system, synthetic_state


@pytest.fixture(scope="module")
def kernels():
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)


@pytest.mark.parametrize("load, indentation, omega", [(150.0, None, None), (None, 1e-4, 2.4)])
def test_matrix_free_product_equals_the_densesynthetic_row_system(kernels, load, indentation, omega):
    """The FFT product of the active-set system equals its dense matrix (both come from
    the same row definitions, the blocks from different code: dense tables vs FFT)."""
    system, C = synthetic_row_system(kernels, load, indentation, omega)
    assert system.n == 3 * C.size + (load is not None) + (omega is None)
    M = system.dense()
    x = np.random.default_rng(3).normal(size=system.n)
    x[:C.size] *= 1e-3  # forces of the scale of a nodal force
    ref = M @ x
    np.testing.assert_allclose(system.matvec(x), ref, rtol=0, atol=1e-12 * np.abs(ref).max())


@pytest.mark.parametrize("compose", [16, 0], ids=["K-inverse", "factors"])
def test_line_preconditioner_inverts_a_contact_on_one_grid_row(kernels, monkeypatch, compose):
    """With every contact node on one grid row (stick and slip mixed; Omega and d given,
    so no global unknowns) and the layer's normal-tangential coupling blocks set to zero
    (the preconditioner leaves them out), the line preconditioner is the exact inverse:
    M A x = x (the inverse of the running sum, the displacement ahead of each run and the
    slip rows are all in the run's block). With the coupling, or on two rows, it is not.
    In double precision the inverse is exact to 1e-12 (|x| ~ 1; measured 1e-15); in
    single precision (the default) to 1e-5 (measured 3e-7). Both forms of the Woodbury
    term: ``K^{-1}`` composed (the run's 8 padded slip places) and its factors applied."""
    from bem.frictional import SetState, SetSystem, SolverOptions
    from bem.frictional.preconditioner import LinePreconditioner

    options = SolverOptions(compose_upto=compose)

    Ky, Kx = GRID.shape
    row = (Ky // 2) * Kx + np.arange(Kx // 2 - 6, Kx // 2 + 6)
    two = np.concatenate([row, row + Kx])
    uncoupled = {b: (np.zeros_like(k) if b in ("wu", "wv", "uw", "vw") else k) for b, k in kernels.items()}
    x = np.random.default_rng(7).normal(size=3 * two.size)
    for kern, nodes, exact in ((uncoupled, row, True), (kernels, row, False), (uncoupled, two, False)):
        system, C = synthetic_row_system(kern, None, 1e-4, 2.4, contact=nodes)
        assert 0 < system.A.size < C.size
        y = x[:system.n]
        for dtype, tol in ((np.float64, 1e-12), (np.float32, 1e-5)):
            lines = LinePreconditioner(dtype=dtype, options=options)
            lines.attach(system)
            err = np.abs(system.precondition(system.matvec(y)) - y).max()
            assert (err < tol) if exact else (err > 1e-3), (dtype, err)
            if exact:
                # other slip directions and slopes on the same slip places: the inverses the
                # first attach kept are reused, and the solve is still exact
                _, _, _, stick, e, k, _, _ = synthetic_state(kern)
                inside = np.zeros(stick.size, bool)
                inside[nodes] = True
                other = SetSystem(system.setup, SetState(contact=inside, stick=stick & inside, direction=e[:, ::-1],
                                                         slope=2.5 * k))
                kept, inverted, inv = dict(lines._blocks), [], np.linalg.inv

                def counting(a):
                    inverted.append(a.ndim)
                    return inv(a)

                monkeypatch.setattr(np.linalg, "inv", counting)
                lines.attach(other)
                monkeypatch.setattr(np.linalg, "inv", inv)
                assert inverted == [3] and lines._blocks.keys() == kept.keys()  # H alone: no G_x, G_y
                assert all(np.array_equal(lines._blocks[key], kept[key]) for key in kept)
                err = np.abs(other.precondition(other.matvec(y)) - y).max()
                assert err < tol, (dtype, err)
    # nine slip nodes in the run (more than one block of 8 padded places), three stick
    system, C = synthetic_row_system(uncoupled, None, 1e-4, 2.4, contact=row)
    _, _, _, _, e, k, _, _ = synthetic_state(uncoupled)
    inside = np.zeros(e.shape[0], bool)
    inside[row] = True
    stick = np.zeros_like(inside)
    stick[row[[0, 5, 11]]] = True
    nine = SetSystem(system.setup, SetState(contact=inside, stick=stick, direction=e, slope=k))
    assert nine.B.size == 9
    LinePreconditioner(dtype=np.float64).attach(nine)
    y = x[:nine.n]
    assert np.abs(nine.precondition(nine.matvec(y)) - y).max() < 1e-12
    # two runs of 3 and 9 slip nodes (two groups of padded sizes): the same on one thread
    inside[row + Kx] = True
    stick[row + Kx] = True
    stick[row[[0, 5, 11]] + Kx] = False
    both = SetSystem(system.setup, SetState(contact=inside, stick=stick, direction=e, slope=k))
    out = []
    for threads in (True, False):
        LinePreconditioner(dtype=np.float64, threads=threads).attach(both)
        out.append(both.precondition(x[:both.n]))
    np.testing.assert_allclose(out[1], out[0], rtol=0, atol=1e-12 * np.abs(out[0]).max())


def test_kept_woodbury_inverses_are_told_apart_by_run_length_and_slip_places(kernels):
    """The ``G_x, G_y`` inverses a preconditioner keeps are looked up by the run's length and
    its slip places. A run of 12 nodes slipping at places 0-9 and, later, a run of 20
    slipping at 1-9 (10 and 9 slip nodes, both padded to 16) must not share them: with the
    length written as ``bytes(n)`` (n zero bytes) their keys would be
    the same, the second attach would reuse the first run's inverses and the solve be off; a
    run of 9 slip nodes after one of 8 (16 and 8 padded places) would raise a shape error
    (as section 11 at 513 x 513 meets). On one grid row without the coupling blocks the solve is
    exact (see the test above), so each attach is checked against its own blocks."""
    from bem.frictional import SetState, SetSystem
    from bem.frictional.preconditioner import LinePreconditioner

    Ky, Kx = GRID.shape
    uncoupled = {b: (np.zeros_like(k) if b in ("wu", "wv", "uw", "vw") else k) for b, k in kernels.items()}
    system, _ = synthetic_row_system(uncoupled, None, 1e-4, 2.4, contact=(Ky // 2) * Kx + np.arange(12))
    _, _, _, _, e, k, _, _ = synthetic_state(uncoupled)
    lines = LinePreconditioner(dtype=np.float64)
    for length, slip in ((12, range(10)), (20, range(1, 10)), (12, range(10)), (20, range(1, 10)),
                         (12, range(8)), (20, range(9))):
        nodes = (Ky // 2) * Kx + np.arange(length)
        inside = np.zeros(e.shape[0], bool)
        inside[nodes] = True
        stick = inside.copy()
        stick[nodes[list(slip)]] = False
        one = SetSystem(system.setup, SetState(contact=inside, stick=stick, direction=e, slope=k))
        lines.attach(one)
        y = np.random.default_rng(length).normal(size=one.n)
        err = np.abs(one.precondition(one.matvec(y)) - y).max()
        assert err < 1e-12, (length, list(slip), err)
    assert len(lines._blocks) == 1  # the last run's, kept


def test_a_row_coupling_uv_block_is_left_out_of_the_runs(kernels):
    """The runs' tangential blocks are ``a_x C_uu`` and ``a_x C_vv`` apart: the layer's
    ``uv`` blocks vanish on a grid row (checked). Kernels whose ``uv`` block couples a row
    (made so here) are not a layer's: the preconditioner leaves that coupling out and is
    no longer the exact inverse, yet GMRES still solves the system (to 1e-10 |b|)."""
    from bem.frictional.active_set import LinearSolves

    Ky, Kx = GRID.shape
    assert not kernels["uv"][Ky - 1].any() and not kernels["vu"][Ky - 1].any()
    row = (Ky // 2) * Kx + np.arange(Kx // 2 - 6, Kx // 2 + 6)
    kern = {b: (np.zeros_like(k) if b in ("wu", "wv", "uw", "vw") else k.copy()) for b, k in kernels.items()}
    x = np.random.default_rng(9).normal(size=3 * row.size)
    for coupled in (False, True):
        if coupled:  # an odd-in-x uv on the row y = 0
            for b in ("uv", "vu"):
                kern[b][Ky - 1] = 0.1 * kern["uu"][Ky - 1] * np.sign(np.arange(2 * Kx - 1) - (Kx - 1))
        system, _ = synthetic_row_system(kern, None, 1e-4, 2.4, contact=row)
        solves = LinearSolves(dense_limit=0)
        solves.lines.attach(system)
        err = np.abs(system.precondition(system.matvec(x)) - x).max() / np.abs(x).max()
        assert (err > 1e-3) if coupled else (err < 1e-5), (coupled, err)  # single precision: 6e-7
        N, Sx, Sy, _, _ = solves(system)
        got = system.unknowns(N, Sx, Sy, 1e-4, 2.4)
        ref = np.linalg.solve(system.dense(), system.b)
        assert np.abs(got - ref).max() < 1e-8 * np.abs(ref).max()
