"""Frictional steady rolling: input checks, kinematics, limits and energy on a coarse grid."""

import math
import re

import numpy as np
import pytest

from bem import Grid, Layer, Loading, Paraboloid, Problem, Sphere, ThreeParameterSolid, influence_kernels
from bem.contact import ContactError
from bem.energy import viscous_dissipation
from bem.friction import Friction, LoadingUnreachable
from bem.kinematics import rolling_radius, upwind_field, upwind_table
from bem.operator import ComplianceOperator
from bem.problem import solve_frictionless
from bem import solve_friction
from bem.spectral import BLOCKS

LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5.5e-3, 5.5e-3))


@pytest.fixture(scope="module")
def kernels():
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)


def problem(indenter=Sphere(0.02), load=150.0):
    return Problem(LAYER, indenter, GRID, Loading(V, load=load))


@pytest.mark.parametrize("kwargs, message", [
    ({"mu": -0.1}, "mu must be >= 0, got -0.1"),
    ({"mu": 0.2, "mode": "pulled"}, "mode must be one of"),
    ({"mu": 0.2, "mode": "omega"}, "omega (rad/s) must be given"),
    ({"mu": 0.2, "omega": 1.0}, "omega (rad/s) must be given"),
    ({"mu": 0.2, "radius": -1.0}, "radius must be > 0 m"),
])
def test_bad_friction_input_is_refused(kwargs, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        Friction(**kwargs)


def test_upwind_table_is_the_upwind_difference_of_the_field(kernels):
    """Kd * F equals (u_{i+1} - u_i) / a_x of u = K * F on every column but the last."""
    rng = np.random.default_rng(1)
    F = rng.normal(size=GRID.shape)
    u = ComplianceOperator(GRID, kernels["uu"]).apply(F)
    du = ComplianceOperator(GRID, upwind_table(kernels["uu"], GRID.spacing_x)).apply(F)
    ref = upwind_field(u, GRID.spacing_x)
    np.testing.assert_allclose(du[:, :-1], ref[:, :-1], rtol=0, atol=1e-12 * np.abs(ref).max())


def test_rolling_radius_is_the_distance_to_the_axis():
    Y = np.array([0.0, 0.01])
    np.testing.assert_allclose(rolling_radius(Sphere(0.02), Y), [0.02, math.sqrt(0.02**2 - 0.01**2)])


def test_zero_friction_is_the_frictionless_solution(kernels):
    p = problem()
    ref, _ = solve_frictionless(p)
    res, _ = solve_friction(p, Friction(0.0, "towed"), kernels=kernels)
    np.testing.assert_allclose(res.force, ref.force, rtol=0, atol=1e-9 * ref.force.max())
    assert res.rolling_resistance == pytest.approx(ref.rolling_resistance, rel=1e-9)
    assert res.rolling_resistance_friction == 0.0


def test_small_friction_tends_to_the_frictionless_solution(kernels):
    """mu -> 0 with Omega prescribed: tangential forces O(mu P) perturb R_r by O(mu)."""
    p = problem()
    ref, _ = solve_frictionless(p)
    diffs = []
    for mu in (1e-2, 1e-3):  # Omega = V / R: a rigid creep of zero
        res, _ = solve_friction(p, Friction(mu, "omega", omega=V / 0.02), kernels=kernels)
        diffs.append(abs(res.rolling_resistance - ref.rolling_resistance))
        # measured 0.746 mu F_max at mu = 1e-2 and 1e-3 (the same constant: linear in mu)
        assert np.abs(res.force - ref.force).max() < 1.0 * mu * ref.force.max()
    assert diffs[1] < 0.2 * diffs[0]  # linear in mu


def test_large_friction_sticks_everywhere(kernels):
    """Axle torque only (Q = 0): the sphere's horizontal equilibrium, recomputed from the
    returned nodal forces, is sum S_x + sum N x / R = Q = 0 (measured 4e-15 N). Solved by
    dense LU (``dense_limit = 1000``; the default takes GMRES here, whose stick residual
    1.6e-13 leaves a frictional power of 2.7e-15 against the 1.5e-15 asked below)."""
    res, _ = solve_friction(problem(), Friction(50.0, "torque", dense_limit=1000), kernels=kernels)
    assert res.record.linear_solver == "dense"
    assert res.stick_fraction == 1.0
    X, _ = GRID.coordinates()
    assert abs(res.force_x.sum() + np.sum(res.force * X) / 0.02) < 1e-12 * res.force.sum()
    assert abs(res.force_x.sum()) > 1e-3 * res.force.sum()  # the balance is not 0 = 0
    assert np.hypot(res.slip_x, res.slip_y).max() == 0.0 and res.rolling_resistance_friction == 0.0
    assert res.record.stick_residual < 1e-10
    # the slip velocity recomputed from the returned forces (upwind differences of the
    # displacements, w = V (1 + du/dx) - Omega l(y), V dv/dx, l = sqrt(R^2 - y^2)) vanishes on
    # every contact node, so the frictional power sum S . w is 0 by the stick condition,
    # not because the result reports w = 0 on stick nodes
    N, Sx, Sy = res.force, res.force_x, res.force_y

    def dx(block, F):
        return ComplianceOperator(GRID, upwind_table(kernels[block], GRID.spacing_x)).apply(F)

    _, Y = GRID.coordinates()
    wx = V * (1 + (-dx("uw", N) + dx("uu", Sx) + dx("uv", Sy))) - res.omega * np.sqrt(0.02**2 - Y * Y)
    wy = V * (-dx("vw", N) + dx("vu", Sx) + dx("vv", Sy))
    c = res.contact
    # measured 4e-14 V and 5e-16 R_r V (allowed: 25x and 20x that)
    assert np.hypot(wx, wy)[c].max() < 1e-12 * V
    assert abs(np.sum(Sx * wx + Sy * wy)) < 1e-14 * res.rolling_resistance * V


def test_pushed_at_top_equilibrium_and_parts(kernels):
    """T = Q R, R_r = Q (1 + R Omega / V) (eq. 4), R_r^F >= 0, a stick zone remains."""
    res, _ = solve_friction(problem(), Friction(0.2), kernels=kernels)
    assert res.driving_torque == pytest.approx(res.driving_force * 0.02, rel=1e-9)
    assert res.rolling_resistance == pytest.approx(res.driving_force * (1 + 0.02 * res.omega / V), rel=1e-9)
    assert 0 <= res.rolling_resistance_friction < 0.05 * res.rolling_resistance
    assert abs(res.stick_fraction - 0.8112) < 0.01  # measured 189 of 233 contact nodes; two nodes either way
    assert res.load == pytest.approx(150.0, rel=1e-9)
    assert res.record.coulomb_residual < 1e-6


def test_too_little_friction_to_push_at_the_top_is_unreachable(kernels):
    with pytest.raises(LoadingUnreachable, match="friction limit"):
        solve_friction(problem(), Friction(1e-3), kernels=kernels)
    assert issubclass(LoadingUnreachable, ContactError)


def test_friction_needs_motion(kernels):
    p = Problem(LAYER, Sphere(0.02), GRID, Loading(0.0, load=150.0))
    with pytest.raises(ValueError, match="speed must be > 0"):
        solve_friction(p, Friction(0.2), kernels=kernels)


def test_energy_balance_braking(kernels):
    """A braked paraboloid (Omega R / V = 0.99): R_r V = P_visc (Fourier, from the layer's
    loss modulus) + P_fric. The residual is the collocation and upwind discretisation
    error (O(a)), well below the frictional part."""
    res, _ = solve_friction(problem(Paraboloid(0.02)), Friction(0.2, "omega", omega=0.99 * V / 0.02),
                            kernels=kernels)
    pv = viscous_dissipation(GRID, LAYER, V, -res.force, res.force_x, res.force_y)
    resid = res.rolling_resistance * V - pv - res.friction_power
    assert res.friction_power > 0.1 * res.rolling_resistance * V
    # O(a) discretisation error at a = 0.5 mm (2.4 % measured); dropping the friction
    # power (20 % of R_r V here) or the tangential work in the layer would fail this
    assert abs(resid) < 0.03 * res.rolling_resistance * V


def _energy_pair(kernels, indenter):
    res, _ = solve_friction(problem(indenter), Friction(0.2), kernels=kernels)
    return res, res.rolling_resistance, res.rolling_resistance_energy


def test_energy_figure_equals_equilibrium_figure_for_a_paraboloid(kernels):
    """Paraboloid: the arm x/R is the profile slope, so R_r (eq. 63) and
    (P_visc + P_fric) / V agree up to the discretisation error: measured -0.23 % here
    (a = 0.5 mm, Nt = 200) and -0.30 % at a = 0.25 mm, Nt = 2000; the tolerance 0.5 % is
    below the sphere's 1.5 % slope term, which this test would catch if the arm were wrong."""
    res, rr, re = _energy_pair(kernels, Paraboloid(0.02))
    assert math.isfinite(re)
    assert abs(re - rr) < 5e-3 * rr


def test_energy_figure_exceeds_equilibrium_figure_by_the_sphere_slope_term(kernels):
    """Exact sphere: the layer is worked by the slope x/zeta (zeta = sqrt(R^2 - r^2)),
    the equilibrium uses the arm x/R, so (P_visc + P_fric)/V - R_r = sum N x (1/zeta - 1/R)
    up to the discretisation error of the paraboloid test (0.5 %). Measured: difference
    1.50 % of R_r, slope term 1.61 %, about 0.7 r_c^2 / 2R^2 (r_c the contact radius)."""
    res, rr, re = _energy_pair(kernels, Sphere(0.02))
    X, Y = GRID.coordinates()
    R = 0.02
    slope_term = float((res.force * X * (1 / np.sqrt(R * R - X * X - Y * Y) - 1 / R)).sum())
    assert re - rr > 0.01 * rr
    assert abs(re - rr - slope_term) < 5e-3 * rr
    assert 0.4 < slope_term / rr / (res.contact_radius**2 / (2 * R * R)) < 1.0


def test_towed_with_tiny_friction_converges_to_the_frictionless_solution(kernels):
    """Towed (T = 0) at mu = 1e-3: the direct start cycles (the moment balance needs one
    stick node where the slip reverses), the continuation in mu from 0.256 finds it;
    R_r differs from the frictionless one by O(mu) (measured 0.03 %)."""
    p = problem()
    ref, _ = solve_frictionless(p)
    res, _ = solve_friction(p, Friction(1e-3, "towed"), kernels=kernels, energy=False)
    assert abs(res.driving_torque) < 1e-12
    assert 0 < res.stick_fraction < 0.02
    assert abs(res.rolling_resistance / ref.rolling_resistance - 1) < 1e-3
    assert res.record.coulomb_residual < 1e-6


@pytest.mark.parametrize("mu", [1e-3, 1.0])
def test_pure_sliding_slips_everywhere_and_saturates(kernels, mu):
    """Omega = 0: every node slips, the layer is dragged forwards with mu P up to the lateral
    slip component (measured 0.99999 and 0.99955 mu P); a few iterations (2-5 measured:
    the start state and joining nodes slip along w with the slip law's own k)."""
    res, _ = solve_friction(problem(), Friction(mu, "omega", omega=0.0), kernels=kernels, energy=False)
    assert res.stick_fraction == 0.0
    assert 0.999 * mu * 150.0 < res.force_x.sum() <= mu * 150.0 * (1 + 1e-9)
    assert res.record.iterations <= 10


def test_a_solve_that_does_not_converge_says_so(kernels):
    from bem.friction import FrictionNotConverged

    with pytest.raises(FrictionNotConverged, match="continuation in mu stopped at mu"):
        solve_friction(problem(), Friction(1e-3, "towed", max_iter=3), kernels=kernels, energy=False)


@pytest.mark.parametrize("mode", ["towed", "torque", "pushed_at_top"])
def test_rolling_modes_converge_over_a_range_of_mu(kernels, mode):
    """Coarse grid (a = 0.5 mm), mu from 0.05 to 2: every solve ends on a discrete
    Coulomb state (before the re-entry rule, torque at mu = 1 cycled on a boundary node
    that joined in stick, went into tension and left); more friction, more stick."""
    fractions = []
    for mu in (0.05, 0.5, 1.0, 2.0):
        res, _ = solve_friction(problem(), Friction(mu, mode), kernels=kernels, energy=False)
        assert res.record.coulomb_residual < 1e-6 and res.record.stick_residual < 1e-10
        assert res.record.gap_residual < 1e-9
        fractions.append(res.stick_fraction)
    assert fractions == sorted(fractions) and fractions[0] < 0.3 < 0.95 < fractions[-1]


def _state(kernels, seed=0):
    """A synthetic active-set state on the frictionless contact of the coarse grid:
    random stick/slip split, slip directions and slip-law slopes."""
    from bem.contact import solve_normal
    from bem.frictional import RollingOperators

    ops = RollingOperators(GRID, kernels)
    X, Y = GRID.coordinates()
    s = Sphere(0.02).profile(X, Y)
    N0 = solve_normal(ops.op("ww"), s, load=150.0).force.ravel()
    rng = np.random.default_rng(seed)
    C = np.flatnonzero(N0 > 0)
    stick = np.zeros(N0.size, bool)
    stick[C] = rng.random(C.size) < 0.7
    ang = rng.uniform(0, 2 * np.pi, N0.size)
    e = np.stack([np.cos(ang), np.sin(ang)], 1)
    k = rng.uniform(0.1, 2.0, N0.size) * V / N0.max()
    ell = rolling_radius(Sphere(0.02), Y).ravel()
    arm = Sphere(0.02).rolling_arm(X, Y).ravel()
    return ops, s.ravel(), C, stick, e, k, ell, arm


def _system(kernels, load, indentation, omega, mode="pushed_at_top", contact=None):
    from bem.frictional import RollingSetup, SetState, SetSystem
    from bem.frictional.loading import constraint

    ops, s, C, stick, e, k, ell, arm = _state(kernels)
    if contact is not None:
        C = contact
    cons = None if omega is not None else constraint(mode, arm, ell, 0.02)
    setup = RollingSetup(ops=ops, profile=s, arm=arm, ell=ell, radius=0.02, speed=V, mu=0.2, load=load,
                         indentation=indentation, omega=omega, constraint=cons)
    inside = np.zeros(s.size, bool)
    inside[C] = True
    return SetSystem(setup, SetState(contact=inside, stick=stick & inside, direction=e, slope=k)), C


@pytest.mark.parametrize("load, indentation, omega", [(150.0, None, None), (None, 1e-4, 2.4)])
def test_matrix_free_product_equals_the_dense_system(kernels, load, indentation, omega):
    """The FFT product of the active-set system equals its dense matrix (both come from
    the same row definitions, the blocks from different code: dense tables vs FFT)."""
    system, C = _system(kernels, load, indentation, omega)
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
    import bem.frictional.preconditioner as pc
    from bem.frictional import SetState, SetSystem
    from bem.frictional.preconditioner import LinePreconditioner

    monkeypatch.setattr(pc, "COMPOSE_UPTO", compose)

    Ky, Kx = GRID.shape
    row = (Ky // 2) * Kx + np.arange(Kx // 2 - 6, Kx // 2 + 6)
    two = np.concatenate([row, row + Kx])
    uncoupled = {b: (np.zeros_like(k) if b in ("wu", "wv", "uw", "vw") else k) for b, k in kernels.items()}
    x = np.random.default_rng(7).normal(size=3 * two.size)
    for kern, nodes, exact in ((uncoupled, row, True), (kernels, row, False), (uncoupled, two, False)):
        system, C = _system(kern, None, 1e-4, 2.4, contact=nodes)
        assert 0 < system.A.size < C.size
        y = x[:system.n]
        for dtype, tol in ((np.float64, 1e-12), (np.float32, 1e-5)):
            lines = LinePreconditioner(dtype=dtype)
            lines.attach(system)
            err = np.abs(system.precondition(system.matvec(y)) - y).max()
            assert (err < tol) if exact else (err > 1e-3), (dtype, err)
            if exact:
                # other slip directions and slopes on the same slip places: the inverses the
                # first attach kept are reused, and the solve is still exact
                _, _, _, stick, e, k, _, _ = _state(kern)
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
    system, C = _system(uncoupled, None, 1e-4, 2.4, contact=row)
    _, _, _, _, e, k, _, _ = _state(uncoupled)
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
    length written as ``bytes(n)`` (n zero bytes, the key until session 31) their keys were
    the same, the second attach reused the first run's inverses and the solve was off; a
    run of 9 slip nodes after one of 8 (16 and 8 padded places) raised a shape error
    (section 11 at 513 x 513). On one grid row without the coupling blocks the solve is
    exact (see the test above), so each attach is checked against its own blocks."""
    from bem.frictional import SetState, SetSystem
    from bem.frictional.preconditioner import LinePreconditioner

    Ky, Kx = GRID.shape
    uncoupled = {b: (np.zeros_like(k) if b in ("wu", "wv", "uw", "vw") else k) for b, k in kernels.items()}
    system, _ = _system(uncoupled, None, 1e-4, 2.4, contact=(Ky // 2) * Kx + np.arange(12))
    _, _, _, _, e, k, _, _ = _state(uncoupled)
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


def test_local_row_solves_hold_their_rows_and_test_the_window_as_the_active_set(kernels, monkeypatch):
    """bem.frictional.local.solve_rows, one round, on a synthetic state (random stick/slip
    split, directions and slopes; random forces): the tangential forces change only on the
    contact nodes within WINDOW of a changed node along its row, and there the system's x
    and y rows hold after the round (b - A x by the FFT product, below 1e-9 of the residual
    before: the window's blocks are exact and the other forces held); the window's sets
    then follow the active set's tests on that solution (cone excess: slip; slip against
    the force: stick), its slip nodes take S / |S| and max(|w|, floor) / (mu N), and
    nothing outside the window changes. A singular window changes nothing (0 rounds)."""
    import bem.frictional.local as local
    from bem.frictional import SetState, SetSystem

    monkeypatch.setattr(local, "ROUNDS", 1)
    monkeypatch.setattr(local, "WINDOW", 4)  # narrower than the contact's rows here
    system, C = _system(kernels, None, 1e-4, 2.4)
    setup, ops = system.setup, system.ops
    _, _, _, stick, e, k, ell, _ = _state(kernels)
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
    new, Sx2, Sy2, rounds = local.solve_rows(setup, state, changed, N, Sx, Sy, 2.4, fields, floor)
    assert rounds == 1 and new.contact is state.contact
    window = np.zeros(stick.size, bool)
    for j, i in zip(*np.divmod(changed, Kx)):
        window[j * Kx + max(0, i - local.WINDOW):j * Kx + min(Kx, i + local.WINDOW + 1)] = True
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
    same, Sx3, Sy3, rounds = local.solve_rows(setup, state, changed, N, Sx, Sy, 2.4, fields, floor)
    assert rounds == 0 and same is state and Sx3 is Sx and Sy3 is Sy


def test_local_rows_after_a_few_changes_are_kept_only_when_they_change_more(kernels, monkeypatch):
    """In the active set (GMRES solves, dense_limit = 0; LOCAL_FROM lowered to 1 node):
    after a solve with 1 to FEW_CHANGES stick/slip changes and no contact change, the
    local row solves run on
    those nodes; their result is kept when it changes more nodes (more than one round);
    otherwise it is dropped, bit for bit (a stub returning other forces in one round
    changes nothing). Every loose solve reduces by LOOSE_REDUCTION."""
    import bem.frictional.active_set as active_set

    calls, reductions, lines = [], [], []
    real_rows, real_call = active_set.solve_rows, active_set.LinearSolves.__call__

    def rows(setup, state, changed, *args):
        out = real_rows(setup, state, changed, *args)
        calls.append((changed.size, out[3]))
        return out

    def call(self, system, guess=None, reduction=None, of_b=False):
        reductions.append(reduction)
        return real_call(self, system, guess, reduction, of_b)

    monkeypatch.setattr(active_set, "LOCAL_FROM", 1)  # this contact has 67 nodes
    # solves at 1e-4 take a path that meets both outcomes (at 3e-3 one round only)
    monkeypatch.setattr(active_set, "LOOSE_REDUCTION", 1e-4)
    monkeypatch.setattr(active_set, "solve_rows", rows)
    monkeypatch.setattr(active_set.LinearSolves, "__call__", call)
    friction = Friction(0.2, mode="towed", dense_limit=0)
    res, _ = solve_friction(problem(), friction, kernels=kernels, energy=False, progress=lines.append)
    fine = [line for line in lines if not line.startswith("coarse")]
    assert [c[1] > 1 for c in calls] == [True, False]  # measured: 17 changes, 2 rounds; 2, 1
    assert all(0 < c[0] <= active_set.FEW_CHANGES for c in calls)
    steps = [line for line in fine if line.startswith("friction ")]
    assert len(steps) == len(reductions) == res.record.iterations
    kept = [i for i, line in enumerate(fine) if line.startswith("  local rows")]
    for i, line in enumerate(steps[:-1]):
        if reductions[i + 1] is not None:  # a loose solve
            assert reductions[i + 1] == active_set.LOOSE_REDUCTION, line
    assert len(kept) == 1

    # one round: the stub's forces are dropped, the run is the same bit for bit
    def stub(setup, state, changed, N, Sx, Sy, *args):
        return state, 2 * Sx, 0 * Sy, 1

    monkeypatch.setattr(active_set, "solve_rows", stub)
    monkeypatch.setattr(active_set.LinearSolves, "__call__", real_call)
    dropped, _ = solve_friction(problem(), friction, kernels=kernels, energy=False)
    monkeypatch.setattr(active_set, "solve_rows", lambda setup, state, changed, N, Sx, Sy, *a: (state, Sx, Sy, 1))
    same, _ = solve_friction(problem(), friction, kernels=kernels, energy=False)
    assert np.array_equal(dropped.force_x, same.force_x) and np.array_equal(dropped.stick, same.stick)
    assert np.array_equal(same.stick, res.stick)


@pytest.mark.parametrize("mode, omega", [("pushed_at_top", None), ("towed", None), ("torque", None),
                                         ("omega", 2.3)])
def test_matrix_free_solve_equals_the_dense_solve(kernels, mode, omega):
    """Preconditioned GMRES (dense_limit = 0) ends on the dense solver's state."""
    p = problem()
    dense, _ = solve_friction(p, Friction(0.3, mode=mode, omega=omega, dense_limit=10**6),
                              kernels=kernels, energy=False)
    it, _ = solve_friction(p, Friction(0.3, mode=mode, omega=omega, dense_limit=0),
                           kernels=kernels, energy=False)
    assert dense.record.linear_solver == "dense" and it.record.linear_solver == "gmres"
    assert it.record.linear_iterations > 0
    assert np.array_equal(it.stick, dense.stick) and np.array_equal(it.contact, dense.contact)
    scale = dense.force.max()
    for a, b in ((it.force, dense.force), (it.force_x, dense.force_x), (it.force_y, dense.force_y)):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * scale)
    assert abs(it.rolling_resistance - dense.rolling_resistance) < 1e-9 * abs(dense.rolling_resistance)
    assert abs(it.omega - dense.omega) < 1e-9 * abs(dense.omega)


def test_coarse_grid_start_ends_on_the_same_state(monkeypatch):
    """Section 11 at 41 x 41 (Nt = 500): starting the active set from the solution on
    every other node gives the all-stick start's state (10 fine-grid iterations against
    11 here; at 257 x 257, 19 against 31)."""
    import bem.frictional.solve as frictional_solve

    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5e-3, 5e-3))
    p = Problem(LAYER, Sphere(0.02), grid, Loading(V, load=150.0))
    kern = influence_kernels(grid, LAYER, V, blocks=BLOCKS)
    lines = []
    coarse, _ = solve_friction(p, Friction(0.2), kernels=kern, energy=False, progress=lines.append)
    assert any(line.startswith("coarse 21 x 21: friction") for line in lines)
    monkeypatch.setattr(frictional_solve, "_coarse_solution", lambda *args: None)
    direct, _ = solve_friction(p, Friction(0.2), kernels=kern, energy=False)
    assert np.array_equal(coarse.stick, direct.stick) and np.array_equal(coarse.contact, direct.contact)
    np.testing.assert_allclose(coarse.force_x, direct.force_x, rtol=0, atol=1e-9 * direct.force.max())
    assert abs(coarse.rolling_resistance - direct.rolling_resistance) < 1e-10 * direct.rolling_resistance


