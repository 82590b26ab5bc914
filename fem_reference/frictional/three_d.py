r"""Frictional steady rolling of a rigid sphere on the 3D FEM half layer: a dense Coulomb
solver on the condensed surface compliance (:mod:`.compliance_3d`). SI units (m, N, Pa,
m/s, rad/s); the result's totals count both halves of the layer.

**Frame and unknowns.** The frame moves with the sphere at V along +x; the material
streams through it at -V. At the candidate nodes (x_i, y_i >= 0) of the half layer the
unknowns are the compressive normal forces N_i >= 0 and the tangential forces S_i =
(S_x,i, S_y,i) on the layer (N; the sphere receives -S_i; S_y = 0 on y = 0), the
indentation d (m) and, unless given, the angular speed Omega (rad/s about the y axis,
forward rolling positive). Displacements (m): u = C [S_x; S_y; -N] (u_z up).

**Normal contact.** gap_i = s_i - d - u_z,i >= 0, N_i >= 0, N_i gap_i = 0; 2 sum N = P.

**Slip velocity.** A surface particle at (x, y) moves in the frame at -V (e_x + du/dx)
(its tangential part; D/Dt = -V d/dx, paper eq. 6). The sphere's surface point at depth
l below the centre moves at Omega e_y x (x, y, -l) = (-Omega l, 0, -Omega x): no y part.
The slip velocity of the sphere relative to the particle (paper eqs. 14, 15):

    w_x = V (1 + du_x/dx) - Omega l = V (xi + du_x/dx),   xi = (V - Omega l) / V,
    w_y = V du_y/dx.

Kinematics (bem/kinematics.py gives the BEM the same two): "small_slope" -- the
paraboloid s = (x^2 + y^2) / 2R, arm x / R, l = R (first order in the slope);
"exact" -- the sphere s = R - sqrt(R^2 - r^2), arm ds/dx = x / D, l = D = sqrt(R^2 -
r^2). Each is hat-weighted at the nodes. In both the arm is the profile's x slope and l
is the same in w_x and in the torque, which closes the energy balance.

**du/dx upwind** (the one-sided derivative along +x, the direction the material comes
from): at node i the surface triangle (i, j, k) of the zone that the ray i + t e_x, t >
0, enters, with e_x = alpha (p_j - p_i) + beta (p_k - p_i), alpha, beta >= 0, gives
(du/dx)_i = alpha (u_j - u_i) + beta (u_k - u_i): exact for a linear field, first order,
and on a line of nodes the plane-strain upwind difference. The stick condition du_x/dx =
-xi is transport along the particle path, entered at the leading edge: each stick row
reads its upstream neighbours. A node on the zone's upstream edge has no such triangle
(row 0): the contact must stay clear of the zone's edge.

**Coulomb.** Stick: w = 0 and |S| <= mu N. Slip: S = mu N w / |w| (the sphere drags
the layer along its own relative motion). The slip direction is two-dimensional, so
the sets of the plane-strain solver (:mod:`.solve`: a sign per slip node) become a
direction per node; a fixed point on those directions inside the set updates cycled on
the section 11 meshes (the directions at the stick/slip border, where |w| -> 0, flip
from one solve to the next). The conditions are therefore written as one semi-smooth
system (Alart and Curnier's augmented form) and solved by a generalized Newton
iteration:

    N_aug = N - c_n gap,   contact where N_aug > 0:  c_n gap = 0,  else N = 0;
    q = S + c_t w,  rho = mu max(N_aug, 0):  stick where |q| <= rho:  -c_t w = 0,
                                             slip otherwise:          S - rho q / |q| = 0,

with c_n = 1 / C_zz,ii (N/m) and c_t (N s/m) the median of 1 / (dw_x/dS_x)_ii; a fixed
point of the slip row has S parallel to q = S + c_t w, i.e. S = mu N w / |w|. The
Jacobian of q / |q| is (I - e e^T) / |q| on the slip rows (the direction's own
derivative, which the fixed point lacked). The loads, the mode's row and Omega enter as
linear rows. Newton starts from the frictionless contact of the same compliance (S = 0,
Omega R / V = 1, or the given creepage), backtracks on the residual norm, and stops when
the sets repeat and the scaled residual is below ``NEWTON_TOL``. On y = 0, S_y = 0 (a
P1 traction odd in y) and w_y = 0 by symmetry.

**Equilibrium of the sphere** (paper eqs. 1-4; totals are twice the half's sums): Q =
sum N arm + sum S_x (the horizontal force on the sphere along +x), T = -sum l S_x
(about the y axis, forward rolling positive), R_r = Q + T Omega / V. Modes
(:class:`~.model.RollingFriction`): "omega" gives Omega; "force" Q = Q_0; "towed" T =
0; "pushed_at_top" T = Q R.

**Energy.** Q V + T Omega = R_r V equals the dashpots' dissipation plus the friction
power sum S . w (slip nodes, both halves) up to the discretization (the result's
``energy_balance``).
"""

