"""Solver of steady rolling/sliding contact with Coulomb friction (see :mod:`bem.friction`).

Kalker's active-set algorithm (Kalker 1990, "Three-dimensional elastic bodies in rolling
contact", ch. 3; the CONTACT code's NORM/TANG iterations), done on the coupled system:
for a trial contact set ``C``, stick set ``A`` (subset of ``C``) and slip directions ``e``
on the slip set ``C \\ A``, every condition is linear in the unknowns
``(N_C, S_A, d, Omega)``:

* gap ``h = 0`` on ``C`` (normal forces of slip nodes bring their friction
  ``S = mu N e`` along, so the normal-tangential coupling of a layer is kept exactly);
* no slip, ``w = 0`` (two rows), on ``A``;
* ``sum N = P`` (load control) and the loading mode's equilibrium row (unless
  ``Omega`` is given).

Linear solves. Up to ``Friction.dense_limit`` unknowns (default 1000) one dense LU
(``O((3 n_C)^3)``); above, restarted GMRES with the nine blocks applied by FFT (three
forward and three inverse transforms per product, ``O(N)`` memory). Its preconditioner
undoes the two things that make the system unlike a static contact: the stick rows are
upwind differences ``u_{i+1} - u_i`` (a circulant embedding of the differenced compliance
is singular at ``nu_x = 0``), so they are first summed along ``x`` from each run of
contact nodes' leading end (the exact inverse of the difference, up to the displacement
just ahead of the run, which is dropped); the displacements so obtained and the gap rows
are mapped to forces by the inverse, frequency by frequency, of the 3 x 3 circulant
embedding of the undifferenced compliance; slip nodes then take their force along ``e``
from their own row ``e . S = mu N``. GMRES solves for the correction to the previous
active-set iterate, reducing its residual by 1e-10, so the solves sharpen as the slip
directions settle. Section 11 at 41 x 41: 30-80 GMRES iterations per solve (1800
without the preconditioner); 257 x 257 (35 000 contact nodes): see ``BENCHMARKS.md``.
Then the sets
are updated: tension leaves the contact, penetration joins it; a stick node whose force
exceeds the cone ``|S| <= mu N`` slips along ``S/|S|``; a slip node whose velocity turns
against its force ``w . e <= 0`` sticks; the slip directions take ``w/|w|`` (a fixed point
that contracts because slip velocities hardly turn between iterations). It stops when
the sets repeat and no direction moves by more than ``direction_tol``; that state
satisfies every discrete condition exactly (to the linear solve). Why this and not a
semi-smooth Newton method on ``S = proj(S + c w)``: the active-set iteration needs no
parameter ``c`` (whose good value depends on the non-symmetric, badly scaled compliance),
ends on an exact complementarity state, each step is one linear solve the size of the
contact, and it typically needs 5-20 steps here because slip zones are small; a recurring
set state (a cycle) switches to one-node updates and then raises.

Robustness. With ``Omega`` prescribed, nodes whose rigid creep ``|V - Omega l|`` exceeds
1 % of ``V`` start (and join the contact) in slip along it with the slip law's own
linearisation ``k = |w| / (mu N)`` (pure sliding then converges in 2-5 steps at any
``mu``). If a cycle of one-node updates cannot be accepted, a node that left the contact
and comes back joins in slip from then on. When the direct
solve of a free-``Omega`` mode fails (typically towed with a tiny ``mu``, where one stick
node must sit where the slip reverses), a continuation in ``mu`` halves ``mu`` from about
0.2 down to the requested value, each solve starting from the previous state; if that
fails too, :class:`FrictionNotConverged` says where it stopped.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Callable

import numpy as np
import scipy.fft as sfft
from scipy.sparse.linalg import LinearOperator, gmres

from .contact import ContactAtEdge, ContactError, solve_normal, _coarse_grid, _edge_nodes
from .energy import viscous_dissipation
from .friction import Friction, FrictionalContact, FrictionNotConverged, FrictionRecord, LoadingUnreachable
from .grid import Grid
from .kinematics import indenter_radius, rolling_radius, upwind_table
from .operator import ComplianceOperator
from .problem import Problem, compute_kernels
from .spectral import BLOCKS

__all__ = ["RollingOperators", "solve_rolling", "solve_friction"]

_DIFFERENCED = ("uw", "uu", "uv", "vw", "vu", "vv")


class RollingOperators:
    """The nine kernel tables of a grid, the upwind-differenced ``u, v`` rows, their
    dense blocks and FFT operators (built on demand), and the inverse of the undifferenced
    3 x 3 circulant embedding (the matrix-free solver's preconditioner)."""

    def __init__(self, grid: Grid, kernels: dict):
        self.grid = grid
        self.kernels = kernels
        self.tables = {b: kernels[b] for b in ("ww", "wu", "wv")}
        for b in _DIFFERENCED:
            self.tables["d" + b] = upwind_table(kernels[b], grid.spacing_x)
        self._ops: dict = {}
        self._inverse3 = None

    def op(self, name: str) -> ComplianceOperator:
        if name not in self._ops:
            table = self.tables[name] if name in self.tables else self.kernels[name]
            self._ops[name] = ComplianceOperator(self.grid, table)
        return self._ops[name]

    def dense(self, name: str, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        Ky, Kx = self.grid.shape
        jr, ir = np.divmod(rows, Kx)
        jc, ic = np.divmod(cols, Kx)
        return self.tables[name][(jr[:, None] - jc[None, :]) + Ky - 1, (ir[:, None] - ic[None, :]) + Kx - 1]

    def _convolve(self, names, N, Sx, Sy):
        """``sum_j sign_j K_j * f_j`` for each row of ``names`` (block names with signs,
        ``-`` for the normal force ``-N``), sharing the three forward FFTs."""
        Ky, Kx = self.grid.shape
        emb = self.op("ww").embedding
        F = [sfft.rfft2(np.asarray(f, float).reshape(Ky, Kx), s=emb, workers=-1) for f in (N, Sx, Sy)]
        out = []
        for row in names:
            acc = sum(sign * self.op(name).spectrum * f for (sign, name), f in zip(row, F))
            out.append(sfft.irfft2(acc, s=emb, workers=-1)[:Ky, :Kx])
        return out

    def fields(self, N, Sx, Sy):
        """Downward deflection (m) and upwind strains ``du/dx, dv/dx`` (-) on the grid."""
        return self._convolve((((1, "ww"), (-1, "wu"), (-1, "wv")),
                               ((-1, "duw"), (1, "duu"), (1, "duv")),
                               ((-1, "dvw"), (1, "dvu"), (1, "dvv"))), N, Sx, Sy)

    def displacements(self, N, Sx, Sy):
        """Horizontal surface displacements ``u, v`` (m)."""
        return self._convolve((((-1, "uw"), (1, "uu"), (1, "uv")),
                               ((-1, "vw"), (1, "vu"), (1, "vv"))), N, Sx, Sy)

    def inverse3(self) -> np.ndarray:
        """Inverse, frequency by frequency, of the circulant embedding of the map from
        ``(N, S_x, S_y)`` to ``(delta, u, v)`` (shape ``(*embedding_spectrum, 3, 3)``).
        Raises ``ZeroDivisionError`` if a frequency's 3 x 3 symbol is (nearly) singular."""
        if self._inverse3 is None:
            sym = np.empty(self.op("ww").spectrum.shape + (3, 3), complex)
            for i, a in enumerate("wuv"):  # delta = C_ww N - C_wu S_x - ..., u = -C_uw N + C_uu S_x + ...
                for j, b in enumerate("wuv"):
                    sym[..., i, j] = (1 if (i == 0) == (j == 0) else -1) * self.op(a + b).spectrum
            s = np.linalg.svd(sym, compute_uv=False)
            if not (s[..., -1] > 1e-12 * s[..., 0].max()).all():
                raise ZeroDivisionError("the 3 x 3 circulant embedding of the compliance is nearly singular")
            self._inverse3 = np.linalg.inv(sym)
        return self._inverse3


def _constraint(mode: str, arm, ell, R):
    """Coefficients ``(c_N, c_x)`` of the loading mode's row ``c_N . N + c_x . S_x = 0``."""
    if mode == "pushed_at_top":  # Q R = -sum l S_x, Q = sum N arm + sum S_x
        return R * arm, R + ell
    if mode == "towed":  # T = 0
        return np.zeros_like(arm), ell
    if mode == "torque":  # Q = 0
        return arm, np.ones_like(arm)
    return None


class _SetSystem:
    """The linear system of one active-set state, dense or matrix-free.

    Unknowns ``x = (N_C, Sx_C, Sy_C, d, Omega / om_unit)`` (``d`` under load control,
    ``Omega`` when free, in units of ``om_unit = V / mean(l)`` rad/s). Rows, all in metres: the gap on ``C``; on stick nodes ``a_x w_x / V`` and
    ``a_x w_y / V`` (the upwind differences ``u_{i+1} - u_i`` plus the rigid creep); on
    slip nodes the Newton linearisation of eqs. 17-18 about the current force direction
    ``e``: ``e . S = mu N`` (times the diagonal compliance) and
    ``a_x (e_perp . w - k e_perp . S) / V = 0`` with ``k = (e . w) / |S|`` from the previous
    iterate; ``sum N = P`` (times the diagonal compliance); the loading mode's row.
    :meth:`rows` writes them once for both the dense matrix and the FFT product.
    """

    def __init__(self, ops, s, C, stick, e, k, mu, ell, V, load, indentation, omega, cons):
        g = ops.grid
        self.ops, self.C, self.mu = ops, C, mu
        nC = self.nC = C.size
        self.free_d, self.free_om = load is not None, omega is None
        self.n = 3 * nC + self.free_d + self.free_om
        self.iD, self.iO = 3 * nC, 3 * nC + self.free_d
        self.diag = float(ops.tables["ww"][g.nodes_y - 1, g.nodes_x - 1])
        self.ax = ax = g.spacing_x
        st = stick[C]
        self.A, self.B = np.flatnonzero(st), np.flatnonzero(~st)
        self.ex, self.ey = e[C[self.B], 0], e[C[self.B], 1]
        self.kk = k[C[self.B]] * ax / V
        # a free Omega is solved for in units of om_unit = V / mean(l) (the free-rolling
        # value), so that the unknowns are O(1) at any speed (unscaled, Omega ~ V / R made
        # GMRES fail from about 1e50 m/s on)
        mean_l = float(np.abs(ell[C]).mean())
        self.om_unit = V / mean_l
        self.ox = -ax * ell[C] / mean_l  # the scaled Omega's coefficient in a_x w_x / V
        if self.free_om:
            cN, cx = cons
            scale = self.diag / max(np.abs(cx).max(), 1e-300)
            self.cN, self.cx = cN[C] * scale, cx[C] * scale
            # the preconditioner's Omega step: the inverse of its stick-row coefficient
            self.om_step = 1.0 / ax
        # right-hand side: the rows' constant parts, moved over
        bx = -ax * np.ones(nC) + (0.0 if self.free_om else ax * omega * ell[C] / V)
        b = np.zeros(self.n)
        b[:nC] = -s[C] + (0.0 if self.free_d else indentation)
        b[nC + self.A] = bx[self.A]
        b[2 * nC + self.B] = -self.ey * bx[self.B]
        if self.free_d:
            b[self.iD] = self.diag * load
        self.b = b
        self.omega, self.indentation = omega, indentation

    def rows(self, gap, Dx, Dy, X):
        """Rows for unknowns ``X`` (``n x m``), given ``gap = C_ww N - C_wu S_x - C_wv S_y``
        and ``Dx, Dy`` (the upwind differences of ``u, v``) on ``C`` (``nC x m``)."""
        nC, A, B = self.nC, self.A, self.B
        N, Sx, Sy = X[:nC], X[nC:2 * nC], X[2 * nC:3 * nC]
        out = np.empty((self.n, X.shape[1]))
        out[:nC] = gap - X[self.iD] if self.free_d else gap
        if self.free_om:
            Dx = Dx + self.ox[:, None] * X[self.iO]
        out[nC + A], out[2 * nC + A] = Dx[A], Dy[A]
        ex, ey = self.ex[:, None], self.ey[:, None]
        out[nC + B] = self.diag * (ex * Sx[B] + ey * Sy[B] - self.mu * N[B])
        out[2 * nC + B] = -ey * Dx[B] + ex * Dy[B] + self.kk[:, None] * (ey * Sx[B] - ex * Sy[B])
        if self.free_d:
            out[self.iD] = self.diag * N.sum(0)
        if self.free_om:
            out[self.iO] = self.cN @ N + self.cx @ Sx
        return out

    def dense(self) -> np.ndarray:
        ops, C, nC, ax = self.ops, self.C, self.nC, self.ax
        pad = np.zeros((nC, self.n - 3 * nC))

        def block(names, factor=1.0):
            return factor * np.hstack([sg * ops.dense(nm, C, C) for sg, nm in names] + [pad])

        gap = block(((1, "ww"), (-1, "wu"), (-1, "wv")))
        Dx = block(((-1, "duw"), (1, "duu"), (1, "duv")), ax)
        Dy = block(((-1, "dvw"), (1, "dvu"), (1, "dvv")), ax)
        return self.rows(gap, Dx, Dy, np.eye(self.n))

    def full(self, x):
        """Full-grid ``N, S_x, S_y`` and ``d, Omega`` from the unknowns."""
        g = self.ops.grid
        size, nC, C = g.nodes_x * g.nodes_y, self.nC, self.C
        N, Sx, Sy = np.zeros(size), np.zeros(size), np.zeros(size)
        N[C], Sx[C], Sy[C] = x[:nC], x[nC:2 * nC], x[2 * nC:3 * nC]
        d = x[self.iD] if self.free_d else self.indentation
        om = x[self.iO] * self.om_unit if self.free_om else self.omega
        return N, Sx, Sy, float(d), float(om)

    def unknowns(self, N, Sx, Sy, d, om):
        """The inverse of :meth:`full` (a starting guess from full-grid fields)."""
        C = self.C
        glob = ([d] if self.free_d else []) + ([om / self.om_unit] if self.free_om else [])
        return np.concatenate([N[C], Sx[C], Sy[C], glob])

    def matvec(self, x):
        N, Sx, Sy, _, _ = self.full(x)
        gap, ex, ey = (f.ravel()[self.C, None] for f in self.ops.fields(N, Sx, Sy))
        return self.rows(gap, self.ax * ex, self.ax * ey, x[:, None])[:, 0]

    def _runs(self):
        """Runs of contact nodes along ``x``: for each contact node the column of the
        first off-contact node at or after it (``K_x`` if none), on the full grid."""
        if not hasattr(self, "_ahead"):
            Ky, Kx = self.ops.grid.shape
            off = np.ones(Ky * Kx, bool)
            off[self.C] = False
            nxt = np.where(off.reshape(Ky, Kx), np.arange(Kx)[None, :], Kx)[:, ::-1]
            self._ahead = np.minimum.accumulate(nxt, axis=1)[:, ::-1]
        return self._ahead

    def _upstream_sum(self, rho):
        """``u`` with ``u_{i+1} - u_i = rho_i`` on each run of contact nodes along ``x``
        and ``u = 0`` at the first node past the run's leading end."""
        Ky, Kx = self.ops.grid.shape
        r = np.zeros(Ky * Kx)
        r[self.C] = rho
        cs = np.cumsum(r.reshape(Ky, Kx)[:, ::-1], axis=1)[:, ::-1]  # sum over j >= i
        past = np.take_along_axis(np.hstack([cs, np.zeros((Ky, 1))]), self._runs(), 1)
        return -(cs - past).ravel()[self.C]

    def _to_forces(self, tw, tu, tv, r1):
        """Unknowns (forces part) from target gap and displacements on ``C`` by the inverse
        3 x 3 circulant embedding; slip nodes take ``e . S = mu N + r1 / diag``."""
        nC, C, B = self.nC, self.C, self.B
        Ky, Kx = self.ops.grid.shape
        emb = self.ops.op("ww").embedding
        F = []
        for target in (tw, tu, tv):
            f = np.zeros(Ky * Kx)
            f[C] = target
            F.append(sfft.rfft2(f.reshape(Ky, Kx), s=emb, workers=-1))
        G = np.einsum("...ij,j...->i...", self.ops.inverse3(), np.stack(F))
        out = np.empty(3 * nC)
        for c in range(3):
            out[c * nC:(c + 1) * nC] = sfft.irfft2(G[c], s=emb, workers=-1)[:Ky, :Kx].ravel()[C]
        sx, sy = out[nC + B], out[2 * nC + B]
        fix = self.mu * out[B] + r1 / self.diag - (self.ex * sx + self.ey * sy)
        out[nC + B], out[2 * nC + B] = sx + fix * self.ex, sy + fix * self.ey
        return out

    def precondition(self, r):
        """Approximate inverse: turn the difference rows into displacements by summing
        them from each run's leading end (dropping the displacement just ahead of it),
        map the displacements to forces by the inverse 3 x 3 circulant embedding, then
        set the slip nodes' force along ``e`` from their first row.

        A Woodbury correction for the dropped displacement (one unknown per run and
        component) was tried and raised the GMRES iterations (78 -> 120 at 61 x 61): a
        uniform displacement of a run moves the node just ahead of it almost as much, so
        the correction's small system is nearly singular and amplifies the circulant
        approximation's error."""
        nC, B = self.nC, self.B
        rg, rx, ry = r[:nC], r[nC:2 * nC], r[2 * nC:3 * nC]
        rho_x, rho_y = rx.copy(), ry.copy()
        rho_x[B], rho_y[B] = -self.ey * ry[B], self.ex * ry[B]
        y = self._to_forces(rg, self._upstream_sum(rho_x), self._upstream_sum(rho_y), rx[B])
        out = np.empty(self.n)
        out[:3 * nC] = y
        if self.free_d:
            out[self.iD] = r[self.iD]
        if self.free_om:
            out[self.iO] = r[self.iO] * self.om_step
        return out


class _LinearSolves:
    """Dense LU up to ``dense_limit`` unknowns, preconditioned GMRES (FFT products,
    ``O(N)`` memory) above; counts the GMRES iterations.

    GMRES solves for the correction to the previous active-set iterate and reduces its
    residual by ``reduction``: each solve gains accuracy as the slip directions settle, so
    the fixed point is not stalled by a tolerance relative to ``b`` (the slip law's misfit
    is measured on the smallest forces and slip speeds, at the edges of the slip zone)."""

    def __init__(self, dense_limit: int, reduction: float = 1e-10):
        self.dense_limit, self.reduction = dense_limit, reduction
        self.used_gmres, self.iterations = False, 0

    def __call__(self, system: _SetSystem, guess=None):
        n = system.n
        if n <= self.dense_limit:
            try:
                return system.full(np.linalg.solve(system.dense(), system.b))
            except np.linalg.LinAlgError as exc:
                raise FrictionNotConverged(f"singular system on {system.nC} contact / "
                                           f"{system.A.size} stick nodes: {exc}") from exc
        self.used_gmres = True
        try:
            system.ops.inverse3()
            M = LinearOperator((n, n), matvec=system.precondition, dtype=float)
        except ZeroDivisionError:
            M = None
        count = [0]
        x0 = np.zeros(n) if guess is None else guess
        r0 = system.b - system.matvec(x0)
        dx, info = gmres(LinearOperator((n, n), matvec=system.matvec, dtype=float), r0,
                         rtol=self.reduction, atol=0.0, restart=200, maxiter=10, M=M,
                         callback=lambda _: count.__setitem__(0, count[0] + 1), callback_type="pr_norm")
        self.iterations += count[0]
        if info != 0:
            raise FrictionNotConverged(
                f"GMRES did not reduce the residual by {self.reduction:.1e} on {system.nC} contact "
                f"nodes ({system.A.size} stick) in {count[0]} iterations")
        return system.full(x0 + dx)


def solve_rolling(ops: RollingOperators, profile, arm, ell, radius: float, speed: float,
                  friction: Friction, *, load=None, indentation=None,
                  progress: Callable[[str], None] | None = None) -> FrictionalContact:
    """Frictional steady rolling/sliding on prepared operators.

    Parameters
    ----------
    ops : RollingOperators
    profile : ndarray ``(K_y, K_x)``
        Indenter profile (m), ``inf`` where it cannot touch.
    arm : ndarray
        Horizontal projection of a unit normal force (-), ``x / R``.
    ell : ndarray
        Distance from the axis of rotation (m), ``l(y)``.
    radius : float
        ``R`` (m), the height of the top point above the centre.
    speed : float
        ``V`` (m/s), > 0.
    friction : Friction
    load, indentation : float
        ``P`` (N) or ``d`` (m), exactly one.

    Raises
    ------
    FrictionNotConverged, LoadingUnreachable, ContactAtEdge, ValueError
    """
    if not (math.isfinite(speed) and speed > 0):
        raise ValueError(f"speed must be > 0 m/s for rolling or sliding with friction, got {speed!r}")
    g = ops.grid
    shape, size = g.shape, g.nodes_x * g.nodes_y
    s = np.asarray(profile, float).ravel()
    arm, ell = np.asarray(arm, float).ravel(), np.asarray(ell, float).ravel()
    reach = np.isfinite(s)
    mu, mode, V = friction.mu, friction.mode, speed
    normal = solve_normal(ops.op("ww"), profile, load=load, indentation=indentation)
    N0 = normal.force.ravel()
    cons = _constraint(mode, arm, ell, radius)
    if cons is not None and mode != "towed":
        need = abs(float(cons[0] @ N0))
        can = mu * float(np.abs(cons[1]) @ N0)
        if can < need:
            raise LoadingUnreachable(
                f"mode {mode!r} needs tangential forces beyond the friction limit: mu = {mu} "
                f"can give a moment/force of {can:.4g}, the rolling resistance asks for {need:.4g} "
                f"(in units of N{' m' if mode == 'pushed_at_top' else ''}); raise mu or use mode "
                "'towed' or 'omega'")
    if mu == 0:
        return _finish(ops, s, arm, ell, V, friction, N0, np.zeros(size), np.zeros(size),
                       normal.indentation, friction.omega if friction.omega is not None else math.nan,
                       np.zeros(size, bool), (), "dense", 0, radius)

    solves = _LinearSolves(friction.dense_limit)
    starts = [_start_state(N0, ell, V, friction)]
    coarse = _coarse_start(ops, s, arm, ell, radius, V, friction, load, indentation, N0, progress)
    if coarse is not None:
        starts.insert(0, coarse)
    try:
        for i, start in enumerate(starts):
            try:
                N, Sx, Sy, d, om, state, history, h, scale = _active_set(
                    ops, s, reach, ell, V, friction, load, indentation, cons, start, progress, solves)
                break
            except FrictionNotConverged as exc:
                if i == len(starts) - 1:
                    raise
                if progress:
                    progress(f"friction: the coarse grid's start failed ({exc}); starting from all stick")
    except LoadingUnreachable:
        raise
    except FrictionNotConverged as exc:
        if mode == "omega":
            raise
        N, Sx, Sy, d, om, state, history, h, scale = _continuation(
            ops, s, reach, ell, V, friction, load, indentation, cons, N0, progress, exc, solves)
    contact, stick = state[0], state[1]
    resid = (max(np.abs(h[contact]).max(initial=0.0), (-h[reach & ~contact]).max(initial=0.0)) / scale,)
    return _finish(ops, s, arm, ell, V, friction, N, Sx, Sy, d, om, stick & contact, tuple(history),
                   "gmres" if solves.used_gmres else "dense", solves.iterations, radius, resid[0])


def _coarse_start(ops, s, arm, ell, radius, V, friction, load, indentation, N0, progress):
    """Start sets from the same problem on every other node (recursively, as the
    frictionless solver's start): the contact of the fine frictionless solve, in stick
    where the nearest coarse node (the upstream one between two) sticks or was out of
    contact, otherwise in slip along the coarse force with ``k = |w| / (mu N)``. Most of
    the stick/slip border is then in place and the fine grid needs a few iterations for
    the rest and for the slip directions. ``None`` below 625 nodes, on even-sized grids
    and when the coarse solve fails."""
    Ky, Kx = ops.grid.shape
    coarse = _coarse_grid(ops.grid)
    if coarse is None:
        return None
    sub = RollingOperators(coarse, {b: k[::2, ::2] for b, k in ops.kernels.items()})

    def fine(a):
        return a.reshape(Ky, Kx)[::2, ::2]

    label = f"coarse {coarse.nodes_x} x {coarse.nodes_y}: "
    try:
        res = solve_rolling(sub, fine(s), fine(arm), fine(ell), radius, V, friction, load=load,
                            indentation=indentation,
                            progress=(lambda m: progress(label + m)) if progress else None)
    except ContactError:
        return None
    jy, ix = (np.arange(Ky) + 1) // 2, (np.arange(Kx) + 1) // 2
    pick = lambda f: f[np.ix_(jy, ix)].ravel()  # noqa: E731
    contact = N0 > 0
    Sx, Sy = pick(res.force_x), pick(res.force_y)
    wmag, smag = pick(np.hypot(res.slip_x, res.slip_y)), np.hypot(Sx, Sy)
    slip = contact & pick(res.contact & ~res.stick) & (smag > 0) & (wmag > 0)
    e = np.zeros((N0.size, 2))
    k = np.zeros(N0.size)
    e[slip] = np.stack([Sx, Sy], 1)[slip] / smag[slip, None]
    k[slip] = wmag[slip] / (friction.mu * N0[slip])
    return contact, contact & ~slip, e, k


def _start_state(N0, ell, V, friction):
    """Initial sets: the frictionless contact, all in stick except (``Omega`` given) the
    nodes whose rigid creep exceeds 1 % of ``V``, which slip along it with the slip law's
    own linearisation ``k = |w| / |S| = |creep| / (mu N)`` (with ``k = 0`` the slip rows
    would force ``w`` along ``e`` with a free perpendicular force, which at small ``mu``
    is orders of magnitude above ``mu N`` and sends the iteration astray)."""
    contact = N0 > 0
    stick = contact.copy()
    e_full = np.zeros((N0.size, 2))
    k_full = np.zeros(N0.size)
    if friction.omega is not None:
        creep = V - friction.omega * ell
        start_slip = contact & (np.abs(creep) > 1e-2 * V)
        stick &= ~start_slip
        e_full[start_slip, 0] = np.sign(creep[start_slip])
        k_full[start_slip] = np.abs(creep[start_slip]) / (friction.mu * N0[start_slip])
    return contact, stick, e_full, k_full


def _active_set(ops, s, reach, ell, V, friction, load, indentation, cons, start, progress, solves):
    """Kalker's active-set iteration from the sets ``start = (contact, stick, e, k)``;
    returns the forces, ``d``, ``Omega``, the final sets, the history and the gap."""
    g = ops.grid
    shape, size = g.shape, g.nodes_x * g.nodes_y
    mu, omega_free = friction.mu, friction.omega is None
    contact, stick, e_full, k_full = (np.array(a, copy=True) for a in start)
    dropped = np.zeros(size, bool)
    reentry = False
    seen: dict = {}
    careful = False
    history = []
    wx = wy = np.zeros(size)
    for it in range(1, friction.max_iter + 1):
        C = np.flatnonzero(contact)
        if omega_free and not (stick & contact).any():  # Omega needs one stick node at least
            Sl = np.flatnonzero(contact)
            stick[Sl[np.argmin(np.hypot(wx[Sl], wy[Sl]))]] = True
        system = _SetSystem(ops, s, C, stick, e_full, k_full, mu, ell, V, load, indentation,
                            friction.omega, cons)
        guess = None if it == 1 else system.unknowns(N, Sx, Sy, d, om)
        lin0 = solves.iterations
        N, Sx, Sy, d, om = solves(system, guess)
        delta, ex, ey = (f.ravel() for f in ops.fields(N.reshape(shape), Sx.reshape(shape), Sy.reshape(shape)))
        h = np.where(reach, s - d + delta, np.inf)
        wx, wy = V * (1 + ex) - om * ell, V * ey
        scale = max(abs(d), 1e-300)
        drop = contact & (N <= 0)
        add = ~contact & (h < -1e-12 * scale)
        smag = np.hypot(Sx, Sy)
        wmag = np.hypot(wx, wy)
        slip = contact & ~stick & ~drop
        to_slip = contact & stick & ~drop & (smag > mu * N * (1 + 1e-10))
        wdot = wx * Sx + wy * Sy
        to_stick = slip & (wdot <= 0)
        slip &= ~to_stick
        with np.errstate(invalid="ignore", divide="ignore"):
            mis_mag = np.abs(smag - mu * N)[slip] / (mu * N[slip])
            mis_dir = np.abs(Sx * wy - Sy * wx)[slip] / (smag * wmag)[slip]
        misfit = float(max(mis_mag.max(initial=0.0), mis_dir.max(initial=0.0)))
        history.append((int(C.size), int((stick & contact).sum()), misfit, om))
        if progress:
            progress(f"friction {it}: {C.size} contact, {int((stick & contact).sum())} stick, "
                     f"Omega = {om:.8g} rad/s, -{int(drop.sum())} +{int(add.sum())} contact, "
                     f"+{int(to_slip.sum())} slip, +{int(to_stick.sum())} stick, slip misfit {misfit:.2e}"
                     + (f", {solves.iterations - lin0} GMRES iterations" if solves.iterations > lin0 else ""))
        changes = drop.any() or add.any() or to_slip.any() or to_stick.any()
        # with Omega prescribed, a node joining the contact where the rigid creep
        # |V - Omega l| exceeds 1 % of V slips (as in the start state: sliding, braking);
        # otherwise material enters the contact in stick, as in free rolling
        join_slip = add & (wmag > 0) & (not omega_free) & (np.abs(V - om * ell) > 1e-2 * V)
        # if a cycle of one-node updates cannot be accepted, a node that left the contact
        # (in stick, pulled into tension by its tangential force) and comes back joins in
        # slip: stick there has no discrete solution
        if reentry:
            join_slip |= add & (wmag > 0) & dropped
        dropped |= drop
        if not changes and misfit <= friction.direction_tol:
            break
        if careful and changes:  # one node at a time, the worst violation first
            new_c, new_s = contact.copy(), stick.copy()
            if drop.any():
                new_c[np.argmin(np.where(drop, N, np.inf))] = False
            elif add.any():
                j = np.argmin(np.where(add, h, np.inf))
                new_c[j] = True
                new_s[j] = not join_slip[j]
            elif to_slip.any():
                new_s[np.argmax(np.where(to_slip, smag - mu * N, -np.inf))] = False
            else:
                new_s[np.argmin(np.where(to_stick, wdot, np.inf))] = True
        else:
            new_c = (contact & ~drop) | add
            new_s = ((stick & ~to_slip) | to_stick | (add & ~join_slip)) & new_c
        new_slip = new_c & ~new_s
        with np.errstate(invalid="ignore", divide="ignore"):
            e_new = np.stack([Sx, Sy], 1) / smag[:, None]
            # k = (e . w) / |S|, floored at 1e-3 V / (mu N): a new or barely slipping node
            # keeps its force near e instead of a free perpendicular component (without the
            # floor, Newton's own slope, the 257 x 257 run oscillated with slip misfits of
            # 1e2-7e2 after the sets had settled)
            k_new = np.maximum(np.where(slip, np.maximum(wdot, 0.0) / smag**2, 0.0), 1e-3 * V / (mu * N))
            # such a node joins in slip along w, k = |w| / (mu N), N the smallest contact force
            joining = new_slip & add
            e_new[joining] = np.stack([wx, wy], 1)[joining] / wmag[joining, None]
            n_ref = float(N[contact & (N > 0)].min(initial=np.inf))
            k_new[joining] = wmag[joining] / (mu * n_ref)
        e_full = np.where(new_slip[:, None] & ((smag[:, None] > 0) | joining[:, None]), e_new, 0.0)
        k_full = np.where(new_slip, np.nan_to_num(k_new), 0.0)
        key = np.packbits(np.concatenate([new_c, new_s])).tobytes()
        # cycles count once the slip law has settled, or when the contact set itself cycles
        if changes and (misfit <= friction.set_tol or drop.any() or add.any()):
            seen[key] = seen.get(key, 0) + 1
            if seen[key] > 2:
                if careful:
                    # a two-state cycle at the stick/slip border: accept the state when its
                    # violations are below the set tolerance (recorded in the residuals)
                    with np.errstate(invalid="ignore", divide="ignore"):
                        over = float(np.nan_to_num(smag / (mu * N) - 1)[contact & stick].max(initial=0.0))
                        back = float(np.nan_to_num(-wdot / (smag * V))[contact & ~stick].max(initial=0.0))
                    gap_v = max(float((-h[add]).max(initial=0.0)) / scale,
                                float((-N[drop]).max(initial=0.0)) / float(N.max()))
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
                        f"contact violation {gap_v:.2e}, "
                        f"set_tol {friction.set_tol})")
                careful = True
                seen.clear()
        contact, stick = new_c, new_s
        if not contact.any():
            raise FrictionNotConverged("the contact set emptied")
    else:
        _unreachable_or_not_converged(friction, history)
    if (contact & _edge_nodes(shape)).any():
        raise ContactAtEdge("the contact reaches the edge of the candidate region: increase grid.half_width")
    return N, Sx, Sy, d, om, (contact, stick, e_full, k_full), history, h, scale


def _continuation(ops, s, reach, ell, V, friction, load, indentation, cons, N0, progress, cause, solves):
    """Continuation in ``mu`` after a failed direct solve (loading modes with a free
    ``Omega``): solve at ``mu 2^K`` (``K >= 1``, the smallest with ``mu 2^K >= 0.2``, where
    a stick zone carries the moment), then halve ``mu`` down to the requested value,
    each solve starting from the previous sets and slip directions. At small ``mu`` the
    contact slips almost everywhere and the moment balance is met by one or a few stick
    nodes near the point where the slip reverses; the direct start (all stick) reaches
    the wrong ones and cycles, the continuation moves them there one step at a time.
    Raises :class:`FrictionNotConverged` naming the ``mu`` at which it stopped.
    """
    mu = friction.mu
    K = max(1, math.ceil(math.log2(0.2 / mu))) if mu < 0.2 else 1
    ladder = [mu * 2.0**j for j in range(K, -1, -1)]
    if progress:
        progress(f"friction: direct solve failed ({cause}); continuation in mu from {ladder[0]:.4g}")
    state = _start_state(N0, ell, V, friction)
    history: list = []
    for m in ladder:
        step = replace(friction, mu=m)
        try:
            N, Sx, Sy, d, om, state, hist, h, scale = _active_set(
                ops, s, reach, ell, V, step, load, indentation, cons, state, progress, solves)
        except FrictionNotConverged as exc:
            raise FrictionNotConverged(
                f"mode {friction.mode!r}, mu = {mu}: the direct solve failed ({cause}) and the "
                f"continuation in mu stopped at mu = {m:.4g} ({exc}); try mode 'omega' with a "
                f"prescribed Omega, or a finer grid") from exc
        history.extend(hist)
    return N, Sx, Sy, d, om, state, history, h, scale


def _unreachable_or_not_converged(friction, history):
    if friction.mode in ("pushed_at_top", "torque") and history and history[-1][1] <= 1:
        raise LoadingUnreachable(f"mode {friction.mode!r}: the whole contact slips and the equilibrium "
                                 f"cannot be met with mu = {friction.mu}")
    raise FrictionNotConverged(f"no converged stick/slip state in {friction.max_iter} iterations "
                               f"(last direction change {history[-1][2]:.2e})")


def _finish(ops, s, arm, ell, V, friction, N, Sx, Sy, d, om, stick, history, solver, lin_it, radius,
            gap_resid=0.0) -> FrictionalContact:
    g = ops.grid
    shape = g.shape
    N2, X2, Y2 = N.reshape(shape), Sx.reshape(shape), Sy.reshape(shape)
    delta, ex, ey = ops.fields(N2, X2, Y2)
    u, v = ops.displacements(N2, X2, Y2)
    contact = N2 > 0
    omega_eff = 0.0 if math.isnan(om) else om
    wx = np.where(contact, V * (1 + ex) - omega_eff * ell.reshape(shape), 0.0)
    wy = np.where(contact, V * ey, 0.0)
    st = stick.reshape(shape)
    wx[st] = wy[st] = 0.0  # exactly zero by the stick equations; clear round-off
    stick_res = float(np.hypot(V * (1 + ex) - omega_eff * ell.reshape(shape), V * ey)[st].max(initial=0.0) / V)
    mu = friction.mu
    with np.errstate(invalid="ignore", divide="ignore"):
        cone = np.hypot(X2, Y2)[st] / (mu * N2[st]) - 1 if mu > 0 else np.zeros(0)
    coul = float(np.maximum(cone, 0).max(initial=0.0))
    sl = contact & ~st
    if mu > 0 and sl.any():
        with np.errstate(invalid="ignore", divide="ignore"):
            sm = np.hypot(X2, Y2)[sl]
            mag = np.abs(sm / (mu * N2[sl]) - 1)
            ang = 1 - (X2 * wx + Y2 * wy)[sl] / (sm * np.hypot(wx, wy)[sl])  # 0 when S || w
        coul = max(coul, float(np.nan_to_num(mag, nan=1.0).max()), float(np.nan_to_num(ang, nan=1.0).max()))
    Q = float((N * arm).sum() + Sx.sum())
    T = float(-(ell * Sx).sum())
    if friction.mode == "torque":
        Q = 0.0 if mu > 0 else Q
    rr = Q + (T * om / V if T != 0.0 else 0.0)
    p_fric = float((X2 * wx + Y2 * wy).sum())
    record = FrictionRecord(len(history), history, solver, lin_it, gap_resid, stick_res, coul)
    return FrictionalContact(
        g, N2, X2, Y2, delta, u, v, s.reshape(shape) - d + delta, wx, wy, st, float(d), float(N.sum()),
        float(om), Q, T, rr, p_fric / V, rr - p_fric / V, V, mu, friction.mode, record)


def solve_friction(problem: Problem, friction: Friction, progress: Callable[[str], None] | None = None,
                   kernels: dict | None = None, energy: bool = True) -> tuple[FrictionalContact, dict]:
    """Steady rolling/sliding of ``problem`` with Coulomb ``friction``.

    Returns the result and the timings (s) of the nine kernels, of the solve and of the
    energy figure. Pass ``kernels`` (all nine blocks for this grid, layer and speed) to
    reuse them. With ``energy`` the result carries ``rolling_resistance_energy``
    ``= (P_visc + P_fric) / V`` (N), the layer's dissipation summed in Fourier space
    (:func:`bem.energy.viscous_dissipation`, about 1.8 s at ``N_t = 2000``); otherwise it
    is ``nan``.
    """
    p = problem
    kernel_s = 0.0
    if kernels is None:
        kernels, kernel_s = compute_kernels(p, BLOCKS, progress)
    t1 = time.perf_counter()
    ops = RollingOperators(p.grid, kernels)
    X, Y = p.grid.coordinates()
    R = indenter_radius(p.indenter, friction.radius)
    res = solve_rolling(ops, p.indenter.profile(X, Y), p.indenter.rolling_arm(X, Y),
                        rolling_radius(p.indenter, Y, friction.radius), R, p.loading.speed, friction,
                        load=p.loading.load, indentation=p.loading.indentation, progress=progress)
    t2 = time.perf_counter()
    timings = {"kernel_s": kernel_s, "solve_s": t2 - t1}
    if energy:
        p_visc = viscous_dissipation(p.grid, p.layer, p.loading.speed, -res.force, res.force_x, res.force_y)
        res = replace(res, rolling_resistance_energy=(p_visc + res.friction_power) / p.loading.speed)
        timings["energy_s"] = time.perf_counter() - t2
        if progress:
            progress(f"energy: (P_visc + P_fric) / V = {res.rolling_resistance_energy:.6g} N, "
                     f"{timings['energy_s']:.2f} s")
    return res, timings
