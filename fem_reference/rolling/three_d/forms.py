"""Weak forms of 3D steady rolling on a viscoelastic layer (frame of the indenter,
material flowing at -V along x), as decorated pure functions.

Coordinates (x[0], x[1], x[2]) = (x, y, z). Unknowns: the displacement u (m), the
pressure p (Pa) and, per Maxwell branch i, the traceless symmetric viscous strain
eps_v,i with the five independent components w_k (-), k = 0..4:

    eps_v = [[w0, w2, w3], [w2, w1, w4], [w3, w4, -w0 - w1]].

E_k(u) is the same component of the deviator dev eps(u) = eps(u) - tr eps(u) I / 3, and
P_k(v) = d(eps_v : eps(v)) / dw_k = (v_xx - v_zz, v_yy - v_zz, 2 eps_xy, 2 eps_xz,
2 eps_yz) its conjugate. The forms (docs/derivations.md, section 9):

    momentum   int 2 G_g eps(u):eps(v) - rho V^2 du/dx . dv/dx - p div v
               - sum_i 2 G_i sum_k w_k,i P_k(v) dV = contact
    mass       - int q div u dV = 0
    branch i   int 2 G_i (-l_i dw_k/dx + w_k - E_k(u)) (phi - delta_i l_i dphi/dx) dV = 0,
               l_i = V tau_i (m), delta_i the SUPG weight (-).

Extra form parameters: ``G`` (Pa), ``rho_v2`` = rho V^2 (Pa), ``ell`` = l_i (m),
``delta`` (-, per element and quadrature point), ``comp`` (k).
"""

from __future__ import annotations

from skfem import BilinearForm, Functional
from skfem.helpers import ddot, sym_grad

from ...shared_forms import coupling_3d as coupling  # mu u_z, as in the stationary 3D model
from ..forms import area, branch_advection, pressure_mass, weighted  # as in plane strain

__all__ = ["glassy_stiffness", "divergence", "branch_stress", "branch_advection",
           "branch_source", "coupling", "area", "weighted", "pressure_mass", "dashpot_power",
           "deviator", "conjugate", "traceless_inner"]

N_COMPONENTS = 5


def deviator(u, k):
    """Component k of dev eps(u) (-) of a vector field (module docstring)."""
    g = u.grad
    if k < 2:
        return g[k, k] - (g[0, 0] + g[1, 1] + g[2, 2]) / 3.0
    i, j = ((0, 1), (0, 2), (1, 2))[k - 2]
    return 0.5 * (g[i, j] + g[j, i])


def conjugate(v, k):
    """P_k(v) = d(eps_v : eps(v)) / dw_k (-) of a vector test field."""
    g = v.grad
    if k < 2:
        return g[k, k] - g[2, 2]
    i, j = ((0, 1), (0, 2), (1, 2))[k - 2]
    return g[i, j] + g[j, i]


def traceless_inner(a, b):
    """A : B (-) of two traceless symmetric tensors given by their five components."""
    return (a[0] * b[0] + a[1] * b[1] + (a[0] + a[1]) * (b[0] + b[1])
            + 2.0 * (a[2] * b[2] + a[3] * b[3] + a[4] * b[4]))


@BilinearForm
def glassy_stiffness(u, v, w):
    """2 G eps(u):eps(v) - rho V^2 du/dx . dv/dx (Pa)."""
    gu, gv = u.grad, v.grad
    inertia = gu[0, 0] * gv[0, 0] + gu[1, 0] * gv[1, 0] + gu[2, 0] * gv[2, 0]
    return 2.0 * w.G * ddot(sym_grad(u), sym_grad(v)) - w.rho_v2 * inertia


@BilinearForm
def divergence(u, q, w):
    """q div u."""
    g = u.grad
    return q * (g[0, 0] + g[1, 1] + g[2, 2])


@BilinearForm
def branch_stress(a, v, w):
    """-2 G w_k P_k(v): a branch's stress on the momentum test function."""
    return -2.0 * w.G * a * conjugate(v, w.comp)


@BilinearForm
def branch_source(u, phi, w):
    """-2 G E_k(u) (phi - delta l dphi/dx): the strain that drives component k."""
    return -2.0 * w.G * deviator(u, w.comp) * (phi - w.delta * w.ell * phi.grad[0])


@Functional
def dashpot_power(w):
    """s : D eps_v / Dt = 2 G (dev eps(u) - eps_v) : (-V d eps_v / dx) (W/m^3) of one
    branch; fields ``u`` and ``w0`` .. ``w4``, parameters ``G``, ``V``."""
    comps = [w[f"w{k}"] for k in range(N_COMPONENTS)]
    diff = [deviator(w.u, k) - comps[k] for k in range(N_COMPONENTS)]
    rate = [-c.grad[0] for c in comps]
    return 2.0 * w.G * w.V * traceless_inner(diff, rate)
