"""bem.frictional.active_set and bem.frictional.solve, fast: every returned field and
figure recomputed from the returned forces and the definitions (eq. 51 with independent
FFT products of the raw kernels, the gap, the slip velocity, the Coulomb and stick
conditions, the loading modes' equilibrium, the record and the progress lines), the
solver's paths (mu = 0, the coarse-grid start, its fallbacks, the continuation) and its
messages whole; on 23 x 23 and 25 x 25 grids (solves of 20-90 ms)."""

import math
import re

import numpy as np
import pytest

from bem import Grid, Layer, Loading, Paraboloid, Problem, Sphere, ThreeParameterSolid, influence_kernels
from bem import solve_friction
from bem.contact import ContactAtEdge, ContactError, solve_normal
from bem.energy import viscous_dissipation
from bem.friction import Friction, FrictionNotConverged, LoadingUnreachable
from bem.kinematics import rolling_radius, upwind_table
from bem.operator import ComplianceOperator
from bem.spectral import BLOCKS

LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
R = 0.02
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (5.5e-3, 5.5e-3))  # 23 x 23, 529 nodes
BIG = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (6.0e-3, 6.0e-3))  # 25 x 25: a coarse level


@pytest.fixture(scope="module")
def kernels():
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)


@pytest.fixture(scope="module")
def big_kernels():
    return influence_kernels(BIG, LAYER, V, blocks=BLOCKS)


def problem(indenter=Sphere(R), grid=GRID, **loading):
    return Problem(LAYER, indenter, grid, Loading(V, **(loading or {"load": 20.0})))


def _apply(grid, table, f):
    return ComplianceOperator(grid, table).apply(f)


def check_result(res, p, friction, kernels, coulomb=1e-6):
    """Every field and figure of ``res`` from its forces and the definitions; returns the
    recomputed slip velocity magnitude on the slip nodes (for further checks)."""
    g, V_ = p.grid, p.loading.speed
    X, Y = g.coordinates()
    ax = g.spacing_x
    N, Sx, Sy = res.force, res.force_x, res.force_y
    scale = np.abs(N).max()
    K = kernels
    delta = _apply(g, K["ww"], N) - _apply(g, K["wu"], Sx) - _apply(g, K["wv"], Sy)
    u = -_apply(g, K["uw"], N) + _apply(g, K["uu"], Sx) + _apply(g, K["uv"], Sy)
    v = -_apply(g, K["vw"], N) + _apply(g, K["vu"], Sx) + _apply(g, K["vv"], Sy)

    def d(b):
        return upwind_table(K[b], ax)

    dux = -_apply(g, d("uw"), N) + _apply(g, d("uu"), Sx) + _apply(g, d("uv"), Sy)
    dvx = -_apply(g, d("vw"), N) + _apply(g, d("vu"), Sx) + _apply(g, d("vv"), Sy)
    for got, want in ((res.deflection, delta), (res.displacement_x, u), (res.displacement_y, v)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * np.abs(want).max())
    s = p.indenter.profile(X, Y)
    h = s - res.indentation + delta
    reach = np.isfinite(s)
    np.testing.assert_allclose(res.gap[reach], h[reach], rtol=0, atol=1e-12 * abs(res.indentation))
    assert np.array_equal(np.isfinite(res.gap), reach)
    contact = N > 0
    np.testing.assert_array_equal(res.contact, contact)
    assert contact.sum() > 20 and not (res.stick & ~contact).any()
    assert (N >= 0).all() and not Sx[~contact].any() and not Sy[~contact].any()
    d_ = res.indentation
    gap_res = max(np.abs(h[contact]).max(), (-h[reach & ~contact]).max(initial=0.0)) / abs(d_)
    assert res.record.gap_residual == pytest.approx(gap_res, rel=1e-6, abs=1e-13)
    assert res.record.gap_residual < 1e-8
    ell = rolling_radius(p.indenter, Y, friction.radius)
    arm = p.indenter.rolling_arm(X, Y)
    om = res.omega
    wx = V_ * (1 + dux) - om * ell
    wy = V_ * dvx
    st, sl = res.stick, contact & ~res.stick
    # slip velocity: w on slip nodes, exactly 0 on stick nodes and off the contact
    np.testing.assert_allclose(res.slip_x[sl], wx[sl], rtol=0, atol=1e-12 * V_)
    np.testing.assert_allclose(res.slip_y[sl], wy[sl], rtol=0, atol=1e-12 * V_)
    assert not res.slip_x[~sl].any() and not res.slip_y[~sl].any()
    stick_res = float(np.hypot(wx, wy)[st].max(initial=0.0) / V_)
    assert res.record.stick_residual == pytest.approx(stick_res, abs=1e-13)
    assert stick_res < 1e-9
    mu = friction.mu
    smag, wmag = np.hypot(Sx, Sy), np.hypot(wx, wy)
    cone = np.maximum(smag[st] / (mu * N[st]) - 1, 0).max(initial=0.0)
    mag = np.abs(smag[sl] / (mu * N[sl]) - 1).max(initial=0.0)
    ang = (1 - (Sx * wx + Sy * wy)[sl] / (smag * wmag)[sl]).max(initial=0.0)
    assert res.record.coulomb_residual == pytest.approx(max(cone, mag, ang), abs=1e-12)
    assert res.record.coulomb_residual < coulomb
    # Q, T, R_r and its parts, eqs. 1-3 and 63
    Q = float((N * arm).sum() + Sx.sum())
    T = float(-(ell * Sx).sum())
    assert res.driving_torque == pytest.approx(T, rel=1e-12, abs=1e-15 * scale)
    if friction.mode == "torque" and mu > 0:
        assert res.driving_force == 0.0 and abs(Q) < 1e-10 * scale
    else:
        assert res.driving_force == pytest.approx(Q, rel=1e-12, abs=1e-15 * scale)
    if friction.mode == "pushed_at_top":
        assert T == pytest.approx(Q * (friction.radius or R), rel=1e-8)
    if friction.mode == "towed":
        assert abs(T) < 1e-12 * scale * R
    if friction.mode == "omega":
        assert om == friction.omega
    rr = res.driving_force + (T * om / V_)
    assert res.rolling_resistance == pytest.approx(rr, rel=1e-12, abs=1e-15 * scale)
    p_fric = float((Sx * res.slip_x + Sy * res.slip_y).sum())
    assert res.rolling_resistance_friction == pytest.approx(p_fric / V_, rel=1e-12, abs=1e-15 * scale)
    assert res.rolling_resistance_viscous == pytest.approx(rr - p_fric / V_, rel=1e-12, abs=1e-15 * scale)
    if p.loading.load is not None:
        assert res.load == pytest.approx(p.loading.load, rel=1e-12)
    else:
        assert res.indentation == p.loading.indentation
    assert res.load == pytest.approx(float(N.sum()), rel=1e-15)
    assert (res.speed, res.mu, res.mode, res.grid) == (V_, mu, friction.mode, g)
    for name in ("indentation", "load", "omega", "driving_force", "driving_torque", "rolling_resistance"):
        assert type(getattr(res, name)) is float, name
    r = res.record
    assert r.iterations == len(r.history) > 0
    last = r.history[-1]
    assert last[:2] == (int(contact.sum()), int(st.sum())) and last[3] == om
    assert last[2] <= max(friction.direction_tol, friction.set_tol if coulomb > 1e-6 else 0)
    return wmag[sl]


MODES = [Friction(0.3), Friction(0.3, "towed"), Friction(0.4, "torque"),
         Friction(0.3, "omega", omega=0.99 * V / R), Friction(0.3, "omega", omega=0.0)]


@pytest.mark.parametrize("friction", MODES, ids=lambda f: f"{f.mode}-{f.omega}")
def test_every_field_of_the_result_from_its_forces(kernels, friction):
    p = problem()
    res, timings = solve_friction(p, friction, kernels=kernels, energy=False)
    check_result(res, p, friction, kernels)
    assert math.isnan(res.rolling_resistance_energy)
    assert set(timings) == {"kernel_s", "solve_s"} and timings["kernel_s"] == 0.0 and timings["solve_s"] > 0
    if friction.omega == 0.0:
        assert res.stick_fraction == 0.0
    else:
        assert 0 < res.stick_fraction < 1
    assert res.record.linear_solver == "dense" and res.record.linear_iterations == 0


@pytest.mark.parametrize("friction", [Friction(0.3, "towed", dense_limit=0),
                                      Friction(0.3, "omega", omega=0.99 * V / R, dense_limit=0)])
