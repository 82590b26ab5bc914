r"""Hunter (1961): a rigid cylinder rolling steadily, without friction, on an
incompressible viscoelastic half-space (the three-parameter, or standard linear, solid) in
plane strain, per unit length along its axis.

Hunter, S.C. (1961), The rolling contact of a rigid cylinder with a viscoelastic half
space, J. Appl. Mech. 28, 611-617. The solution is re-derived in ``docs/derivations.md``
(section 8, "Hunter (1961)"): a Chebyshev-Bessel series for the pressure, two closed-form
conditions and one quadrature for the contact's half-width. At rest, or with ``f = 0``,
it is relaxed 2D Hertz (:func:`.hertz.hertz_line_contact`).

SI units: N/m, m, Pa, s, m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.special import ive

from ._checks import number, positive

__all__ = ["HunterRollingContact", "hunter_rolling_contact"]


@dataclass(frozen=True)
class HunterRollingContact:
    """Steady rolling of a rigid cylinder on an incompressible three-parameter (standard
    linear solid) viscoelastic half-space, frictionless, per unit length (Hunter 1961).

    Inputs as :func:`hunter_rolling_contact`; lengths in m, measured in the frame of the
    cylinder with ``x > 0`` ahead (the direction of motion).

    Attributes
    ----------
    load : float
        ``P`` (N/m).
    radius : float
        ``R`` (m).
    G0 : float
        Relaxed shear modulus (Pa).
    tau : float
        Creep (retardation) time (s).
    f : float
        ``G1 / G2`` (-); the glassy modulus is ``G0 (1 + f)``.
    speed : float
        ``V`` (m/s).
    half_width : float
        ``a`` (m), half the contact length.
    centre : float
        ``c`` (m), the middle of the contact: ``x`` in ``[c - a, c + a]``.
    trailing_edge, leading_edge : float
        ``c - a`` and ``c + a`` (m).
    rolling_resistance : float
        ``R_r = integral p x dx / R`` (N/m): the moment of the pressure about the axis over
        the radius, the BEM's definition.
    pressure_centroid_x : float
        ``integral p x dx / P`` (m).
    coefficients : ndarray
        ``beta_n`` (Pa), ``n = 1, 2, ...``: ``p = sum_n beta_n sin(n theta)`` with
        ``x = c + a cos(theta)``.
    amplitude : float
        ``A`` (Pa): the exponential part ``A exp(kappa (x - c - a))`` of the
        unit-modulus surface slope in the contact, ``kappa = (1 + f) / (V tau)``.
    """

    load: float
    radius: float
    G0: float
    tau: float
    f: float
    speed: float
    half_width: float
    centre: float
    amplitude: float
    coefficients: np.ndarray

    @property
    def trailing_edge(self) -> float:
        """``c - a`` (m), the rear end of the contact."""
        return self.centre - self.half_width

    @property
    def leading_edge(self) -> float:
        """``c + a`` (m), the front end of the contact."""
        return self.centre + self.half_width

    @property
    def pressure_centroid_x(self) -> float:
        """``integral p x dx / P = c + pi a^2 beta_2 / (4 P)`` (m)."""
        b = self.coefficients
        second = b[1] if b.size > 1 else 0.0
        return self.centre + self.half_width**2 * math.pi * second / (4 * self.load)

    @property
    def rolling_resistance(self) -> float:
        """``R_r = integral p x dx / R`` (N/m), positive when it resists the motion."""
        return self.load * self.pressure_centroid_x / self.radius

    @property
    def rolling_resistance_coefficient(self) -> float:
        """``R_r / P`` (-)."""
        return self.pressure_centroid_x / self.radius

    @property
    def peak_pressure(self) -> float:
        """Largest pressure (Pa), on a fine sampling of the contact."""
        th = np.linspace(0, math.pi, 4001)
        return float(self._series(th).max())

    def _series(self, theta) -> np.ndarray:
        """``sum_n beta_n sin(n theta) = Im sum_n beta_n exp(i n theta)``, by Horner."""
        z = np.exp(1j * np.asarray(theta, dtype=float))
        return np.polynomial.polynomial.polyval(z, np.concatenate([[0.0], self.coefficients])).imag

    def pressure(self, x) -> np.ndarray:
        """Contact pressure (Pa, compressive) at ``x`` (m, array_like), 0 outside the
        contact: ``sum_n beta_n sin(n theta)``, ``cos(theta) = (x - c) / a``."""
        x = np.asarray(x, dtype=float)
        t = (x - self.centre) / self.half_width
        inside = np.abs(t) < 1
        th = np.arccos(np.where(inside, t, 0.0))
        return np.where(inside, self._series(th), 0.0)


def _hunter_terms(k: float, count: int | None = None) -> np.ndarray:
    """``exp(-k) I_n(k)`` for ``n = 0 .. N`` with ``N`` large enough that the rest is below
    1e-17 of the first terms."""
    if count is None:
        count = int(k + 12 * math.sqrt(k + 1) + 40)
    n = np.arange(count + 1)
    return ive(n, k)


def _hunter_nodes(t_max: float, terms: int, order: int = 20) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on ``[0, t_max]`` split into dyadic panels
    ``[t_max 2^-(j+1), t_max 2^-j]`` down to ``1e-3 / terms`` (then one panel to 0): the
    sums ``sum_n beta_n exp(-n t)`` vary on the scale ``t`` itself near 0, and on each
    dyadic panel they are analytic with a radius comparable to its length (geometric
    convergence; checked against adaptive quadrature to 1e-12)."""
    x, wx = np.polynomial.legendre.leggauss(order)
    edges = [t_max]
    while edges[-1] > 1e-3 / terms:
        edges.append(edges[-1] / 2)
    edges.append(0.0)
    nodes, weights = [], []
    for hi, lo in zip(edges[:-1], edges[1:]):
        nodes.append(lo + (hi - lo) * (x + 1) / 2)
        weights.append(wx * (hi - lo) / 2)
    return np.concatenate(nodes), np.concatenate(weights)


