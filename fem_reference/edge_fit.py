"""Contact radius from the gap just outside the contact.

Outside the edge of a smooth (Hertz-like) contact the gap opens like
g ~ (r - r_c)^(3/2), so g^(2/3) is linear in r there. The contact radius is
the zero of the least-squares line g^(2/3) = alpha + beta r through the
top-surface vertices just outside the contact: those with
r_last < r <= r_last + (fit_nodes + 1/4) h, with r_last the largest radius of a
node carrying pressure and h the element size of the zone (``fit_nodes``
vertices along a radius in the axisymmetric model, a band of them in 3D).
The gap g = s(r) - d - u_z is the pointwise gap of the P2 displacement at the
vertices. This estimate moves smoothly with the mesh, unlike the last contact
node or a fit of the nodal pressures (the P1 contact multiplier wobbles by a few
per cent over the last elements), and it is exact for the Hertz gap to leading
order in (r - r_c).
"""

from __future__ import annotations

import numpy as np

from .errors import ContactNotConvergedError

__all__ = ["fit_contact_radius"]


def fit_contact_radius(r_last: float, surface_radius: np.ndarray, gap: np.ndarray,
                       element_size: float, fit_nodes: int) -> float:
    """Contact radius (m) by the gap fit (module docstring).

    Parameters
    ----------
    r_last : float
        Largest distance from the axis of a node in contact (m).
    surface_radius : ndarray
        Distance of the top-surface vertices from the axis (m).
    gap : ndarray
        Pointwise gap s(r) - d - u_z at those vertices (m).
    element_size : float
        Element size h_c (m) of the contact zone.
    fit_nodes : int
        Vertices along a radius used in the fit (>= 2).

    Raises
    ------
    ContactNotConvergedError
        If fewer than two vertices lie in the band, or the gap does not open.
    """
    h = element_size
    band = (surface_radius > r_last + 1e-6 * h) & \
           (surface_radius <= r_last + (fit_nodes + 0.25) * h)
    if band.sum() < 2:
        raise ContactNotConvergedError(f"only {int(band.sum())} surface vertex(es) within "
                                       f"{fit_nodes} element sizes outside the contact: "
                                       "the contact radius cannot be fitted")
    x = surface_radius[band]
    y = np.maximum(gap[band], 0.0) ** (2.0 / 3.0)
    beta, alpha = np.polyfit(x, y, 1)
    if not beta > 0:
        raise ContactNotConvergedError("the gap does not open outside the contact: the contact "
                                       "radius cannot be fitted (refine fem.element_size)")
    return float(-alpha / beta)