def test_displacement_control_and_gmres(kernels, friction):
    """d given (the indentation of the 20 N solve); GMRES with the line preconditioner ends
    on the same state as dense LU."""
    p = problem(indentation=1.0e-4)
    res, _ = solve_friction(p, friction, kernels=kernels, energy=False)
    check_result(res, p, friction, kernels)
    assert res.record.linear_solver == "gmres" and res.record.linear_iterations > 0
    dense, _ = solve_friction(p, Friction(**{**friction.__dict__, "dense_limit": 1000}), kernels=kernels,
                              energy=False)
    assert np.array_equal(dense.stick, res.stick) and dense.record.linear_solver == "dense"
    np.testing.assert_allclose(res.force_x, dense.force_x, rtol=0, atol=1e-9 * dense.force.max())


def test_radius_override_sets_the_distance_to_the_axis(kernels):
    """friction.radius replaces the sphere's radius in R and l(y) (l = radius everywhere)."""
    friction = Friction(0.3, radius=0.03)
    p = problem()
    res, _ = solve_friction(p, friction, kernels=kernels, energy=False)
    check_result(res, p, friction, kernels)
    assert res.driving_torque == pytest.approx(-0.03 * res.force_x.sum(), rel=1e-12)
    assert res.driving_torque == pytest.approx(0.03 * res.driving_force, rel=1e-8)


def test_energy_figure_and_progress_lines(kernels):
    """With energy: (P_visc + P_fric) / V from bem.energy and the friction power; the
    progress lines carry the record's history (counts, Omega, misfit) and the set changes
    between lines add up; the kernels are computed (and timed) when not given."""
    friction = Friction(0.3, "omega", omega=0.99 * V / R)
    p = problem(Paraboloid(R))
    lines = []
    import time
    t0 = time.perf_counter()
    res, timings = solve_friction(p, friction, progress=lines.append)
    wall = time.perf_counter() - t0
    assert sum(timings.values()) <= wall
    pv = viscous_dissipation(GRID, LAYER, V, -res.force, res.force_x, res.force_y)
    assert res.rolling_resistance_energy == pytest.approx((pv + res.friction_power) / V, rel=1e-12)
    # the two figures differ by the discretisation error: 6.2 % measured on 67 contact nodes
    assert abs(res.rolling_resistance_energy / res.rolling_resistance - 1) < 0.1
    assert set(timings) == {"kernel_s", "solve_s", "energy_s"} and min(timings.values()) > 0
    assert lines[0] == (f"compliance ({len(BLOCKS)} block(s)): 23 x 23 nodes, Nt = 100 x 100, "
                        f"{timings['kernel_s']:.2f} s")
    assert lines[-1] == (f"energy: (P_visc + P_fric) / V = {res.rolling_resistance_energy:.6g} N, "
                         f"{timings['energy_s']:.2f} s")
    fr = [ln for ln in lines if ln.startswith("friction ")]
    assert len(fr) == res.record.iterations >= 3 and len(lines) == len(fr) + 2
    pattern = (r"friction (\d+): (\d+) contact, (\d+) stick, Omega = (\S+) rad/s, -(\d+) \+(\d+) contact, "
               r"\+(\d+) slip, \+(\d+) stick, slip misfit (\S+)")
    prev = None
    for it, (line, h) in enumerate(zip(fr, res.record.history), start=1):
        m = re.fullmatch(pattern, line)
        assert m, line
        assert int(m[1]) == it and (int(m[2]), int(m[3])) == h[:2]
        assert m[4] == f"{h[3]:.8g}" and m[9] == f"{h[2]:.2e}"
        if prev is not None:  # the sets change by what the previous line announced
            assert int(m[2]) == int(prev[2]) - int(prev[5]) + int(prev[6])
        prev = m
    assert fr[-1].endswith(f"slip misfit {res.record.history[-1][2]:.2e}")
    assert (int(prev[5]), int(prev[6]), int(prev[7]), int(prev[8])) == (0, 0, 0, 0)
    quiet, _ = solve_friction(p, friction, energy=False)
    np.testing.assert_array_equal(quiet.force_x, res.force_x)


def test_gmres_progress_counts_its_iterations(kernels):
    lines = []
    res, _ = solve_friction(problem(), Friction(0.3, "towed", dense_limit=0), kernels=kernels, energy=False,
                            progress=lines.append)
    counts = [int(m[1]) for m in (re.search(r", (\d+) GMRES iterations$", ln) for ln in lines) if m]
    assert len(counts) == res.record.iterations and sum(counts) == res.record.linear_iterations


@pytest.mark.parametrize("friction", [Friction(0.0, "towed"), Friction(0.0, "omega", omega=1.5)],
                         ids=lambda f: f.mode)
def test_zero_friction_returns_the_frictionless_contact(kernels, friction):
    p = problem()
    normal = solve_normal(ComplianceOperator(GRID, kernels["ww"]), Sphere(R).profile(*GRID.coordinates()),
                          load=20.0)
    res, _ = solve_friction(p, friction, kernels=kernels, energy=False)
    np.testing.assert_array_equal(res.force, normal.force)
    assert not res.force_x.any() and not res.force_y.any() and not res.stick.any()
    assert res.indentation == normal.indentation
    X, Y = GRID.coordinates()
    Q = float((normal.force * Sphere(R).rolling_arm(X, Y)).sum())
    assert res.driving_force == pytest.approx(Q, rel=1e-12) and res.rolling_resistance == res.driving_force
    assert res.driving_torque == 0.0 and res.rolling_resistance_friction == 0.0
    if friction.omega is None:
        assert math.isnan(res.omega)
    else:
        assert res.omega == friction.omega
    # the slip velocity V (1 + du/dx) - Omega l on the contact, with Omega = 0 where it is
    # free (undefined without friction): every node slips, S = 0, no friction power
    K = kernels
    dux = -_apply(GRID, upwind_table(K["uw"], GRID.spacing_x), res.force)
    ell = rolling_radius(Sphere(R), GRID.coordinates()[1])
    om = 0.0 if friction.omega is None else friction.omega
    on = res.force > 0
    np.testing.assert_allclose(res.slip_x[on], (V * (1 + dux) - om * ell)[on], rtol=0, atol=1e-12 * V)
    assert not res.slip_x[~on].any() and res.friction_power == 0.0
    r = res.record
    assert (r.iterations, r.history, r.linear_solver, r.linear_iterations) == (0, (), "dense", 0)
    assert (r.gap_residual, r.stick_residual, r.coulomb_residual) == (0.0, 0.0, 0.0)
    assert res.mu == 0.0


@pytest.mark.parametrize("speed", [0.0, -1.0, math.nan, math.inf])
def test_speed_must_be_positive_and_finite(kernels, speed):
    from bem.frictional import RollingOperators, solve_rolling

    X, Y = GRID.coordinates()
    with pytest.raises(ValueError) as info:
        solve_rolling(RollingOperators(GRID, kernels), Sphere(R).profile(X, Y), Sphere(R).rolling_arm(X, Y),
                      rolling_radius(Sphere(R), Y), R, speed, Friction(0.3), load=20.0)
    assert str(info.value) == f"speed must be > 0 m/s for rolling or sliding with friction, got {speed!r}"


