"""bem.frictional.solve's starts: the coarse level (its start and forces, when it is skipped,
its shared frictionless solve, how it settles early), the frictionless start on a second
thread, and the fallbacks (a failed coarse solve or start, the continuation in mu, an
unreachable loading not continued); on a 25 x 25 grid with a 13 x 13 level.
"""

import re

import numpy as np
import pytest

from bem import Grid, Sphere, influence_kernels
from bem.contact import ContactAtEdge, solve_normal
from bem.frictional import Friction, FrictionNotConverged, LoadingUnreachable, SolverOptions, solve_friction
from bem.operator import ComplianceOperator
from bem.spectral import BLOCKS
from tests.bem.frictional.solve_checks import GRID, LAYER, R, V, _apply, check_result, problem


BIG = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (6.0e-3, 6.0e-3))  # 25 x 25: a coarse level


@pytest.fixture(scope="module")
def big_kernels():
    return influence_kernels(BIG, LAYER, V, blocks=BLOCKS)


MODES = [Friction(0.3), Friction(0.3, "towed"), Friction(0.4, "torque"),
         Friction(0.3, "omega", omega=0.99 * V / R), Friction(0.3, "omega", omega=0.0)]


def test_coarse_start_runs_and_ends_on_the_direct_state(big_kernels, monkeypatch):
    import bem.frictional.solve as fs

    friction = Friction(0.3)
    p = problem(grid=BIG)
    lines = []
    res, _ = solve_friction(p, friction, kernels=big_kernels, energy=False, progress=lines.append)
    check_result(res, p, friction, big_kernels)
    coarse = [ln for ln in lines if ln.startswith("coarse 13 x 13: ")]
    assert coarse and all(re.match(r"coarse 13 x 13: friction \d+: ", ln) for ln in coarse)
    assert lines[len(coarse)].startswith("friction 1: ")  # the coarse solve comes first
    quiet, _ = solve_friction(p, friction, kernels=big_kernels, energy=False)  # no progress: no label
    np.testing.assert_array_equal(quiet.stick, res.stick)
    seen = []
    real = fs.coarse_start

    def spy(*args):
        seen.append(args)
        return real(*args)

    monkeypatch.setattr(fs, "coarse_start", spy)
    solve_friction(p, friction, kernels=big_kernels, energy=False)
    (cres, shape, N0, mu), = seen
    assert cres.grid.shape == (13, 13) and shape == (25, 25) and mu == 0.3 and N0.shape == (625,)
    assert cres.load == pytest.approx(20.0, rel=1e-12)
    monkeypatch.setattr(fs, "_coarse_solution", lambda *a: None)
    direct, _ = solve_friction(p, friction, kernels=big_kernels, energy=False)
    assert np.array_equal(direct.stick, res.stick) and np.array_equal(direct.contact, res.contact)
    np.testing.assert_allclose(direct.force_x, res.force_x, rtol=0, atol=1e-9 * res.force.max())


def test_a_dense_coarse_level_under_a_gmres_level_is_skipped(big_kernels):
    """The coarse 13 x 13 level is solved when it and the 25 x 25 grid are both dense
    (the default ``dense_limit``) or both by GMRES, and skipped when it alone would be
    dense (``dense_limit`` between its unknowns and four times them): the fine grid then
    starts from its frictionless start and ends on the same state."""
    p = problem(grid=BIG)
    X, Y = BIG.coordinates()
    normal = solve_normal(ComplianceOperator(BIG, big_kernels["ww"]), p.indenter.profile(X, Y), load=20.0,
                          dense_limit=0, rtol=1e-11)
    nodes = int((normal.coarse.force > 0).sum())  # the coarse level's contact
    assert normal.coarse.grid.shape == (13, 13) and nodes > 10
    glob = 1 + (Friction(0.3).omega is None)  # d (load control) and a free Omega
    states = {}
    for limit, coarse in ((Friction(0.3).dense_limit, True), (0, True), (3 * nodes + glob, False),
                          (12 * nodes + glob - 1, False), (12 * nodes + glob, True), (3 * nodes + glob - 1, True)):
        lines = []
        res, _ = solve_friction(p, Friction(0.3, dense_limit=limit), kernels=big_kernels, energy=False,
                                progress=lines.append)
        assert any(ln.startswith("coarse 13 x 13: friction 1: ") for ln in lines) == coarse, limit
        states[limit] = res
    first = states[Friction(0.3).dense_limit]
    for res in states.values():
        assert np.array_equal(res.stick, first.stick) and np.array_equal(res.contact, first.contact)
        np.testing.assert_allclose(res.force_x, first.force_x, rtol=0, atol=1e-9 * first.force.max())


