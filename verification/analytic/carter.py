r"""Carter (1926): steady rolling of a rigid cylinder with creepage on an elastic
half-space in plane strain, with Coulomb friction (Johnson, *Contact Mechanics*, 1985,
sec. 8.2).

The half-space is incompressible (``nu = 0.5``): a rigid cylinder then has no coupling
between the normal and the tangential problems (Dundurs' ``beta = 0``), and Carter's
solution is exact for it. The normal problem is Hertz's line contact
(:func:`verification.analytic.hertz_line_contact`): half-width ``a = sqrt(P R / (pi G))``
(``E* = 4 G``), pressure ``p(x) = p0 sqrt(1 - x^2 / a^2)``, ``p0 = 2 P / (pi a)``.

Conventions (those of :mod:`bem`, docs/conventions.md): the frame moves with the
cylinder at ``V`` along ``+x`` (the leading edge is ``x = +a``); ``Q`` (N/m) is the
tangential force on the half-space along ``+x`` (the cylinder receives ``-Q``); the
creepage is ``xi = (V - Omega R) / V`` (-), the slip velocity of the cylinder relative to
the surface in a rigid contact, positive when the cylinder's surface turns slower than it
advances (braking). Tangential traction on the half-space (Pa), for ``0 <= Q <= mu P``:

    q(x) = mu p0 [ sqrt(1 - x^2 / a^2) - (c / a) sqrt(1 - (x - d)^2 / c^2) ]

(the second term on ``|x - d| < c`` only), with the stick zone ``[a - 2c, a]`` at the
leading edge, ``c / a = sqrt(1 - Q / (mu P))`` and ``d = a - c``. In the stick zone the
surface strain is uniform, ``du/dx = -(2 mu p0 / E*) d / a = -xi``; hence the creepage law

    xi(Q) = (mu a / R) (1 - sqrt(1 - Q / (mu P))),     full slip at xi = mu a / R.

Negative ``Q`` (driving) mirrors ``q`` and ``xi``; the stick zone stays at the leading
edge. Derivation and sign checks: docs/derivations.md ("Carter's rolling contact") and
``tests/verification/analytic/test_carter.py``. SI units throughout (m, N/m, Pa).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._checks import number, positive

__all__ = ["CarterRolling", "carter_rolling", "carter_rolling_from_creepage"]


@dataclass(frozen=True)
class CarterRolling:
    """Carter's steady rolling contact (SI units).

    Attributes
    ----------
    load : float
        ``P`` (N/m), per unit length.
    radius : float
        ``R`` (m).
    shear_modulus : float
        ``G`` (Pa) of the incompressible half-space.
    mu : float
        Coulomb coefficient (-).
    tangential_force : float
        ``Q`` (N/m) on the half-space along ``+x``, ``|Q| <= mu P``.
    half_width : float
        ``a`` (m).
    peak_pressure : float
        ``p0`` (Pa).
    stick_half_width : float
        ``c`` (m): the stick zone is ``[a - 2c, a]``; 0 in full slip.
    creepage : float
        ``xi = (V - Omega R) / V`` (-); in full slip, the creepage asked for (beyond
        the onset ``mu a / R`` when built from the creepage).
    """

    load: float
    radius: float
    shear_modulus: float
    mu: float
    tangential_force: float
    half_width: float
    peak_pressure: float
    stick_half_width: float
    creepage: float

    @property
    def stick_centre(self) -> float:
        """``d = a - c`` (m), the centre of the stick zone."""
        return self.half_width - self.stick_half_width

    @property
    def full_slip_creepage(self) -> float:
        """``mu a / R`` (-): the creepage at which the stick zone vanishes."""
        return self.mu * self.half_width / self.radius

    def pressure(self, x) -> np.ndarray:
        """``p(x)`` (Pa), compressive, 0 outside ``|x| < a``; ``x`` in m."""
        s = 1.0 - (np.asarray(x, float) / self.half_width) ** 2
        return self.peak_pressure * np.sqrt(np.maximum(s, 0.0))

    def traction(self, x) -> np.ndarray:
        """``q(x)`` (Pa) on the half-space along ``+x``; ``x`` in m."""
        x = np.asarray(x, float)
        c, sign = self.stick_half_width, math.copysign(1.0, self.tangential_force)
        q = self.mu * self.pressure(x)
        if c > 0:
            s = 1.0 - ((x - self.stick_centre) / c) ** 2
            q = q - self.mu * self.peak_pressure * (c / self.half_width) * np.sqrt(np.maximum(s, 0.0))
        return sign * q

    def in_stick(self, x) -> np.ndarray:
        """Whether ``x`` (m) lies in the stick zone ``[a - 2c, a]`` (none in full slip)."""
        x = np.asarray(x, float)
        return (self.stick_half_width > 0) & (np.abs(x - self.stick_centre) <= self.stick_half_width)


def _normal(load, radius, shear_modulus, mu):
    P = positive("load", load, "N/m")
    R = positive("radius", radius, "m")
    G = positive("shear_modulus", shear_modulus, "Pa")
    m = positive("mu", mu, "(-)")
    a = math.sqrt(P * R / (math.pi * G))
    return P, R, G, m, a, 2.0 * P / (math.pi * a)


def carter_rolling(load: float, radius: float, shear_modulus: float, mu: float,
                   tangential_force: float) -> CarterRolling:
    """Carter's solution for a given tangential force.

    Parameters
    ----------
    load : float
        ``P`` (N/m), > 0.
    radius : float
        ``R`` (m), > 0.
    shear_modulus : float
        ``G`` (Pa), > 0, of the incompressible half-space.
    mu : float
        Coulomb coefficient (-), > 0.
    tangential_force : float
        ``Q`` (N/m) on the half-space along ``+x``, ``|Q| <= mu P``.

    Returns
    -------
    CarterRolling
        With ``c = a sqrt(1 - |Q| / (mu P))`` and ``xi = sign(Q) (mu a / R)(1 - c / a)``.
    """
    P, R, G, m, a, p0 = _normal(load, radius, shear_modulus, mu)
    Q = number("tangential_force", tangential_force, "N/m")
    if abs(Q) > m * P * (1 + 1e-12):
        raise ValueError(f"tangential_force must satisfy |Q| <= mu P = {m * P!r} N/m (friction limit), got {Q!r}")
    ratio = math.sqrt(max(1.0 - abs(Q) / (m * P), 0.0))
    xi = math.copysign(m * a / R * (1.0 - ratio), Q)
    return CarterRolling(P, R, G, m, Q, a, p0, a * ratio, xi)


def carter_rolling_from_creepage(load: float, radius: float, shear_modulus: float, mu: float,
                                 creepage: float) -> CarterRolling:
    """Carter's solution for a given creepage ``xi = (V - Omega R) / V`` (-, any sign):
    ``Q = sign(xi) mu P (1 - (1 - |xi| R / (mu a))^2)`` up to the full-slip creepage
    ``mu a / R``, ``sign(xi) mu P`` beyond. Other parameters as :func:`carter_rolling`."""
    P, R, G, m, a, p0 = _normal(load, radius, shear_modulus, mu)
    xi = number("creepage", creepage, "(-)")
    ratio = max(1.0 - abs(xi) * R / (m * a), 0.0)
    Q = math.copysign(m * P * (1.0 - ratio * ratio), xi)
    return CarterRolling(P, R, G, m, Q, a, p0, a * ratio, xi)
