"""Local solves on the grid rows where a few nodes change between stick and slip.

Why. Near the contact's lateral tips the stick zone of a row can grow by a node or two a
global solve: a slip node there sticks only once its neighbour along the row has, and
that neighbour only once the solve after its own change has moved the forces. Section 11
at 513 x 513 took four global solves for it (+8, +8, +4, +2 stick nodes), each a GMRES
solve of the whole contact.

What. After a global solve whose stick and slip sets change at a few nodes (the contact
set unchanged), the tangential forces of the contact nodes within ``local_window`` nodes
along the row of each changed node are solved again, exactly, for the new sets: the
normal forces, ``d``, ``Omega`` and every other force held, the window's own compliance
blocks dense (the rows of :func:`~bem.frictional.system.force_rows`, written from the
slip velocities ``w`` and forces the last solve left). The window's nodes are then tested
as the active set tests every node (a stick node beyond the cone slips, a slip node whose
slip turned against its force sticks), its slip directions and slopes renewed, and solved
again until its sets repeat, at most ``local_rounds`` times
(:class:`~bem.frictional.options.SolverOptions`' fields). The active set
(:func:`~bem.frictional.active_set.run_active_set`) starts its next global solve from
these forces when they changed more nodes than the global solve did; at 513 x 513 four
rounds (30 ms) settled the +8 of the first of those solves and +10 more, and the run took
9 active-set iterations instead of 10. A round costs the window's dense solve, ``(2 m)^3``
for ``m`` window nodes: the active set calls it on large contacts only
(``local_from``).
"""

from __future__ import annotations

import numpy as np

from .options import SolverOptions
from .system import RollingSetup, SetState

__all__ = ["solve_rows"]


def solve_rows(setup: RollingSetup, state: SetState, changed: np.ndarray, N, Sx, Sy, omega: float, fields,
               floor: float, options: SolverOptions | None = None):
    """The local solves after a global solve (see the module docstring).

    Parameters
    ----------
    setup : RollingSetup
    state : SetState
        The sets, slip directions and slopes the global solve's violations give.
    changed : ndarray of int
        Flat indices of the nodes whose stick/slip state changed.
    N, Sx, Sy : ndarray
        The global solve's forces (N), full grid.
    omega : float
        Its ``Omega`` (rad/s).
    fields : tuple of ndarray
        Its deflection (m) and upwind strains ``du/dx, dv/dx`` (-), full grid.
    floor : float
        The smallest slip speed (m/s) the slopes take (``slope_floor`` times ``V``, faded
        by the slip misfit, as the active set does).
    options : SolverOptions, optional
        ``local_window``, ``local_rounds`` and ``cone_tol``; default ``SolverOptions()``.

    Returns
    -------
    state : SetState
        The sets, directions and slopes after the local rounds.
    Sx, Sy : ndarray
        The tangential forces (N), new arrays.
    rounds : int
        Local solves done; 0 (and the state and forces given) when the window's rows are
        singular.
    """
    o = SolverOptions() if options is None else options
    ops, V, mu = setup.ops, setup.speed, setup.mu
    Kx = ops.grid.nodes_x
    row, col = np.divmod(np.asarray(changed), Kx)
    cols = col[:, None] + np.arange(-o.local_window, o.local_window + 1)
    inside = (cols >= 0) & (cols < Kx)
    near = np.unique((row[:, None] * Kx + cols)[inside])
    near = near[state.contact[near]]
    m = near.size
    ax, diag = ops.grid.spacing_x, ops.diagonal
    # a_x times the strains of the window's S_x, S_y (the system's stick rows)
    Dx = ax * np.hstack([ops.dense("duu", near, near), ops.dense("duv", near, near)])
    Dy = ax * np.hstack([ops.dense("dvu", near, near), ops.dense("dvv", near, near)])
    n = N[near]
    sx, sy = fields[1][near].copy(), fields[2][near].copy()
    Sx0, Sy0, Sx, Sy = Sx, Sy, Sx.copy(), Sy.copy()
    stick, direction, slope = state.stick.copy(), state.direction.copy(), state.slope.copy()
    ell = setup.ell[near]
    for rounds in range(1, o.local_rounds + 1):
        st = stick[near]
        ex, ey = direction[near, 0], direction[near, 1]
        kk = slope[near] * ax / V
        wx, wy = V * (1 + sx) - omega * ell, V * sy
        fx, fy = Sx[near], Sy[near]
        # the rows' residuals (the system's rows, b - A x, on the window)
        rx = np.where(st, -ax * wx / V, -diag * (ex * fx + ey * fy - mu * n))
        ry = np.where(st, -ax * wy / V, -(ax / V * (-ey * wx + ex * wy) + kk * (ey * fx - ex * fy)))
        slip = ~st
        # the rows on the window's S_x, S_y (force_rows' x and y rows, without N)
        A = np.vstack([Dx, Dy])
        B = np.flatnonzero(slip)
        A[B] = 0.0
        A[B, B], A[B, m + B] = diag * ex[B], diag * ey[B]
        A[m + B] = -ey[B, None] * Dx[B] + ex[B, None] * Dy[B]
        A[m + B, B] += kk[B] * ey[B]
        A[m + B, m + B] -= kk[B] * ex[B]
        try:
            step = np.linalg.solve(A, np.concatenate([rx, ry]))
        except np.linalg.LinAlgError:  # a singular window: left to the global solve
            return state, Sx0, Sy0, 0
        Sx[near] += step[:m]
        Sy[near] += step[m:]
        sx += Dx @ step / ax
        sy += Dy @ step / ax
        # the window's violations, as the active set's
        fx, fy = Sx[near], Sy[near]
        wx, wy = V * (1 + sx) - omega * ell, V * sy
        smag, wmag = np.hypot(fx, fy), np.hypot(wx, wy)
        to_slip = st & (smag > mu * n * (1 + o.cone_tol))
        to_stick = slip & (wx * fx + wy * fy <= 0)
        new = (st & ~to_slip) | to_stick
        stick[near] = new
        slips = ~new
        with np.errstate(invalid="ignore", divide="ignore"):
            e = np.stack([fx, fy], 1) / smag[:, None]
            k = np.maximum(np.where(slip & ~to_stick, wmag, 0.0), floor) / (mu * n)
        direction[near] = np.where(slips[:, None] & (smag[:, None] > 0), e, 0.0)
        slope[near] = np.where(slips, np.nan_to_num(k), 0.0)
        if not (to_slip.any() or to_stick.any()):
            break
    return SetState(contact=state.contact, stick=stick, direction=direction, slope=slope), Sx, Sy, rounds