# --- the coarse-grid start and the fallbacks (25 x 25, coarse 13 x 13) -----------------

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
    assert [n.grid.shape for n in normals] == [(25, 25)] and rtols == [fs.START_RTOL] == [1e-8]
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
    """From OVERLAP_FROM nodes on, the fine frictionless solve runs on a second thread
    while the coarse levels solve, from the coarse frictionless solution solved first
    (once: the coarse level is handed it): the result is bit for bit the one-thread
    result, the fine solves' preconditioner prepared there on the frictionless contact,
    the transforms of both threads on one worker each meanwhile (``one_worker``), and the
    fine grid's field spectra built once, by the thread free first; below OVERLAP_FROM
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
    assert [c[:2] for c in calls] == [((25, 25), True)] and fs.OVERLAP_FROM > 625
    calls.clear()
    monkeypatch.setattr(fs, "OVERLAP_FROM", 625)
    prepared = []
    real_prepare = fs.LinearSolves.prepare

    def prepare(self, system):
        inverses = self.lines.inverses
        real_prepare(self, system)
        prepared.append((threading.current_thread() is threading.main_thread(), system.nC, inverses,
                         self.lines.inverses, system.stick.all()))

    monkeypatch.setattr(fs.LinearSolves, "prepare", prepare)
    workers.clear()
    two, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False)
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
    solve_friction(problem(grid=BIG), Friction(0.0, "towed"), kernels=big_kernels, energy=False)
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

    monkeypatch.setattr(fs, "OVERLAP_FROM", 625)
    monkeypatch.setattr(fs, "solve_normal", fails)
    lines = []
    with pytest.raises(ContactAtEdge, match="planted on the fine grid"):
        solve_friction(problem(grid=BIG), Friction(0.3), kernels=big_kernels, energy=False, progress=lines.append)
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

    def first_fails(setup, friction, start, solves, progress=None, settle=None, forces=None):
        starts.append((setup.ops.grid.shape, start))
        guesses.append((setup.ops.grid.shape, forces))
        if setup.ops.grid.shape == (25, 25) and len([s for s in starts if s[0] == (25, 25)]) == 1:
            raise FrictionNotConverged("planted")
        return real(setup, friction, start, solves, progress, settle, forces)

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

    def continuation(setup, friction, N0, solves, progress, cause):
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


CYCLE = (r"the stick/slip sets cycle after (\d+) iterations even with one-node updates \(cone excess (\S+), "
         r"reversed slip (\S+) V, slip misfit (\S+), contact violation (\S+), set_tol (\S+)\); refine the grid, "
         r"or raise friction\.set_tol to accept such a state")


def test_a_cycling_set_switches_to_one_node_updates_then_says_so(kernels):
    """Towed at mu = 1e-3 on 67 contact nodes: the direct start cycles (the moment balance
    wants one stick node where the slip reverses), one-node updates follow (each line's
    sets differ from the previous line's by one node at most), then returning nodes join
    in slip, then the error with the figures of the last state (0.2 s)."""
    from bem.contact import solve_normal as normal
    from bem.frictional import RollingOperators, RollingSetup
    from bem.frictional.active_set import LinearSolves, run_active_set
    from bem.frictional.loading import constraint
    from bem.frictional.starts import frictionless_start

    ops = RollingOperators(GRID, kernels)
    X, Y = GRID.coordinates()
    s = Sphere(R).profile(X, Y)
    N0 = normal(ops.op("ww"), s, load=20.0).force.ravel()
    ell, arm = rolling_radius(Sphere(R), Y).ravel(), Sphere(R).rolling_arm(X, Y).ravel()
    friction = Friction(1e-3, "towed")  # set_tol 0.01: cone excesses of 0.6 to 29 measured
    setup = RollingSetup(ops=ops, profile=s.ravel(), arm=arm, ell=ell, radius=R, speed=V, mu=1e-3, load=20.0,
                         indentation=None, omega=None, constraint=constraint("towed", arm, ell, R))
    lines = []
    with pytest.raises(FrictionNotConverged) as info:
        run_active_set(setup, friction, frictionless_start(N0, ell, V, friction), LinearSolves(1000), lines.append)
    m = re.fullmatch(CYCLE, str(info.value))
    assert m, str(info.value)
    assert int(m[1]) == len(lines) and m[6] == "0.01" and float(m[2]) > 0.01
    assert m[4] == re.search(r"slip misfit (\S+)$", lines[-1])[1]
    counts = [tuple(int(c) for c in re.match(r"friction \d+: (\d+) contact, (\d+) stick", ln).groups())
              for ln in lines]
    tail = counts[-6:]
    assert all(abs(a[0] - b[0]) <= 1 and abs(a[1] - b[1]) <= 1 for a, b in zip(tail, tail[1:]))
    assert max(abs(a[1] - b[1]) for a, b in zip(counts, counts[1:])) > 1  # all at once at first


def test_a_cycle_within_set_tol_is_accepted(kernels):
    """The same case with set_tol = 100: the two-state cycle's cone excess (2.5 to 29
    measured: the path depends on rounding, e.g. the BLAS threads) is accepted and
    recorded in the Coulomb residual; with the default 0.01 it is not, and the continuation
    in mu stops on the same kind of cycle."""
    friction = Friction(1e-3, "towed", set_tol=100.0)
    res, _ = solve_friction(problem(), friction, kernels=kernels, energy=False)
    check_result(res, problem(), friction, kernels, coulomb=100.0)
    assert 1e-2 < res.record.coulomb_residual <= 100.0
    with pytest.raises(FrictionNotConverged) as info:
        solve_friction(problem(), Friction(1e-3, "towed"), kernels=kernels, energy=False)
    text = str(info.value)
    head = "mode 'towed', mu = 0.001: the direct solve failed ("
    assert text.startswith(head) and ") and the continuation in mu stopped at mu = " in text
    first = text[len(head):text.index(") and the continuation")]
    assert re.fullmatch(CYCLE, first), first


# --- run_active_set directly: its errors, whole ----------------------------------------

def _setup(kernels, profile=None, omega=0.99 * V / R, load=None, indentation=1e-4, mode="omega", mu=0.3):
    from bem.frictional import RollingOperators, RollingSetup
    from bem.frictional.loading import constraint

    ops = RollingOperators(GRID, kernels)
    X, Y = GRID.coordinates()
    s = (Sphere(R).profile(X, Y) if profile is None else profile).ravel()
    ell, arm = rolling_radius(Sphere(R), Y).ravel(), Sphere(R).rolling_arm(X, Y).ravel()
    cons = None if omega is not None else constraint(mode, arm, ell, R)
    return RollingSetup(ops=ops, profile=s, arm=arm, ell=ell, radius=R, speed=V, mu=mu, load=load,
                        indentation=indentation, omega=omega, constraint=cons)


def _all_stick(setup, N0=None):
    from bem.frictional import SetState

    contact = (setup.profile < 1e-4) if N0 is None else N0 > 0
    n = contact.size
    return SetState(contact=contact, stick=contact.copy(), direction=np.zeros((n, 2)), slope=np.zeros(n))


def test_out_of_iterations_message_whole(kernels):
    from bem.frictional.active_set import LinearSolves, run_active_set

    setup = _setup(kernels)
    lines = []
    with pytest.raises(FrictionNotConverged) as info:
        run_active_set(setup, Friction(0.3, "omega", omega=setup.omega, max_iter=1), _all_stick(setup),
                       LinearSolves(1000), lines.append)
    misfit = re.search(r"slip misfit (\S+)$", lines[-1])[1]
    assert len(lines) == 1
    assert str(info.value) == (f"no converged stick/slip state in 1 iterations (last direction change {misfit}); "
                               "raise friction.max_iter or friction.direction_tol")


@pytest.mark.parametrize("mode, unreachable", [("torque", True), ("pushed_at_top", True), ("towed", False)])
def test_whole_contact_slipping_is_unreachable_for_the_driven_modes(kernels, mode, unreachable):
    """A start with every node slipping and Omega free: one node is made to stick (Omega
    needs one); out of iterations with one stick node, the modes that need friction to
    carry a load say it cannot be met; towed is merely not converged."""
    from bem.frictional import SetState
    from bem.frictional.active_set import LinearSolves, run_active_set

    setup = _setup(kernels, omega=None, load=20.0, indentation=None, mode=mode, mu=0.05)
    start = _all_stick(setup)
    n = start.contact.size
    direction = np.zeros((n, 2))
    direction[start.contact, 0] = 1.0
    slope = np.where(start.contact, 1e-3 * V / 0.05, 0.0)
    start = SetState(contact=start.contact, stick=np.zeros(n, bool), direction=direction, slope=slope)
    lines = []
    with pytest.raises(FrictionNotConverged if not unreachable else LoadingUnreachable) as info:
        run_active_set(setup, Friction(0.05, mode, max_iter=1), start, LinearSolves(1000), lines.append)
    assert re.match(r"friction 1: \d+ contact, 1 stick, ", lines[0])
    if unreachable:
        assert str(info.value) == (f"mode {mode!r}: the whole contact slips and the equilibrium cannot be met "
                                   "with mu = 0.05; raise mu or use mode 'towed' or 'omega'")
    else:
        assert str(info.value).startswith("no converged stick/slip state in 1 iterations")


def test_two_stick_nodes_out_of_iterations_is_not_unreachable(kernels):
    from bem.frictional.active_set import LinearSolves, run_active_set

    setup = _setup(kernels, omega=None, load=20.0, indentation=None, mode="torque", mu=0.3)
    with pytest.raises(FrictionNotConverged) as info:
        run_active_set(setup, Friction(0.3, "torque", max_iter=1), _all_stick(setup), LinearSolves(1000))
    assert not isinstance(info.value, LoadingUnreachable)


def test_contact_at_the_edge_and_emptied_contact_messages_whole(kernels):
    """A flat strip pressed in touches every node it covers, edges included; pulled away (d < 0)
    the whole contact goes into tension and the set empties."""
    from bem.frictional.active_set import LinearSolves, run_active_set

    flat = np.full(GRID.shape, np.inf)
    flat[10:13, :] = 0.0  # a flat strip of three grid rows across the region, edge to edge
    setup = _setup(kernels, profile=flat, omega=V / R, indentation=1e-5)
    friction = Friction(0.3, "omega", omega=V / R)
    with pytest.raises(ContactAtEdge) as info:
        run_active_set(setup, friction, _all_stick(setup), LinearSolves(10000))
    assert str(info.value) == "the contact reaches the edge of the candidate region: increase grid.half_width"
    setup = _setup(kernels, indentation=-1e-6)
    start = _all_stick(setup)
    with pytest.raises(FrictionNotConverged) as info:
        run_active_set(setup, Friction(0.3, "omega", omega=setup.omega), start, LinearSolves(1000))
    assert str(info.value) == "the contact set emptied: check the load and the indenter profile"


def test_failing_gmres_names_the_set_and_what_to_change(kernels):
    from bem.frictional.active_set import LOOSE_REDUCTION, LinearSolves, run_active_set

    setup = _setup(kernels)
    start = _all_stick(setup)
    solves = LinearSolves(0)
    solves.solver.maxiter = solves.solver.restart = 1
    with pytest.raises(FrictionNotConverged) as info:
        run_active_set(setup, Friction(0.3, "omega", omega=setup.omega), start, solves)
    nC = int(start.contact.sum())
    assert str(info.value) == (f"GMRES did not reduce the residual by {LOOSE_REDUCTION:.1e} on {nC} contact nodes ({nC} stick) "
                               "in 1 iterations; refine the grid less or raise friction.dense_limit")
    assert solves.used_gmres and solves.iterations == 1


def test_active_set_result_against_its_definitions(kernels):
    """run_active_set's own result: gap = s - d + delta (inf off reach), scale |d|, the
    final sets those of the forces, the history's last row."""
    from bem.frictional.active_set import LinearSolves, run_active_set

    X, Y = GRID.coordinates()
    s = Sphere(R).profile(X, Y)
    s[0, :] = np.inf
    setup = _setup(kernels, profile=s, omega=None, load=20.0, indentation=None, mode="towed")
    solves = LinearSolves(1000)
    out = run_active_set(setup, Friction(0.3, "towed"), _all_stick(setup), solves)
    assert not solves.used_gmres and solves.iterations == 0
    K = kernels
    N2, X2, Y2 = out.N.reshape(GRID.shape), out.Sx.reshape(GRID.shape), out.Sy.reshape(GRID.shape)
    delta = _apply(GRID, K["ww"], N2) - _apply(GRID, K["wu"], X2) - _apply(GRID, K["wv"], Y2)
    h = (s - out.indentation + delta).ravel()
    reach = np.isfinite(s).ravel()
    np.testing.assert_allclose(out.gap[reach], h[reach], rtol=0, atol=1e-12 * out.indentation)
    assert np.isinf(out.gap[~reach]).all()
    assert out.scale == abs(out.indentation) and out.indentation > 0
    np.testing.assert_array_equal(out.state.contact, out.N > 0)
    assert out.N.sum() == pytest.approx(20.0, rel=1e-12)
    assert out.history[-1][:2] == (int(out.state.contact.sum()), int(out.state.stick.sum()))
    assert out.history[-1][3] == out.omega
    assert abs((setup.ell * out.Sx).sum()) < 1e-12 * out.N.max() * R  # towed: T = 0
    slip = out.state.contact & ~out.state.stick
    e = out.state.direction[slip]
    np.testing.assert_allclose(np.hypot(e[:, 0], e[:, 1]), 1.0, rtol=1e-12)
    assert not out.state.direction[~slip].any() and not out.state.slope[~slip].any()
    assert (out.state.slope[slip] > 0).all()