def test_the_coarse_level_reuses_the_fine_frictionless_solve_s_coarse_solution(big_kernels, monkeypatch):
    """One frictionless solve for the two levels: the coarse level is handed the fine
    solve's ``coarse`` (the same problem on every other node), and a coarse level that
    computes its own gets the same forces."""
    import bem.frictional.solve as fs

    real_normal, real_rolling = fs.solve_normal, fs.solve_rolling
    normals, handed, rtols = [], [], []

    def count(op, *args, **kw):
        out = real_normal(op, *args, **kw)
        normals.append(out)
        rtols.append(kw["rtol"])
        limits.append(kw["dense_limit"])
        return out

    limits = []

    def spy(ops, *args, normal=None, **kw):
        handed.append((ops.grid.shape, normal))
        return real_rolling(ops, *args, normal=normal, **kw)

    monkeypatch.setattr(fs, "solve_normal", count)
    monkeypatch.setattr(fs, "solve_rolling", spy)
    friction = Friction(0.3)
    res, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False)
    assert [n.grid.shape for n in normals] == [(25, 25)] and rtols == [SolverOptions().start_rtol] == [1e-8]
    assert limits == [friction.dense_limit // 3] == [200]  # 3 unknowns a node with friction
    assert [shape for shape, _ in handed] == [(25, 25), (13, 13)]
    assert handed[0][1] is None and handed[1][1] is normals[0].coarse is not None
    own = real_normal(ComplianceOperator(normals[0].coarse.grid, big_kernels["ww"][::2, ::2]),
                      Sphere(R).profile(*normals[0].coarse.grid.coordinates()), load=20.0, dense_limit=333,
                      rtol=1e-8)
    np.testing.assert_array_equal(own.force, normals[0].coarse.force)
    # without friction the frictionless solve is the result: solve_normal's own tolerance
    normals.clear(), rtols.clear(), handed.clear()
    solve_friction(problem(grid=BIG), Friction(0.0, "towed"), kernels=big_kernels, energy=False)
    assert rtols == [1e-11] and [shape for shape, _ in handed] == [(25, 25)]  # no coarse frictional level


def test_the_frictionless_start_on_a_second_thread_changes_nothing(big_kernels, monkeypatch):
    """From ``overlap_from`` nodes on, the fine frictionless solve runs on a second thread
    while the coarse levels solve, from the coarse frictionless solution solved first
    (once: the coarse level is handed it): the result is bit for bit the one-thread
    result, the fine solves' preconditioner prepared there on the frictionless contact,
    the transforms of both threads on one worker each meanwhile (``one_worker``), and the
    fine grid's field spectra built once, by the thread free first; below it
    everything runs on the caller's thread."""
    import threading

    import bem.frictional.solve as fs
    from bem import operator as op_module
    from bem.frictional.operators import RollingOperators

    real_normal = fs.solve_normal
    calls = []
    workers = []
    real_fields = RollingOperators.fields

    def fields(self, *a):
        if self.grid.shape == (25, 25) and not any(np.any(f) for f in a):  # the spectra's build
            workers.append((threading.current_thread() is threading.main_thread(), op_module._ONE_WORKER))
        return real_fields(self, *a)

    monkeypatch.setattr(RollingOperators, "fields", fields)

    def spy(op, *args, **kw):
        workers.append(op_module._ONE_WORKER)
        calls.append((op.grid.shape, threading.current_thread() is threading.main_thread(), kw.get("coarse")))
        if not calls[-1][1]:
            names.append(threading.current_thread().name)
        normals.append(real_normal(op, *args, **kw))
        return normals[-1]

    names = []

    normals = []
    monkeypatch.setattr(fs, "solve_normal", spy)
    friction = Friction(0.3, dense_limit=0)  # GMRES and the line preconditioner on every level
    one, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False)
    assert [c[:2] for c in calls] == [((25, 25), True)] and SolverOptions().overlap_from > 625
    calls.clear()
    overlap = SolverOptions(overlap_from=625)  # a second thread from this grid's 625 nodes on
    prepared = []
    real_prepare = fs.LinearSolves.prepare

    def prepare(self, system):
        inverses = self.lines.inverses
        real_prepare(self, system)
        prepared.append((threading.current_thread() is threading.main_thread(), system.nC, inverses,
                         self.lines.inverses, system.stick.all()))

    monkeypatch.setattr(fs.LinearSolves, "prepare", prepare)
    workers.clear()
    two, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False, options=overlap)
    # the fine frictionless solve (second thread) and the fine fields' spectra (built once,
    # by either thread, before the fine grid's first measure) on one worker each, every
    # core after
    assert sorted(workers, key=str) in ([(False, 1), 1], [(True, 1), 1]) and op_module._ONE_WORKER == 0
    (shape, main, coarse), = calls
    assert shape == (25, 25) and not main and coarse is not None and coarse.grid.shape == (13, 13)
    assert names == ["frictionless-start_0"]
    # the fine grid's solves prepared on the same thread, on the frictionless contact, all in stick
    (main, nC, before, after, all_stick), = prepared
    assert not main and before is None and after is not None and all_stick and nC == (normals[-1].force > 0).sum()
    # without friction the frictionless solve is the result: on the caller's thread, no
    # coarse frictional level
    calls.clear()
    levels = []
    real_coarse = fs._coarse_solution
    monkeypatch.setattr(fs, "_coarse_solution", lambda *a: levels.append(a) or real_coarse(*a))
    solve_friction(problem(grid=BIG), Friction(0.0, "towed"), kernels=big_kernels, energy=False, options=overlap)
    assert [c[:2] for c in calls] == [((25, 25), True)] and levels == []
    for a, b in ((one.force, two.force), (one.force_x, two.force_x), (one.force_y, two.force_y)):
        np.testing.assert_array_equal(a, b)
    assert np.array_equal(one.stick, two.stick) and one.record == two.record