def test_a_solve_out_of_iterations_says_what_to_change(kernels):
    """Mode omega (no continuation): running out of active-set iterations raises
    FrictionNotConverged naming the setting to change, never a silent result."""
    from bem.friction import FrictionNotConverged

    with pytest.raises(FrictionNotConverged, match=r"raise friction\.max_iter or friction\.direction_tol"):
        solve_friction(problem(), Friction(0.2, "omega", omega=0.99 * V / 0.02, max_iter=1), kernels=kernels,
                       energy=False)


def test_flexible_gmres_solves_to_the_asked_residual():
    """bem.linear.fgmres against a dense solve: a nonsymmetric system (n = 300) with a
    preconditioner applied in single precision (a slightly different operator at every
    call, which the flexible variant allows), restarted every 7 iterations: the true
    residual is below the asked 1e-11 |b| and x equals the dense solution to 1e-9 (the
    system's condition is ~10); without enough iterations it says so."""
    from bem.linear import fgmres

    rng = np.random.default_rng(11)
    n = 300
    A = np.diag(rng.uniform(1, 10, n)) + rng.normal(size=(n, n)) / np.sqrt(n)
    b = rng.normal(size=n)
    approx = np.linalg.inv(A + 0.3 * rng.normal(size=(n, n)) / np.sqrt(n)).astype(np.float32)

    def precondition(r):
        return (approx @ r.astype(np.float32)).astype(float)

    tol = 1e-11 * np.linalg.norm(b)
    x, ok, its = fgmres(lambda v: A @ v, b, precondition, tol=tol, restart=7, maxiter=50)
    assert ok and 0 < its <= 350
    assert np.linalg.norm(b - A @ x) <= tol
    np.testing.assert_allclose(x, np.linalg.solve(A, b), rtol=0, atol=1e-9 * np.abs(x).max())
    x, ok, its = fgmres(lambda v: A @ v, b, None, tol=tol, restart=2, maxiter=1)
    assert not ok and its == 2


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
        system, _ = _system(kern, None, 1e-4, 2.4, contact=row)
        solves = LinearSolves(dense_limit=0)
        solves.lines.attach(system)
        err = np.abs(system.precondition(system.matvec(x)) - x).max() / np.abs(x).max()
        assert (err > 1e-3) if coupled else (err < 1e-5), (coupled, err)  # single precision: 6e-7
        N, Sx, Sy, _, _ = solves(system)
        got = system.unknowns(N, Sx, Sy, 1e-4, 2.4)
        ref = np.linalg.solve(system.dense(), system.b)
        assert np.abs(got - ref).max() < 1e-8 * np.abs(ref).max()