def test_residuals_of_a_state_off_the_solution(kernels, monkeypatch):
    """The record's residuals are measured on what is returned: with the active set's
    result disturbed (one slip force turned by 0.1 rad at its magnitude, one stick force
    scaled by 1.5, an off-contact node penetrating by 1e-9 d) each residual is the one
    recomputed here from the returned forces and gap."""
    import dataclasses

    import bem.frictional.solve as fs

    real = fs.run_active_set

    def disturbed(*args, **kw):
        out = real(*args, **kw)
        st = out.state
        Sx, Sy, gap = out.Sx.copy(), out.Sy.copy(), out.gap.copy()
        slip = np.flatnonzero(st.contact & ~st.stick)
        j = slip[np.argmax(np.hypot(Sx, Sy)[slip])]
        c, s_ = math.cos(0.1), math.sin(0.1)
        Sx[j], Sy[j] = c * Sx[j] - s_ * Sy[j], s_ * Sx[j] + c * Sy[j]
        k = np.flatnonzero(st.stick)[0]
        Sx[k] *= 1.5
        off = np.flatnonzero(np.isfinite(gap) & ~st.contact)[0]
        gap[off] = -1e-9 * out.scale
        return dataclasses.replace(out, Sx=Sx, Sy=Sy, gap=gap, fields=None)  # fields: of the new forces

    monkeypatch.setattr(fs, "run_active_set", disturbed)
    friction = Friction(0.3, "omega", omega=0.99 * V / R)
    res, _ = solve_friction(problem(), friction, kernels=kernels, energy=False)
    K, ax = kernels, GRID.spacing_x
    N, Sx, Sy = res.force, res.force_x, res.force_y
    dux = (-_apply(GRID, upwind_table(K["uw"], ax), N) + _apply(GRID, upwind_table(K["uu"], ax), Sx)
           + _apply(GRID, upwind_table(K["uv"], ax), Sy))
    dvx = (-_apply(GRID, upwind_table(K["vw"], ax), N) + _apply(GRID, upwind_table(K["vu"], ax), Sx)
           + _apply(GRID, upwind_table(K["vv"], ax), Sy))
    ell = rolling_radius(Sphere(R), GRID.coordinates()[1])
    wx, wy = V * (1 + dux) - friction.omega * ell, V * dvx
    st, sl = res.stick, res.contact & ~res.stick
    stick_res = np.hypot(wx, wy)[st].max() / V
    smag, wmag = np.hypot(Sx, Sy), np.hypot(wx, wy)
    cone = np.maximum(smag[st] / (0.3 * N[st]) - 1, 0).max()
    mag = np.abs(smag[sl] / (0.3 * N[sl]) - 1).max()
    ang = (1 - (Sx * wx + Sy * wy)[sl] / (smag * wmag)[sl]).max()
    r = res.record
    assert r.gap_residual == pytest.approx(1e-9, rel=1e-9)
    assert r.stick_residual == pytest.approx(stick_res, rel=1e-6) and stick_res > 1e-4
    assert r.coulomb_residual == pytest.approx(max(cone, mag, ang), rel=1e-6)
    assert ang > 1e-3  # the direction misfit shows (1.68 measured: the slip velocities move too)


def test_displacement_control_with_a_coarse_start(big_kernels):
    """d given on the 25 x 25 grid: the coarse level solves under displacement control too."""
    friction = Friction(0.3, "towed")
    p = problem(grid=BIG, indentation=1.0e-4)
    lines = []
    res, _ = solve_friction(p, friction, kernels=big_kernels, energy=False, progress=lines.append)
    check_result(res, p, friction, big_kernels)
    assert any(ln.startswith("coarse 13 x 13: friction 1: ") for ln in lines)


def test_unreachable_loading_message_from_the_frictionless_forces(kernels):
    """Pushed at the top at mu = 1e-3: |sum R arm N0| asked, mu sum |R + l| N0 available,
    from the frictionless forces N0 (N m)."""
    p = problem()
    X, Y = GRID.coordinates()
    N0 = solve_normal(ComplianceOperator(GRID, kernels["ww"]), Sphere(R).profile(X, Y), load=20.0).force
    need = abs(float((R * Sphere(R).rolling_arm(X, Y) * N0).sum()))
    can = 1e-3 * float((np.abs(R + rolling_radius(Sphere(R), Y)) * N0).sum())
    with pytest.raises(LoadingUnreachable) as info:
        solve_friction(p, Friction(1e-3), kernels=kernels, energy=False)
    assert str(info.value) == (
        f"mode 'pushed_at_top' needs tangential forces beyond the friction limit: mu = 0.001 can give a "
        f"moment/force of {can:.4g}, the rolling resistance asks for {need:.4g} (in units of N m); raise mu "
        "or use mode 'towed' or 'omega'")