from __future__ import annotations

import time
from typing import Callable, Optional

import numpy as np

from ..contact import solve_contact
from ..errors import ContactNotConvergedError, ContactZoneError, InputError
from ..problem import ContactProblem
from .compliance_3d import SurfaceCompliance3D, check_sphere, surface_compliance_3d
from .model import RollingFriction
from .result_3d import FrictionalSphereResult

__all__ = ["solve_frictional_3d", "upwind_gradient_x", "sphere_geometry"]

#: scaled residual (of P and mu P) at which the Newton iteration stops, the sets repeating
NEWTON_TOL = 1e-12
#: a node with no triangle ahead whose ray still counts as inside one (-)
RAY_TOL = 1e-9


def upwind_gradient_x(xy: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """D (n, n) (1/m): the one-sided derivative along +x of the P1 field on the nodes
    ``xy`` (m) and ``triangles`` (3, n_t) (module docstring); 0 rows at the zone's
    upstream edge."""
    n = len(xy)
    D = np.zeros((n, n))
    best = np.full(n, -np.inf)
    for c in range(3):
        i, j, k = triangles[c], triangles[(c + 1) % 3], triangles[(c + 2) % 3]
        a, b = xy[j] - xy[i], xy[k] - xy[i]
        det = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
        alpha, beta = b[:, 1] / det, -a[:, 1] / det  # e_x = alpha a + beta b
        scale = np.hypot(*a.T) + np.hypot(*b.T)
        inside = np.minimum(alpha, beta) * scale
        for t in np.flatnonzero(inside >= -RAY_TOL * scale):
            if inside[t] > best[i[t]]:
                best[i[t]] = inside[t]
                D[i[t]] = 0.0
                D[i[t], j[t]], D[i[t], k[t]] = alpha[t], beta[t]
                D[i[t], i[t]] = -alpha[t] - beta[t]
    return D


def sphere_geometry(comp: SurfaceCompliance3D, R: float, kinematics: str):
    """(s, arm, l): the nodal profile (m), the arm of the normal forces (-) and the
    rolling radius (m) of ``kinematics`` (module docstring), hat-weighted averages."""
    if kinematics == "small_slope":
        s = comp.hat_average(lambda x, y: (x * x + y * y) / (2.0 * R))
        arm = comp.hat_average(lambda x, y: x / R)
        return s, arm, np.full(comp.n, R)
    sysm = comp.system
    depth = comp.hat_average(lambda x, y: np.sqrt(R * R - x * x - y * y))
    return sysm.q / sysm.m, sysm.ms / sysm.m, depth


def _mode_row(friction, arm, ell, R, n):
    """(coefficients on N, on S_x, on Omega R / V, right-hand side) of the mode's row."""
    zero = np.zeros(n)
    if friction.mode == "omega":
        return zero, zero, 1.0, 1.0 - friction.creepage
    if friction.mode == "force":
        return 2.0 * arm, np.full(n, 2.0), 0.0, friction.driving_force
    if friction.mode == "towed":
        return zero, ell, 0.0, 0.0
    return R * arm, R + ell, 0.0, 0.0  # pushed at the top: Q R + sum l S_x = 0


def solve_frictional_3d(problem: ContactProblem, friction: RollingFriction,
                        compliance: Optional[SurfaceCompliance3D] = None,
                        progress: Optional[Callable[[str], None]] = None) -> FrictionalSphereResult:
    """Solve the frictional steady rolling of the sphere of ``problem`` (``fem.model =
    "3d"``, ``loading.speed`` > 0, a load) with ``friction`` (module docstring).

    ``compliance``: the condensed half layer of ``problem`` (:func:`surface_compliance_3d`),
    to reuse one factorization over several solves; made here if None.

    Raises
    ------
    InputError
        Not a rolling sphere in the 3D model, or no ``loading.load``.
    ContactZoneError
        The contact reaches the edge of the candidate zone (``fem.contact_zone``).
    ContactNotConvergedError
        The Newton iteration is singular or reaches ``friction.max_iterations``.
    """
    say = progress or (lambda _: None)
    check_sphere(problem)
    if problem.loading.load is None:
        raise InputError("loading.load: the 3D frictional FEM reference is load-controlled; give loading.load (N)")
    t0 = time.perf_counter()
    comp = compliance if compliance is not None else surface_compliance_3d(problem, progress)
    t1 = time.perf_counter()
    V, R, mu, P = problem.loading.speed, problem.indenter.radius, friction.mu, problem.loading.load
    n, m, plane = comp.n, comp.weights, comp.on_plane
    s, arm, ell = sphere_geometry(comp, R, friction.kinematics)
    C = comp.matrix
    B = C[:, :2 * n]  # columns of S_x, S_y
    Cn = -C[:, 2 * n:]  # columns of N (the force on the layer is -N e_z)
    D = upwind_gradient_x(comp.xy, comp.triangles)
    cN, cS, cO, rhs_mode = _mode_row(friction, arm, ell, R, n)
    edge = np.abs(D).sum(axis=1) == 0  # the zone's upstream edge

    # affine maps of z = [N, S_x, S_y, d, Omega R / V]: u, gap, w
    k = 3 * n + 2
    U = np.hstack([Cn, B, np.zeros((3 * n, 2))])
    G, g0 = -U[2 * n:], s.copy()
    G[:, 3 * n] = -1.0
    Wx, wx0 = V * (D @ U[:n]), np.full(n, V)
    Wx[:, 3 * n + 1] = -V * ell / R
    Wy = V * (D @ U[n:2 * n])
    Wy[plane] = 0.0
    Czz = C[2 * n:, 2 * n:]
    cn = 1.0 / np.diag(Czz)  # N per m: the augmentation of the gap
    ct = 1.0 / (V * np.median(np.abs(np.diag(Wx[:, n:2 * n])) / V))  # N per m/s: of the slip velocity
    rows_mode = np.zeros(k)
    rows_mode[:n], rows_mode[n:2 * n], rows_mode[3 * n + 1] = cN, cS, cO

    def residual(z, jacobian=True):
        """(F, J, sets) of the semi-smooth system at z (module docstring)."""
        N, Sx, Sy = z[:n], z[n:2 * n], z[2 * n:3 * n]
        g, wx, wy = G @ z + g0, Wx @ z + wx0, Wy @ z
        naug = N - cn * g
        contact = naug > 0
        rho = mu * np.maximum(naug, 0.0)
        qx, qy = Sx + ct * wx, np.where(plane, 0.0, Sy + ct * wy)
        qm = np.hypot(qx, qy)
        slip = contact & (qm > rho) & (mu > 0) | (~contact) | (mu == 0)
        stick = ~slip
        F = np.zeros(k)
        F[:n] = np.where(contact, cn * g, N)
        safe = np.maximum(qm, 1e-300)
        ex, ey = np.where(qm > 0, qx / safe, 1.0), np.where(qm > 0, qy / safe, 0.0)
        F[n:2 * n] = np.where(stick, -ct * wx, Sx - rho * ex)
        F[2 * n:3 * n] = np.where(plane, Sy, np.where(stick, -ct * wy, Sy - rho * ey))
        F[3 * n] = 2.0 * N.sum() - P
        F[3 * n + 1] = rows_mode @ z - rhs_mode
        if not jacobian:
            return F, None, (contact, stick)
        J = np.zeros((k, k))
        idx = np.arange(n)
        J[:n] = np.where(contact[:, None], cn[:, None] * G, 0.0)
        J[idx[~contact], idx[~contact]] = 1.0
        dq_x = Wx * ct
        dq_x[idx, n + idx] += 1.0
        dq_y = Wy * ct
        dq_y[idx, 2 * n + idx] += 1.0
        dq_y[plane] = 0.0
        drho = mu * (np.eye(n, k) - cn[:, None] * G) * contact[:, None]
        f = rho / safe  # rho / |q| (I - e e^T) dq
        Jx = -(f * (1 - ex * ex))[:, None] * dq_x + (f * ex * ey)[:, None] * dq_y - ex[:, None] * drho
        Jy = (f * ex * ey)[:, None] * dq_x - (f * (1 - ey * ey))[:, None] * dq_y - ey[:, None] * drho
        Jx[idx, n + idx] += 1.0
        Jy[idx, 2 * n + idx] += 1.0
        J[n:2 * n] = np.where(stick[:, None], -ct * Wx, Jx)
        J[2 * n:3 * n] = np.where(stick[:, None], -ct * Wy, Jy)
        J[2 * n + idx[plane]] = 0.0
        J[2 * n + idx[plane], 2 * n + idx[plane]] = 1.0
        J[3 * n, :n] = 2.0
        J[3 * n + 1] = rows_mode
        return F, J, (contact, stick)

    W0 = Czz * m[:, None] * m[None, :]  # the frictionless solve's weighted compliance (m^5/N)
    start = solve_contact(W0, m, s * m, load=P / 2.0, max_iterations=200)
    z = np.zeros(k)
    z[:n], z[3 * n], z[3 * n + 1] = start.pressure * m, start.indentation, 1.0
    if friction.mode == "omega":
        z[3 * n + 1] = 1.0 - friction.creepage
    scale = np.concatenate([np.full(n, P), np.full(2 * n, max(mu, 1e-3) * P), [P, P]])
    F, J, sets = residual(z)
    norm = np.linalg.norm(F / scale)
    for it in range(1, friction.max_iterations + 1):
        try:
            step = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            raise ContactNotConvergedError(
                f"the frictional Newton system of iteration {it} is singular ({int(sets[0].sum())} nodes in "
                f"contact, {int(sets[1].sum())} in stick, mode {friction.mode!r})") from None
        t = 1.0
        while True:  # backtracking on ||F||: a full step first
            z_new = z + t * step
            F_new, _, _ = residual(z_new, jacobian=False)
            new_norm = np.linalg.norm(F_new / scale)
            if new_norm < (1 - 1e-4 * t) * norm or t < 1e-3:
                break
            t *= 0.5
        z = z_new
        F, J, new_sets = residual(z)
        norm = np.linalg.norm(F / scale)
        same = all(np.array_equal(a, b) for a, b in zip(sets, new_sets))
        sets = new_sets
        say(f"3d frictional Newton {it}: {int(sets[0].sum())} in contact, {int(sets[1].sum())} in stick, "
            f"residual {norm:.2e}, step {t:g}")
        if same and norm <= NEWTON_TOL:
            break
    else:
        raise ContactNotConvergedError(f"the 3d frictional Newton iteration did not converge in "
                                       f"{friction.max_iterations} iterations (residual {norm:.2e}; "
                                       "friction.max_iterations)")
    contact, stick = sets
    N, S, d, Om = z[:n], z[n:3 * n].reshape(2, n).T, z[3 * n], z[3 * n + 1] * V / R
    u = U @ z
    w = np.column_stack([Wx @ z + wx0, Wy @ z])
    if np.any(contact & edge):
        raise ContactZoneError(f"the contact reaches the upstream edge of the candidate zone (r <= "
                               f"{np.hypot(*comp.xy.T).max():.4e} m): raise fem.contact_zone or lower the load")
    t2 = time.perf_counter()
    F = np.concatenate([S[:, 0], S[:, 1], -N])
    diss = comp.dissipation(F)
    t3 = time.perf_counter()
    Q = 2.0 * float(arm @ N + S[:, 0].sum())
    T = -2.0 * float(ell @ S[:, 0])
    slip = contact & ~stick
    times = dict(comp.times) if compliance is None else {}
    times.update(contact=t2 - t1, dissipation=t3 - t2, total=t3 - t0)
    return FrictionalSphereResult(
        xy=comp.xy, weights=m, normal=N, tangential=S, u=u.reshape(3, n).T, slip_velocity=w,
        contact=contact.copy(), stick=stick & contact, slip=slip, speed=V, radius=R, mu=mu, mode=friction.mode,
        kinematics=friction.kinematics, load=2.0 * float(N.sum()), indentation=float(d), omega=float(Om),
        creepage=float(1.0 - Om * R / V), driving_force=Q, torque=T, rolling_resistance=Q + T * Om / V,
        friction_power=2.0 * float(np.sum(S[slip] * w[slip])), dissipation=float(diss), iterations=it, times=times)
