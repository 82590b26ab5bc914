"""bem.frictional.active_set and bem.frictional.violations: every step of real runs (23 x 23
grid) replayed from the recorded solutions with independent FFT products against the
rules (violations and their thresholds, next sets, one-node updates, slip directions and
slopes, tight or loose solves, cycle bookkeeping, local row solves), the one-node order of
violations, and the next residual read from the last solution's fields.
"""

import re

import numpy as np
import pytest

from bem import Grid, Layer, Sphere, ThreeParameterSolid, influence_kernels
from bem.contact import solve_normal
from bem.frictional import Friction, FrictionNotConverged, LoadingUnreachable, SolverOptions
from bem.kinematics import rolling_radius, upwind_table
from bem.operator import ComplianceOperator
from bem.spectral import BLOCKS


LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
R = 0.02
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (5.5e-3, 5.5e-3))  # 23 x 23, 529 nodes


@pytest.fixture(autouse=True)
def one_blas_thread():
    """The steps are run and replayed here by calling the active set directly, outside
    :func:`bem.frictional.solve_friction`, which runs its BLAS on one thread
    (:mod:`bem.threads`): so do these tests. The replay redoes each step's arithmetic in
    its own order and compares the sets; on the cycling case (towed, mu = 1e-3), a near tie,
    OpenBLAS's two threads round the run and the replay apart and one node differs."""
    from bem.threads import one_blas_thread as limit

    with limit():
        yield


@pytest.fixture(scope="module")
def kernels():
    return influence_kernels(GRID, LAYER, V, blocks=BLOCKS)


def _apply(grid, table, f):
    return ComplianceOperator(grid, table).apply(f)


CYCLE = (r"the stick/slip sets cycle after (\d+) iterations even with one-node updates \(cone excess (\S+), "
         r"reversed slip (\S+) V, slip misfit (\S+), contact violation (\S+), set_tol (\S+)\); refine the grid, "
         r"or raise friction\.set_tol to accept such a state")


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


def _replay(kernels, setup, friction, start, expect_error=None, options=None):
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
    round; ``options`` as the run's). Returns the step
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
            out = act.run_active_set(setup, friction, start, Solves(friction.dense_limit), options=options)
        else:
            with pytest.raises(expect_error):
                act.run_active_set(setup, friction, start, Solves(friction.dense_limit), options=options)
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
        if 0 < n_changes <= 20 and c.sum() >= (options or SolverOptions()).local_from and not (careful or drop.any() or add.any() or dense):
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
        if rows is not None:  # the local rows' own (tested in test_local.py)
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


def _violations(n, **over):
    from bem.frictional.violations import Violations

    zero, no = np.zeros(n), np.zeros(n, bool)
    fields = dict(gap=np.ones(n), wx=zero, wy=zero, wmag=zero, smag=zero, wdot=zero, drop=no, add=no,
                  to_slip=no, to_stick=no, slip=no, misfit=0.0, scale=1.0, fields=())
    fields.update({k: np.asarray(v) for k, v in over.items()})
    return Violations(**fields)


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
    reductions around it. With the default ``local_from`` they do not run on this contact."""
    friction = Friction(0.3, "omega", omega=0.99 * V / R, dense_limit=0)
    setup, start = _rolling_setup(kernels, friction, start_load=8.0)
    counts, *_ = _replay(kernels, setup, friction, start)
    assert counts["local"] == 0, counts  # a contact of 67 nodes: below local_from
    counts, *_ = _replay(kernels, setup, friction, start, options=SolverOptions(local_from=1))
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


@pytest.mark.parametrize("misfit, changes, careful, dense, tight", [
    (np.inf, True, False, False, False),  # the first solve
    (1e-2, False, False, False, True),  # the sets repeat: tight from 1e-2 on
    (1.01e-2, False, False, False, False),
    (1e-2, False, True, True, True),
    (1e-5, True, False, False, True),  # right after a set change: tight from 1e-5 on
    (1.01e-5, True, False, False, False),
    (1e-4, True, False, False, False),
    (3.3e-3, True, False, False, False),  # 513 x 513's four nodes stuck at 3.3e-3 (the measurement behind ``settled``)
    (3.3e-3, True, True, False, True),  # one-node updates: an accepted cycle keeps this solve
    (3.3e-3, True, False, True, True),  # dense LU is exact whatever the reduction
    (1.01e-2, True, True, True, False),  # above 1e-2 never
])
def test_which_solves_are_tight(misfit, changes, careful, dense, tight):
    """The rule the replay checks on the runs it meets, at its thresholds: ``loose_until`` =
    1e-2 and ``settled`` = 1e-5, both inclusive, and its three ways around ``settled``
    (no set change, one-node updates, dense LU). The replayed runs do not pin ``settled``'s
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


def test_which_solves_are_tight_follows_its_options():
    """The thresholds are ``loose_until`` and ``settled`` of the options given."""
    from bem.frictional import SolverOptions
    from bem.frictional.active_set import tight_solve

    assert tight_solve(5e-2, False, False, False, SolverOptions(loose_until=0.1))
    assert not tight_solve(5e-3, False, False, False, SolverOptions(loose_until=1e-3))
    assert tight_solve(5e-4, True, False, False, SolverOptions(settled=1e-3))
    assert not tight_solve(5e-6, True, False, False, SolverOptions(settled=1e-6))


def test_the_cone_and_penetration_margins_are_the_options(kernels):
    """measure's margins are ``cone_tol`` and ``penetration_tol`` of the options given (the
    defaults without): on the fully stuck state (torque, mu = 50) with mu set so that the
    most loaded stick node has |S| = mu N (1 + 2e-10), the default margin (1e-10) slips
    it and a margin of 1e-9 keeps it in stick; with d raised by half, nodes outside the
    contact penetrate by far more than 1e-12 |d| but less than 10 |d|."""
    import dataclasses

    from bem.frictional import SolverOptions
    from bem.frictional.active_set import LinearSolves, run_active_set
    from bem.frictional.violations import measure

    setup, start = _rolling_setup(kernels, Friction(50.0, "torque"))
    stuck = run_active_set(setup, Friction(50.0, "torque"), start, LinearSolves(1000))
    st = stuck.state
    c = st.contact
    q = np.where(c, np.hypot(stuck.Sx, stuck.Sy) / np.where(c, stuck.N, 1.0), 0.0).max()
    again = dataclasses.replace(setup, mu=q / (1 + 2e-10))
    args = (again, st.contact, st.stick, stuck.N, stuck.Sx, stuck.Sy, stuck.indentation, stuck.omega)
    assert measure(*args).to_slip.any() and measure(*args, SolverOptions()).to_slip.any()
    assert not measure(*args, SolverOptions(cone_tol=1e-9)).to_slip.any()
    deeper = args[:6] + (1.5 * stuck.indentation, stuck.omega)
    assert measure(*deeper).add.any() and measure(*deeper, SolverOptions()).add.any()
    assert not measure(*deeper, SolverOptions(penetration_tol=10.0)).add.any()