def test_an_error_on_the_second_thread_reaches_the_caller(big_kernels, monkeypatch):
    """A fine frictionless solve that fails on the second thread raises from
    ``solve_friction`` once the coarse levels are done, as on one thread."""
    import bem.frictional.solve as fs

    real_normal = fs.solve_normal

    def fails(op, *args, **kw):
        if op.grid.shape == (25, 25):
            raise ContactAtEdge("planted on the fine grid")
        return real_normal(op, *args, **kw)

    monkeypatch.setattr(fs, "solve_normal", fails)
    lines = []
    with pytest.raises(ContactAtEdge, match="planted on the fine grid"):
        solve_friction(problem(grid=BIG), Friction(0.3), kernels=big_kernels, energy=False, progress=lines.append,
                       options=SolverOptions(overlap_from=625))
    assert any(ln.startswith("coarse 13 x 13: friction") for ln in lines)


def test_coarse_solve_that_fails_is_skipped(big_kernels, monkeypatch):
    """A ContactError on the coarse grid: no coarse start, the all-stick start solves."""
    import bem.frictional.solve as fs

    real = fs.solve_rolling
    shapes = []

    def coarse_fails(ops, *args, **kw):
        shapes.append(ops.grid.shape)
        if ops.grid.shape == (13, 13):
            raise ContactAtEdge("planted")
        return real(ops, *args, **kw)

    monkeypatch.setattr(fs, "solve_rolling", coarse_fails)
    friction = Friction(0.3)
    lines = []
    res, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False, progress=lines.append)
    assert shapes == [(25, 25), (13, 13)] and not any(ln.startswith("coarse") for ln in lines)
    check_result(res, problem(grid=BIG), friction, big_kernels)


