"""bem.frictional.active_set: the handling of a cycling set state, driven by a scripted layer.

Why scripted: the rules for a cycle (one-node updates after a set state recurs a third
time, the acceptance within ``set_tol``, the re-entry rule, the figures of the error) act
only on states that cycle in particular ways: with no stick node, with a tensile node whose
slip opposes its force, with a slip misfit above ``set_tol`` next to a tiny contact
violation, with several violations at once, with a node that returns after leaving. The one
cycling input found cheaply on a real layer (towed, ``mu = 1e-3``, 67 contact nodes; see
``test_active_set_rules.py``) has a single cone excess per step and none of these.
So here :func:`run_active_set` runs unchanged with its own ``measure``, ``next_sets`` and
``next_directions`` (:mod:`bem.frictional.violations`), but the linear solve of each set
state is replaced by a table: the forces of the contact nodes and the fields (gap ``h``,
slip velocity ``w``) that the layer would give for that state, chosen so that the state
cycles. Each test asserts what the
module docstring and the comments of the rules say must happen (the sequence of set states,
the iteration the run stops at, the figures of the error) against values worked out here by
hand from the scripted numbers, not read from the code. Each run takes milliseconds.

Units: forces in N, lengths in m, speeds in m/s, ``Omega`` in rad/s.
"""

import re
from types import SimpleNamespace

import numpy as np
import pytest

import bem.frictional.active_set as act
from bem.frictional import Friction, FrictionNotConverged, SolverOptions


V = 0.05  # m/s
R = 0.02  # m: ell = R has no rigid creep at Omega = V / R
OMEGA = V / R  # rad/s
D = 1e-4  # m: the indentation (prescribed), the scale of the gap residual
MU = 0.3
SHAPE = (5, 5)  # the grid; the contact stays inside (nodes 6-8, 11-13, 16-18)
SIZE = 25
C0 = [6, 7, 8, 11, 13]  # contact nodes that never change
Q, Q2, RR = 12, 17, 16  # the nodes that come and go
N0 = 2.0  # N: the force of the fixed contact nodes (the largest force of every state)
W_SLIP = 0.01 * V  # m/s: slip speed of a slip node
W_OUT = np.array([0.6, 0.8]) * 0.01 * V  # m/s: slip velocity of a node outside the contact
H_OUT = 1e-6  # m: clearance of a node outside the contact
CYCLE = (r"the stick/slip sets cycle after (\d+) iterations even with one-node updates \(cone excess (\S+), "
         r"reversed slip (\S+) V, slip misfit (\S+), contact violation (\S+), set_tol (\S+)\); refine the grid, "
         r"or raise friction\.set_tol to accept such a state")


def _base(state, slip_angle=0.0):
    """The layer's answer for a state with every condition met: contact nodes carry N0;
    a stick node a force inside the cone and no slip; a slip node the force mu N e along its
    direction e and a slip velocity at ``slip_angle`` (rad) from e; outside, no force, a
    clearance H_OUT and the slip velocity W_OUT."""
    c, k, e = state.contact, state.stick, state.direction
    N = np.where(c, N0, 0.0)
    S = np.zeros((SIZE, 2))
    w = np.tile(W_OUT, (SIZE, 1))
    h = np.full(SIZE, H_OUT)
    stick, slip = c & k, c & ~k
    S[stick] = [0.5 * MU * N0, 0.0]
    w[stick] = 0.0
    S[slip] = MU * N[slip, None] * e[slip]
    rot = np.array([[np.cos(slip_angle), -np.sin(slip_angle)], [np.sin(slip_angle), np.cos(slip_angle)]])
    w[slip] = W_SLIP * e[slip] @ rot.T
    return N, S, h, w


