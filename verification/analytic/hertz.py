r"""Hertz contact of a rigid paraboloid on an elastic half-space, in 3D (a sphere) and in
plane strain (a cylinder, per unit length).

* :func:`hertz_contact` / :func:`hertz_contact_from_indentation`: the sphere, from the
  load or from the indentation (Hertz 1882; Johnson, *Contact Mechanics*, 1985, secs. 3.4
  and 4.2); :func:`effective_modulus_from_shear` gives the contact modulus they take.
* :func:`hertz_line_contact`: the cylinder on an incompressible half-space (Johnson 1985,
  eq. 4.43); the slow and fast limits of
  :func:`verification.analytic.hunter_rolling_contact`.

SI units throughout (m, N or N/m, Pa). Pressures are compressive and positive
(``p = -sigma_z``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._checks import disc, poisson, positive

__all__ = [
    "HertzContact",
    "HertzLineContact",
    "effective_modulus_from_shear",
    "hertz_contact",
    "hertz_contact_from_indentation",
    "hertz_line_contact",
]


def effective_modulus_from_shear(shear_modulus: float, poisson_ratio: float = 0.5) -> float:
    """Contact modulus ``E* = E / (1 - nu^2) = 2 G / (1 - nu)`` (Pa) of an elastic body
    against a rigid indenter.

    Parameters
    ----------
    shear_modulus : float
        ``G`` (Pa), > 0.
    poisson_ratio : float
        ``nu`` (-), in (-1, 0.5]. For an incompressible body ``E* = 4 G``.

    Returns
    -------
    float
        ``E*`` (Pa), the modulus :func:`hertz_contact` expects (Johnson 1985, eq. 4.22 with
        a rigid second body).
    """
    G = positive("shear_modulus", shear_modulus, "Pa")
    nu = poisson(poisson_ratio)
    return 2.0 * G / (1.0 - nu)


@dataclass(frozen=True)
class HertzContact:
    """Hertz contact of a rigid paraboloid on an elastic half-space (all SI).

    Attributes
    ----------
    load : float
        ``P`` (N).
    radius : float
        Indenter radius ``R`` (m).
    effective_modulus : float
        ``E* = E / (1 - nu^2)`` (Pa).
    contact_radius : float
        ``a = (3 P R / (4 E*))^(1/3)`` (m).
    indentation : float
        ``d = a^2 / R`` (m).
    peak_pressure : float
        ``p0 = 3 P / (2 pi a^2)`` (Pa).
    mean_pressure : float
        ``P / (pi a^2) = 2 p0 / 3`` (Pa).
    """

    load: float
    radius: float
    effective_modulus: float
    contact_radius: float
    indentation: float
    peak_pressure: float
    mean_pressure: float

    def pressure(self, r) -> np.ndarray:
        """Contact pressure ``p0 sqrt(1 - r^2/a^2)`` (Pa, compressive), 0 for ``|r| >= a``.

        ``r`` (m) is the distance from the axis (array_like; the sign is ignored).
        """
        return self.peak_pressure * disc(r, self.contact_radius, np.sqrt)


def _hertz(load: float, radius: float, modulus: float, a: float) -> HertzContact:
    return HertzContact(
        load=load,
        radius=radius,
        effective_modulus=modulus,
        contact_radius=a,
        indentation=a * a / radius,
        peak_pressure=3.0 * load / (2.0 * math.pi * a * a),
        mean_pressure=load / (math.pi * a * a),
    )


def hertz_contact(load: float, radius: float, effective_modulus: float) -> HertzContact:
    """Hertz solution for a given load (Johnson 1985, eqs. 4.22-4.23).

    Parameters
    ----------
    load : float
        ``P`` (N), > 0.
    radius : float
        Indenter radius ``R`` (m), > 0.
    effective_modulus : float
        ``E* = E / (1 - nu^2)`` (Pa), > 0, the half-space's contact modulus against a
        rigid indenter; see :func:`effective_modulus_from_shear` (``E* = 4 G`` when
        incompressible). Not Young's modulus.

    Returns
    -------
    HertzContact
        ``a = (3 P R / (4 E*))^(1/3)``, ``d = a^2 / R``, ``p0 = 3 P / (2 pi a^2)``.
    """
    P = positive("load", load, "N")
    R = positive("radius", radius, "m")
    Es = positive("effective_modulus", effective_modulus, "Pa")
    return _hertz(P, R, Es, (3.0 * P * R / (4.0 * Es)) ** (1.0 / 3.0))


def hertz_contact_from_indentation(indentation: float, radius: float, effective_modulus: float) -> HertzContact:
    """Inverse of :func:`hertz_contact`: ``P = (4/3) E* sqrt(R) d^(3/2)``, ``a = sqrt(R d)``.

    Parameters
    ----------
    indentation : float
        ``d`` (m), > 0.
    radius, effective_modulus : float
        As in :func:`hertz_contact` (m, Pa).

    Returns
    -------
    HertzContact
    """
    d = positive("indentation", indentation, "m")
    R = positive("radius", radius, "m")
    Es = positive("effective_modulus", effective_modulus, "Pa")
    P = 4.0 / 3.0 * Es * math.sqrt(R) * d**1.5
    return _hertz(P, R, Es, math.sqrt(R * d))


# ---------------------------------------------------------------------------------------
# plane strain: a cylinder, per unit length


@dataclass(frozen=True)
class HertzLineContact:
    """Rigid cylinder (parabolic profile ``x^2 / (2 R)``) on an incompressible elastic
    half-space in plane strain, per unit length along the axis (all SI).

    Attributes
    ----------
    load : float
        ``P`` (N/m).
    radius : float
        ``R`` (m).
    shear_modulus : float
        ``G`` (Pa); the contact modulus is ``E* = 4 G``.
    half_width : float
        ``b = sqrt(4 P R / (pi E*)) = sqrt(P R / (pi G))`` (m) (Johnson 1985, eq. 4.43).
    peak_pressure : float
        ``p0 = 2 P / (pi b) = 2 G b / R`` (Pa).
    """

    load: float
    radius: float
    shear_modulus: float
    half_width: float
    peak_pressure: float

    def pressure(self, x) -> np.ndarray:
        """``p0 sqrt(1 - x^2 / b^2)`` (Pa, compressive) at ``x`` (m), 0 for ``|x| >= b``."""
        return self.peak_pressure * disc(x, self.half_width, np.sqrt)


def hertz_line_contact(load: float, radius: float, shear_modulus: float) -> HertzLineContact:
    """2D Hertz (line contact) of a rigid cylinder on an incompressible half-space.

    Parameters
    ----------
    load : float
        Load per unit length ``P`` (N/m), > 0.
    radius : float
        ``R`` (m), > 0.
    shear_modulus : float
        ``G`` (Pa), > 0.

    Returns
    -------
    HertzLineContact
        ``b = sqrt(P R / (pi G))``, ``p0 = 2 P / (pi b)``.
    """
    P = positive("load", load, "N/m")
    R = positive("radius", radius, "m")
    G = positive("shear_modulus", shear_modulus, "Pa")
    b = math.sqrt(P * R / (math.pi * G))
    return HertzLineContact(P, R, G, b, 2 * P / (math.pi * b))