def hunter_rolling_contact(load: float, radius: float, G0: float, tau: float, f: float,
                           speed: float) -> HunterRollingContact:
    r"""Hunter's (1961) rigid cylinder rolling on a standard-linear-solid half-space.

    The material is the paper's three-parameter solid (eq. 71, :class:`bem.materials.
    ThreeParameterSolid`): relaxed shear modulus ``G0``, glassy ``G0 (1 + f)``, creep
    (retardation) time ``tau``, relaxation time ``tau / (1 + f)``; shear creep compliance
    ``J(t) = 1/G0 - f / (G0 (1 + f)) exp(-t / tau)``; incompressible.
    In the frame of the cylinder (speed ``V`` in ``+x``) the unit-modulus surface slope
    ``phi = (1 / 2 pi) PV integral p(s) / (s - x) ds`` satisfies, in the contact
    ``[c - a, c + a]``, the first-order equation

    .. math:: \frac{\phi}{G_0} - \frac{V\tau}{G_0(1+f)}\phi' = -\frac{x - V\tau}{R}

    whose solution is ``phi = -(G0/R) x + G0 f V tau / ((1+f) R) + A exp(kappa (x - c - a))``,
    ``kappa = (1 + f) / (V tau)``. Inverting the finite Hilbert transform with the pressure
    bounded at both edges (Chebyshev-Bessel series, ``k = kappa a``) gives the pressure
    ``p = sum beta_n sin(n theta)`` with ``beta_1 = 2 G0 a / R - 4 A e^{-k} I_1(k)``,
    ``beta_n = -4 A e^{-k} I_n(k)``, and two closed-form conditions (solvability and load);
    the third, the slope equation itself at the leading edge (which the differentiated form
    lost), holds the memory of the material ahead of the contact and is one quadrature
    (composite Gauss-Legendre). The series has about ``k + 12 sqrt(k) + 40`` terms, ``k``
    about ``(1 + f) b0 / (V tau)``: a slow speed costs that many terms (``V tau / b0 =
    1e-3``: about 0.1 s).
    ``a`` is found by a bracketed root search. Derivation: ``docs/derivations.md``.

    Parameters
    ----------
    load : float
        Load per unit length ``P`` (N/m), > 0.
    radius : float
        Cylinder radius ``R`` (m), > 0 (parabolic profile, ``a << R``).
    G0 : float
        Relaxed shear modulus (Pa), > 0.
    tau : float
        Creep (retardation) time of eq. 71 (s), > 0.
    f : float
        ``G1 / G2`` (-), >= 0; glassy modulus ``G0 (1 + f)``.
    speed : float
        ``V`` (m/s), >= 0; 0 gives relaxed 2D Hertz.

    Returns
    -------
    HunterRollingContact
    """
    P = positive("load", load, "N/m")
    R = positive("radius", radius, "m")
    G0 = positive("G0", G0, "Pa")
    tau = positive("tau", tau, "s")
    f = number("f", f, "(dimensionless)")
    if f < 0:
        raise ValueError(f"f must be >= 0, got {f!r}")
    V = number("speed", speed, "m/s")
    if V < 0:
        raise ValueError(f"speed must be >= 0 m/s, got {speed!r}")
    b0 = math.sqrt(P * R / (math.pi * G0))
    if V == 0 or f == 0:
        return HunterRollingContact(P, R, G0, tau, f, V, b0, 0.0, 0.0, np.array([2 * G0 * b0 / R]))
    lam = V * tau  # creep length (m)
    kappa = (1 + f) / lam  # 1 / (V tau_relax)
    B = G0 * f / (kappa * R)  # the constant of the particular solution (-)
    Jg, dJ = 1 / (G0 * (1 + f)), f / (G0 * (1 + f))

    def state(a: float):
        k = kappa * a
        e = _hunter_terms(k)
        A = (math.pi * G0 * a * a / R - P) / (2 * math.pi * a * e[1])  # load
        c = R / G0 * (B + A * e[0])  # solvability
        beta = -4 * A * e[1:]
        beta[0] += 2 * G0 * a / R
        return k, A, c, beta

    def residual(a: float) -> float:
        k, A, c, beta = state(a)
        mu = a / lam
        # tail integral I(c2) = a int_0^inf exp(-mu (cosh t - 1)) sinh t Phi(cosh t) dt,
        # Phi(cosh t) = -(1/2) sum beta_n exp(-n t): the slope ahead of the contact
        t, w = _hunter_nodes(min(math.acosh(1 + 745.0 / mu), 60.0), beta.size)
        terms = np.polynomial.polynomial.polyval(np.exp(-t), np.concatenate([[0.0], beta]))  # Horner, |r| < 1
        tail = float(np.sum(w * np.exp(-mu * (np.cosh(t) - 1)) * np.sinh(t) * terms))
        I_c2 = -0.5 * a * tail
        phi_c2 = -0.5 * beta.sum()  # the slope at the leading edge, from either side
        return Jg * phi_c2 + dJ / lam * I_c2 + (c + a) / R

    bg = math.sqrt(P * R / (math.pi * G0 * (1 + f)))
    lo, hi = 0.5 * bg, 1.5 * b0
    r_lo, r_hi = residual(lo), residual(hi)
    if not r_lo * r_hi < 0:
        raise ArithmeticError(f"Hunter's end condition is not bracketed in a in [{lo:g}, {hi:g}] m "
                              f"(residuals {r_lo:g}, {r_hi:g}) at V tau / b0 = {lam / b0:g}")
    a = brentq(residual, lo, hi, xtol=1e-15 * b0, rtol=1e-15, maxiter=200)
    k, A, c, beta = state(a)
    return HunterRollingContact(P, R, G0, tau, f, V, a, c, A, beta)
