"""Weak forms every model shares, as decorated pure functions.

The contact multiplier mu (a P1 pressure, Pa) on the candidate zone of the top surface:
its measure ``area_3d`` (int mu dS) and its mortar coupling with the vertical
displacement in 3D, ``coupling_3d`` (int mu u_z dS); and the ``pressure_mass`` int p q
dV of the pressure unknowns. The models' own forms are in
:mod:`fem_reference.stationary.forms`, :mod:`fem_reference.rolling.plane_strain.forms` and
:mod:`fem_reference.rolling.three_d.forms`.
"""

from __future__ import annotations

from skfem import BilinearForm, LinearForm

__all__ = ["area_3d", "coupling_3d", "pressure_mass"]


@BilinearForm
def coupling_3d(u, mu, w):
    """mu u_z on the top surface of a 3D mesh."""
    return mu * u[2]


@LinearForm
def area_3d(mu, w):
    """mu: m^2 on a 3D surface (m per unit length on the plane-strain section's top)."""
    return mu


@BilinearForm
def pressure_mass(p, q, w):
    """p q (the pressure mass matrix, m^3; m^2 per unit length in plane strain)."""
    return p * q
