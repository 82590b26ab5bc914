"""Concrete mesh sizes of a problem: the defaults of :class:`FemSettings` resolved.

The defaults scale with an a-priori estimate a_est (m) of the contact radius,
the smaller of the Hertz radius of the incompressible half-space,
a_H = (3 P R / (16 G))^(1/3) (E* = 4 G), and the thin-layer asymptote of
Jaffar (1997), a_T = (32 P R H^3 / (pi G))^(1/6) (paper eq. 70 at nu = 1/2).
A bonded layer is stiffer than the half-space, so a_H bounds the radius from
above; a_T is close when a / H is large. Under displacement control a_est is the
radius sqrt(2 R d) where the undeformed surface meets the indenter. G is the
relaxed modulus G_inf (the widest contact; the shear modulus of an elastic layer):
the 3D rolling model (:mod:`.rolling3d_discretization`) sizes its mesh with the same
estimate.

:func:`check_zone` holds the rules every model's candidate zone obeys.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import InputError
from .problem import ContactProblem

__all__ = ["Discretization", "check_zone", "estimate_contact_radius", "resolve"]


@dataclass(frozen=True)
class Discretization:
    """Resolved sizes (m) of the mesh; see :class:`~fem_reference.problem.FemSettings`.

    ``mesh_size`` is the size gmsh meshes the zone with, ``element_size`` =
    mesh_size / 2^refine the size after the uniform refinements.
    """

    element_size: float
    contact_zone: float
    domain_radius: float
    far_size: float
    grading: float
    estimated_radius: float
    mesh_size: float
    refine: int


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


def resolve(problem: ContactProblem) -> Discretization:
    """Fill in the default sizes of ``problem.fem`` and check that they fit together.

    Raises
    ------
    InputError
        If the candidate zone is not inside the domain, not below the sphere's
        radius, or not several elements wide.
    """
    fem = problem.fem
    H = problem.layer.thickness
    a = estimate_contact_radius(problem)
    three_d = fem.model == "3d"
    h = fem.element_size or (min(a / 8.0, H / 2.0) if three_d else min(a / 24.0, H / 4.0))
    zone = fem.contact_zone or 1.4 * a
    domain = fem.domain_radius or zone + 8.0 * H
    far = fem.far_size or min(H if three_d else H / 2.0, domain / 4.0)
    far = max(far, h)
    check_zone(problem, zone, h)
    if domain <= zone + h:
        raise InputError(f"fem.domain_radius must exceed fem.contact_zone + element_size = "
                         f"{zone + h} m, got {domain}")
    return Discretization(element_size=h / 2 ** fem.refine, contact_zone=zone,
                          domain_radius=domain, far_size=far, grading=fem.grading,
                          estimated_radius=a, mesh_size=h, refine=fem.refine)