def test_failed_coarse_start_falls_back_to_all_stick(big_kernels, monkeypatch):
    import bem.frictional.solve as fs

    real = fs.run_active_set
    starts = []

    def first_fails(setup, friction, start, solves, progress=None, settle=None, forces=None, options=None):
        starts.append((setup.ops.grid.shape, start))
        guesses.append((setup.ops.grid.shape, forces))
        if setup.ops.grid.shape == (25, 25) and len([s for s in starts if s[0] == (25, 25)]) == 1:
            raise FrictionNotConverged("planted")
        return real(setup, friction, start, solves, progress, settle, forces, options)

    guesses = []

    monkeypatch.setattr(fs, "run_active_set", first_fails)
    lines = []
    friction = Friction(0.1)  # the coarse grid's start has 4 slip nodes of 67
    res, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False, progress=lines.append)
    fine = [s for shape, s in starts if shape == (25, 25)]
    assert len(fine) == 2
    assert not (fine[1].contact & ~fine[1].stick).any()  # the second start: all stick
    assert (fine[0].contact & ~fine[0].stick).any()  # the first: the coarse grid's, with slip
    assert "friction: the coarse grid's start failed (planted); starting from all stick" in lines
    # the coarse start brings the coarse forces as the first iterate; the all-stick one none
    fine_forces = [f for shape, f in guesses if shape == (25, 25)]
    assert fine_forces[0] is not None and len(fine_forces[0]) == 5 and fine_forces[1] is None
    check_result(res, problem(grid=BIG), friction, big_kernels)


@pytest.mark.parametrize("mode, omega", [("towed", None), ("omega", 2.4)])
def test_a_failed_direct_solve_continues_in_mu_unless_omega_is_given(kernels, monkeypatch, mode, omega):
    import bem.frictional.solve as fs

    def fails(*args, **kw):
        raise FrictionNotConverged("planted")

    calls = []

    def continuation(setup, friction, N0, solves, progress, cause, options=None):
        calls.append((friction, cause, N0.sum(), setup.mu, progress))
        raise RuntimeError("continued")

    monkeypatch.setattr(fs, "run_active_set", fails)
    monkeypatch.setattr(fs, "continuation", continuation)
    friction = Friction(0.3, mode, omega=omega)
    if mode == "omega":
        with pytest.raises(FrictionNotConverged, match="^planted$"):
            solve_friction(problem(), friction, kernels=kernels, energy=False)
        assert not calls
    else:
        lines = []
        with pytest.raises(RuntimeError, match="continued"):
            solve_friction(problem(), friction, kernels=kernels, energy=False, progress=lines.append)
        (f, cause, load, mu, progress), = calls
        assert progress == lines.append
        assert f is friction and str(cause) == "planted" and load == pytest.approx(20.0) and mu == 0.3


def test_unreachable_loading_is_not_continued(kernels, monkeypatch):
    import bem.frictional.solve as fs

    def unreachable(*args, **kw):
        raise LoadingUnreachable("planted")

    monkeypatch.setattr(fs, "run_active_set", unreachable)
    monkeypatch.setattr(fs, "continuation", lambda *a: pytest.fail("continued"))
    with pytest.raises(LoadingUnreachable, match="^planted$"):
        solve_friction(problem(), Friction(0.3), kernels=kernels, energy=False)


def test_displacement_control_with_a_coarse_start(big_kernels):
    """d given on the 25 x 25 grid: the coarse level solves under displacement control too."""
    friction = Friction(0.3, "towed")
    p = problem(grid=BIG, indentation=1.0e-4)
    lines = []
    res, _ = solve_friction(p, friction, kernels=big_kernels, energy=False, progress=lines.append)
    check_result(res, p, friction, big_kernels)
    assert any(ln.startswith("coarse 13 x 13: friction 1: ") for ln in lines)


