"""Concrete mesh sizes of a stationary problem: the defaults of :class:`FemSettings`
resolved.

The defaults scale with the a-priori contact radius a_est (m) of
:func:`fem_reference.sizing.estimate_contact_radius` (the smaller of the Hertz radius
and the thin-layer asymptote): an element size min(a_est / 24, H / 4) in the
axisymmetric section, min(a_est / 8, H / 2) in the quarter cylinder, a candidate zone
1.4 a_est, a domain radius contact_zone + 8 H.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError
from ..problem import ContactProblem
from ..sizing import check_zone, estimate_contact_radius

__all__ = ["Discretization", "resolve"]


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