class ScriptedLayer:
    """Stands in for the linear solves (``solves``) and the set system (``SetSystem``):
    ``respond(state) -> (N, S, h, w)`` gives the forces and the fields the layer would
    return for a set state; :meth:`fields` hands ``h`` and ``w`` to the module's own
    ``measure`` through ``delta = h - s + d`` (profile ``s = 0``) and the strains
    ``(w_x + Omega l) / V - 1``, ``w_y / V``. Records every state solved."""

    iterations = 0  # GMRES iterations (none: read by the progress line)

    def __init__(self, respond, ell=None):
        self.respond = respond
        self.states = []
        self.asked = []  # (reduction, of_b) of each solve
        self.ell = np.full(SIZE, R) if ell is None else ell
        grid = SimpleNamespace(shape=SHAPE, nodes_x=SHAPE[1], nodes_y=SHAPE[0])
        self.setup = SimpleNamespace(ops=SimpleNamespace(grid=grid, fields=self.fields), profile=np.zeros(SIZE),
                                     reach=np.ones(SIZE, bool), ell=self.ell, speed=V, mu=MU, omega=OMEGA)

    def system(self, setup, state):
        self.states.append(SimpleNamespace(contact=state.contact.copy(), stick=state.stick.copy(),
                                           direction=state.direction.copy()))
        return SimpleNamespace(state=state, unknowns=lambda *a: None)

    def __call__(self, system, guess=None, reduction=None, of_b=False):
        self.asked.append((reduction, of_b))
        N, S, h, w = self.respond(system.state)
        self._fields = (h + D, (w[:, 0] + OMEGA * self.ell) / V - 1.0, w[:, 1] / V)
        return N, S[:, 0].copy(), S[:, 1].copy(), D, OMEGA

    def fields(self, N, Sx, Sy):
        return np.stack([f.reshape(SHAPE) for f in self._fields])

    def dense(self, system):
        return False  # solved "iteratively": tight only by the misfit and the sets (tight_solve)

    def run(self, monkeypatch, start, friction=None, lines=None, forces=None):
        monkeypatch.setattr(act, "SetSystem", self.system)
        return act.run_active_set(self.setup, friction or Friction(MU, "omega", omega=OMEGA), start, self,
                                  None if lines is None else lines.append, forces=forces)


def _state(contact, stick=(), direction=None):
    c = np.zeros(SIZE, bool)
    c[list(contact)] = True
    k = np.zeros(SIZE, bool)
    k[list(stick)] = True
    e = np.zeros((SIZE, 2))
    e[c & ~k] = [1.0, 0.0] if direction is None else direction
    return act.SetState(contact=c, stick=k, direction=e, slope=np.where(c & ~k, 1.0, 0.0))


def _figures(text):
    m = re.fullmatch(CYCLE, text)
    assert m, text
    return int(m[1]), [float(x) for x in m.groups()[1:]]


# The two-state contact cycle of one node q (start: q in the contact and in tension; then
# out of the contact and penetrating; Omega given). Counted every step (the contact changes),
# a state recurring a third time switches to one-node updates at step 5; a third recurrence
# under them is checked at step 10 (the state without q) and, rejected, turns the re-entry
# rule on; the next one at step 15 (the state with q) is checked again and raises with the
# figures of that state:
#   cone excess   max(|S| / (mu N) - 1) over the stick contact nodes (none: 0),
#   reversed slip max(-w . S / (|S| V)) over the contact nodes not in stick,
#   misfit        the slip law's misfit,
#   contact       max(penetration / d, tension / max N).
CASES = {
    # q slips against its force while in tension (w_q = 0.5 V along e_q, S_q = mu N_q e_q with
    # N_q < 0): the reversed slip 0.5 V exceeds set_tol = 0.01 while the contact violation
    # (1e-7) and the misfit (0) are tiny; the state without q penetrates by 1e-6 m = 1e-2 d.
    "reversed-slip": dict(n_q=-2e-7, w_q=0.5 * V, h_q=-1e-6, angle=0.0,
                          last=dict(over=0.0, back=0.5, misfit=0.0, contact=2e-7 / N0)),
    # every slip node's velocity 30 degrees off its force (misfit sin 30 = 0.5 > set_tol),
    # contact violations tiny (1e-9 m = 1e-5 d, 1e-7 of max N), no reversed slip (w_q
    # along -e_q: w . S = -mu N_q |w_q| > 0)
    "misfit": dict(n_q=-2e-7, w_q=-0.5 * V, h_q=-1e-9, angle=np.pi / 6,
                   last=dict(over=0.0, back=0.0, misfit=0.5, contact=2e-7 / N0)),
}


