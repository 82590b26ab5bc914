"""Weak forms of the stationary incompressible layer, as decorated pure functions.

Mixed displacement-pressure form with sigma = -p I + 2 G eps(u) (Pa):

    a(u, v) = int 2 G eps(u) : eps(v) dV,   b(u, q) = int q div u dV,
    c(u, mu) = int mu u_z dS  (top surface; mu the contact pressure, Pa).

The saddle system is [[A, -B^T], [-B, 0]], the stationarity conditions of
1/2 a(u, u) - b(u, p). Axisymmetric forms use (x[0], x[1]) = (r, z), the hoop
strain u_r / r and the measure dV = 2 pi r dr dz, dS = 2 pi r dr, so forces
are totals in N. The constraint is the exact axisymmetric divergence
div u = du_r/dr + u_r/r + du_z/dz. Quadrature points are interior, so 1/r is
never evaluated on the axis. Extra form parameters: ``G`` (Pa) and ``s``, the
indenter profile s(r) (m) at the quadrature points. The 3D multiplier's area and
coupling and the pressure mass are the forms every model shares
(:mod:`fem_reference.shared_forms`), named here too so that this module holds the
stationary model's whole set.
"""

from __future__ import annotations

import numpy as np
from skfem import BilinearForm, LinearForm
from skfem.helpers import ddot, div, sym_grad

from ..shared_forms import area_3d, coupling_3d, pressure_mass

__all__ = ["axi_stiffness", "axi_divergence", "axi_coupling", "axi_area", "axi_profile",
           "stiffness_3d", "divergence_3d", "coupling_3d", "area_3d", "profile_3d",
           "pressure_mass"]

TWO_PI = 2.0 * np.pi


def _axi_strains(u, r):
    """(eps_rr, eps_zz, eps_tt, eps_rz) of an axisymmetric displacement."""
    ur, g = u[0], u.grad
    return g[0, 0], g[1, 1], ur / r, 0.5 * (g[0, 1] + g[1, 0])


@BilinearForm
def axi_stiffness(u, v, w):
    r = w.x[0]
    eu, ev = _axi_strains(u, r), _axi_strains(v, r)
    inner = eu[0] * ev[0] + eu[1] * ev[1] + eu[2] * ev[2] + 2.0 * eu[3] * ev[3]
    return 2.0 * w.G * inner * TWO_PI * r


@BilinearForm
def axi_divergence(u, q, w):
    r = w.x[0]
    g = u.grad
    return q * (g[0, 0] + u[0] / r + g[1, 1]) * TWO_PI * r


@BilinearForm
def axi_coupling(u, mu, w):
    return mu * u[1] * TWO_PI * w.x[0]


@LinearForm
def axi_area(mu, w):
    return mu * TWO_PI * w.x[0]


@LinearForm
def axi_profile(mu, w):
    return mu * w.s * TWO_PI * w.x[0]


@BilinearForm
def stiffness_3d(u, v, w):
    return 2.0 * w.G * ddot(sym_grad(u), sym_grad(v))


@BilinearForm
def divergence_3d(u, q, w):
    return q * div(u)


@LinearForm
def profile_3d(mu, w):
    return mu * w.s