def test_height_map_indenter_with_a_friction_radius(kernels):
    """A sphere given as a height map (a table of its profile, 0.25 mm steps): its arm is
    the table's slope dh/dx at (x, y), its l(y) the friction radius; the result is checked
    field by field against those."""
    from bem.indenters import HeightMap

    x = np.arange(-8e-3, 8e-3 + 1e-12, 0.25e-3)
    Xt, Yt = np.meshgrid(x, x)
    hm = HeightMap(x, x, Sphere(R).profile(Xt, Yt))
    friction = Friction(0.3, "towed", radius=R)
    p = problem(hm)
    res, _ = solve_friction(p, friction, kernels=kernels, energy=False)
    check_result(res, p, friction, kernels)
    X, Y = GRID.coordinates()
    Q = float((res.force * hm.rolling_arm(X, Y)).sum() + res.force_x.sum())
    assert res.driving_force == pytest.approx(Q, rel=1e-12)


@pytest.mark.parametrize("friction", [Friction(0.3), Friction(0.3, "towed"), Friction(0.3, "omega", omega=0.0)],
                         ids=lambda f: f"{f.mode}-{f.omega}")
def test_a_cylinder_with_friction(kernels, friction):
    """A roller of finite length (R = 20 mm, 6 mm long, flat ends; issue 14: cylinder
    indenters never ran with friction): every field and figure from the returned forces;
    its axis is parallel to the surface, so every point is R from it (l = R: T = -R sum S_x)
    and its arm is x / R (Q = sum N x / R + sum S_x), written here from the geometry; the
    contact stays within the roller's length (no force beyond |y| = 3 mm). Pure sliding
    (Omega = 0) drags the layer with mu P less the lateral slip component, as for the
    sphere (measured 0.999996 mu P; 0.999 allowed)."""
    from bem.indenters import Cylinder

    cyl = Cylinder(R, 6e-3)
    p = problem(cyl)
    res, _ = solve_friction(p, friction, kernels=kernels, energy=False)
    check_result(res, p, friction, kernels)
    X, Y = GRID.coordinates()
    assert not res.force[np.abs(Y) > 3e-3 + 1e-12].any() and res.contact[np.abs(Y) < 2.5e-3].any()
    assert res.driving_torque == pytest.approx(-R * res.force_x.sum(), rel=1e-12, abs=1e-15)
    Q = float((res.force * X).sum() / R + res.force_x.sum())
    assert res.driving_force == pytest.approx(Q, rel=1e-12, abs=1e-15)
    if friction.omega == 0.0:
        assert res.stick_fraction == 0.0
        assert 0.999 * 0.3 * 20.0 < res.force_x.sum() <= 0.3 * 20.0 * (1 + 1e-9)
    else:
        assert 0 < res.stick_fraction < 1


# --- the active set's steps replayed from its rules --------------------------------------

def _replay(kernels, setup, friction, start, expect_error=None):
    """Run the active set recording every state and solution, then replay the module's
    rules from the recorded solutions (independent FFT products) and check each step: the
    violations (tension, penetration beyond 1e-12 d, cone excess beyond 1e-10, slip
    against the force), the next sets (all at once; after a set recurs a third time, the
    worst violation only: tension, then penetration, cone excess, reversed slip), nodes
    joining in slip (Omega given and the rigid creep over 1 %; after the re-entry rule
    also the nodes that left the contact before), the Omega-free rule (a stick node at
    least: the contact node slipping least), the slip directions S/|S| and slopes
    max(|w|, 1e-3 min(1, misfit) V) / (mu N), joiners in slip along w with
    k = |w| / (mu N_min); which solves are tight (from a misfit of 1e-2 on, right after a
    set change only from 1e-5, in one-node updates or by dense LU); the cycle bookkeeping (a state counted when the sets change and
    the slip law has settled below set_tol or the contact changes) and, when the run
    ends on a cycle, the step and the figures of the error; the loose solves' reduction
    (3e-3); the local row solves (after 1 to 20 stick/slip changes with the contact
    unchanged, outside one-node updates and dense LU, on the changed nodes of the
    predicted state; their sets, directions and slopes taken when they ran more than one
    round). Returns the step
    counts by kind, the result and the states, and the predicted error (step, cone excess,
    reversed slip, misfit, contact violation) or None."""
    import bem.frictional.active_set as act

    states, sols = [], []
    real_system = act.SetSystem

    def spy_system(setup_, state):
        states.append(state)
        return real_system(setup_, state)

    reductions = []

    class Solves(act.LinearSolves):
        def __call__(self, system, guess=None, reduction=None, of_b=False):
            out = super().__call__(system, guess, reduction, of_b)
            sols.append(out)
            reductions.append(reduction)
            return out

    local = []
    real_rows = act.solve_rows

    def spy_rows(setup_, state, changed, *args):
        out = real_rows(setup_, state, changed, *args)
        local.append((state, changed, out))
        return out

    mp = pytest.MonkeyPatch()
    mp.setattr(act, "SetSystem", spy_system)
    mp.setattr(act, "solve_rows", spy_rows)
    try:
        if expect_error is None:
            out = act.run_active_set(setup, friction, start, Solves(friction.dense_limit))
        else:
            with pytest.raises(expect_error):
                act.run_active_set(setup, friction, start, Solves(friction.dense_limit))
            out = None
    finally:
        mp.undo()
    K, ax, V_, mu = kernels, GRID.spacing_x, setup.speed, setup.mu
    s, ell, reach = setup.profile, setup.ell, np.isfinite(setup.profile)
    omega_free = setup.omega is None
    counts = {"all": 0, "drop": 0, "add": 0, "slip": 0, "stick": 0, "held": 0, "local": 0}
    dropped = np.zeros(s.size, bool)
    seen, careful, reentry, predicted, prev_misfit, prev_changes = {}, False, False, None, np.inf, True
    for i, (st, (N, Sx, Sy, d, om)) in enumerate(zip(states, sols)):
        N2, X2, Y2 = (a.reshape(GRID.shape) for a in (N, Sx, Sy))
        delta = (_apply(GRID, K["ww"], N2) - _apply(GRID, K["wu"], X2) - _apply(GRID, K["wv"], Y2)).ravel()
        dux = (-_apply(GRID, upwind_table(K["uw"], ax), N2) + _apply(GRID, upwind_table(K["uu"], ax), X2)
               + _apply(GRID, upwind_table(K["uv"], ax), Y2)).ravel()
        dvx = (-_apply(GRID, upwind_table(K["vw"], ax), N2) + _apply(GRID, upwind_table(K["vu"], ax), X2)
               + _apply(GRID, upwind_table(K["vv"], ax), Y2)).ravel()
        h = np.where(reach, s - d + delta, np.inf)
        wx, wy = V_ * (1 + dux) - om * ell, V_ * dvx
        c, k = st.contact, st.stick
        drop = c & (N <= 0)
        add = ~c & (h < -1e-12 * abs(d))
        smag, wmag = np.hypot(Sx, Sy), np.hypot(wx, wy)
        slip = c & ~k & ~drop
        to_slip = c & k & ~drop & (smag > mu * N * (1 + 1e-10))
        wdot = wx * Sx + wy * Sy
        to_stick = slip & (wdot <= 0)
        slip &= ~to_stick
        changes = bool(drop.any() or add.any() or to_slip.any() or to_stick.any())
        with np.errstate(invalid="ignore", divide="ignore"):
            misfit = max((np.abs(smag - mu * N) / (mu * N))[slip].max(initial=0.0),
                         (np.abs(Sx * wy - Sy * wx) / (smag * wmag))[slip].max(initial=0.0))
        # tight from a misfit of 1e-2 on, after a set change only below 1e-5, in one-node
        # updates or by dense LU
        dense = 3 * c.sum() + (setup.load is not None) + omega_free <= friction.dense_limit
        tight = prev_misfit <= 1e-2 and (not prev_changes or prev_misfit <= 1e-5 or careful or dense)
        assert (reductions[i] is None) == tight, f"step {i + 1}: tight {tight}, reduction {reductions[i]}"
        assert tight or reductions[i] == 3e-3, f"step {i + 1}: reduction {reductions[i]}"
        counts["held"] += prev_misfit <= 1e-2 and not tight  # inexact only for the set change
        prev_misfit, prev_changes = misfit, changes
        join = add & (wmag > 0) & (not omega_free) & (np.abs(V_ - om * ell) > 1e-2 * V_)
        if reentry:
            join |= add & (wmag > 0) & dropped
        dropped |= drop
        if not changes and misfit <= friction.direction_tol and tight:
            assert i + 1 == len(states), f"step {i + 1}: converged, yet the run went on"
            ends = "converged"
            break
        one = careful and changes
        nc, ns = c.copy(), k.copy()
        if not one:
            nc = (c & ~drop) | add
            ns = ((k & ~to_slip) | to_stick | (add & ~join)) & nc
            kind = "all"
        elif drop.any():
            nc[np.argmin(np.where(drop, N, np.inf))] = False
            kind = "drop"
        elif add.any():
            j = np.argmin(np.where(add, h, np.inf))
            nc[j], ns[j] = True, not join[j]
            kind = "add"
        elif to_slip.any():
            ns[np.argmax(np.where(to_slip, smag - mu * N, -np.inf))] = False
            kind = "slip"
        else:
            ns[np.argmin(np.where(to_stick, wdot, np.inf))] = True
            kind = "stick"
        counts[kind] += 1
        # the cycle bookkeeping
        ends = None
        key = np.concatenate([nc, ns]).tobytes()
        if changes and (misfit <= friction.set_tol or drop.any() or add.any()):
            seen[key] = seen.get(key, 0) + 1
            if seen[key] > 2 and not careful:
                careful, seen = True, {}
            elif seen[key] > 2:
                with np.errstate(invalid="ignore", divide="ignore"):
                    over = float(np.nan_to_num(smag / (mu * N) - 1)[c & k].max(initial=0.0))
                    back = float(np.nan_to_num(-wdot / (smag * V_))[c & ~k].max(initial=0.0))
                gap_v = max(float((-h[add]).max(initial=0.0)) / abs(d),
                            float((-N[drop]).max(initial=0.0)) / N.max())
                if gap_v <= 1e-2 * friction.set_tol and max(over, back, misfit) <= friction.set_tol:
                    ends = "accepted"
                elif not reentry:
                    reentry, seen = True, {}
                else:
                    ends = "cycle"
                    predicted = (i + 1, over, back, misfit, gap_v)
        if ends:
            assert i + 1 == len(states), f"step {i + 1}: the run should have ended ({ends})"
            break
        nxt = states[i + 1]
        n_changes = int(drop.sum() + add.sum() + to_slip.sum() + to_stick.sum())
        rows = None
        if 0 < n_changes <= 20 and c.sum() >= act.LOCAL_FROM and not (careful or drop.any() or add.any() or dense):
            state, changed, rows = local.pop(0)
            assert np.array_equal(state.contact, nc) and np.array_equal(state.stick, ns), f"step {i + 1}: local"
            assert np.array_equal(changed, np.flatnonzero(ns != k)), f"step {i + 1}: local rows' nodes"
            if rows[3] > 1:
                ns = rows[0].stick
                counts["local"] += 1
            else:
                rows = None
        fixed = ns.copy()
        if omega_free and not (fixed & nc).any():
            sl_ = np.flatnonzero(nc)
            fixed[sl_[np.argmin(wmag[sl_])]] = True
        assert np.array_equal(nxt.contact, nc), f"step {i + 1} ({kind}): contact set"
        assert np.array_equal(nxt.stick & nxt.contact, fixed & nc), f"step {i + 1} ({kind}): stick set"
        # directions and slopes of the next slip set (before the Omega-free fix)
        new_slip = nc & ~ns
        with np.errstate(invalid="ignore", divide="ignore"):
            e = np.stack([Sx, Sy], 1) / smag[:, None]
            kk = np.maximum(np.where(slip, wmag, 0.0), 1e-3 * min(1.0, misfit) * V_) / (mu * N)
            joining = new_slip & add
            e[joining] = np.stack([wx, wy], 1)[joining] / wmag[joining, None]
            kk[joining] = wmag[joining] / (mu * N[c & (N > 0)].min())
        e = np.where(new_slip[:, None] & ((smag[:, None] > 0) | joining[:, None]), e, 0.0)
        kk = np.where(new_slip, np.nan_to_num(kk), 0.0)
        if rows is not None:  # the local rows' own (tested in test_friction.py)
            e, kk = rows[0].direction, rows[0].slope
        np.testing.assert_allclose(nxt.direction, e, rtol=1e-7, atol=1e-9)
        np.testing.assert_allclose(nxt.slope, kk, rtol=1e-5, atol=1e-9 * kk.max())
    assert not local, "local row solves the rules do not call for"
    assert ends == {None: "converged", FrictionNotConverged: "cycle"}.get(expect_error, ends) or ends == "accepted"
    return counts, out, states, predicted if ends != "accepted" else "accepted"