def test_prolong_is_exact_on_bilinear_fields_and_coarse_forces_scale_by_the_node_area():
    """:func:`bem.frictional.starts.prolong` reproduces ``a + b x + c y + e x y`` sampled on
    every other node at every node of the fine grid (the mean of two neighbours is exact
    along an edge, of four at a cell's centre); :func:`coarse_forces` hands on the fine
    frictionless forces, a quarter of the prolonged coarse tangential forces on their
    contact (a fine node's area is a quarter of a coarse node's) and nothing off it, the
    fine indentation plus what friction added on the coarse grid, and the coarse Omega."""
    from types import SimpleNamespace

    from bem.frictional.starts import coarse_forces, prolong

    Ky, Kx = 9, 13
    y, x = np.mgrid[0:Ky, 0:Kx].astype(float)
    f = 0.3 + 1.7 * x - 0.4 * y + 0.05 * x * y
    np.testing.assert_allclose(prolong(f[::2, ::2], (Ky, Kx)), f, rtol=0, atol=1e-13)
    rng = np.random.default_rng(3)
    N0 = np.where(rng.random(Ky * Kx) < 0.6, rng.uniform(0.1, 1.0, Ky * Kx), 0.0)
    coarse = SimpleNamespace(force_x=np.full((5, 7), 0.8), force_y=f[::2, ::2], indentation=2.5e-4, omega=3.1)
    below = SimpleNamespace(indentation=2.0e-4)
    N, Sx, Sy, d, om = coarse_forces(coarse, (Ky, Kx), N0, 1.1e-4, below)
    assert N is N0 and om == 3.1 and d == pytest.approx(1.1e-4 + 0.5e-4, rel=1e-12)
    np.testing.assert_allclose(Sx, np.where(N0 > 0, 0.2, 0.0), rtol=1e-14)
    np.testing.assert_allclose(Sy, np.where(N0 > 0, f.ravel() / 4, 0.0), rtol=0, atol=1e-13)
    assert coarse_forces(coarse, (Ky, Kx), N0, 1.1e-4)[3] == 1.1e-4  # no coarse frictionless solution
