"""Weak forms both steady-rolling models share, as decorated pure functions.

The SUPG advection-relaxation operator of a viscous-strain component (the same scalar
equation for each component in plane strain and in 3D), the multiplier's weighted
areas int mu f dS (f = 1: ``area``, the indenter's profile, x, ds/dx), and the pressure
mass. Extra form parameters: ``G`` (Pa), ``ell`` = V tau_i (m), ``delta`` (-, per
element and quadrature point), ``f`` (at the quadrature points).
"""

from __future__ import annotations

from skfem import BilinearForm, LinearForm

from ..shared_forms import area_3d as area, pressure_mass  # mu and p q: the same in every model

__all__ = ["area", "branch_advection", "pressure_mass", "weighted"]


@BilinearForm
def branch_advection(a, phi, w):
    """2 G (-l da/dx + a) (phi - delta l dphi/dx): the SUPG advection-relaxation operator."""
    return 2.0 * w.G * (-w.ell * a.grad[0] + a) * (phi - w.delta * w.ell * phi.grad[0])


@LinearForm
def weighted(mu, w):
    """mu f with f = ``w.f`` at the quadrature points."""
    return mu * w.f
