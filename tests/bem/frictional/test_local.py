"""bem.frictional.local: the local row solves hold their rows and test their window as the
active set does; in the active set they are kept only when they change more nodes.
"""

import numpy as np
import pytest

from bem import Loading, Problem, Sphere, influence_kernels
from bem.frictional import Friction
from bem.frictional import solve_friction
from bem.spectral import BLOCKS
from tests.bem.frictional.row_states import GRID, LAYER, V, synthetic_row_system, synthetic_state


@pytest.fixture(scope="module")
def kernels():
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)


def problem(indenter=Sphere(0.02), load=150.0):
    return Problem(LAYER, indenter, GRID, Loading(V, load=load))


def test_local_row_solves_hold_their_rows_and_test_the_window_as_the_active_set(kernels, monkeypatch):
    """bem.frictional.local.solve_rows, one round, on a synthetic state (random stick/slip
    split, directions and slopes; random forces): the tangential forces change only on the
    contact nodes within ``local_window`` (4 here) of a changed node along its row, and
    there the system's x and y rows hold after the round (b - A x by the FFT product, below 1e-9 of the residual
    before: the window's blocks are exact and the other forces held); the window's sets
    then follow the active set's tests on that solution (cone excess: slip; slip against
    the force: stick), its slip nodes take S / |S| and max(|w|, floor) / (mu N), and
    nothing outside the window changes. A singular window changes nothing (0 rounds)."""
    import bem.frictional.local as local
    from bem.frictional import SetState, SetSystem, SolverOptions

    options = SolverOptions(local_rounds=1, local_window=4)  # narrower than the contact's rows here
    system, C = synthetic_row_system(kernels, None, 1e-4, 2.4)
    setup, ops = system.setup, system.ops
    _, _, _, stick, e, k, ell, _ = synthetic_state(kernels)
    # and contact nodes at the ends of a row and of its neighbours, where a window that
    # ran past the row's end would reach the next row's first or the last row's last node
    Ky, Kx = GRID.shape
    j0 = Ky // 2
    edge = np.array([j0 * Kx, j0 * Kx + 1, j0 * Kx + Kx - 2, j0 * Kx + Kx - 1, j0 * Kx - 1, (j0 + 1) * Kx])
    C = np.union1d(C, edge)
    contact = np.zeros(stick.size, bool)
    contact[C] = True
    state = SetState(contact=contact, stick=stick & contact, direction=np.where(contact[:, None], e, 0.0),
                     slope=np.where(contact, k, 0.0))
    rng = np.random.default_rng(11)
    N, Sx, Sy = (np.zeros(stick.size) for _ in range(3))
    N[C] = 150.0 / C.size * rng.uniform(0.5, 1.5, C.size)
    Sx[C], Sy[C] = (0.3 * N[C] * rng.uniform(-1, 1, C.size) for _ in range(2))
    fields = [f.ravel() for f in ops.fields(*(a.reshape(GRID.shape) for a in (N, Sx, Sy)))]
    changed = np.r_[C[[C.size // 3, C.size // 2]], edge[[1, 2]]]
    floor = 1e-3 * V
    new, Sx2, Sy2, rounds = local.solve_rows(setup, state, changed, N, Sx, Sy, 2.4, fields, floor, options)
    assert rounds == 1 and new.contact is state.contact
    window = np.zeros(stick.size, bool)
    for j, i in zip(*np.divmod(changed, Kx)):
        window[j * Kx + max(0, i - options.local_window):j * Kx + min(Kx, i + options.local_window + 1)] = True
    window &= contact
    moved = (Sx2 != Sx) | (Sy2 != Sy)
    assert not (moved & ~window).any() and moved.sum() >= 0.9 * window.sum()
    full = SetSystem(setup, state)
    at = np.searchsorted(full.C, np.flatnonzero(window))
    nC = full.nC
    rows = np.concatenate([nC + at, 2 * nC + at])
    before = full.b - full.matvec(full.unknowns(N, Sx, Sy, 1e-4, 2.4))
    after = full.b - full.matvec(full.unknowns(N, Sx2, Sy2, 1e-4, 2.4))
    assert np.abs(after[rows]).max() < 1e-9 * np.abs(before[rows]).max()
    _, sx, sy = (f.ravel() for f in ops.fields(*(a.reshape(GRID.shape) for a in (N, Sx2, Sy2))))
    wx, wy = V * (1 + sx) - 2.4 * ell, V * sy
    smag = np.hypot(Sx2, Sy2)
    to_slip = state.stick & (smag > 0.2 * N * (1 + 1e-10))
    to_stick = contact & ~state.stick & (wx * Sx2 + wy * Sy2 <= 0)
    expect = np.where(window, (state.stick & ~to_slip) | to_stick, state.stick)
    assert np.array_equal(new.stick, expect) and to_slip[window].any() and to_stick[window].any()
    slip = window & ~new.stick
    np.testing.assert_allclose(new.direction[slip], np.stack([Sx2, Sy2], 1)[slip] / smag[slip, None], atol=1e-12)
    speed = np.where(to_slip, 0.0, np.hypot(wx, wy))
    np.testing.assert_allclose(new.slope[slip], np.maximum(speed, floor)[slip] / (0.2 * N[slip]), rtol=1e-9)
    outside = ~window
    assert np.array_equal(new.direction[outside], state.direction[outside])
    assert np.array_equal(new.slope[outside], state.slope[outside])
    assert not new.slope[window & new.stick].any() and not new.direction[window & new.stick].any()

    def singular(a, b):
        raise np.linalg.LinAlgError("singular")

    monkeypatch.setattr(np.linalg, "solve", singular)
    same, Sx3, Sy3, rounds = local.solve_rows(setup, state, changed, N, Sx, Sy, 2.4, fields, floor, options)
    assert rounds == 0 and same is state and Sx3 is Sx and Sy3 is Sy


def test_local_rows_after_a_few_changes_are_kept_only_when_they_change_more(kernels, monkeypatch):
    """In the active set (GMRES solves, dense_limit = 0; ``local_from`` lowered to 1 node):
    after a solve with 1 to ``few_changes`` stick/slip changes and no contact change, the
    local row solves run on
    those nodes; their result is kept when it changes more nodes (more than one round);
    otherwise it is dropped, bit for bit (a stub returning other forces in one round
    changes nothing). Every loose solve reduces by ``loose_reduction``."""
    import bem.frictional.active_set as active_set
    from bem.frictional import SolverOptions

    calls, reductions, lines = [], [], []
    real_rows, real_call = active_set.solve_rows, active_set.LinearSolves.__call__

    def rows(setup, state, changed, *args):
        out = real_rows(setup, state, changed, *args)
        calls.append((changed.size, out[3]))
        return out

    def call(self, system, guess=None, reduction=None, of_b=False):
        reductions.append(reduction)
        return real_call(self, system, guess, reduction, of_b)

    # local rows from 1 node on (this contact has 67 nodes); solves at 1e-4 take a path that
    # meets both outcomes (at 3e-3 one round only)
    options = SolverOptions(local_from=1, loose_reduction=1e-4)
    monkeypatch.setattr(active_set, "solve_rows", rows)
    monkeypatch.setattr(active_set.LinearSolves, "__call__", call)
    friction = Friction(0.2, mode="towed", dense_limit=0)
    res, _ = solve_friction(problem(), friction, kernels=kernels, energy=False, progress=lines.append,
                            options=options)
    fine = [line for line in lines if not line.startswith("coarse")]
    assert [c[1] > 1 for c in calls] == [True, False]  # measured: 17 changes, 2 rounds; 2, 1
    assert all(0 < c[0] <= options.few_changes for c in calls)
    steps = [line for line in fine if line.startswith("friction ")]
    assert len(steps) == len(reductions) == res.record.iterations
    kept = [i for i, line in enumerate(fine) if line.startswith("  local rows")]
    for i, line in enumerate(steps[:-1]):
        if reductions[i + 1] is not None:  # a loose solve
            assert reductions[i + 1] == options.loose_reduction, line
    assert len(kept) == 1

    # one round: the stub's forces are dropped, the run is the same bit for bit
    def stub(setup, state, changed, N, Sx, Sy, *args):
        return state, 2 * Sx, 0 * Sy, 1

    monkeypatch.setattr(active_set, "solve_rows", stub)
    monkeypatch.setattr(active_set.LinearSolves, "__call__", real_call)
    dropped, _ = solve_friction(problem(), friction, kernels=kernels, energy=False, options=options)
    monkeypatch.setattr(active_set, "solve_rows", lambda setup, state, changed, N, Sx, Sy, *a: (state, Sx, Sy, 1))
    same, _ = solve_friction(problem(), friction, kernels=kernels, energy=False, options=options)
    assert np.array_equal(dropped.force_x, same.force_x) and np.array_equal(dropped.stick, same.stick)
    assert np.array_equal(same.stick, res.stick)


def test_local_row_solves_take_the_default_options_without_any(kernels):
    """Without options the local rows are those of ``SolverOptions()`` (a window of 8, up
    to 8 rounds), bit for bit; a narrower window moves fewer forces."""
    import bem.frictional.local as local
    from bem.frictional import SetState, SolverOptions

    system, C = synthetic_row_system(kernels, None, 1e-4, 2.4)
    setup, ops = system.setup, system.ops
    _, _, _, stick, e, k, _, _ = synthetic_state(kernels)
    contact = np.zeros(stick.size, bool)
    contact[C] = True
    state = SetState(contact=contact, stick=stick & contact, direction=np.where(contact[:, None], e, 0.0),
                     slope=np.where(contact, k, 0.0))
    rng = np.random.default_rng(11)
    N, Sx, Sy = (np.zeros(stick.size) for _ in range(3))
    N[C] = 150.0 / C.size * rng.uniform(0.5, 1.5, C.size)
    Sx[C], Sy[C] = (0.3 * N[C] * rng.uniform(-1, 1, C.size) for _ in range(2))
    fields = [f.ravel() for f in ops.fields(*(a.reshape(GRID.shape) for a in (N, Sx, Sy)))]
    changed = C[[C.size // 3, C.size // 2]]
    args = (setup, state, changed, N, Sx, Sy, 2.4, fields, 1e-3 * V)
    plain, given = local.solve_rows(*args), local.solve_rows(*args, SolverOptions())
    assert plain[3] == given[3] >= 1
    for a, b in zip(plain[1:3], given[1:3]):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(plain[0].stick, given[0].stick)
    narrow = local.solve_rows(*args, SolverOptions(local_window=2))
    assert ((narrow[1] != Sx) | (narrow[2] != Sy)).sum() < ((plain[1] != Sx) | (plain[2] != Sy)).sum()

