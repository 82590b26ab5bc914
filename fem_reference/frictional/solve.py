r"""Frictional steady rolling of a rigid cylinder on the plane-strain FEM layer: a dense
active-set solver on the condensed surface compliance (:mod:`.compliance`), per unit
length along y. SI units (m, N/m, Pa, m/s, rad/s).

**Frame and unknowns.** The frame moves with the cylinder at V along +x; the material
streams through it at -V. At the candidate nodes x_i (increasing) the unknowns are the
compressive normal line loads N_i >= 0 and the tangential line loads S_i on the layer
along +x (N/m; the cylinder receives -S_i), the indentation d (m) and, unless given, the
angular speed Omega (rad/s, clockwise seen with +x to the right: forward rolling).
Surface displacements (m): u_x = C_xx S - C_xz N, u_z = C_zx S - C_zz N (u_z up).

**Normal contact.** gap_i = s_i - d - u_z,i >= 0, N_i >= 0, N_i gap_i = 0, with s_i the
profile (hat-weighted, as the frictionless FEM solve takes it); sum N = P' (load
control) or d given.

**Slip velocity.** A surface particle at x has the material position x' = x + V t and
the displacement u(x, t) = u(x) (steady); its velocity in the moving frame is
-V (1 + du_x/dx) along x (D/Dt = -V d/dx, paper eq. 6). The cylinder's surface point at
depth l below the axle moves at -Omega l. The slip velocity of the cylinder relative to
the particle is (paper eq. 14 in plane strain)

    w = -Omega l + V (1 + du_x/dx) = V (xi + du_x/dx),   xi = (V - Omega l) / V

(creepage xi; l = R with "small_slope", D = sqrt(R^2 - x^2) with "exact"). Coulomb:
stick, w = 0 and |S| <= mu N; slip, S = mu N w / |w|: the cylinder drags the layer
along its own relative motion (braking, xi > 0, pushes the layer forward: Carter's
Q > 0).

**du_x/dx upwind.** (u_x,i+1 - u_x,i) / (x_i+1 - x_i): the material carries its state
from the leading edge (+x) backwards, and the stick condition is the transport equation
du_x/dx = -xi along the particle path, integrated from where the particle enters the
stick zone; the upwind difference integrates it in that direction, a node's stick row
reading its upstream neighbour, so a stick zone starts at the leading edge as Carter's
does. The central difference decouples odd and even nodes in a stick zone (a uniform
strain leaves a free alternating u_x) and makes no direction of travel; the upwind one
is first order, like the BEM's (bem/kinematics.py). The last (most upstream) candidate
node has no upstream neighbour: the contact must stay clear of it.

**Equilibrium of the cylinder** (docs/derivations.md, section 4): Q' = sum N arm + sum S
(the horizontal force on the cylinder along +x), T' = -sum l S (clockwise), R_r = Q' +
T' Omega / V (eq. 1); arm x / R ("small_slope") or s'(x) ("exact"), hat-weighted. Modes
(:class:`~.model.RollingFriction`) close the system with one row: "omega" gives Omega;
"force" Q' = Q'_0; "towed" T' = 0; "pushed_at_top" T' = Q' R.

**Energy.** The drive's power Q' V + T' Omega equals the bulk dissipation plus the
friction power sum S w when the arm is the profile's slope (both kinematics), up to the
discretization (the result's ``energy_balance``).

**Iteration.** From the frictionless solution (all contact nodes in stick), each step
solves the dense linear system of the current sets (contact: gap = 0; off contact: N =
S = 0; stick: w = 0; slip: S = mu sigma N with sigma = +-1) and updates every set at
once: a contact node in tension leaves, a penetrating node joins; a stick node with
|S| > mu N slips along sign S; a slip node with sigma w < 0 sticks; a joining node
sticks, unless it has left the contact before: then it joins in slip along its w (at a
contact edge that flickers between the sets stick may have no discrete solution; measured
on a 1 mm layer at h = 25 um, where the contact set cycled by one node). With Omega free
one node at least sticks. A state met again switches to one change per step (the
largest violation first); a state met again then raises :class:`~fem_reference.errors.
ContactNotConvergedError`. The solution ends the iteration only when it violates no
condition: N >= 0 and gap >= 0, |S| <= mu N on stick, S w >= 0 on slip.
"""

