r"""Frictionless contact of a rigid sphere with a thin incompressible elastic layer bonded
to a rigid base: Jaffar (1997) as quoted by Zehil and Gavin (2013), sec. 10.2, eqs. 69-70,
with the indentation derived here (lubrication limit ``H / r_c -> 0``).

Transcription notes (checked in ``tests/verification/analytic/test_jaffar_thin.py``):

* Sec. 10.2 calls the thin-layer limit ``epsilon = r_c / H -> 0``; a thin layer is
  ``H / r_c -> 0`` (``epsilon = H / r_c``).
* Eq. 70 carries ``(1 + nu)``, but the lubrication derivation needs incompressibility;
  only ``nu = 1/2`` is meaningful (``48 / (1 + nu) = 32``, i.e. ``96 P R H^3 / (pi E)``).
* Eq. 69 prints the pressure as ``sigma_z``; the pressure here is compressive and positive
  (``p = -sigma_z``).

SI units: N, m, Pa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._checks import disc, poisson, positive

__all__ = ["ThinLayerContact", "jaffar_thin_layer_contact"]


@dataclass(frozen=True)
class ThinLayerContact:
    """Jaffar (1997) thin incompressible layer (eqs. 69-70 and the derived indentation).

    Attributes
    ----------
    load, radius, thickness, shear_modulus : float
        ``P`` (N), ``R`` (m), ``H`` (m), ``G`` (Pa).
    contact_radius : float
        ``r_c = (32 P R H^3 / (pi G))^(1/6)`` (m).
    peak_pressure : float
        ``p0 = 3 P / (pi r_c^2)`` (Pa).
    indentation : float
        ``d = 8 H^3 p0 / (3 G r_c^2) = r_c^2 / (4 R)`` (m).
    thickness_ratio : float
        ``H / r_c`` (-); the asymptote holds as it tends to 0.
    """

    load: float
    radius: float
    thickness: float
    shear_modulus: float
    contact_radius: float
    peak_pressure: float
    indentation: float
    thickness_ratio: float

    def pressure(self, r) -> np.ndarray:
        """Eq. 69: ``3 P / (pi r_c^2) (1 - r^2/r_c^2)^2`` (Pa, compressive), 0 outside.

        ``r`` (m) is the distance from the axis (array_like).
        """
        return self.peak_pressure * disc(r, self.contact_radius, np.square)


def jaffar_thin_layer_contact(
    load: float, radius: float, thickness: float, shear_modulus: float, poisson_ratio: float = 0.5
) -> ThinLayerContact:
    r"""Thin incompressible bonded layer, Jaffar (1997) (paper eqs. 69-70).

    Jaffar, M.J. (1997), asymptotic contact of a rigid sphere with a thin incompressible
    elastic layer on a rigid base; quoted by Zehil and Gavin (2013), sec. 10.2.

    Derivation (lubrication limit ``H / r_c -> 0``, re-done here). The layer carries the
    pressure ``p(x, y)`` uniformly across its depth; horizontal displacement ``u`` obeys
    ``G d^2u/dz^2 = grad p`` with ``u = 0`` on the base and no shear on the free surface,
    so ``u = (grad p / G)(z^2/2 - H z)`` and the flux ``int_0^H u dz = -(H^3/(3G)) grad p``.
    Incompressibility turns the flux divergence into the surface deflection, positive
    into the layer:

    .. math:: u_z = -\frac{H^3}{3G}\nabla^2 p ,

    (in Fourier space ``k^2 H^3 / (3 G)``, the small-``kH`` limit of
    :func:`.bonded_layer.layer_normal_compliance_static`). Inside the contact
    ``u_z = d - r^2/(2R)``, and a smooth edge needs ``p = dp/dr = 0`` at ``r_c``. The solution is
    ``p = C (r_c^2 - r^2)^2`` with ``16 C = 3 G / (2 R H^3)``, i.e. eq. 69 with
    ``p0 = C r_c^4 = 3 P / (pi r_c^2)`` (so that ``int p dA = P``), which is eq. 70 at
    ``nu = 1/2``: ``r_c^6 = 32 P R H^3 / (pi G)``; and ``d = u_z(0) = 8 H^3 p0 / (3 G
    r_c^2) = r_c^2 / (4 R)``.

    Parameters
    ----------
    load : float
        ``P`` (N), > 0.
    radius : float
        Sphere radius ``R`` (m), > 0.
    thickness : float
        Layer thickness ``H`` (m), > 0.
    shear_modulus : float
        ``G`` (Pa), > 0.
    poisson_ratio : float
        Must be 0.5: eq. 70's ``(1 + nu)`` form is only meaningful for the incompressible
        layer (``48 / (1 + nu) = 32``).

    Returns
    -------
    ThinLayerContact

    Notes
    -----
    With ``R = 80 m, H = 0.1 mm, P = 10 N, G = 3 MPa`` it gives ``r_c = 3.735 mm``, the
    paper's 3.7 mm (``H / r_c = 0.027``).
    """
    P = positive("load", load, "N")
    R = positive("radius", radius, "m")
    H = positive("thickness", thickness, "m")
    G = positive("shear_modulus", shear_modulus, "Pa")
    nu = poisson(poisson_ratio, "incompressible")
    rc = (48 * P * R * H**3 / (math.pi * G * (1 + nu))) ** (1 / 6)
    p0 = 3 * P / (math.pi * rc * rc)
    return ThinLayerContact(
        load=P, radius=R, thickness=H, shear_modulus=G, contact_radius=rc,
        peak_pressure=p0, indentation=8 * H**3 * p0 / (3 * G * rc * rc),
        thickness_ratio=H / rc,
    )
