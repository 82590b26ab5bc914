"""The unknowns and the linear system of one active-set state.

For a trial contact set ``C``, stick set ``A`` (a subset of ``C``) and, on the slip set
``B = C \\ A``, slip directions ``e`` with slip-law slopes ``k``, every condition is linear
in the unknowns ``x = (N_C, Sx_C, Sy_C, d, Omega / om_unit)`` (``d`` under load control,
``Omega`` when the loading mode leaves it free, in units of ``om_unit = V / mean(l)``
rad/s so that the unknowns are O(1) at any speed). Rows, all in metres:

* the gap ``h = 0`` on ``C`` (a slip node's normal force brings its friction along, so the
  layer's normal-tangential coupling is kept exactly);
* on stick nodes ``a_x w_x / V`` and ``a_x w_y / V`` (the upwind differences
  ``u_{i+1} - u_i`` plus the rigid creep);
* on slip nodes the Newton linearisation of the slip law (eqs. 17-18) about the
  direction ``e``: ``diag (e . S - mu N)`` and ``a_x (e_perp . w - k e_perp . S) / V``;
* ``diag sum N = diag P`` (load control) and the loading mode's row (``Omega`` free).

``diag`` is ``C_ww`` of a node on itself (m/N). :func:`force_rows` writes the rows of
the forces once, for the dense matrix and the FFT product (the preconditioner writes the
slip rows' Woodbury matrices from the same equations, :mod:`bem.frictional.preconditioner`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .operators import RollingOperators

__all__ = ["SetState", "RollingSetup", "SetSystem", "force_rows"]


@dataclass(frozen=True, eq=False, repr=False)
class SetState:
    """Contact, stick and slip sets on the full grid (flat arrays).

    Attributes
    ----------
    contact, stick : ndarray of bool
        Contact nodes and stick nodes (``stick`` within ``contact``).
    direction : ndarray, shape ``(nodes, 2)``
        Slip direction ``e`` (unit, -) of the force on slip nodes; 0 elsewhere.
    slope : ndarray
        Slip-law slope ``k`` (m/(s N)) of the slip rows on slip nodes; 0 elsewhere.
    """

    contact: np.ndarray
    stick: np.ndarray
    direction: np.ndarray
    slope: np.ndarray

    @property
    def slip(self) -> np.ndarray:
        """Contact nodes in slip."""
        return self.contact & ~self.stick


@dataclass(frozen=True, eq=False, repr=False)
class RollingSetup:
    """What stays fixed while the sets change (flat arrays on the grid).

    Attributes
    ----------
    ops : RollingOperators
    profile : ndarray
        Indenter profile ``s`` (m), ``inf`` where it cannot touch.
    arm : ndarray
        Horizontal projection of a unit normal force (-).
    ell : ndarray
        Distance ``l(y)`` from the axis of rotation (m).
    radius : float
        ``R`` (m).
    speed : float
        ``V`` (m/s).
    mu : float
        Coulomb coefficient (-).
    load, indentation : float or None
        ``P`` (N) or ``d`` (m), exactly one.
    omega : float or None
        ``Omega`` (rad/s) when prescribed.
    constraint : tuple of ndarray or None
        ``(c_N, c_x)`` of the loading mode's row ``c_N . N + c_x . S_x = 0``
        (:func:`bem.frictional.loading.constraint`), ``None`` when ``Omega`` is given.
    """

    ops: RollingOperators
    profile: np.ndarray
    arm: np.ndarray
    ell: np.ndarray
    radius: float
    speed: float
    mu: float
    load: float | None
    indentation: float | None
    omega: float | None
    constraint: tuple | None

    @property
    def reach(self) -> np.ndarray:
        """Nodes the indenter can touch."""
        return np.isfinite(self.profile)


def force_rows(B, dir_x, dir_y, slope, mu, diag, gap, Dx, Dy, N, Sx, Sy):
    """The rows of the forces' unknowns, ``(3 m, k)`` for ``m`` contact nodes and ``k``
    columns: gap rows, then the ``x`` and ``y`` rows (stick: ``Dx, Dy``; slip: the slip law).

    ``B`` the slip nodes (indices into the contact, increasing), ``dir_x, dir_y, slope``
    on them (``slope`` already times ``a_x / V``), ``gap, Dx, Dy`` (``m x k``) the gap and
    the upwind differences ``a_x w / V`` without the rigid creep, ``N, Sx, Sy`` (``m x k``).
    """
    m = gap.shape[0]
    out = np.empty((3 * m, gap.shape[1]))
    # every row as a stick row first (contiguous copies), then the slip rows over them:
    # fancy-indexed copies of the stick rows cost twice the whole for one column
    out[:m], out[m:2 * m], out[2 * m:] = gap, Dx, Dy
    ex, ey, kk = dir_x[:, None], dir_y[:, None], slope[:, None]
    out[m + B] = diag * (ex * Sx[B] + ey * Sy[B] - mu * N[B])
    out[2 * m + B] = -ey * Dx[B] + ex * Dy[B] + kk * (ey * Sx[B] - ex * Sy[B])
    return out


class SetSystem:
    """The linear system of one active-set state (see the module docstring): its
    right-hand side ``b``, dense matrix, FFT product and the map between its unknowns and
    full-grid fields. ``precondition`` is set by the solver (see
    :mod:`bem.frictional.preconditioner`)."""

    precondition = None
    _known = None  # (x, its fields on C), see know

    def __init__(self, setup: RollingSetup, state: SetState):
        ops, V = setup.ops, setup.speed
        self.setup, self.ops = setup, ops
        C = self.C = np.flatnonzero(state.contact)
        self.Cj, self.Ci = np.divmod(C, ops.grid.nodes_x)
        # the FFT products on a box around the contact (RollingOperators.window_around):
        # the forces live there and the rows read there
        self.box, j0, i0 = ops.window_around(self.Cj, self.Ci)
        self.in_box = (self.Cj - j0) * self.box.grid.nodes_x + (self.Ci - i0)
        nC = self.nC = C.size
        self.free_d, self.free_om = setup.load is not None, setup.omega is None
        self.n = 3 * nC + self.free_d + self.free_om
        self.iD, self.iO = 3 * nC, 3 * nC + self.free_d
        self.diag = ops.diagonal
        self.ax = ax = ops.grid.spacing_x
        self.stick = state.stick[C]
        self.A, self.B = np.flatnonzero(self.stick), np.flatnonzero(~self.stick)
        self.dir_x, self.dir_y = state.direction[C[self.B], 0], state.direction[C[self.B], 1]
        self.slope = state.slope[C[self.B]] * ax / V
        ell = setup.ell
        mean_l = float(np.abs(ell[C]).mean())
        self.om_unit = V / mean_l
        self.om_coef = -ax * ell[C] / mean_l  # the scaled Omega's coefficient in a_x w_x / V
        if self.free_om:
            cN, cx = setup.constraint
            scale = self.diag / max(np.abs(cx).max(), 1e-300)
            self.cN, self.cx = cN[C] * scale, cx[C] * scale
        # right-hand side: the rows' constant parts, moved over
        creep = -ax * np.ones(nC) + (0.0 if self.free_om else ax * setup.omega * ell[C] / V)
        b = np.zeros(self.n)
        b[:nC] = -setup.profile[C] + (0.0 if self.free_d else setup.indentation)
        b[nC + self.A] = creep[self.A]
        b[2 * nC + self.B] = -self.dir_y * creep[self.B]
        if self.free_d:
            b[self.iD] = self.diag * setup.load
        self.b = b

    def rows(self, gap, Dx, Dy, X):
        """Rows for unknowns ``X`` (``n x k``), given ``gap = C_ww N - C_wu S_x - C_wv S_y``
        and ``Dx, Dy`` (the upwind differences of ``u, v``) on ``C`` (``nC x k``)."""
        nC = self.nC
        if self.free_om:
            Dx = Dx + self.om_coef[:, None] * X[self.iO]
        if self.free_d:
            gap = gap - X[self.iD]
        out = np.empty((self.n, X.shape[1]))
        out[:3 * nC] = force_rows(self.B, self.dir_x, self.dir_y, self.slope, self.setup.mu, self.diag,
                                  gap, Dx, Dy, X[:nC], X[nC:2 * nC], X[2 * nC:3 * nC])
        out[3 * nC:] = self.global_rows(X[:3 * nC])
        return out

    def global_rows(self, X):
        """The rows of the global unknowns (the load's ``diag sum N``, the loading mode's
        ``c_N . N + c_x . S_x``; as many as there are global unknowns) on force unknowns
        ``X`` (``3 nC x k``): they read no displacement."""
        nC = self.nC
        out = np.empty((self.n - 3 * nC, X.shape[1]))
        if self.free_d:
            out[self.iD - 3 * nC] = self.diag * X[:nC].sum(0)
        if self.free_om:
            out[self.iO - 3 * nC] = self.cN @ X[:nC] + self.cx @ X[nC:2 * nC]
        return out

    def blocks(self, rows: np.ndarray, cols: np.ndarray):
        """Dense ``gap, Dx, Dy`` blocks (``rows x 3 cols``) between contact nodes
        ``C[rows]`` and ``C[cols]``."""
        ops, ax = self.ops, self.ax
        r, c = self.C[rows], self.C[cols]

        def block(names, factor=1.0):
            return factor * np.hstack([sg * ops.dense(nm, r, c) for sg, nm in names])

        return (block(((1, "ww"), (-1, "wu"), (-1, "wv"))),
                block(((-1, "duw"), (1, "duu"), (1, "duv")), ax),
                block(((-1, "dvw"), (1, "dvu"), (1, "dvv")), ax))

    def dense(self) -> np.ndarray:
        allC = np.arange(self.nC)
        pad = np.zeros((self.nC, self.n - 3 * self.nC))
        gap, Dx, Dy = (np.hstack([blk, pad]) for blk in self.blocks(allC, allC))
        return self.rows(gap, Dx, Dy, np.eye(self.n))

    def full(self, x):
        """Full-grid ``N, S_x, S_y`` (N) and ``d`` (m), ``Omega`` (rad/s) from the unknowns."""
        g = self.ops.grid
        size, nC, C = g.nodes_x * g.nodes_y, self.nC, self.C
        N, Sx, Sy = np.zeros(size), np.zeros(size), np.zeros(size)
        N[C], Sx[C], Sy[C] = x[:nC], x[nC:2 * nC], x[2 * nC:3 * nC]
        d = x[self.iD] if self.free_d else self.setup.indentation
        om = x[self.iO] * self.om_unit if self.free_om else self.setup.omega
        return N, Sx, Sy, float(d), float(om)

    def unknowns(self, N, Sx, Sy, d, om):
        """The inverse of :meth:`full` (a starting guess from full-grid fields)."""
        C = self.C
        glob = ([d] if self.free_d else []) + ([om / self.om_unit] if self.free_om else [])
        return np.concatenate([N[C], Sx[C], Sy[C], glob])

    def know(self, x: np.ndarray, fields) -> None:
        """Record the fields of the forces of ``x`` on ``C``: the deflection and the upwind
        strains ``du/dx, dv/dx`` (``nC`` each, :meth:`~bem.frictional.operators.
        RollingOperators.fields`); :meth:`residual` of that very array then takes no product."""
        self._known = (x, fields)

    def residual(self, x: np.ndarray) -> np.ndarray:
        """``b - A x``, from the fields recorded by :meth:`know` when ``x`` is that array."""
        if self._known is None or self._known[0] is not x:
            return self.b - self.matvec(x)
        gap, sx, sy = (f[:, None] for f in self._known[1])
        return self.b - self.rows(gap, self.ax * sx, self.ax * sy, x[:, None])[:, 0]

    def matvec(self, x, dtype=np.float64):
        """The product ``A x``; its FFT convolution in ``dtype`` (the rows in double)."""
        fields = self.box.fields_on(self.in_box, x[:3 * self.nC].reshape(3, self.nC), dtype)
        gap, sx, sy = fields.astype(np.float64, copy=False)[:, :, None]
        return self.rows(gap, self.ax * sx, self.ax * sy, x[:, None])[:, 0]

    def matvec_single(self, x):
        """:meth:`matvec` with the convolution in single precision (rounding about 1e-7 of
        the fields): the products inside a loose solve's GMRES cycles."""
        return self.matvec(x, np.float32)