def _rolling_setup(kernels, friction, load=20.0, start_load=None):
    from bem.frictional import RollingOperators, RollingSetup
    from bem.frictional.loading import constraint
    from bem.frictional.starts import frictionless_start

    ops = RollingOperators(GRID, kernels)
    X, Y = GRID.coordinates()
    s = Sphere(R).profile(X, Y)
    N0 = solve_normal(ops.op("ww"), s, load=start_load or load).force.ravel()
    ell, arm = rolling_radius(Sphere(R), Y).ravel(), Sphere(R).rolling_arm(X, Y).ravel()
    cons = None if friction.omega is not None else constraint(friction.mode, arm, ell, R)
    setup = RollingSetup(ops=ops, profile=s.ravel(), arm=arm, ell=ell, radius=R, speed=V, mu=friction.mu,
                         load=load, indentation=None, omega=friction.omega, constraint=cons)
    return setup, frictionless_start(N0, ell, V, friction)


@pytest.mark.parametrize("friction", [Friction(0.3, "towed"), Friction(0.3, "omega", omega=0.9 * V / R),
                                      Friction(0.3, "omega", omega=V / R), Friction(0.3, "omega", omega=0.0),
                                      Friction(0.3, "omega", omega=0.99 * V / R, dense_limit=0)],
                         ids=lambda f: f"{f.mode}-{f.omega}-{f.dense_limit}")
def test_active_set_steps_follow_the_rules_from_a_small_start(kernels, friction):
    """From the frictionless contact of 8 N under 20 N the contact grows: nodes join in
    stick, or (Omega given, rigid creep over 1 %) in slip along w with k = |w| / (mu N_min).
    By GMRES (``dense_limit = 0``; from 10 N: since the local row solves, every set change
    from 8 N comes at a misfit above 1e-2) a set changes at a misfit between 1e-5 and 1e-2,
    and the next solve stays inexact."""
    setup, start = _rolling_setup(kernels, friction, start_load=8.0 if friction.dense_limit else 10.0)
    assert start.contact.sum() < 50
    counts, out, states, _ = _replay(kernels, setup, friction, start)
    assert counts["held"] >= (friction.dense_limit == 0), counts
    assert out.state.contact.sum() > start.contact.sum() + 10


def test_local_row_solves_are_replayed_from_a_small_start(kernels):
    """By GMRES from 8 N (Omega 0.99 V / R), with local row solves from one contact node
    on: after a step with a few stick/slip changes they run two rounds and their sets start
    the next solve, at 1e-4; the replay checks the call, its nodes, the sets and the
    reductions around it. With the default LOCAL_FROM they do not run on this contact."""
    import bem.frictional.active_set as act

    friction = Friction(0.3, "omega", omega=0.99 * V / R, dense_limit=0)
    setup, start = _rolling_setup(kernels, friction, start_load=8.0)
    counts, *_ = _replay(kernels, setup, friction, start)
    assert counts["local"] == 0, counts  # a contact of 67 nodes: below LOCAL_FROM
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(act, "LOCAL_FROM", 1)
        counts, *_ = _replay(kernels, setup, friction, start)
    assert counts["local"] == 1, counts


@pytest.mark.parametrize("friction", [Friction(0.3), Friction(0.3, "omega", omega=0.99 * V / R),
                                      Friction(0.3, "omega", omega=0.0), Friction(0.05, "torque")],
                         ids=lambda f: f"{f.mode}-{f.omega}")
def test_active_set_steps_follow_the_rules(kernels, friction):
    setup, start = _rolling_setup(kernels, friction)
    counts, out, states, _ = _replay(kernels, setup, friction, start)
    assert counts["all"] >= 2 and len(states) == len(out.history)


def test_cycling_steps_follow_the_one_node_rules(kernels):
    """The cycling case (towed, mu = 1e-3): every step up to the cycle error follows the
    rules (all at once, one node at a time after a set recurs, the re-entry rule), and the
    error names the step and the figures of the last state, recomputed here."""
    friction = Friction(1e-3, "towed")
    setup, start = _rolling_setup(kernels, friction)
    import bem.frictional.active_set as act

    with pytest.raises(FrictionNotConverged) as info:
        act.run_active_set(setup, friction, start, act.LinearSolves(1000))
    counts, _, states, predicted = _replay(kernels, setup, friction, start, expect_error=FrictionNotConverged)
    assert len(states) >= 10 and predicted is not None, counts
    it, over, back, misfit, gap_v = predicted
    m = re.fullmatch(CYCLE, str(info.value))
    assert int(m[1]) == it == len(states)
    for got, want in zip((m[2], m[3], m[5]), (over, back, gap_v)):
        assert float(got) == pytest.approx(want, rel=0.01, abs=1e-12), str(info.value)
    assert float(m[4]) == pytest.approx(misfit, rel=0.01, abs=1e-9)