def _q_cycle(p):
    """The layer of the two tests below: every node at the base answer (slip at angle
    ``p["angle"]``), and q (at l = 0.9 R: a rigid creep of 10 %) with its own normal force
    ``p["n_q"]`` and slip speed ``p["w_q"]`` along its direction in the contact, its own
    clearance ``p["h_q"]`` out of it."""
    ell = np.full(SIZE, R)
    ell[Q] = 0.9 * R

    def respond(state):
        N, S, h, w = _base(state, p["angle"])
        if state.contact[Q]:
            e = state.direction[Q]
            N[Q], S[Q], w[Q] = p["n_q"], MU * p["n_q"] * e, p["w_q"] * e
        else:
            h[Q] = p["h_q"]
        return N, S, h, w

    return ScriptedLayer(respond, ell)


class CountingLayer(ScriptedLayer):
    """A scripted layer whose every solve counts ``its`` GMRES iterations."""

    def __init__(self, respond, its):
        super().__init__(respond)
        self.its = its

    def __call__(self, system, guess=None, reduction=None, of_b=False):
        self.iterations += self.its
        return super().__call__(system, guess, reduction, of_b)


@pytest.mark.parametrize("case", CASES, ids=list(CASES))
def test_a_cycle_without_stick_nodes_is_rejected_and_reports_its_figures(monkeypatch, case):
    """Omega given, every contact node in slip (q joins in slip: a rigid creep of 10 % at
    its l = 0.9 R), so the cycling states have no stick node and the cone excess is 0 by
    definition. Each acceptance test fails on one figure alone (step 10: the contact
    violation 1e-2 > 1e-2 set_tol, or the misfit 0.5 > set_tol; step 15: the reversed slip
    0.5 > set_tol, or the misfit), so the run raises at step 15 naming that state's figures."""
    p = CASES[case]
    layer = _q_cycle(p)
    lines = []
    with pytest.raises(FrictionNotConverged) as info:
        layer.run(monkeypatch, _state(C0 + [Q]), lines=lines)
    it, (over, back, misfit, contact, set_tol) = _figures(str(info.value))
    assert it == 15 == len(lines) == len(layer.states)
    with_q = [s.contact[Q] for s in layer.states]
    assert with_q == [i % 2 == 0 for i in range(15)]  # q in, out, in, ...: the cycle
    assert not any((s.stick & s.contact).any() for s in layer.states)
    want = p["last"]
    assert set_tol == 0.01
    for got, key in ((over, "over"), (back, "back"), (misfit, "misfit"), (contact, "contact")):
        # printed to three digits (%.2e): 5e-3 relative; exact zeros print as 0.00e+00
        assert got == pytest.approx(want[key], rel=5e-3, abs=1e-15), (key, str(info.value))
    # q joined along its slip velocity outside the contact (joiners in slip slip along w)
    np.testing.assert_allclose(layer.states[2].direction[Q], W_OUT / np.hypot(*W_OUT), rtol=1e-9)


@pytest.mark.parametrize("case", CASES, ids=list(CASES))
def test_the_same_cycles_are_accepted_within_a_larger_set_tol(monkeypatch, case):
    """With set_tol above every figure of the state checked first (step 10: contact
    violation 1e-2 <= 1e-2 set_tol at set_tol = 2, misfit 0.5 <= 2), the cycle is accepted
    there and the run returns that state's solution (q out of the contact)."""
    p = CASES[case]
    layer = _q_cycle(p)
    out = layer.run(monkeypatch, _state(C0 + [Q]), friction=Friction(MU, "omega", omega=OMEGA, set_tol=2.0))
    assert len(out.history) == len(layer.states) == 10
    assert not out.state.contact[Q] and out.gap[Q] == pytest.approx(p["h_q"], rel=1e-6)


