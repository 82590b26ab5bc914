"""Kalker's active-set iteration on the contact, stick and slip sets.

From a start state, each step solves the linear system of the current sets
(:class:`~bem.frictional.system.SetSystem`), then updates the sets: tension leaves the
contact, penetration joins it; a stick node whose force exceeds the cone
``|S| <= mu N`` slips along ``S/|S|``; a slip node whose velocity turns against its
force ``w . e <= 0`` sticks; the slip directions take ``S/|S|`` and the slopes
``k = |w| / (mu N)`` (Newton's at the solution; floored while the slip law is far from
settled, see :data:`~bem.frictional.violations.SLOPE_FLOOR`). It stops when the sets
repeat and no direction moves by more than ``direction_tol``: that state satisfies every
discrete condition exactly (to the linear solve). A recurring set state (a cycle)
switches to one-node updates; a cycle there is accepted within ``set_tol``, then
returning nodes join in slip, then it raises :class:`FrictionNotConverged`.

The solves are inexact (GMRES reducing the residual by :data:`LOOSE_REDUCTION`) until the
slip law has nearly settled, then tight. On large contacts a few stick/slip changes are
first followed along their grid rows by local solves (:mod:`bem.frictional.local`,
:data:`LOCAL_FROM`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..contact import ContactAtEdge, edge_nodes
from ..friction import Friction, FrictionNotConverged, LoadingUnreachable
from ..linear import LinearSolver
from .local import solve_rows
from .preconditioner import LinePreconditioner
from .system import RollingSetup, SetState, SetSystem
from .violations import SLOPE_FLOOR, measure, next_directions, next_sets

__all__ = ["ActiveSetResult", "LinearSolves", "run_active_set", "tight_solve"]

#: GMRES reduction of the inexact solves, and the slip misfit below which solves are tight.
#: With the row filter (:data:`bem.frictional.preconditioner.FILTER_POWER`) a reduction of
#: 1e-4 left the slip directions of the inexact solves too rough to settle: section 11 at
#: 257 x 257 11 active-set iterations (the misfit at 0.5-0.7 for four of them), at
#: 129 x 129 8; with 1e-5 7 and 7 (fine-grid GMRES 289 -> 150 at 257 x 257; 120 -> 124 at
#: 129 x 129, 86 -> 100 and 91 -> 106 on the issue-11 case at 61 x 61 and 121 x 121, the
#: same active-set iterations); 1e-6 7 iterations too but more GMRES (146 at 129 x 129).
#: Once the preconditioner eliminated ``d`` and ``Omega`` exactly (session 27) 1e-4 paid:
#: fine-grid active-set / GMRES iterations 1e-5 -> 3e-5 / 1e-4 / 3e-4 / 1e-3: issue case
#: 61 x 61 5/91 -> 5/83, 5/78, 5/70, 6/69; 121 x 121 5/99 -> 5/91, 5/86, 6/95, 7/92;
#: section 11 at 129 x 129 7/103 -> 7/93, 7/85, 8/84, 8/78; 257 x 257 7/126 -> 7/115,
#: 8/111, 10/134, 9/123; 513 x 513 10/289 -> 10/259, 9/193 (the same converged states).
#: Session 35 (coarse levels that end with a few changes left, the run inverses dense, the
#: tight solves refined in single precision), 1e-4 with 1e-3 after at most 20 changes (the
#: former ``FEW_REDUCTION``) -> 3e-3 throughout: section 11 41 x 41 5/42 -> 5/38, issue case
#: 61 x 61 5/59 -> 5/52, 121 x 121 5/67 -> 5/56, section 11 129 x 129 7/63 -> 7/54, 257 x
#: 257 7/80 -> 7/64, 513 x 513 7/121 -> 8/95 (23.5 against 25.5 s, one run each); whole
#: solves alternated, median ratios: 0.952, 0.930 (wall), 0.954 and 0.920 (CPU) at 61 x 61,
#: 121 x 121, 41 x 41 and 129 x 129; the same converged states, forces within 1.8e-10 of
#: the largest. 1e-3: 40/56/60/60/69; 2e-3 and 5e-3 8 active-set iterations at 257 x 257;
#: 1e-2 6 at 41 x 41 and 8 at 257 x 257; a second, looser or tighter reduction after at
#: most 20 changes (1e-2, 1e-3, 3e-4): no better on any grid
LOOSE_REDUCTION = 3e-3
LOOSE_UNTIL = 1e-2
#: a solve right after a set change is tight only when the misfit is at most this (-),
#: in one-node updates (whose accepted cycles keep the last solve) or by dense LU: from a
#: misfit above it the new sets' slip law is seldom settled by one solve. Measured:
#: section 11 at 513 x 513, 4 nodes stuck at a misfit of 3.3e-3, a tight solve (53 GMRES
#: iterations) left 3.1e-3; inexact (36 iterations), then tight: 303 -> 270-284 fine-grid
#: GMRES iterations (two runs), the same 9 active-set iterations and converged state; the issue-11
#: case and section 11 up to 257 x 257 unchanged (their tight solves follow no change)
SETTLED = 1e-5
#: solves that reduce their residual by this or less (the loose ones) take the products
#: inside their GMRES cycles in single precision
#: (:meth:`~bem.frictional.system.SetSystem.matvec_single`), the residual at each
#: cycle's end in double
SINGLE_FROM = 1e-4
#: a tight solve is iterative refinement: phases that each reduce the residual left by this
#: as a loose solve does (products and Krylov vectors in single precision), the residual
#: recomputed in double between them (:class:`bem.linear.LinearSolver`'s ``single_start``).
#: Measured, section 11 at 513 x 513 (the last, tight solve, from the last loose one's
#: state): all in double 31 GMRES iterations, 2.67 s; 1e-4 in single then double 20 + 12,
#: 1.46 + 0.43 s. Then every phase in single (session 35), the issue-11 case at 121 x 121
#: solved from zero to the residual floor on its converged state: 49 iterations in 228-251
#: ms against 47 (16 single, 31 double) in 270-361 ms (medians of 8, three alternations);
#: the same fine-grid iteration counts on the benchmark grids
SINGLE_START = 1e-4
#: a solve stops once its residual is below this fraction of ``|b|`` (-), whatever the
#: reduction asked: the last, tight solve starts near 1e-9 |b| and its 1e-10 reduction
#: chased rounding. Measured against the session's starting solver (GMRES iterations
#: without the floor -> with it; forces, relative to the largest): issue-11 case 61 x 61
#: 218 -> 190 (1.6e-12), 121 x 121 272 -> 233 (1.8e-11), section 11 257 x 257 455 -> 379
#: (2.0e-11). With 1e-14: 183, 223, 362 iterations but 2.2e-10 at 257 x 257
RESIDUAL_FLOOR = 1e-15
#: at most this many stick/slip changes after a solve (nodes that join or leave the stick or
#: the slip set) are few: on large contacts their rows are solved locally
#: (:data:`LOCAL_FROM`). (Until session 35 the next loose solve also reduced its residual
#: by 1e-3 only after so few changes, against 1e-4 after more; a single reduction of
#: 3e-3 for all, :data:`LOOSE_REDUCTION`, took fewer iterations on every grid.)
FEW_CHANGES = 20
#: after a solve with 1 to :data:`FEW_CHANGES` stick/slip changes on a contact of this many
#: nodes or more, the changed nodes' rows are solved locally (:mod:`bem.frictional.local`):
#: their cost does not grow with the grid, a global solve's does. Measured (the same paths
#: either way below it, where they never changed more nodes): 41 x 41 and the issue case at
#: 61 x 61 3-4 % slower with them; section 11 at 513 x 513 (141 000 contact nodes) 10 -> 9
#: active-set iterations
LOCAL_FROM = 20_000
#: the first solve from forces given (the coarse grid's, :func:`~bem.frictional.starts.
#: coarse_forces`) stops once its residual is this fraction of ``|b|`` (-): reduced by
#: :data:`LOOSE_REDUCTION` from the guess's own residual instead, it was 500 times more
#: accurate than a first solve from zero at 513 x 513 (the guess's residual 2e-3 |b|) and
#: cost GMRES iterations on the small grids. Measured (fine-grid active-set / GMRES
#: iterations; from zero (session 30) -> the guess's residual reduced by 1e-4 -> to 1e-4,
#: 1e-5, 1e-6, 1e-7 |b|): section 11 at 41 x 41 5/41 -> 5/44 -> 5/40, 5/41, 5/43, 5/46;
#: issue case 61 x 61 5/61 -> 5/66 -> 5/56, 5/59, 5/61, 5/64; 121 x 121 5/74 -> 5/77 ->
#: 6/75, 5/67, 5/70, 5/74; section 11 at 129 x 129 7/67 -> 7/70 -> 7/64, 7/63, 7/68, 7/71;
#: 257 x 257 7/90 -> 7/87 -> 8/83, 7/79, 7/85, 7/89; 513 x 513 9/159 -> 7/133 -> 8/139,
#: 7/121, 7/127, 7/141 (the same converged states throughout)
START_REDUCTION = 1e-5
#: a coarse level (``settle`` given) ends once its slip misfit is at most ``settle`` and its
#: sets change by at most this fraction of its contact nodes (-): the fine grid reads its
#: sets and forces as a start and moves its stick/slip border anyway; the solve that would
#: confirm the last few changes is saved. Measured (whole solves alternated with 0, median
#: ratios; fine-grid active-set / GMRES iterations): issue-11 case 61 x 61 0.948 (5/59
#: both), 121 x 121 0.966 (5/67 both; its 61 x 61 level ends one solve earlier, after 4
#: changes on 2061 contact nodes); section 11 41 x 41 0.907 (5/41 -> 5/42), 129 x 129 0.997
#: (7/63 both); 257 x 257 7/79 -> 7/80; the same converged states. With ``COARSE_SETTLE``
#: 1.0 as well the 61 x 61 grid took 5/64
SETTLE_CHANGES = 0.01


def tight_solve(misfit: float, changes: bool, careful: bool, dense: bool) -> bool:
    """Whether the next solve is tight (GMRES to 1e-10) rather than inexact
    (:data:`LOOSE_REDUCTION`), from the slip ``misfit`` (-) after the last solve, whether
    its sets then ``changes``, one-node updates (``careful``) and a ``dense`` LU solve: from
    a misfit of :data:`LOOSE_UNTIL` on, but right after a set change only from
    :data:`SETTLED` on, unless in one-node updates or by dense LU."""
    return misfit <= LOOSE_UNTIL and (not changes or misfit <= SETTLED or careful or dense)


@dataclass(frozen=True)
class ActiveSetResult:
    """The converged state of :func:`run_active_set` (flat full-grid arrays).

    Attributes
    ----------
    N, Sx, Sy : ndarray
        Normal (compressive) and tangential nodal forces (N).
    indentation : float
        ``d`` (m).
    omega : float
        ``Omega`` (rad/s).
    state : SetState
        The final sets.
    history : list of tuple
        Per iteration: contact nodes, stick nodes, slip misfit (-), ``Omega`` (rad/s).
    gap : ndarray
        ``h`` (m), ``inf`` where the indenter cannot touch.
    scale : float
        ``|d|`` (m), the scale of the gap residual.
    fields : tuple of ndarray or None
        The deflection (m) and upwind strains (-) of the forces (:meth:`~bem.frictional.
        operators.RollingOperators.fields`, flat); ``None``: computed by who needs them.
    """

    N: np.ndarray
    Sx: np.ndarray
    Sy: np.ndarray
    indentation: float
    omega: float
    state: SetState
    history: list
    gap: np.ndarray
    scale: float
    fields: tuple | None


class LinearSolves:
    """The linear solves of one frictional solve: :class:`bem.linear.LinearSolver` (dense
    LU up to ``dense_limit`` unknowns, flexible GMRES reducing the residual of the
    correction to the previous iterate by ``reduction``, or to :data:`RESIDUAL_FLOOR`
    ``|b|``, above) with the line preconditioner."""

    def __init__(self, dense_limit: int, reduction: float = 1e-10):
        self.solver = LinearSolver(dense_limit, reduction, restart=200, maxiter=10, correction=True,
                                   error=FrictionNotConverged, floor=RESIDUAL_FLOOR, single_from=SINGLE_FROM,
                                   single_start=SINGLE_START)
        self.lines = LinePreconditioner()

    @property
    def iterations(self) -> int:
        return self.solver.iterations

    @property
    def used_gmres(self) -> bool:
        return self.solver.used_gmres

    def dense(self, system: SetSystem) -> bool:
        """Whether ``system`` is solved by dense LU (exactly, whatever the reduction)."""
        return system.n <= self.solver.dense_limit

    def prepare(self, system: SetSystem) -> None:
        """Build ahead what the solves of ``system``'s contact set share (the line
        preconditioner's row inverses and row filter, the spectra of the products in both
        precisions; not the whole grid's field spectra: :func:`bem.frictional.solve.
        _first_solves` has them built by whichever thread is free first), e.g. on an idle
        thread: the first solve then starts sooner. Nothing for a dense system. (Not the
        Schur parts of ``d`` and ``Omega``: from an all-stick state they differ a little
        from the first state's, and that moved the active set's path: 121 x 121 issue case
        7 iterations instead of 5.)"""
        if self.dense(system):
            return
        self.lines.prepare(system)
        zero = np.zeros(system.n)
        system.matvec(zero)
        system.matvec_single(zero)

    def __call__(self, system: SetSystem, guess=None, reduction: float | None = None, of_b: bool = False):
        if not self.dense(system):
            self.lines.attach(system)
        x = self.solver(system, guess, rtol=reduction, what=f"{system.nC} contact nodes ({system.A.size} stick)",
                        hint="refine the grid less or raise friction.dense_limit", of_b=of_b)
        return system.full(x)


def run_active_set(setup: RollingSetup, friction: Friction, start: SetState, solves: LinearSolves,
                   progress: Callable[[str], None] | None = None, settle: float | None = None,
                   forces: tuple | None = None) -> ActiveSetResult:
    """Kalker's active-set iteration from the sets ``start`` (see the module docstring).

    With ``settle`` (-) it ends as soon as the sets change by at most
    :data:`SETTLE_CHANGES` of the contact nodes and the slip misfit is at most ``settle``,
    without the tight solve: for a coarse level whose solution only starts the
    fine grid's iteration (its sets, slip directions and slip speeds). ``forces``: ``(N,
    S_x, S_y, d, Omega)`` (flat full-grid forces in N, m, rad/s) that start the first
    solve (:func:`~bem.frictional.starts.coarse_forces`); from zero without.

    It also ends, the sets repeating, after a tight solve that took no GMRES iteration with
    the misfit at most :data:`SETTLED`: that solve started below the residual floor, so the
    directions cannot move any more (section 11 at 513 x 513 from another start stopped at
    a misfit of 2.6e-7 in ``||S| / (mu N) - 1|`` at an edge node carrying 2.5e-5 of the
    largest force, and repeated that state until ``max_iter``).

    Raises
    ------
    FrictionNotConverged, LoadingUnreachable, ContactAtEdge
    """
    ops = setup.ops
    g = ops.grid
    shape, size = g.shape, g.nodes_x * g.nodes_y
    ell, V = setup.ell, setup.speed
    mu, omega_free = setup.mu, setup.omega is None
    contact, stick = start.contact.copy(), start.stick.copy()
    e_full, k_full = start.direction.copy(), start.slope.copy()
    dropped = np.zeros(size, bool)
    solved = contact  # the contact set of the last solution
    reentry = False
    seen: dict = {}
    careful = False
    history = []
    wx = wy = np.zeros(size)
    misfit = np.inf
    changes = True
    changed = np.inf  # set changes at the last measure
    known = None  # the fields of the last solution's forces, when the next guess holds them
    for it in range(1, friction.max_iter + 1):
        if omega_free and not (stick & contact).any():  # Omega needs one stick node at least
            Sl = np.flatnonzero(contact)
            stick[Sl[np.argmin(np.hypot(wx[Sl], wy[Sl]))]] = True
        system = SetSystem(setup, SetState(contact=contact, stick=stick, direction=e_full, slope=k_full))
        start_guess = forces if it == 1 else (N, Sx, Sy, d, om)
        guess = None if start_guess is None else system.unknowns(*start_guess)
        if guess is not None and known is not None and not (solved & ~contact).any():
            # the guess's forces are the last solution's: its fields, computed for the
            # violations, give the new rows' residual without another product
            system.know(guess, [f[system.C] for f in known])
        solved = contact
        lin0 = solves.iterations
        # inexact solves while the slip law is far from settled (the sets and directions
        # change by more than the solve's error); only a tight solve can end the iteration
        tight = tight_solve(misfit, changes, careful, solves.dense(system))
        # the first solve from forces given (the coarse grid's) asks START_REDUCTION of |b|
        first = it == 1 and forces is not None and not tight
        reduction = START_REDUCTION if first else None if tight else LOOSE_REDUCTION
        N, Sx, Sy, d, om = solves(system, guess, reduction, of_b=first)
        v = measure(setup, contact, stick, N, Sx, Sy, d, om)
        misfit, wx, wy = v.misfit, v.wx, v.wy
        n_contact, n_stick = int(contact.sum()), int((stick & contact).sum())
        history.append((n_contact, n_stick, misfit, om))
        if progress:
            progress(f"friction {it}: {n_contact} contact, {n_stick} stick, "
                     f"Omega = {om:.8g} rad/s, -{int(v.drop.sum())} +{int(v.add.sum())} contact, "
                     f"+{int(v.to_slip.sum())} slip, +{int(v.to_stick.sum())} stick, slip misfit {misfit:.2e}"
                     + (f", {solves.iterations - lin0} GMRES iterations" if solves.iterations > lin0 else ""))
        changes = v.changes
        changed = int(v.drop.sum() + v.add.sum() + v.to_slip.sum() + v.to_stick.sum())
        # with Omega prescribed, a node joining the contact where the rigid creep
        # |V - Omega l| exceeds 1 % of V slips (as in the start state: sliding, braking);
        # otherwise material enters the contact in stick, as in free rolling
        join_slip = v.add & (v.wmag > 0) & (not omega_free) & (np.abs(V - om * ell) > 1e-2 * V)
        # if a cycle of one-node updates cannot be accepted, a node that left the contact
        # (in stick, pulled into tension by its tangential force) and comes back joins in
        # slip: stick there has no discrete solution
        if reentry:
            join_slip |= v.add & (v.wmag > 0) & dropped
        dropped |= v.drop
        # a tight solve that took no GMRES iteration started at the residual floor: the
        # directions it was given are as settled as the solve can make them (a misfit left
        # above direction_tol is then rounding at a node with a tiny force or slip)
        stalled = tight and solves.iterations == lin0 and not solves.dense(system) and misfit <= SETTLED
        if (not changes and tight and (misfit <= friction.direction_tol or stalled)
                or settle is not None and misfit <= settle and changed <= SETTLE_CHANGES * n_contact):
            break
        prev_stick = stick
        new_c, new_s = next_sets(setup, v, contact, stick, N, join_slip, careful and changes)
        e_full, k_full = next_directions(setup, v, contact, new_c & ~new_s, N, Sx, Sy)
        key = np.packbits(np.concatenate([new_c, new_s])).tobytes()
        # cycles count once the slip law has settled, or when the contact set itself cycles
        if changes and (misfit <= friction.set_tol or v.drop.any() or v.add.any()):
            seen[key] = seen.get(key, 0) + 1
            if seen[key] > 2:
                if careful:
                    # a two-state cycle at the stick/slip border: accept the state when its
                    # violations are below the set tolerance (recorded in the residuals)
                    with np.errstate(invalid="ignore", divide="ignore"):
                        over = float(np.nan_to_num(v.smag / (mu * N) - 1)[contact & stick].max(initial=0.0))
                        back = float(np.nan_to_num(-v.wdot / (v.smag * V))[contact & ~stick].max(initial=0.0))
                    gap_v = max(float((-v.gap[v.add]).max(initial=0.0)) / v.scale,
                                float((-N[v.drop]).max(initial=0.0)) / float(N.max()))
                    if gap_v <= 1e-2 * friction.set_tol and max(over, back, misfit) <= friction.set_tol:
                        break
                    if not reentry:  # last resort: returning nodes join in slip
                        reentry = True
                        seen.clear()
                        contact, stick = new_c, new_s
                        continue
                    raise FrictionNotConverged(
                        f"the stick/slip sets cycle after {it} iterations even with one-node updates "
                        f"(cone excess {over:.2e}, reversed slip {back:.2e} V, slip misfit {misfit:.2e}, "
                        f"contact violation {gap_v:.2e}, set_tol {friction.set_tol}); refine the grid, "
                        "or raise friction.set_tol to accept such a state")
                careful = True
                seen.clear()
        contact, stick = new_c, new_s
        known = v.fields
        if (0 < changed <= FEW_CHANGES and n_contact >= LOCAL_FROM
                and not (careful or v.drop.any() or v.add.any() or solves.dense(system))):
            # a few stick/slip changes: their rows solved locally (bem.frictional.local); kept
            # when that changes more nodes
            state, Sx2, Sy2, rounds = solve_rows(setup, SetState(contact=contact, stick=stick, direction=e_full,
                                                                 slope=k_full),
                                                 np.flatnonzero(stick != prev_stick), N, Sx, Sy, om, v.fields,
                                                 SLOPE_FLOOR * min(1.0, misfit) * V)
            if rounds > 1:
                if progress:
                    progress(f"  local rows: {rounds} rounds, {int((state.stick & ~stick).sum())} more stick, "
                             f"{int((stick & ~state.stick).sum())} more slip")
                stick, e_full, k_full, Sx, Sy, known = state.stick, state.direction, state.slope, Sx2, Sy2, None
        if not contact.any():
            raise FrictionNotConverged("the contact set emptied: check the load and the indenter profile")
    else:
        _unreachable_or_not_converged(friction, history)
    if (contact & edge_nodes(shape)).any():
        raise ContactAtEdge("the contact reaches the edge of the candidate region: increase grid.half_width")
    state = SetState(contact=contact, stick=stick, direction=e_full, slope=k_full)
    return ActiveSetResult(N=N, Sx=Sx, Sy=Sy, indentation=d, omega=om, state=state, history=history, gap=v.gap,
                           scale=v.scale, fields=v.fields)


def _unreachable_or_not_converged(friction: Friction, history) -> None:
    if friction.mode in ("pushed_at_top", "torque") and history and history[-1][1] <= 1:
        raise LoadingUnreachable(f"mode {friction.mode!r}: the whole contact slips and the equilibrium "
                                 f"cannot be met with mu = {friction.mu}; raise mu or use mode 'towed' or 'omega'")
    raise FrictionNotConverged(f"no converged stick/slip state in {friction.max_iter} iterations "
                               f"(last direction change {history[-1][2]:.2e}); raise friction.max_iter "
                               "or friction.direction_tol")