from __future__ import annotations

import time
from typing import Callable, Optional

import numpy as np

from ..contact import solve_contact
from ..errors import ContactNotConvergedError, ContactZoneError, InputError
from ..problem import ContactProblem
from .compliance import SurfaceCompliance, check_plane_strain, surface_compliance
from .model import FrictionalRollingResult, RollingFriction

__all__ = ["solve_frictional", "hat_moment", "geometry", "upwind_derivative"]

#: relative tolerances of the set changes: cone excess (of mu N), reversed slip (of V)
CONE_TOL = 1e-9
SLIP_TOL = 1e-12


def hat_moment(x: np.ndarray, f: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """int phi_i f dx (m times f's unit) of the P1 hats on the nodes ``x`` (m,
    increasing), by Simpson's rule on each interval (exact for f a polynomial of degree
    <= 2)."""
    a, b = x[:-1], x[1:]
    mid = 0.5 * (a + b)
    h = b - a
    fa, fm, fb = f(a), f(mid), f(b)
    left = h / 6.0 * (fa + 2.0 * fm)   # hat of the node a: 1, 1/2, 0 at a, mid, b
    right = h / 6.0 * (2.0 * fm + fb)  # hat of the node b: 0, 1/2, 1
    out = np.zeros(len(x))
    out[:-1] += left
    out[1:] += right
    return out


def geometry(comp: SurfaceCompliance, R: float, kinematics: str):
    """(s, arm, l): the nodal profile s_i (m), the arm of the normal forces (-) and the
    rolling radius (m) of ``kinematics`` (module docstring), hat-weighted averages."""
    x, m, sysm = comp.x, comp.weights, comp.system
    if kinematics == "small_slope":
        s = hat_moment(x, lambda t: t * t / (2.0 * R)) / m
        arm = hat_moment(x, lambda t: t / R) / m
        ell = np.full(len(x), R)
    else:
        s, arm = sysm.q / m, sysm.ms / m
        ell = np.sqrt(R * R - x * x)
    return s, arm, ell


def upwind_derivative(x: np.ndarray) -> np.ndarray:
    """D (n, n) (1/m): (D u)_i = (u_i+1 - u_i) / (x_i+1 - x_i); the last row is 0."""
    n = len(x)
    D = np.zeros((n, n))
    h = np.diff(x)
    i = np.arange(n - 1)
    D[i, i] = -1.0 / h
    D[i, i + 1] = 1.0 / h
    return D


def _mode_row(mode, friction, arm, ell, R, n):
    """(coefficients on N, on S, on Omega R / V, right-hand side) of the mode's row."""
    zero = np.zeros(n)
    if mode == "omega":
        return zero, zero, 1.0, 1.0 - friction.creepage
    if mode == "force":
        return arm, np.ones(n), 0.0, friction.driving_force
    if mode == "towed":
        return zero, ell, 0.0, 0.0
    return R * arm, R + ell, 0.0, 0.0  # pushed at the top: Q R + sum l S = 0


class _Sets:
    """The contact/stick/slip state: ``contact``, ``stick`` (bool) and ``sigma`` (+-1 on
    slip nodes)."""

    def __init__(self, contact, stick, sigma):
        self.contact, self.stick, self.sigma = contact.copy(), stick & contact, np.where(contact & ~stick, sigma, 0)

    def key(self):
        return self.contact.tobytes() + self.stick.tobytes() + self.sigma.astype(np.int8).tobytes()


def solve_frictional(problem: ContactProblem, friction: RollingFriction,
                     compliance: Optional[SurfaceCompliance] = None,
                     progress: Optional[Callable[[str], None]] = None) -> FrictionalRollingResult:
    """Solve the frictional steady rolling of ``problem`` (a line indenter in plane strain,
    ``loading.speed`` > 0) with ``friction`` (module docstring).

    ``compliance``: the condensed layer of ``problem`` (:func:`surface_compliance`), to
    reuse one factorization over several solves; made here if None.

    Raises
    ------
    InputError
        Not a plane-strain line contact (``fem.model``), or ``loading.speed`` not > 0.
    ContactZoneError
        The contact reaches the ends of the candidate zone (``fem.contact_zone``).
    ContactNotConvergedError
        The active set cycles or reaches ``friction.max_iterations``.
    """
    say = progress or (lambda _: None)
    check_plane_strain(problem)
    V = problem.loading.speed
    if not V > 0:
        raise InputError(f"loading.speed = {V!r} m/s: frictional rolling needs loading.speed > 0 (the slip "
                         "velocity V (xi + du_x/dx) and the rolling resistance are per unit speed)")
    t0 = time.perf_counter()
    comp = compliance if compliance is not None else surface_compliance(problem, progress)
    t1 = time.perf_counter()
    R, mu, mode = problem.indenter.radius, friction.mu, friction.mode
    x, m, n = comp.x, comp.weights, comp.n
    s, arm, ell = geometry(comp, R, friction.kinematics)
    Cxx, Cxz, Czx, Czz = (comp.block(a, b) for a, b in (("x", "x"), ("x", "z"), ("z", "x"), ("z", "z")))
    D = upwind_derivative(x)
    DCxx, DCxz = D @ Cxx, D @ Cxz
    load, d0 = problem.loading.load, problem.loading.indentation
    cN, cS, cO, rhs_mode = _mode_row(mode, friction, arm, ell, R, n)
    free_omega = mode != "omega"

    def solve_sets(st: _Sets):
        A, St = st.contact, st.stick
        Sl = A & ~St
        M = np.zeros((2 * n + 2, 2 * n + 2))
        r = np.zeros(2 * n + 2)
        i = np.flatnonzero(A)
        M[i, :n], M[i, n:2 * n], M[i, 2 * n], r[i] = Czz[i], -Czx[i], -1.0, -s[i]
        i = np.flatnonzero(~A)
        M[i, i] = 1.0
        i = np.flatnonzero(St)  # V (1 + D u_x) - Omega l = 0, divided by V
        M[n + i, :n], M[n + i, n:2 * n], M[n + i, 2 * n + 1], r[n + i] = -DCxz[i], DCxx[i], -ell[i] / R, -1.0
        i = np.flatnonzero(Sl)
        M[n + i, n + i], M[n + i, i] = 1.0, -mu * st.sigma[i]
        i = np.flatnonzero(~A)
        M[n + i, n + i] = 1.0
        if load is not None:
            M[2 * n, :n], r[2 * n] = 1.0, load
        else:
            M[2 * n, 2 * n], r[2 * n] = 1.0, d0
        M[2 * n + 1, :n], M[2 * n + 1, n:2 * n], M[2 * n + 1, 2 * n + 1], r[2 * n + 1] = cN, cS, cO, rhs_mode
        z = np.linalg.solve(M, r)
        N, S, d, Om = z[:n], z[n:2 * n], z[2 * n], z[2 * n + 1] * V / R
        gap = s - d - (Czx @ S - Czz @ N)
        w = V * (1.0 + D @ (Cxx @ S - Cxz @ N)) - Om * ell
        return N, S, d, Om, gap, w

    W0 = Czz * m[:, None] * m[None, :]  # the frictionless FEM's weighted compliance
    start = solve_contact(W0, m, s * m, load=load, indentation=d0, max_iterations=200)
    A0 = start.active.copy()
    sets = _Sets(A0, A0 & (mu > 0), np.ones(n, int))
    c = 1.0 / np.diag(Czz)
    seen, single = set(), False
    left = np.zeros(n, bool)  # nodes that have left the contact: they come back in slip
    for it in range(1, friction.max_iterations + 1):
        if sets.contact[0] or sets.contact[-1]:
            raise ContactZoneError(f"the contact reaches the end of the candidate zone |x| <= {x[-1]:.4e} m: "
                                   "raise fem.contact_zone or lower the load")
        try:
            N, S, d, Om, gap, w = solve_sets(sets)
        except np.linalg.LinAlgError:
            raise ContactNotConvergedError(
                f"the frictional system of iteration {it} is singular ({int(sets.contact.sum())} nodes in "
                f"contact, {int(sets.stick.sum())} in stick, mode {mode!r})") from None
        A, St = sets.contact, sets.stick
        newA = np.where(A, N > 0, gap < 0)
        cone = A & St & (np.abs(S) > mu * N * (1 + CONE_TOL) + 1e-300)
        reverse = A & ~St & (sets.sigma * w < -SLIP_TOL * V) & (mu > 0)  # mu = 0: S = 0 either way
        changes = int(np.sum(newA != A) + cone.sum() + reverse.sum())
        say(f"frictional iteration {it}: {int(A.sum())} in contact, {int(St.sum())} in stick, "
            f"{changes} changes")
        if changes == 0:
            break
        if single:  # one change: contact first, then the largest cone excess, then reversed slip
            Fs = max(float(N.max()), 1e-300)
            if np.any(newA != A):
                viol = np.where(A, -N, c * -gap) / Fs
                viol[newA == A] = -np.inf
                k = int(np.argmax(viol))
                newA = A.copy()
                newA[k] = not A[k]
                cone[:], reverse[:] = False, False
            elif cone.any():
                k = int(np.argmax(np.where(cone, np.abs(S) - mu * N, -np.inf)))
                cone[:] = False
                cone[k] = True
                reverse[:] = False
            else:
                k = int(np.argmax(np.where(reverse, -sets.sigma * w, -np.inf)))
                reverse[:] = False
                reverse[k] = True
        join = newA & ~A
        stick = (St & ~cone) | reverse | (join & ~left & (mu > 0))
        sigma = np.where(cone, np.sign(S), np.where(join, np.where(w < 0, -1, 1), sets.sigma))
        left |= A & ~newA
        new = _Sets(newA, stick & newA, sigma.astype(int))
        if free_omega and not new.stick.any() and new.contact.any():
            k = int(np.argmin(np.where(new.contact, np.abs(w), np.inf)))
            new.stick[k], new.sigma[k] = True, 0
        key = new.key()
        if key in seen:
            if single:
                raise ContactNotConvergedError(
                    f"the frictional active set cycles after {it} iterations (mu = {mu}, mode {mode!r}): "
                    "refine or coarsen fem.element_size, or change friction.mu")
            single = True
            seen = set()
        seen.add(sets.key())
        sets = new
    else:
        raise ContactNotConvergedError(f"the frictional active set did not settle in {friction.max_iterations} "
                                       "iterations (friction.max_iterations)")
    A = sets.contact
    t2 = time.perf_counter()
    diss = comp.dissipation(S, -N)
    t3 = time.perf_counter()
    Q = float(arm @ N + S.sum())
    T = float(-(ell @ S))
    st = sets.stick & A
    times = dict(comp.times) if compliance is None else {}
    times.update(contact=t2 - t1, dissipation=t3 - t2, total=t3 - t0)
    return FrictionalRollingResult(
        x=x, normal=N, tangential=S, pressure=N / m, shear=S / m, u_x=Cxx @ S - Cxz @ N,
        u_z=Czx @ S - Czz @ N, slip_velocity=w, contact=A.copy(), stick=st, slip=A & ~st, speed=V,
        radius=R, mu=mu, mode=mode, kinematics=friction.kinematics, load=float(N.sum()), indentation=float(d),
        omega=float(Om), creepage=float(1.0 - Om * R / V), driving_force=Q, torque=T,
        rolling_resistance=Q + T * Om / V, friction_power=float(S[A & ~st] @ w[A & ~st]), dissipation=float(diss),
        iterations=it, times=times)
