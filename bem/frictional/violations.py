"""What the solution of one set state violates (:func:`measure`: tension, penetration,
the cone, slip against the force, the slip law's misfit) and the state the active set
(:func:`bem.frictional.active_set.run_active_set`) takes next: its contact and stick sets
(:func:`next_sets`), its slip directions and slopes (:func:`next_directions`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .options import SolverOptions
from .system import RollingSetup

__all__ = ["Violations", "measure", "next_sets", "next_directions"]


@dataclass(frozen=True, eq=False, repr=False)
class Violations:
    """What the solution of one set state violates (flat full-grid arrays).

    Attributes
    ----------
    gap : ndarray
        ``h`` (m), ``inf`` where the indenter cannot touch.
    wx, wy, wmag : ndarray
        Slip velocity (m/s) and its magnitude.
    smag, wdot : ndarray
        ``|S|`` (N) and ``w . S`` (W).
    drop, add : ndarray of bool
        Contact nodes in tension; other nodes that penetrate.
    to_slip, to_stick : ndarray of bool
        Stick nodes beyond the cone; slip nodes whose slip turned against their force.
    slip : ndarray of bool
        Slip nodes that stay in slip.
    misfit : float
        Largest slip-law misfit on them (-): ``||S| / (mu N) - 1|`` or ``|sin(S, w)|``.
    scale : float
        ``|d|`` (m), the scale of the gap.
    fields : tuple of ndarray
        The deflection (m) and upwind strains ``du/dx, dv/dx`` (-) of the forces.
    """

    gap: np.ndarray
    wx: np.ndarray
    wy: np.ndarray
    wmag: np.ndarray
    smag: np.ndarray
    wdot: np.ndarray
    drop: np.ndarray
    add: np.ndarray
    to_slip: np.ndarray
    to_stick: np.ndarray
    slip: np.ndarray
    misfit: float
    scale: float
    fields: tuple

    @property
    def changes(self) -> bool:
        """Whether the sets must change."""
        return bool(self.drop.any() or self.add.any() or self.to_slip.any() or self.to_stick.any())


def measure(setup: RollingSetup, contact, stick, N, Sx, Sy, d, om,
            options: SolverOptions | None = None) -> Violations:
    """The violations of the solution ``N, S_x, S_y`` (N), ``d`` (m), ``Omega`` (rad/s): a
    stick node slips beyond ``mu N (1 + cone_tol)``, a node outside the contact joins once
    it penetrates by more than ``penetration_tol |d|`` (``options``' fields, default
    ``SolverOptions()``)."""
    o = SolverOptions() if options is None else options
    ops, V, mu = setup.ops, setup.speed, setup.mu
    shape = ops.grid.shape
    fields = tuple(f.ravel() for f in ops.fields(N.reshape(shape), Sx.reshape(shape), Sy.reshape(shape)))
    delta, sx, sy = fields
    h = np.where(setup.reach, setup.profile - d + delta, np.inf)
    wx, wy = V * (1 + sx) - om * setup.ell, V * sy
    scale = max(abs(d), 1e-300)
    drop = contact & (N <= 0)
    add = ~contact & (h < -o.penetration_tol * scale)
    smag = np.hypot(Sx, Sy)
    wmag = np.hypot(wx, wy)
    slip = contact & ~stick & ~drop
    to_slip = contact & stick & ~drop & (smag > mu * N * (1 + o.cone_tol))
    wdot = wx * Sx + wy * Sy
    to_stick = slip & (wdot <= 0)
    slip &= ~to_stick
    with np.errstate(invalid="ignore", divide="ignore"):
        mis_mag = np.abs(smag - mu * N)[slip] / (mu * N[slip])
        mis_dir = np.abs(Sx * wy - Sy * wx)[slip] / (smag * wmag)[slip]
    misfit = float(max(mis_mag.max(initial=0.0), mis_dir.max(initial=0.0)))
    return Violations(gap=h, wx=wx, wy=wy, wmag=wmag, smag=smag, wdot=wdot, drop=drop, add=add, to_slip=to_slip,
                      to_stick=to_stick, slip=slip, misfit=misfit, scale=scale, fields=fields)


def next_sets(setup: RollingSetup, v: Violations, contact, stick, N, join_slip, one_node: bool):
    """The next contact and stick sets: all violations at once, or (``one_node``) only the
    worst one (tension first, then penetration, cone excess, reversed slip)."""
    mu = setup.mu
    if not one_node:
        new_c = (contact & ~v.drop) | v.add
        return new_c, ((stick & ~v.to_slip) | v.to_stick | (v.add & ~join_slip)) & new_c
    new_c, new_s = contact.copy(), stick.copy()
    if v.drop.any():
        new_c[np.argmin(np.where(v.drop, N, np.inf))] = False
    elif v.add.any():
        j = np.argmin(np.where(v.add, v.gap, np.inf))
        new_c[j] = True
        new_s[j] = not join_slip[j]
    elif v.to_slip.any():
        new_s[np.argmax(np.where(v.to_slip, v.smag - mu * N, -np.inf))] = False
    else:
        new_s[np.argmin(np.where(v.to_stick, v.wdot, np.inf))] = True
    return new_c, new_s


def next_directions(setup: RollingSetup, v: Violations, contact, new_slip, N, Sx, Sy,
                    slope_floor: float = SolverOptions.slope_floor):
    """Slip directions ``e = S / |S|`` and slopes ``k`` (m/(s N)) of the next slip set, the
    slopes floored at ``slope_floor min(1, misfit) V / (mu N)``
    (:class:`~bem.frictional.options.SolverOptions`)."""
    V, mu = setup.speed, setup.mu
    with np.errstate(invalid="ignore", divide="ignore"):
        e_new = np.stack([Sx, Sy], 1) / v.smag[:, None]
        # the slope k = |w| / (mu N): Newton's (e . w) / |S| at the solution (where
        # e . w = |w| and |S| = mu N), and away from it a bound on the force's turn,
        # |e_perp . S| = mu N |sin(e, w)|; floored at slope_floor min(1, misfit) V / (mu N),
        # so that a barely slipping node keeps its force near e while the slip law is far
        # from settled
        k_new = np.maximum(np.where(v.slip, v.wmag, 0.0), slope_floor * min(1.0, v.misfit) * V) / (mu * N)
        # a node joining the contact in slip slips along w, k = |w| / (mu N), N the
        # smallest contact force
        joining = new_slip & v.add
        e_new[joining] = np.stack([v.wx, v.wy], 1)[joining] / v.wmag[joining, None]
        n_ref = float(N[contact & (N > 0)].min(initial=np.inf))
        k_new[joining] = v.wmag[joining] / (mu * n_ref)
    direction = np.where(new_slip[:, None] & ((v.smag[:, None] > 0) | joining[:, None]), e_new, 0.0)
    return direction, np.where(new_slip, np.nan_to_num(k_new), 0.0)
