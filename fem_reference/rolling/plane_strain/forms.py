"""Weak forms of steady rolling on a plane-strain viscoelastic layer (frame of the
indenter, material flowing at -V along x), as decorated pure functions.

Coordinates (x[0], x[1]) = (x, z), per unit length along y (forces N/m). Unknowns:
the displacement u (m), the pressure p (Pa) and, per Maxwell branch i, the viscous
strain eps_v,i = [[a_i, c_i], [c_i, -a_i]] (traceless, in the x-z plane; -). With
e(u) = ((du_x/dx - du_z/dz) / 2, (du_x/dz + du_z/dx) / 2) the in-plane deviatoric
strain, the deviatoric stress is 2 G_g eps(u) - sum_i 2 G_i eps_v,i, G_g = G_inf +
sum G_i the glassy modulus (Pa). The forms (docs/derivations.md, "Steady rolling FEM"):

    momentum   int 2 G_g eps(u):eps(v) - rho V^2 du/dx . dv/dx - p div v
               - sum_i 2 G_i (a_i (v_xx - v_zz) + 2 c_i v_xz) dA = contact
    mass       - int q div u dA = 0
    branch i   int 2 G_i (-l_i dw/dx + w - e(u)) (phi - delta_i l_i dphi/dx) dA = 0,
               w = a_i or c_i, l_i = V tau_i (m), delta_i the SUPG weight (-).

Extra form parameters: ``G`` (Pa), ``rho_v2`` = rho V^2 (Pa), ``ell`` = l_i (m),
``delta`` (-, per element and quadrature point), ``comp`` (0 for a, 1 for c). The
advection-relaxation operator and the multiplier's weighted areas are the same in 3D
(:mod:`fem_reference.rolling.forms`), named here too so that this module holds the
plane-strain model's whole set.
"""

from __future__ import annotations

from skfem import BilinearForm, Functional
from skfem.helpers import ddot, sym_grad

from ..forms import area, branch_advection, pressure_mass, weighted  # the same in 3D

__all__ = ["glassy_stiffness", "divergence", "branch_stress", "branch_advection",
           "branch_source", "coupling", "area", "weighted", "pressure_mass", "dissipation",
           "dashpot_power", "rate_power"]


def _e(u, comp):
    """Component ``comp`` of the in-plane deviatoric strain e(u) of a vector field."""
    g = u.grad
    if comp == 0:
        return 0.5 * (g[0, 0] - g[1, 1])
    return 0.5 * (g[0, 1] + g[1, 0])


@BilinearForm
def glassy_stiffness(u, v, w):
    """2 G eps(u):eps(v) - rho V^2 du/dx . dv/dx (Pa)."""
    gu, gv = u.grad, v.grad
    inertia = gu[0, 0] * gv[0, 0] + gu[1, 0] * gv[1, 0]
    return 2.0 * w.G * ddot(sym_grad(u), sym_grad(v)) - w.rho_v2 * inertia


@BilinearForm
def divergence(u, q, w):
    """q div u."""
    g = u.grad
    return q * (g[0, 0] + g[1, 1])


@BilinearForm
def branch_stress(a, v, w):
    """-2 G a (v_xx - v_zz) for comp 0, -2 G c 2 v_xz for comp 1: a branch's stress on
    the momentum test function (trial a scalar strain field, test a vector)."""
    return -2.0 * w.G * a * 2.0 * _e(v, w.comp)


@BilinearForm
def branch_source(u, phi, w):
    """-2 G e(u) (phi - delta l dphi/dx): the strain that drives a branch."""
    return -2.0 * w.G * _e(u, w.comp) * (phi - w.delta * w.ell * phi.grad[0])


@BilinearForm
def coupling(u, mu, w):
    """mu u_z on the top surface."""
    return mu * u[1]


@Functional
def dashpot_power(w):
    """s : D eps_v / Dt = 2 G (eps(u) - eps_v) : (-V d eps_v / dx)
    = 4 G V ((e_0 - a)(-da/dx) + (e_1 - c)(-dc/dx)) (W/m^3): the branch stress times
    the dashpot's strain rate; fields ``u``, ``a``, ``c``, parameters ``G``, ``V``."""
    u = w.u
    return 4.0 * w.G * w.V * ((_e(u, 0) - w.a) * (-w.a.grad[0]) + (_e(u, 1) - w.c) * (-w.c.grad[0]))


@Functional
def rate_power(w):
    """eta |D eps_v / Dt|^2 = 2 G tau V^2 2 ((da/dx)^2 + (dc/dx)^2) (W/m^3)."""
    return 4.0 * w.G * w.tau * w.V ** 2 * (w.a.grad[0] ** 2 + w.c.grad[0] ** 2)


@Functional
def dissipation(w):
    """(2 G / tau) |eps(u) - eps_v|^2 = (2 G / tau) 2 ((e_0 - a)^2 + (e_1 - c)^2) (W/m^3)
    of one branch; fields ``u``, ``a``, ``c``."""
    u = w.u
    da = _e(u, 0) - w.a
    dc = _e(u, 1) - w.c
    return 2.0 * w.G / w.tau * 2.0 * (da * da + dc * dc)
