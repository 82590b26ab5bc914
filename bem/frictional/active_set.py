"""Kalker's active-set iteration on the contact, stick and slip sets.

From a start state, each step solves the linear system of the current sets
(:class:`~bem.frictional.system.SetSystem`), then updates the sets: tension leaves the
contact, penetration joins it; a stick node whose force exceeds the cone
``|S| <= mu N`` slips along ``S/|S|``; a slip node whose velocity turns against its
force ``w . e <= 0`` sticks; the slip directions take ``S/|S|`` and the slopes
``k = |w| / (mu N)`` (Newton's at the solution; floored while the slip law is far from
settled, ``slope_floor``). It stops when the sets
repeat and no direction moves by more than ``direction_tol``: that state satisfies every
discrete condition exactly (to the linear solve). A recurring set state (a cycle)
switches to one-node updates; a cycle there is accepted within ``set_tol``, then
returning nodes join in slip, then it raises :class:`FrictionNotConverged`.

The solves are inexact (GMRES reducing the residual by ``loose_reduction``) until the
slip law has nearly settled, then tight. On large contacts a few stick/slip changes are
first followed along their grid rows by local solves (:mod:`bem.frictional.local`,
``local_from``). The thresholds named here are fields of
:class:`~bem.frictional.options.SolverOptions`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..contact import ContactAtEdge, edge_nodes
from .model import Friction, FrictionNotConverged, LoadingUnreachable
from ..linear import LinearSolver
from .local import solve_rows
from .options import SolverOptions
from .preconditioner import LinePreconditioner
from .system import RollingSetup, SetState, SetSystem
from .violations import measure, next_directions, next_sets

__all__ = ["ActiveSetResult", "LinearSolves", "run_active_set", "tight_solve"]


def tight_solve(misfit: float, changes: bool, careful: bool, dense: bool,
                options: SolverOptions | None = None) -> bool:
    """Whether the next solve is tight (GMRES to ``tight_reduction``) rather than inexact
    (``loose_reduction``), from the slip ``misfit`` (-) after the last solve, whether
    its sets then ``changes``, one-node updates (``careful``) and a ``dense`` LU solve: from
    a misfit of ``loose_until`` on, but right after a set change only from ``settled`` on,
    unless in one-node updates or by dense LU (``options``' fields, default
    ``SolverOptions()``)."""
    o = SolverOptions() if options is None else options
    return misfit <= o.loose_until and (not changes or misfit <= o.settled or careful or dense)


@dataclass(frozen=True, eq=False, repr=False)
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
    correction to the previous iterate by ``options.tight_reduction`` (or the reduction a
    call asks), or to ``options.residual_floor`` ``|b|``, above) with the line
    preconditioner. ``options``: :class:`~bem.frictional.options.SolverOptions`, default
    ``SolverOptions()``."""

    def __init__(self, dense_limit: int, options: SolverOptions | None = None):
        o = self.options = SolverOptions() if options is None else options
        self.solver = LinearSolver(dense_limit, o.tight_reduction, restart=o.restart, maxiter=o.max_cycles,
                                   correction=True, error=FrictionNotConverged, floor=o.residual_floor,
                                   single_from=o.single_from, single_start=o.single_start)
        self.lines = LinePreconditioner(options=o)

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
        from the first state's, and that moved the active set's path: the elastic
        paraboloid at 121 x 121 took 7 iterations instead of 5.)"""
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
                   forces: tuple | None = None, options: SolverOptions | None = None) -> ActiveSetResult:
    """Kalker's active-set iteration from the sets ``start`` (see the module docstring).

    ``options``: :class:`~bem.frictional.options.SolverOptions` (default
    ``SolverOptions()``; ``solves`` carries its own, for the linear solves). With
    ``settle`` (-) it ends as soon as the sets change by at most ``options.settle_changes``
    of the contact nodes and the slip misfit is at most ``settle``,
    without the tight solve: for a coarse level whose solution only starts the
    fine grid's iteration (its sets, slip directions and slip speeds). ``forces``: ``(N,
    S_x, S_y, d, Omega)`` (flat full-grid forces in N, m, rad/s) that start the first
    solve (:func:`~bem.frictional.starts.coarse_forces`); from zero without.

    It also ends, the sets repeating, after a tight solve that took no GMRES iteration with
    the misfit at most ``options.settled``: that solve started below the residual floor, so the
    directions cannot move any more (section 11 at 513 x 513 from another start stopped at
    a misfit of 2.6e-7 in ``||S| / (mu N) - 1|`` at an edge node carrying 2.5e-5 of the
    largest force, and repeated that state until ``max_iter``).

    Raises
    ------
    FrictionNotConverged, LoadingUnreachable, ContactAtEdge
    """
    o = SolverOptions() if options is None else options
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
        tight = tight_solve(misfit, changes, careful, solves.dense(system), o)
        # the first solve from forces given (the coarse grid's) asks start_reduction of |b|
        first = it == 1 and forces is not None and not tight
        reduction = o.start_reduction if first else None if tight else o.loose_reduction
        N, Sx, Sy, d, om = solves(system, guess, reduction, of_b=first)
        v = measure(setup, contact, stick, N, Sx, Sy, d, om, o)
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
        # |V - Omega l| exceeds slip_creep V slips (as in the start state: sliding,
        # braking); otherwise material enters the contact in stick, as in free rolling
        join_slip = v.add & (v.wmag > 0) & (not omega_free) & (np.abs(V - om * ell) > o.slip_creep * V)
        # if a cycle of one-node updates cannot be accepted, a node that left the contact
        # (in stick, pulled into tension by its tangential force) and comes back joins in
        # slip: stick there has no discrete solution
        if reentry:
            join_slip |= v.add & (v.wmag > 0) & dropped
        dropped |= v.drop
        # a tight solve that took no GMRES iteration started at the residual floor: the
        # directions it was given are as settled as the solve can make them (a misfit left
        # above direction_tol is then rounding at a node with a tiny force or slip)
        stalled = tight and solves.iterations == lin0 and not solves.dense(system) and misfit <= o.settled
        if (not changes and tight and (misfit <= friction.direction_tol or stalled)
                or settle is not None and misfit <= settle and changed <= o.settle_changes * n_contact):
            break
        prev_stick = stick
        new_c, new_s = next_sets(setup, v, contact, stick, N, join_slip, careful and changes)
        e_full, k_full = next_directions(setup, v, contact, new_c & ~new_s, N, Sx, Sy, o.slope_floor)
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
        if (0 < changed <= o.few_changes and n_contact >= o.local_from
                and not (careful or v.drop.any() or v.add.any() or solves.dense(system))):
            # a few stick/slip changes: their rows solved locally (bem.frictional.local); kept
            # when that changes more nodes
            state, Sx2, Sy2, rounds = solve_rows(setup, SetState(contact=contact, stick=stick, direction=e_full,
                                                                 slope=k_full),
                                                 np.flatnonzero(stick != prev_stick), N, Sx, Sy, om, v.fields,
                                                 o.slope_floor * min(1.0, misfit) * V, o)
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