def test_one_node_updates_take_one_violation_at_a_time_in_a_cycle(monkeypatch):
    """Two nodes, each in tension in the contact and penetrating out of it (q2 the deeper,
    2e-6 m against 1e-6 m; Omega given, joiners in slip): all at once the sets alternate
    between both in and both out; after that state recurs a third time (step 5) each step
    changes one node: the deeper q2 joins, then leaves (tension comes before penetration),
    and so on; the check at step 10 (both out: 2e-6 / d = 2e-2) rejects, the one at step 15
    (q2 in: max(1e-6 / d, 0.2 N / 2 N) = 0.1) raises."""
    ell = np.full(SIZE, 0.9 * R)  # 10 % rigid creep everywhere: joiners slip

    def respond(state):
        N, S, h, w = _base(state)
        for j, n, depth in ((Q, -0.1, -1e-6), (Q2, -0.2, -2e-6)):
            if state.contact[j]:
                N[j], S[j] = n, MU * n * state.direction[j]
                w[j] = -W_SLIP * state.direction[j]  # w . S > 0: no reversed slip
            else:
                h[j] = depth
        return N, S, h, w

    layer = ScriptedLayer(respond, ell)
    with pytest.raises(FrictionNotConverged) as info:
        layer.run(monkeypatch, _state(C0 + [Q, Q2]))
    it, (over, back, misfit, contact, _) = _figures(str(info.value))
    seq = [(int(s.contact[Q]), int(s.contact[Q2])) for s in layer.states]
    both, none, q2 = (1, 1), (0, 0), (0, 1)
    assert seq == [both, none, both, none, both, none] + [q2, none] * 4 + [q2]
    assert it == 15
    assert (over, back, misfit) == (0.0, 0.0, 0.0)
    assert contact == pytest.approx(0.1, rel=5e-3)


@pytest.mark.parametrize("creep", [0.0, 0.05], ids=["no-creep", "creep-5%"])
def test_a_returning_node_joins_in_slip_once_the_reentry_rule_is_on(monkeypatch, creep):
    """Omega given, every contact node in stick. q leaves the contact in tension while it
    sticks, comes back penetrating (no rigid creep at q: it joins in stick), and cycles;
    the first check (step 10, q out: penetration 1e-6 m = 1e-2 d > 1e-2 set_tol) rejects
    and turns the re-entry rule on, so q, having left before, returns in slip (step 12), is
    then compressed (N = 1 N) and meets the slip law. Its slip lets a fresh node r penetrate;
    r never left the contact, so the re-entry rule does not apply to it: it joins in stick
    without rigid creep at its l, in slip (along its w) with a creep of 5 %. Then nothing is
    violated: converged at step 14."""
    ell = np.full(SIZE, R)
    ell[RR] = (1.0 - creep) * R

    def respond(state):
        N, S, h, w = _base(state)
        if state.contact[Q] and state.stick[Q]:
            N[Q], S[Q] = -0.1, [0.5 * MU * 0.1, 0.0]  # pulled into tension by its tangential force
        elif state.contact[Q]:
            N[Q] = 1.0
            S[Q], w[Q] = MU * 1.0 * state.direction[Q], W_SLIP * state.direction[Q]
        else:
            h[Q] = -1e-6
        if not state.contact[RR] and state.contact[Q] and not state.stick[Q]:
            h[RR] = -5e-7
        return N, S, h, w

    layer = ScriptedLayer(respond, ell)
    out = layer.run(monkeypatch, _state(C0 + [Q], stick=C0 + [Q]))
    # (in contact, in stick) of q and r; a one-node drop leaves the stick flag of the node
    # that left (unread off the contact), hence "stick & contact"
    k = [s.stick & s.contact for s in layer.states]
    seq = [(int(s.contact[Q]), int(ki[Q]), int(s.contact[RR]), int(ki[RR])) for s, ki in zip(layer.states, k)]
    q_stick, out_, q_slip = (1, 1, 0, 0), (0, 0, 0, 0), (1, 0, 0, 0)
    r_joined = (1, 0, 1, int(creep == 0.0))
    assert seq == [q_stick, out_] * 6 + [q_slip, r_joined]
    assert len(out.history) == 14 and out.state.contact[[Q, RR]].all()
    assert not out.state.stick[Q] and out.state.stick[RR] == (creep == 0.0)
    # q returned along its slip velocity outside the contact
    np.testing.assert_allclose(out.state.direction[Q], W_OUT / np.hypot(*W_OUT), rtol=1e-9)
    if creep:
        np.testing.assert_allclose(out.state.direction[RR], W_OUT / np.hypot(*W_OUT), rtol=1e-9)


