"""Sizes of the 3D steady-rolling model (sphere or roller, half box y >= 0): the ``[fem]``
defaults resolved, and the checks that the truncated layer is long and wide enough.

The defaults scale with an a-priori contact radius a_est (m) for the relaxed modulus
G_inf (the widest contact), the smaller of the Hertz radius (3 P R / (16 G_inf))^(1/3)
and the thin-layer asymptote (32 P R H^3 / (pi G_inf))^(1/6)
(:func:`fem_reference.sizing.estimate_contact_radius`, the stationary models' estimate);
under displacement control sqrt(2 R d).

Lengths (m): the material enters at x = upstream, undeformed and relaxed, and leaves at
x = -downstream; the half layer ends at y = lateral (``fem.domain_radius``, traction
free). Defaults: upstream = lateral = Z + max(6 H, 4 a_est), downstream = Z + max(6 H,
4 a_est, 6 V t_r), t_r the longest creep time. Shorter than Z + 2 max(H, a_est)
(upstream, lateral) or Z + 2 max(H, a_est) + 3 V t_r (downstream) is an error. The mesh
is mirror-symmetric about x = 0 (:mod:`fem_reference.mesh.half_box`), so both lengths
become the larger of the two (``upstream`` = ``downstream`` in the resolved sizes).
Element size h_c = ``fem.element_size`` (default min(a_est / 10, H / 5)) on the zone,
growing as h_c + grading * distance up to ``fem.far_size`` (default H).

A roller (``indenter.shape = "cylinder"``, length L) has a line contact: a_est is then
its half-width b_est under the load per unit length P' = P / L, the smaller of the
plane-strain Hertz half-width sqrt(P' R / (pi G_inf)) (E* = 4 G) and the thin-layer
asymptote (15 P' R H^3 / (2 G_inf))^(1/5) (the incompressible bonded layer's surface
deflection -(H^3 / 3 G) p'' with p = A (b^2 - x^2)^2, as Jaffar's axisymmetric one);
sqrt(2 R d) under displacement control. The candidate zone is the rectangle |x| <=
contact_zone (default 2 b_est: the contact widens where the pressure peaks near the
ends), y <= L/2 (the roller ends there), and the half box reaches y = L/2 +
max(6 H, 4 b_est) by default.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ...errors import InputError
from ...problem import ContactProblem
from ...sizing import check_zone, estimate_contact_radius
from ..flow_lengths import check_flow_lengths, creep_length

__all__ = ["BoxDiscretization", "resolve_box", "roller_half_width"]


@dataclass(frozen=True)
class BoxDiscretization:
    """Resolved sizes (m) of the half-box mesh (:mod:`fem_reference.mesh.half_box`):
    ``mesh_size`` the zone size gmsh meshes with, ``element_size`` = mesh_size / 2^refine."""

    element_size: float
    mesh_size: float
    contact_zone: float
    upstream: float
    downstream: float
    lateral: float
    far_size: float
    grading: float
    estimated_radius: float
    creep_length: float
    refine: int
    zone_y: float | None = None


def resolve_box(problem: ContactProblem) -> BoxDiscretization:
    """Fill in the 3D rolling defaults of ``problem.fem`` and check the lengths.

    Raises
    ------
    InputError
        A candidate zone not several elements wide or not inside the sphere, or an
        upstream (inflow), downstream or lateral length too short (the message names the
        setting and the length needed).
    """
    fem = problem.fem
    H = problem.layer.thickness
    roller = problem.indenter.shape == "cylinder"
    a = roller_half_width(problem) if roller else estimate_contact_radius(problem)
    h = fem.element_size or min(a / 10.0, H / 5.0)
    zone = fem.contact_zone or (2.0 if roller else 1.5) * a  # a roller's contact widens at its ends
    lv = creep_length(problem)
    near = max(H, a)
    upstream = fem.upstream or zone + max(6.0 * H, 4.0 * a)
    downstream = fem.downstream or zone + max(6.0 * H, 4.0 * a, 6.0 * lv)
    zone_y = 0.5 * problem.indenter.length if roller else None
    lateral = fem.domain_radius or (zone_y if roller else zone) + max(6.0 * H, 4.0 * a)
    far = max(fem.far_size or H, h)
    check_zone(problem, zone, h)
    if roller and zone >= problem.indenter.radius - problem.indenter.axial_drop(zone_y):
        raise InputError(f"fem.contact_zone must be < the roller's radius at its ends, "
                         f"{problem.indenter.radius - problem.indenter.axial_drop(zone_y):.4g} m, got {zone}")
    if roller and lateral < zone_y + 2.0 * near:
        raise InputError(
            f"fem.domain_radius = {lateral:.4g} m (the lateral extent y of the 3d rolling model) is too "
            f"short for the roller: it needs at least length / 2 + 2 max(H, b_est) = {zone_y + 2.0 * near:.4g} m; "
            "raise fem.domain_radius")
    if lateral < zone + 2.0 * near:
        raise InputError(
            f"fem.domain_radius = {lateral:.4g} m (the lateral extent y of the 3d rolling model) is "
            f"too short: it needs at least contact_zone + 2 max(H, a_est) = {zone + 2.0 * near:.4g} m; "
            "raise fem.domain_radius")
    check_flow_lengths(problem, zone, near, upstream, downstream, "a_est",
                       ("6 H, 4 a_est", "6 H, 4 a_est, 6 V t_r"))
    length = max(upstream, downstream)  # the mesh is mirror-symmetric about x = 0
    return BoxDiscretization(element_size=h / 2 ** fem.refine, mesh_size=h, contact_zone=zone,
                             upstream=length, downstream=length, lateral=lateral,
                             far_size=far, grading=fem.grading, estimated_radius=a,
                             creep_length=lv, refine=fem.refine, zone_y=zone_y)


def roller_half_width(problem: ContactProblem) -> float:
    """A-priori half-width b_est (m) of a roller's contact (module docstring)."""
    R, H, L = problem.indenter.radius, problem.layer.thickness, problem.indenter.length
    G = problem.material.relaxed_modulus
    if problem.loading.load is None:
        return math.sqrt(2.0 * R * problem.loading.indentation)
    per_length = problem.loading.load / L
    return min(math.sqrt(per_length * R / (math.pi * G)), (7.5 * per_length * R * H ** 3 / G) ** 0.2)
