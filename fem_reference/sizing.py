"""The a-priori contact radius that sizes a sphere's mesh, and the rules every model's
candidate zone obeys.

The estimate a_est (m) of the contact radius is the smaller of the Hertz radius of the
incompressible half-space, a_H = (3 P R / (16 G))^(1/3) (E* = 4 G), and the thin-layer
asymptote of Jaffar (1997), a_T = (32 P R H^3 / (pi G))^(1/6) (paper eq. 70 at nu =
1/2). A bonded layer is stiffer than the half-space, so a_H bounds the radius from
above; a_T is close when a / H is large. Under displacement control a_est is the radius
sqrt(2 R d) where the undeformed surface meets the indenter. G is the relaxed modulus
G_inf (the widest contact; the shear modulus of an elastic layer): the stationary
models and the 3D rolling model size their meshes with it.
"""

from __future__ import annotations

import math

from .errors import InputError
from .problem import ContactProblem

__all__ = ["check_zone", "estimate_contact_radius"]


def estimate_contact_radius(problem: ContactProblem) -> float:
    """A-priori contact radius a_est (m) used to size the mesh (module docstring)."""
    R = problem.indenter.radius
    H = problem.layer.thickness
    G = problem.material.relaxed_modulus
    if problem.loading.load is not None:
        P = problem.loading.load
        a_hertz = (3.0 * P * R / (16.0 * G)) ** (1.0 / 3.0)
        a_thin = (32.0 * P * R * H ** 3 / (math.pi * G)) ** (1.0 / 6.0)
        return min(a_hertz, a_thin)
    return math.sqrt(2.0 * R * problem.loading.indentation)


def check_zone(problem: ContactProblem, zone: float, h: float) -> None:
    """Raise :class:`InputError` unless the candidate zone's (half-)width ``zone`` (m)
    is below the indenter's radius (a sphere's or a cylinder's: beyond it the profile is
    not a height) and at least 4 element sizes ``h`` (m) wide."""
    shape = problem.indenter.shape
    if shape in ("sphere", "line") and zone >= problem.indenter.radius:
        raise InputError(f"fem.contact_zone must be < indenter.radius = {problem.indenter.radius} m "
                         f"for a {'cylinder' if shape == 'line' else 'sphere'}, got {zone}")
    if zone < 4.0 * h:
        raise InputError(f"fem.contact_zone must be >= 4 element sizes = {4.0 * h} m, got {zone}")