@pytest.mark.parametrize("angle, its, ends", [
    (2.6e-7, 0, 2),     # the tight solve took no iteration: the misfit 2.6e-7 is the floor's
    (2.6e-7, 5, None),  # it moved the forces, and the misfit did not fall: no converged state
    (2e-5, 0, None),    # no iteration, but a misfit above ``settled`` is not rounding: not accepted
    (5e-8, 5, 2),       # below direction_tol: converged, whatever the solve took
])
def test_a_tight_solve_at_the_residual_floor_ends_the_iteration(monkeypatch, angle, its, ends):
    """Every slip velocity ``angle`` (rad) off its force, so the slip misfit stays
    ``sin(angle)`` whatever the directions: the sets repeat from the first solve, the second
    is tight (misfit <= ``loose_until``). When that tight solve took no GMRES iteration (it
    started below the residual floor) and the misfit is at most ``settled``, the state is
    accepted at iteration 2; otherwise, above direction_tol, the run goes on to max_iter and
    raises."""
    layer = CountingLayer(lambda state: _base(state, angle), its)
    friction = Friction(MU, "omega", omega=OMEGA, max_iter=6)
    start = _state(C0, stick=C0[:3])
    if ends is None:
        with pytest.raises(FrictionNotConverged, match="no converged stick/slip state in 6 iterations"):
            layer.run(monkeypatch, start, friction)
        assert len(layer.states) == 6
        return
    out = layer.run(monkeypatch, start, friction)
    assert len(out.history) == ends == len(layer.states)
    assert out.history[-1][2] == pytest.approx(np.sin(angle), rel=1e-6)


@pytest.mark.parametrize("given", [False, True])
def test_the_first_solve_from_given_forces_is_asked_its_tolerance_of_b(monkeypatch, given):
    """With ``forces`` (the coarse grid's) the first solve asks ``start_reduction`` of ``|b|``
    (``of_b``); the first without them ``loose_reduction`` of its own residual, and every later
    one ``loose_reduction`` of its own (the sets never change; the misfit, every slip velocity
    30 degrees off its force, stays 0.5: never tight)."""
    layer = CountingLayer(lambda state: _base(state, np.pi / 6), 5)
    start = _state(C0, stick=C0[:3])
    forces = (np.zeros(SIZE), np.zeros(SIZE), np.zeros(SIZE), D, OMEGA) if given else None
    with pytest.raises(FrictionNotConverged):
        layer.run(monkeypatch, start, Friction(MU, "omega", omega=OMEGA, max_iter=3), forces=forces)
    first = (SolverOptions().start_reduction, True) if given else (SolverOptions().loose_reduction, False)
    assert layer.asked == [first, (SolverOptions().loose_reduction, False), (SolverOptions().loose_reduction, False)]
    assert SolverOptions().loose_reduction == 3e-3 and SolverOptions().start_reduction == 1e-5
