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

__all__ = ["check_zone", "estimate_contact_radius", "estimate_size", "MAX_UNKNOWNS"]

#: the largest system a solve starts, as estimated unknowns, 2D sections and 3D models: sparse LU of a
#: 3D Taylor-Hood system took 1.6 GB at 46k unknowns (the section 11 sphere), a 2D one far
#: less; beyond these the factorization outgrows a workstation's memory and hours
MAX_UNKNOWNS = {2: 200_000, 3: 100_000}  # estimated (a lower bound): 2-10 times fewer than measured
#: the widest span of sizes, layer thickness or zone over element size (-), a mesh takes:
#: gmsh merges points closer than 1e-8 of the model's size
MAX_SPAN = 1e8


def estimate_contact_radius(problem: ContactProblem) -> float:
    """A-priori contact radius a_est (m) used to size the mesh (module docstring)."""
    R = problem.indenter.radius
    H = problem.layer.thickness
    G = problem.material.relaxed_modulus
    if problem.loading.load is not None:
        P = problem.loading.load
        a_hertz = (3.0 * P * R / (16.0 * G)) ** (1.0 / 3.0)
        a_thin = (32.0 * P * R / (math.pi * G)) ** (1.0 / 6.0) * math.sqrt(H)  # H^3 would overflow
        return min(a_hertz, a_thin)
    return math.sqrt(2.0 * R * problem.loading.indentation)


def estimate_size(problem: ContactProblem, zone: float, h: float) -> tuple[int, float, float]:
    """``(dimension, elements, unknowns)``: an estimate, before meshing, of the mesh that
    element size ``h`` (m) over the candidate zone ``zone`` (m) makes, after
    ``fem.refine`` uniform refinements.

    The element size grows as ``h + g d`` with the distance ``d`` (m) from the zone
    (``g`` = ``fem.grading``) down to the base at depth ``H``; the elements below a
    surface zone of length (2D) or area (3D) ``S`` number at least ``int_0^H S / (h + g
    d)^(D)`` (D = 2, 3) per cell area or volume: ``2 S / (g h) (1 - h / (h + g H))``
    triangles, ``5 S / (2 g h^2) (1 - (h / (h + g H))^2)`` tetrahedra. The rest of the
    domain adds to that, so it is a lower bound of the count of the zone's region.
    Taylor-Hood unknowns: about 4.5 per triangle, 4.4 per tetrahedron (P2 displacements
    at vertices and edges, P1 pressure).
    """
    fem, H = problem.fem, problem.layer.thickness
    g = fem.grading
    three_d = fem.model == "3d"
    rolling = problem.loading.speed > 0
    if not three_d:
        S = (2.0 if fem.model == "plane_strain" else 1.0) * zone
        elements = 2.0 * S / (g * h) * (1.0 - h / (h + g * H))
    else:
        width = 0.5 * problem.indenter.length if problem.indenter.shape == "cylinder" else zone
        S = 2.0 * zone * width if rolling else math.pi * zone * zone / 4.0
        elements = 5.0 * S / (2.0 * g * h * h) * (1.0 - (h / (h + g * H)) ** 2)
    elements = max(elements, 1.0) * float((8 if three_d else 4) ** fem.refine)
    return (3 if three_d else 2), elements, (4.4 if three_d else 4.5) * elements


def check_zone(problem: ContactProblem, zone: float, h: float) -> None:
    """Raise :class:`InputError` unless the candidate zone's (half-)width ``zone`` (m)
    is below the indenter's radius (a sphere's or a cylinder's: beyond it the profile is
    not a height) and at least 4 element sizes ``h`` (m) wide, and unless the mesh's
    estimated size (:func:`estimate_size`) is within :data:`MAX_UNKNOWNS`."""
    shape = problem.indenter.shape
    if shape in ("sphere", "line") and zone >= problem.indenter.radius:
        raise InputError(f"fem.contact_zone must be < indenter.radius = {problem.indenter.radius} m "
                         f"for a {'cylinder' if shape == 'line' else 'sphere'}, got {zone}")
    if zone < 4.0 * h:
        raise InputError(f"fem.contact_zone must be >= 4 element sizes = {4.0 * h} m, got {zone}")
    H = problem.layer.thickness
    if max(H, zone) / h > MAX_SPAN:
        raise InputError(
            f"the mesh would span {max(H, zone) / h:.3g} element sizes (layer.thickness = {H:.3g} m, contact zone "
            f"{zone:.3g} m, element size {h:.3g} m), more than the {MAX_SPAN:g} a mesh can hold (gmsh merges "
            "points closer than 1e-8 of the model's size): check layer.thickness, the load and fem.element_size")
    dim, elements, unknowns = estimate_size(problem, zone, h)
    if unknowns > MAX_UNKNOWNS[dim]:
        raise InputError(
            f"the mesh would have at least ~{elements:.3g} elements and ~{unknowns:.3g} unknowns (element size "
            f"{h:.3g} m over a contact zone of {zone:.3g} m, layer.thickness = {problem.layer.thickness:.3g} m, "
            f"fem.refine = {problem.fem.refine}), above the {MAX_UNKNOWNS[dim]:.3g} unknowns a {dim}D solve "
            "accepts (sparse LU memory grows faster than the unknowns): raise fem.element_size, lower "
            "fem.refine, or check layer.thickness and the load")