def test_an_accepted_cycle_ends_on_the_replayed_step(kernels):
    friction = Friction(1e-3, "towed", set_tol=100.0)
    setup, start = _rolling_setup(kernels, friction)
    counts, out, states, ends = _replay(kernels, setup, friction, start)
    assert ends == "accepted" and len(states) == len(out.history) and counts["all"] >= 2


def _violations(n, **over):
    from bem.frictional.violations import Violations

    zero, no = np.zeros(n), np.zeros(n, bool)
    fields = dict(gap=np.ones(n), wx=zero, wy=zero, wmag=zero, smag=zero, wdot=zero, drop=no, add=no,
                  to_slip=no, to_stick=no, slip=no, misfit=0.0, scale=1.0, fields=())
    fields.update({k: np.asarray(v) for k, v in over.items()})
    return Violations(**fields)


def test_one_node_updates_take_the_worst_violation_in_order():
    """next_sets (the active set's module docstring: after a cycle "one-node updates"; its
    docstring: tension first, then penetration, cone excess, reversed slip, the worst one): on 6 nodes with two
    violations of each kind, the most tensile node leaves; without tension the deepest
    penetrating node joins (in stick unless it joins in slip); then the stick node furthest
    beyond the cone slips; then the slip node whose w . S is most negative sticks. All at
    once: tension leaves, penetration joins (in stick unless in slip), cone excess slips,
    reversed slip sticks."""
    from types import SimpleNamespace

    from bem.frictional.violations import next_sets

    setup = SimpleNamespace(mu=0.5)
    c = np.array([1, 1, 1, 1, 0, 0], bool)
    k = np.array([1, 1, 0, 0, 0, 0], bool)
    N = np.array([-1.0, -2.0, 3.0, 4.0, 0.0, 0.0])
    drop = np.array([1, 1, 0, 0, 0, 0], bool)
    add = np.array([0, 0, 0, 0, 1, 1], bool)
    gap = np.array([1.0, 1.0, 1.0, 1.0, -1.0, -3.0])
    smag = np.array([3.0, 2.0, 0.0, 0.0, 0.0, 0.0])
    to_slip = np.array([1, 1, 0, 0, 0, 0], bool)
    wdot = np.array([0.0, 0.0, -1.0, -5.0, 0.0, 0.0])
    to_stick = np.array([0, 0, 1, 1, 0, 0], bool)
    no = np.zeros(6, bool)
    join = np.array([0, 0, 0, 0, 0, 1], bool)

    def step(v, one, join_slip=no, contact=c, stick=k, forces=N):
        nc, ns = next_sets(setup, v, contact.copy(), stick.copy(), forces, join_slip, one)
        return nc.tolist(), (ns & nc).tolist()

    v = _violations(6, gap=gap, smag=smag, wdot=wdot, drop=drop, add=add, to_slip=to_slip, to_stick=to_stick)
    assert step(v, True) == ([1, 0, 1, 1, 0, 0], [1, 0, 0, 0, 0, 0])  # N = -2 leaves
    v = _violations(6, gap=gap, smag=smag, wdot=wdot, add=add, to_slip=to_slip, to_stick=to_stick)
    assert step(v, True) == ([1, 1, 1, 1, 0, 1], [1, 1, 0, 0, 0, 1])  # h = -3 joins in stick
    assert step(v, True, join) == ([1, 1, 1, 1, 0, 1], [1, 1, 0, 0, 0, 0])  # ... or in slip
    # mu N = 2.5 and 0.5: cone excess 0.5 N and 1.5 N, node 1 slips (node 0 has the larger |S|)
    Np = np.array([5.0, 1.0, 3.0, 4.0, 0.0, 0.0])
    v = _violations(6, smag=smag, wdot=wdot, to_slip=to_slip, to_stick=to_stick)
    assert step(v, True, forces=Np) == ([1, 1, 1, 1, 0, 0], [1, 0, 0, 0, 0, 0])
    v = _violations(6, wdot=wdot, to_stick=to_stick)
    assert step(v, True, forces=Np) == ([1, 1, 1, 1, 0, 0], [1, 1, 0, 1, 0, 0])  # w . S = -5 sticks
    # all at once
    v = _violations(6, gap=gap, smag=smag, wdot=wdot, drop=drop, add=add, to_slip=no, to_stick=to_stick)
    assert step(v, False, join) == ([0, 0, 1, 1, 1, 1], [0, 0, 1, 1, 1, 0])
    v = _violations(6, smag=smag, wdot=wdot, to_slip=to_slip, to_stick=no)
    assert step(v, False, forces=Np) == ([1, 1, 1, 1, 0, 0], [0, 0, 0, 0, 0, 0])


def test_two_stick_nodes_out_of_iterations_are_not_unreachable(kernels):
    """Torque mode with exactly two stick nodes when the iterations run out: not the
    whole contact slipping, so not LoadingUnreachable (one stick node would be)."""
    from bem.frictional import SetState
    from bem.frictional.active_set import LinearSolves, run_active_set

    setup = _setup(kernels, omega=None, load=20.0, indentation=None, mode="torque", mu=0.05)
    contact = setup.profile < 1e-4
    n = contact.size
    direction = np.zeros((n, 2))
    direction[contact, 0] = 1.0
    stick = np.zeros(n, bool)
    stick[np.flatnonzero(contact)[[10, 20]]] = True
    slope = np.where(contact & ~stick, 1e-3 * V / 0.05, 0.0)
    start = SetState(contact=contact, stick=stick, direction=direction, slope=slope)
    lines = []
    with pytest.raises(FrictionNotConverged) as info:
        run_active_set(setup, Friction(0.05, "torque", max_iter=1), start, LinearSolves(1000), lines.append)
    assert re.match(r"friction 1: \d+ contact, 2 stick, ", lines[0])
    assert not isinstance(info.value, LoadingUnreachable)
    assert str(info.value).startswith("no converged stick/slip state in 1 iterations")


def test_add_threshold_is_a_penetration_of_1e_12_d(kernels):
    """From a converged state, two nodes outside the contact are given profiles that put
    them 1e-10 m into the layer (1e-6 d: it joins) and 1e-17 m above it (h = 1e-13 d > 0:
    it stays out), the forces unchanged by the first solve of the same sets."""
    import dataclasses

    from bem.frictional.active_set import LinearSolves, run_active_set

    friction = Friction(0.3, "omega", omega=0.99 * V / R)
    setup, start = _rolling_setup(kernels, friction)
    first = run_active_set(setup, friction, start, LinearSolves(1000))
    outside = np.flatnonzero(np.isfinite(first.gap) & ~first.state.contact)
    j_in, j_out = outside[np.argsort(first.gap[outside])[:2]]  # the two closest to the surface
    s = setup.profile.copy()
    s[j_in] -= first.gap[j_in] + 1e-10
    s[j_out] -= first.gap[j_out] - 1e-17
    moved = dataclasses.replace(setup, profile=s)
    lines = []
    out = run_active_set(moved, friction, first.state, LinearSolves(1000), lines.append)
    assert re.search(r", -0 \+1 contact, ", lines[0]), lines[0]
    assert out.state.contact[j_in] and not out.state.contact[j_out]
    assert len(out.history) == 2


def test_cone_test_has_a_margin_of_1e_10(kernels):
    """A fully stuck state (torque, mu = 50) does not depend on mu; re-run from it with mu
    set so that the most loaded stick node has |S| = mu N (1 + 5e-11): within the
    1e-10 margin, it stays in stick; at |S| = mu N (1 + 2e-10) it slips (with its mirror
    image in y, loaded alike)."""
    import dataclasses

    from bem.frictional.active_set import LinearSolves, run_active_set

    setup, start = _rolling_setup(kernels, Friction(50.0, "torque"))
    stuck = run_active_set(setup, Friction(50.0, "torque"), start, LinearSolves(1000))
    c = stuck.state.contact
    assert (stuck.state.stick[c]).all()
    ratio = np.where(c, np.hypot(stuck.Sx, stuck.Sy) / np.where(c, stuck.N, 1.0), 0.0)
    q = ratio.max()
    for excess, slips in ((5e-11, 0), (2e-10, 1)):
        mu = q / (1 + excess)
        lines = []
        again = dataclasses.replace(setup, mu=mu)
        if slips:
            with pytest.raises(FrictionNotConverged):  # it slips, and 1 iteration is not enough
                run_active_set(again, Friction(mu, "torque", max_iter=1), stuck.state, LinearSolves(1000),
                               lines.append)
        else:  # nothing changes: converged at the second, tight solve
            run_active_set(again, Friction(mu, "torque", max_iter=2), stuck.state, LinearSolves(1000), lines.append)
        n_slip = int(re.search(r", \+(\d+) slip, ", lines[0])[1])
        assert (n_slip >= 1) if slips else (n_slip == 0), lines[0]  # 2: the node and its mirror in y


