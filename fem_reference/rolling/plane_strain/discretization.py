"""Sizes of the plane-strain rolling model: the ``[fem]`` defaults resolved, and the
checks that the truncated layer is long enough.

The defaults scale with an a-priori contact half-width b_est (m) for the relaxed
modulus G_inf (the widest contact), the smaller of the plane-strain Hertz half-width
b_H = sqrt(4 P R / (pi E*)) = sqrt(P R / (pi G_inf)) (E* = 4 G; Johnson 1985, eq. 4.43) and the thin-layer
asymptote b_T = (15 P R H^3 / (2 G_inf))^(1/5) (bonded incompressible layer,
frictionless top: p = G (b^2 - x^2)^2 / (8 R H^3), docs/derivations.md); under
displacement control b_est = sqrt(2 R d).

Lengths: the material enters at x = upstream, undeformed and relaxed, and leaves at
x = -downstream. The influence of the clamped ends decays over about the thickness H
(and the contact size), and behind the indenter the material recovers over V t_r,
with t_r the longest creep time. Defaults: upstream = Z + max(8 H, 6 b_est),
downstream = Z + max(8 H, 6 b_est, 8 V t_r). Shorter than Z + 2 max(H, b_est)
(upstream) or Z + 2 max(H, b_est) + 3 V t_r (downstream) is an error
(:func:`~fem_reference.rolling.flow_lengths.check_flow_lengths`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ...problem import ContactProblem
from ...sizing import check_zone
from ..flow_lengths import check_flow_lengths, creep_length

__all__ = ["PlaneDiscretization", "band_depth", "estimate_half_width", "resolve_plane"]


@dataclass(frozen=True)
class PlaneDiscretization:
    """Resolved sizes (m) of the plane-strain mesh (see
    :mod:`fem_reference.mesh.plane_strain_strip`):
    ``mesh_size`` the spacing the structured mesh is made with, ``element_size`` =
    mesh_size / 2^refine after the uniform (nested) refinements."""

    element_size: float
    mesh_size: float
    contact_zone: float
    band: float
    upstream: float
    downstream: float
    far_x_up: float
    far_x_down: float
    far_z: float
    grading: float
    estimated_half_width: float
    creep_length: float
    refine: int

    @property
    def far_size(self) -> float:
        """``fem.far_size`` resolved (m): far_z, the largest row height, and far_x_up (the
        x spacing downstream may grow further, to far_x_down)."""
        return self.far_z


def estimate_half_width(problem: ContactProblem) -> float:
    """A-priori contact half-width b_est (m) for the relaxed modulus (module docstring)."""
    R = problem.indenter.radius
    H = problem.layer.thickness
    G = problem.material.relaxed_modulus
    if problem.loading.load is not None:
        P = problem.loading.load
        b_hertz = math.sqrt(P * R / (math.pi * G))
        b_thin = (15.0 * P * R * H ** 3 / (2.0 * G)) ** 0.2
        return min(b_hertz, b_thin)
    return math.sqrt(2.0 * R * problem.loading.indentation)


def band_depth(thickness: float, zone: float, h: float) -> float:
    """Depth (m) of the band of uniform rows (``h`` tall) under the top surface:
    min(H, max(4 h, (Z / 2) min(1, Z / H))), Z the candidate zone's half-width (m).

    A layer up to Z thick keeps the band down to min(H, Z / 2): its fields fill the
    thickness and the bonded base (H = b0: R_r 0.26% lower with a band of 4 h instead of
    Z / 2, measured). Deeper, the band shrinks as Z^2 / (2 H) down to 4 h, and the rows
    below it grow as h + grading * depth: under a deep layer's contact the fields vary
    over the depth itself. On a layer 160 b0 deep (h = b0 / 30, V tau / b0 = 1) the band
    of Z / 2 held half of the unknowns (74 772 against 38 463) and moved R_r by 0.04% of
    its value; at H = 4 b0 a band of 4 h moved it by 0.03% (measured)."""
    return min(thickness, max(4.0 * h, 0.5 * zone * min(1.0, zone / thickness)))


def resolve_plane(problem: ContactProblem) -> PlaneDiscretization:
    """Fill in the plane-strain defaults of ``problem.fem`` and check the lengths.

    Raises
    ------
    InputError
        A candidate zone not several elements wide or wider than the cylinder, or an
        upstream (inflow) or downstream length too short (the message names the
        setting and the length needed).
    """
    fem = problem.fem
    H = problem.layer.thickness
    b = estimate_half_width(problem)
    h = fem.element_size or min(b / 30.0, H / 8.0)
    zone = fem.contact_zone or 1.5 * b
    lv = creep_length(problem)
    upstream = fem.upstream or zone + max(8.0 * H, 6.0 * b)
    downstream = fem.downstream or zone + max(8.0 * H, 6.0 * b, 8.0 * lv)
    far = fem.far_size or max(H / 2.0, h)
    far = max(far, h)
    check_zone(problem, zone, h)
    check_flow_lengths(problem, zone, max(H, b), upstream, downstream, "b_est",
                       ("8 H, 6 b_est", "8 H, 6 b_est, 8 V t_r"))
    return PlaneDiscretization(element_size=h / 2 ** fem.refine, mesh_size=h, contact_zone=zone,
                               band=band_depth(H, zone, h), upstream=upstream, downstream=downstream,
                               far_x_up=far, far_x_down=max(far, lv / 4.0), far_z=far,
                               grading=fem.grading, estimated_half_width=b, creep_length=lv,
                               refine=fem.refine)