def test_coarse_level_settles_without_the_tight_solve(big_kernels, monkeypatch):
    """The coarse level ends as soon as its sets repeat with a slip misfit of at most
    ``coarse_settle``: its history is the converged one's, cut short; the fine grid converges
    fully (settle None, as the coarse level with ``coarse_settle = None``) to the same state."""
    import bem.frictional.solve as fs

    real = fs.run_active_set
    calls = []

    def spy(setup, friction, start, solves, progress=None, settle=None, forces=None, options=None):
        out = real(setup, friction, start, solves, progress, settle, forces, options)
        calls.append((setup.ops.grid.shape, settle, out.history))
        return out

    monkeypatch.setattr(fs, "run_active_set", spy)
    p, friction = problem(grid=BIG), MODES[3]  # omega = 0.99 V / R: the coarse level slips
    settled, _ = solve_friction(p, friction, kernels=big_kernels, energy=False)
    (cshape, csettle, chist), (fshape, fsettle, _) = calls
    assert (cshape, csettle, fshape, fsettle) == ((13, 13), 0.3, (25, 25), None) and SolverOptions().coarse_settle == 0.3
    assert friction.direction_tol < chist[-1][2] <= 0.3
    calls.clear()
    full, _ = solve_friction(p, friction, kernels=big_kernels, energy=False, options=SolverOptions(coarse_settle=None))
    converged = calls[0][2]
    assert calls[0][1] is None and converged[-1][2] <= friction.direction_tol
    assert chist == converged[:len(chist)] and len(chist) < len(converged)
    assert np.array_equal(full.stick, settled.stick) and np.array_equal(full.contact, settled.contact)
    np.testing.assert_allclose(full.force_x, settled.force_x, rtol=0, atol=1e-9 * full.force.max())


@pytest.mark.parametrize("fraction", [0.0, 0.05, 0.1, 1.0])
@pytest.mark.parametrize("friction", MODES[:4] + [Friction(0.3, "omega", omega=0.98 * V / R)],
                         ids=lambda f: f"{f.mode}-{f.omega}")
def test_a_coarse_level_ends_with_a_few_set_changes_left(big_kernels, friction, fraction):
    """The coarse level ends at its first solve whose slip misfit is at most
    ``coarse_settle`` and whose sets change by at most ``settle_changes`` of its contact nodes
    (read from its progress lines); 0 waits for the sets to repeat. (With ``Omega = 0.98
    V / R`` the 21 coarse contact nodes change by 8, 2, 2, 0 at misfits 0.036, 0.195, 0.019,
    1e-4: 4, 4, 2 and 1 solves for the four fractions.) The fine grid ends on the state it
    reaches from the default."""
    lines = []
    res, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False, progress=lines.append,
                            options=SolverOptions(settle_changes=fraction))
    steps = [re.match(r"coarse 13 x 13: friction \d+: (\d+) contact, .* -(\d+) \+(\d+) contact, \+(\d+) slip, "
                      r"\+(\d+) stick, slip misfit (\S+)", ln) for ln in lines if ln.startswith("coarse 13 x 13: ")]
    assert steps and all(steps)
    ends = [int(m[2]) + int(m[3]) + int(m[4]) + int(m[5]) <= fraction * int(m[1]) and float(m[6]) <= 0.3
            for m in steps]
    assert ends[-1] and not any(ends[:-1])
    if friction.omega == 0.98 * V / R:
        assert len(steps) == {0.0: 4, 0.05: 4, 0.1: 2, 1.0: 1}[fraction]
    ref, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False,
                            options=SolverOptions(settle_changes=0.01))
    assert np.array_equal(res.stick, ref.stick) and np.array_equal(res.contact, ref.contact)
    np.testing.assert_allclose(res.force_x, ref.force_x, rtol=0, atol=1e-9 * ref.force.max())