def test_coarse_level_settles_without_the_tight_solve(big_kernels, monkeypatch):
    """The coarse level ends as soon as its sets repeat with a slip misfit of at most
    COARSE_SETTLE: its history is the converged one's, cut short; the fine grid converges
    fully (settle None) to the same state."""
    import bem.frictional.solve as fs

    real = fs.run_active_set
    calls = []

    def spy(setup, friction, start, solves, progress=None, settle=None, forces=None):
        out = real(setup, friction, start, solves, progress, settle, forces)
        calls.append((setup.ops.grid.shape, settle, out.history))
        return out

    monkeypatch.setattr(fs, "run_active_set", spy)
    p, friction = problem(grid=BIG), MODES[3]  # omega = 0.99 V / R: the coarse level slips
    settled, _ = solve_friction(p, friction, kernels=big_kernels, energy=False)
    (cshape, csettle, chist), (fshape, fsettle, _) = calls
    assert (cshape, csettle, fshape, fsettle) == ((13, 13), 0.3, (25, 25), None) and fs.COARSE_SETTLE == 0.3
    assert friction.direction_tol < chist[-1][2] <= 0.3
    calls.clear()
    monkeypatch.setattr(fs, "COARSE_SETTLE", None)
    full, _ = solve_friction(p, friction, kernels=big_kernels, energy=False)
    converged = calls[0][2]
    assert calls[0][1] is None and converged[-1][2] <= friction.direction_tol
    assert chist == converged[:len(chist)] and len(chist) < len(converged)
    assert np.array_equal(full.stick, settled.stick) and np.array_equal(full.contact, settled.contact)
    np.testing.assert_allclose(full.force_x, settled.force_x, rtol=0, atol=1e-9 * full.force.max())


@pytest.mark.parametrize("fraction", [0.0, 0.05, 0.1, 1.0])
@pytest.mark.parametrize("friction", MODES[:4] + [Friction(0.3, "omega", omega=0.98 * V / R)],
                         ids=lambda f: f"{f.mode}-{f.omega}")
def test_a_coarse_level_ends_with_a_few_set_changes_left(big_kernels, monkeypatch, friction, fraction):
    """The coarse level ends at its first solve whose slip misfit is at most
    COARSE_SETTLE and whose sets change by at most SETTLE_CHANGES of its contact nodes
    (read from its progress lines); 0 waits for the sets to repeat. (With ``Omega = 0.98
    V / R`` the 21 coarse contact nodes change by 8, 2, 0 at misfits 0.036, 0.19, 0.018:
    3, 3, 2 and 1 solves for the four fractions.) The fine grid ends on the state it
    reaches from the default."""
    import bem.frictional.active_set as fa

    monkeypatch.setattr(fa, "SETTLE_CHANGES", fraction)
    lines = []
    res, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False, progress=lines.append)
    steps = [re.match(r"coarse 13 x 13: friction \d+: (\d+) contact, .* -(\d+) \+(\d+) contact, \+(\d+) slip, "
                      r"\+(\d+) stick, slip misfit (\S+)", ln) for ln in lines if ln.startswith("coarse 13 x 13: ")]
    assert steps and all(steps)
    ends = [int(m[2]) + int(m[3]) + int(m[4]) + int(m[5]) <= fraction * int(m[1]) and float(m[6]) <= 0.3
            for m in steps]
    assert ends[-1] and not any(ends[:-1])
    if friction.omega == 0.98 * V / R:
        assert len(steps) == {0.0: 3, 0.05: 3, 0.1: 2, 1.0: 1}[fraction]
    monkeypatch.setattr(fa, "SETTLE_CHANGES", 0.01)
    ref, _ = solve_friction(problem(grid=BIG), friction, kernels=big_kernels, energy=False)
    assert np.array_equal(res.stick, ref.stick) and np.array_equal(res.contact, ref.contact)
    np.testing.assert_allclose(res.force_x, ref.force_x, rtol=0, atol=1e-9 * ref.force.max())


@pytest.mark.parametrize("misfit, changes, careful, dense, tight", [
    (np.inf, True, False, False, False),  # the first solve
    (1e-2, False, False, False, True),  # the sets repeat: tight from 1e-2 on
    (1.01e-2, False, False, False, False),
    (1e-2, False, True, True, True),
    (1e-5, True, False, False, True),  # right after a set change: tight from 1e-5 on
    (1.01e-5, True, False, False, False),
    (1e-4, True, False, False, False),
    (3.3e-3, True, False, False, False),  # 513 x 513's four nodes stuck at 3.3e-3 (SETTLED's measurement)
    (3.3e-3, True, True, False, True),  # one-node updates: an accepted cycle keeps this solve
    (3.3e-3, True, False, True, True),  # dense LU is exact whatever the reduction
    (1.01e-2, True, True, True, False),  # above 1e-2 never
])
def test_which_solves_are_tight(misfit, changes, careful, dense, tight):
    """The rule the replay checks on the runs it meets, at its thresholds: ``LOOSE_UNTIL`` =
    1e-2 and ``SETTLED`` = 1e-5, both inclusive, and its three ways around ``SETTLED``
    (no set change, one-node updates, dense LU). The replayed runs do not pin ``SETTLED``'s
    value: of their steps right after a set change at a misfit between 1e-5 and 1e-2 (4e-4
    to 9.8e-3), seven are dense LU (tight whatever the misfit) and one is GMRES (5.2e-3,
    held inexact); none is GMRES between 1e-5 and 1e-3."""
    from bem.frictional.active_set import tight_solve

    assert tight_solve(misfit, changes, careful, dense) is tight


def test_the_next_residual_reads_the_last_solution_s_fields(kernels, monkeypatch):
    """A solve after the first starts from the last solution. When none of its forces lies
    outside the new contact, the fields the violations computed are handed over
    (``SetSystem.know``): they are the guess's fields (recomputed here by FFT products of
    the guess's forces) and its residual then takes no product; after the contact lost a
    node they are not handed over (they would hold that node's force). From the
    frictionless contact of 30 N under 20 N the contact shrinks first."""
    import bem.frictional.active_set as act
    from bem.frictional import SetSystem

    calls = []  # per system: (its contact, whether know was called)
    products = []

    class Spy(SetSystem):
        def __init__(self, setup, state):
            super().__init__(setup, state)
            calls.append([state.contact.copy(), False])

        def know(self, x, fields):
            size = GRID.nodes_x * GRID.nodes_y
            N, Sx, Sy = (np.zeros(size) for _ in range(3))
            N[self.C], Sx[self.C], Sy[self.C] = x[:self.nC], x[self.nC:2 * self.nC], x[2 * self.nC:3 * self.nC]
            want = self.ops.fields(*(a.reshape(GRID.shape) for a in (N, Sx, Sy))).reshape(3, -1)[:, self.C]
            for got, ref in zip(fields, want):
                np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12 * np.abs(ref).max())
            calls[-1][1] = True
            super().know(x, fields)

        def residual(self, x):
            before = len(products)
            out = super().residual(x)
            calls[-1].append(len(products) - before)  # the products it took
            return out

        def matvec(self, x, dtype=np.float64):
            products.append(dtype)
            return super().matvec(x, dtype)

    monkeypatch.setattr(act, "SetSystem", Spy)
    friction = Friction(0.3, "omega", omega=0.99 * V / R, dense_limit=0)
    setup, start = _rolling_setup(kernels, friction, start_load=30.0)
    solves = act.LinearSolves(0)
    out = act.run_active_set(setup, friction, start, solves)
    assert len(calls) == len(out.history) >= 3
    dropped = [bool((a[0] & ~b[0]).any()) for a, b in zip(calls, calls[1:])]
    assert calls[0][1] is False and [c[1] for c in calls[1:]] == [not d for d in dropped]
    assert any(dropped) and not all(dropped)
    # the starting residual took one product exactly where the fields were not known
    assert [c[2] for c in calls[1:]] == [int(d) for d in dropped]
    # the result's fields are the last violations' (those of its forces)
    N2, X2, Y2 = (a.reshape(GRID.shape) for a in (out.N, out.Sx, out.Sy))
    for got, ref in zip(out.fields, setup.ops.fields(N2, X2, Y2)):
        np.testing.assert_allclose(got, ref.ravel(), rtol=0, atol=1e-12 * np.abs(ref).max())
