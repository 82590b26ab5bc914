r"""Analytic references for the stationary frictionless contact of a rigid sphere.

A rigid sphere of radius ``R`` (paraboloid approximation ``h(r) = r^2 / (2 R)``) is pressed
by a load ``P`` into an elastic layer of thickness ``H`` and shear modulus ``G`` bonded to a
rigid base. Three limits have closed forms, and the layer's Fourier-space compliance has
one that checks the boundary-element kernel:

* :func:`hertz_contact` / :func:`hertz_contact_from_indentation`: half-space (Hertz 1882;
  Johnson, *Contact Mechanics*, 1985, sec. 3.4 and 4.2).
* :func:`jaffar_thick_layer_contact`: thick layer, Jaffar (2008) as quoted by Zehil and
  Gavin (2013), eqs. 64-68.
* :func:`jaffar_thin_layer_contact`: thin incompressible layer, Jaffar (1997) as quoted by
  Zehil and Gavin (2013), eqs. 69-70, plus the indentation derived here.
* :func:`layer_normal_compliance_static` and its two asymptotes.

SI units throughout (m, N, Pa). Pressures returned here are compressive and positive
(``p = -sigma_z``); eqs. 64 and 69 of the paper print them as ``sigma_z`` although the
paper's convention elsewhere is ``sigma_z`` positive in tension.

Transcription notes (Zehil and Gavin 2013, sec. 10; checked in ``tests/unit/test_analytic.py``)
-----------------------------------------------------------------------------------------
* Next to eq. 64 the text reads ``gamma = r/r_c <= 0.9``. ``D`` (eq. 66) is a constant,
  so ``gamma`` cannot depend on ``r``: it is ``gamma = r_c / H``, the contact radius over
  the layer thickness. Re-deriving eq. 66 (see :func:`jaffar_thick_layer_contact`) gives
  exactly this; it reproduces the paper's 4.56 mm. ``gamma <= 0.9`` is the validity range;
  for ``nu = 1/2`` the truncated ``D(gamma)`` is stationary at ``gamma = 0.906``.
* Sec. 10.2 calls the thin-layer limit ``epsilon = r_c / H -> 0``; a thin layer is
  ``H / r_c -> 0`` (``epsilon = H / r_c``).
* Eq. 70 carries ``(1 + nu)``, but the lubrication derivation needs incompressibility;
  only ``nu = 1/2`` is meaningful (``48 / (1 + nu) = 32``, i.e. ``96 P R H^3 / (pi E)``).
* Eqs. 67-68 are right as printed: ``L(w) -> 1`` as ``w -> inf``, ``1 - L`` decays like
  ``(4 w^2 + 4 w + kappa^2 + 1) exp(-2 w) / kappa``; ``b_1 < 0 < b_2``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq

__all__ = [
    "HertzContact",
    "ThickLayerContact",
    "ThinLayerContact",
    "effective_modulus_from_shear",
    "hertz_contact",
    "hertz_contact_from_indentation",
    "bonded_layer_kernel",
    "bonded_layer_kernel_complement",
    "jaffar_b_coefficient",
    "jaffar_thick_layer_contact",
    "jaffar_thin_layer_contact",
    "layer_normal_compliance_static",
    "halfspace_normal_compliance_static",
    "thin_layer_normal_compliance_static",
]


# ---------------------------------------------------------------------------------------
# validation


def _number(name: str, value, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a real number in {unit}, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return value


def _positive(name: str, value, unit: str) -> float:
    v = _number(name, value, unit)
    if not v > 0:
        raise ValueError(f"{name} must be > 0 {unit}, got {value!r}")
    return v


def _poisson(value, allowed: str = "open") -> float:
    v = _number("poisson_ratio", value, "(-)")
    if allowed == "incompressible":
        if v != 0.5:
            raise ValueError(
                f"poisson_ratio must be 0.5 (the thin-layer solution assumes an "
                f"incompressible layer), got {value!r}"
            )
    elif not -1.0 < v <= 0.5:
        raise ValueError(f"poisson_ratio must be in (-1, 0.5], got {value!r}")
    return v


def _wavenumbers(k) -> np.ndarray:
    k = np.asarray(k, dtype=float)
    bad = ~np.isfinite(k) | (k < 0)
    if bad.any():
        raise ValueError(f"wavenumber must be >= 0 rad/m and finite, got {k[bad].flat[0]!r}")
    return k


def _disc(r, contact_radius: float, shape) -> np.ndarray:
    """``shape(rho)`` for ``rho = |r| / a < 1``, 0 outside; ``r`` in m."""
    rho2 = (np.abs(np.asarray(r, dtype=float)) / contact_radius) ** 2
    inside = rho2 < 1.0
    return np.where(inside, shape(np.where(inside, 1.0 - rho2, 0.0)), 0.0)


# ---------------------------------------------------------------------------------------
# Hertz


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
    G = _positive("shear_modulus", shear_modulus, "Pa")
    nu = _poisson(poisson_ratio)
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

    def pressure(self, r):
        """Contact pressure ``p0 sqrt(1 - r^2/a^2)`` (Pa, compressive), 0 for ``|r| >= a``.

        ``r`` (m) is the distance from the axis (array_like; the sign is ignored).
        """
        return self.peak_pressure * _disc(r, self.contact_radius, np.sqrt)


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
    P = _positive("load", load, "N")
    R = _positive("radius", radius, "m")
    Es = _positive("effective_modulus", effective_modulus, "Pa")
    return _hertz(P, R, Es, (3.0 * P * R / (4.0 * Es)) ** (1.0 / 3.0))


def hertz_contact_from_indentation(indentation: float, radius: float, effective_modulus: float) -> HertzContact:
    """Inverse of :func:`hertz_contact`: ``P = (4/3) E* sqrt(R) d^(3/2)``, ``a = sqrt(R d)``.

    Parameters
    ----------
    indentation : float
        ``d`` (m), > 0.
    radius, effective_modulus : float
        As in :func:`hertz_contact` (m, Pa).
    """
    d = _positive("indentation", indentation, "m")
    R = _positive("radius", radius, "m")
    Es = _positive("effective_modulus", effective_modulus, "Pa")
    P = 4.0 / 3.0 * Es * math.sqrt(R) * d**1.5
    return _hertz(P, R, Es, math.sqrt(R * d))


# ---------------------------------------------------------------------------------------
# bonded layer kernel and Jaffar (2008), thick layer


def _sinh2_minus(w):
    """``sinh(2 w) - 2 w`` for ``0 <= w <= 1`` by its series (no cancellation)."""
    x = 2.0 * np.asarray(w, dtype=float)
    x2 = x * x
    term = x * x2 / 6.0
    acc = term
    for j in range(2, 14):  # x <= 2: the last term is below 1e-16 of the first
        term = term * x2 / ((2 * j) * (2 * j + 1))
        acc = acc + term
    return acc


def bonded_layer_kernel(w, poisson_ratio: float = 0.5):
    r"""Layer-to-half-space compliance ratio ``L(w)`` of eq. 68, ``w = k H``.

    .. math:: L(w) = \frac{2\kappa\sinh 2w - 4w}{2\kappa\cosh 2w + 4w^2 + \kappa^2 + 1},
              \qquad \kappa = 3 - 4\nu .

    The normal surface compliance of the bonded layer is ``(1 - nu) L(kH) / (G k)``, the
    half-space's ``(1 - nu) / (G k)`` times ``L``. ``L(0) = 0``, ``L -> 1`` as ``w -> inf``.
    Evaluated without overflow or cancellation (series below ``w = 1``, ``exp(-2w)`` above).

    Parameters
    ----------
    w : array_like
        Dimensionless wavenumber ``k H`` (-), >= 0.
    poisson_ratio : float
        ``nu`` (-), in (-1, 0.5].
    """
    kap = 3.0 - 4.0 * _poisson(poisson_ratio)
    w = _wavenumbers(w)
    small = w <= 1.0
    ws = np.where(small, w, 0.0)
    num_s = 2 * kap * _sinh2_minus(ws) + 4 * (kap - 1) * ws
    den_s = 2 * kap * np.cosh(2 * ws) + 4 * ws * ws + kap * kap + 1
    wl = np.where(small, 1.0, w)
    e2 = np.exp(-2 * wl)
    num_l = kap * (1 - e2 * e2) - 4 * wl * e2
    den_l = kap * (1 + e2 * e2) + (4 * wl * wl + kap * kap + 1) * e2
    return np.where(small, num_s / den_s, num_l / den_l)


def bonded_layer_kernel_complement(w, poisson_ratio: float = 0.5):
    """``1 - L(w)`` (eq. 67's integrand without ``w^(2m)``), evaluated from positive terms.

    ``1 - L = (2 kappa e^{-4w} + (4w^2 + 4w + kappa^2 + 1) e^{-2w})
    / (kappa (1 + e^{-4w}) + (4w^2 + kappa^2 + 1) e^{-2w})``; it is 1 at ``w = 0`` and
    decays like ``e^{-2w}``, so the ``b_m`` integrals converge.
    """
    kap = 3.0 - 4.0 * _poisson(poisson_ratio)
    w = _wavenumbers(w)
    e2 = np.exp(-2 * w)
    e4 = e2 * e2
    return (2 * kap * e4 + (4 * w * w + 4 * w + kap * kap + 1) * e2) / (
        kap * (1 + e4) + (4 * w * w + kap * kap + 1) * e2
    )


@lru_cache(maxsize=64)
def jaffar_b_coefficient(m: int, poisson_ratio: float = 0.5) -> float:
    """``b_m = (-1/4)^m int_0^inf (1 - L(w)) w^(2m) dw`` (eq. 67), by quadrature (cached).

    Parameters
    ----------
    m : int
        Order, >= 0 (eq. 66 uses 1 and 2).
    poisson_ratio : float
        ``nu`` (-), in (-1, 0.5].

    Returns
    -------
    float
        ``b_m`` (-). For ``nu = 1/2``: ``b_1 = -0.957769...``, ``b_2 = 1.749436...``.
    """
    if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or m < 0:
        raise ValueError(f"m must be an integer >= 0, got {m!r}")
    nu = _poisson(poisson_ratio)
    val, err = quad(
        lambda w: float(bonded_layer_kernel_complement(w, nu)) * w ** (2 * m),
        0.0, np.inf, epsabs=0.0, epsrel=1e-12, limit=200,
    )
    if not err <= 1e-9 * abs(val):
        raise RuntimeError(f"b_{m} quadrature did not converge: {val!r} +- {err!r}")
    return (-0.25) ** m * val


@dataclass(frozen=True)
class ThickLayerContact:
    """Jaffar (2008) thick-layer contact (eqs. 64-68), all SI.

    Attributes
    ----------
    load, radius, thickness, shear_modulus, poisson_ratio : float
        Inputs ``P`` (N), ``R`` (m), ``H`` (m), ``G`` (Pa), ``nu`` (-).
    contact_radius : float
        ``r_c`` (m), the root of eq. 65.
    gamma : float
        ``r_c / H`` (-); the expansion is meant for ``gamma <~ 0.9``.
    b1, b2 : float
        Eq. 67 coefficients (-).
    D : float
        Eq. 66 at ``gamma`` (-); ``3 pi`` for a half-space.
    peak_pressure : float
        ``3 P / (2 pi r_c^2)`` (Pa).
    """

    load: float
    radius: float
    thickness: float
    shear_modulus: float
    poisson_ratio: float
    contact_radius: float
    gamma: float
    b1: float
    b2: float
    D: float
    peak_pressure: float

    def pressure(self, r):
        """Eq. 64: ``3 P / (2 pi r_c^2) sqrt(1 - r^2/r_c^2)`` (Pa, compressive), 0 outside.

        ``r`` (m) is the distance from the axis (array_like).
        """
        return self.peak_pressure * _disc(r, self.contact_radius, np.sqrt)


def jaffar_thick_layer_contact(
    load: float, radius: float, thickness: float, shear_modulus: float, poisson_ratio: float = 0.5
) -> ThickLayerContact:
    r"""Contact radius on a thick bonded layer, Jaffar (2008) (paper eqs. 64-68).

    Jaffar, M.J. (2008), frictionless contact of a rigid sphere with an elastic layer on a
    rigid base; quoted by Zehil and Gavin (2013), sec. 10.1. The pressure keeps the Hertz
    shape (eq. 64) and the contact radius solves, with ``gamma = r_c / H``,

    .. math:: r_c^3 = \frac{P R D(\gamma) (1 - \nu)}{8 \pi G},\qquad
              D = 3\pi + 8\gamma^3 \left(b_1 + \tfrac{2}{5} b_2 \gamma^2\right).

    Derivation (re-done here). The layer's surface deflection is the half-space one with
    the kernel ``L(kH)`` inserted: ``w(r) = (1-nu)/G int p^(k) L(kH) J0(kr) dk`` with
    ``p^(k) = int p(s) J0(ks) s ds``. Write ``L = 1 - (1 - L)``; ``1 - L`` lives at
    ``k ~ 1/H << 1/r_c``, so expand ``p^`` (Hertz: ``p0 a^2 (1/3 - (ka)^2/30 + ...)``) and
    ``J0`` in ``k``. Matching the curvature at ``r = 0`` to the sphere's ``-1/R`` gives
    ``D`` above, term by term, with ``b_m`` of eq. 67: the ``gamma^3`` and ``gamma^5``
    terms are the first two corrections, so ``D`` is truncated at ``O(gamma^7)``.

    Solution. ``gamma^3 H^3 = c' D(gamma)`` is the polynomial
    ``(1 - 8 b1 c) gamma^3 - (16/5) b2 c gamma^5 - 3 pi c = 0``, ``c = (1-nu) P R /
    (8 pi G H^3)``; with ``b1 < 0 < b2`` it rises from ``-3 pi c`` to one maximum, and the
    physical root is the smaller one (it tends to Hertz as ``H -> inf``). If the maximum
    is below zero the truncated expansion has no root (layer too thin for this load).

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
        ``nu`` (-), in (-1, 0.5]; default incompressible.

    Returns
    -------
    ThickLayerContact

    Raises
    ------
    ValueError
        Invalid inputs, or no root (use :func:`jaffar_thin_layer_contact` for thin layers).

    Notes
    -----
    Valid for a thick layer, ``gamma = r_c / H <~ 0.9`` (the paper's "gamma = r/r_c <= 0.9"
    is a transcription slip). With ``R = 2 cm, H = 5 mm, P = 100 N, G = 3 MPa, nu = 0.5``
    it gives ``r_c = 4.559 mm`` (``gamma = 0.912``), the paper's 4.56 mm.
    """
    P = _positive("load", load, "N")
    R = _positive("radius", radius, "m")
    H = _positive("thickness", thickness, "m")
    G = _positive("shear_modulus", shear_modulus, "Pa")
    nu = _poisson(poisson_ratio)
    b1, b2 = jaffar_b_coefficient(1, nu), jaffar_b_coefficient(2, nu)
    if not b1 < 0 < b2:  # holds for every nu in (-1, 0.5]; guards the bracket below
        raise RuntimeError(f"unexpected signs b1 = {b1}, b2 = {b2}")
    c = (1 - nu) * P * R / (8 * math.pi * G * H**3)
    A, B = 1 - 8 * b1 * c, 3.2 * b2 * c

    def residual(g):
        return A * g**3 - B * g**5 - 3 * math.pi * c

    g_max = math.sqrt(3 * A / (5 * B))
    if residual(g_max) < 0:
        raise ValueError(
            f"no thick-layer solution: load {P!r} N is too large for thickness {H!r} m "
            f"(the truncated D of eq. 66 has no root); use jaffar_thin_layer_contact"
        )
    gamma = brentq(residual, 0.0, g_max, xtol=1e-15, rtol=1e-14)
    D = 3 * math.pi + 8 * gamma**3 * (b1 + 0.4 * b2 * gamma**2)
    rc = gamma * H
    return ThickLayerContact(
        load=P, radius=R, thickness=H, shear_modulus=G, poisson_ratio=nu,
        contact_radius=rc, gamma=gamma, b1=b1, b2=b2, D=D,
        peak_pressure=3 * P / (2 * math.pi * rc * rc),
    )


# ---------------------------------------------------------------------------------------
# Jaffar (1997), thin incompressible layer


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

    def pressure(self, r):
        """Eq. 69: ``3 P / (pi r_c^2) (1 - r^2/r_c^2)^2`` (Pa, compressive), 0 outside.

        ``r`` (m) is the distance from the axis (array_like).
        """
        return self.peak_pressure * _disc(r, self.contact_radius, np.square)


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
    :func:`layer_normal_compliance_static`). Inside the contact ``u_z = d - r^2/(2R)``, and
    a smooth edge needs ``p = dp/dr = 0`` at ``r_c``. The solution is
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
    P = _positive("load", load, "N")
    R = _positive("radius", radius, "m")
    H = _positive("thickness", thickness, "m")
    G = _positive("shear_modulus", shear_modulus, "Pa")
    nu = _poisson(poisson_ratio, "incompressible")
    rc = (48 * P * R * H**3 / (math.pi * G * (1 + nu))) ** (1 / 6)
    p0 = 3 * P / (math.pi * rc * rc)
    return ThinLayerContact(
        load=P, radius=R, thickness=H, shear_modulus=G, contact_radius=rc,
        peak_pressure=p0, indentation=8 * H**3 * p0 / (3 * G * rc * rc),
        thickness_ratio=H / rc,
    )


# ---------------------------------------------------------------------------------------
# Fourier-space normal compliance (static, incompressible, bonded)


def layer_normal_compliance_static(wavenumber, thickness: float, shear_modulus: float):
    r"""Normal surface compliance ``w / sigma_z`` (m/Pa) of an incompressible bonded layer.

    For a surface traction ``sigma_z exp(i k x)`` (positive in tension, no shear) on a
    layer of thickness ``H`` bonded to a rigid base, the surface moves by
    ``w exp(i k x)``, ``w`` positive upwards (away from the base):

    .. math:: \frac{w}{\sigma_z} = \frac{1}{2 G k}\,
              \frac{\sinh 2kH - 2kH}{\cosh 2kH + 2(kH)^2 + 1} = \frac{L(kH)}{2 G k}

    (``L`` of eq. 68 at ``nu = 1/2``). It is positive: pulling lifts the surface, and a
    compressive pressure ``p = -sigma_z`` pushes it down by ``p L / (2 G k)``. Limits:
    ``k^2 H^3 / (3 G)`` for ``kH -> 0`` (lubrication, see
    :func:`jaffar_thin_layer_contact`) and ``1 / (2 G k)`` for ``kH -> inf`` (half-space,
    ``(1 - nu) / (G k)``). At ``k = 0`` it is exactly 0: a bonded incompressible layer does
    not move under uniform pressure. Evaluated through :func:`bonded_layer_kernel` (series
    below ``kH = 1``, decaying exponentials above).

    Parameters
    ----------
    wavenumber : array_like
        ``k = sqrt(nu_x^2 + nu_y^2)`` (rad/m), >= 0.
    thickness : float
        ``H`` (m), > 0.
    shear_modulus : float
        ``G`` (Pa), > 0.

    Returns
    -------
    ndarray
        ``w / sigma_z`` (m/Pa), same shape as ``wavenumber``.
    """
    H = _positive("thickness", thickness, "m")
    G = _positive("shear_modulus", shear_modulus, "Pa")
    t = _wavenumbers(wavenumber) * H
    tt = np.where(t > 0, t, 1.0)
    return np.where(t > 0, H / (2 * G) * bonded_layer_kernel(t) / tt, 0.0)


def halfspace_normal_compliance_static(wavenumber, shear_modulus: float):
    """``w / sigma_z = 1 / (2 G k)`` (m/Pa) of an incompressible half-space (``inf`` at
    ``k = 0``); conventions of :func:`layer_normal_compliance_static`. ``k`` in rad/m,
    ``G`` in Pa."""
    G = _positive("shear_modulus", shear_modulus, "Pa")
    k = _wavenumbers(wavenumber)
    with np.errstate(divide="ignore"):
        return 1.0 / (2 * G * k)


def thin_layer_normal_compliance_static(wavenumber, thickness: float, shear_modulus: float):
    """``w / sigma_z = k^2 H^3 / (3 G)`` (m/Pa), the lubrication limit ``kH -> 0`` of
    :func:`layer_normal_compliance_static`. ``k`` in rad/m, ``H`` in m, ``G`` in Pa."""
    H = _positive("thickness", thickness, "m")
    G = _positive("shear_modulus", shear_modulus, "Pa")
    k = _wavenumbers(wavenumber)
    return k * k * H**3 / (3 * G)


# ---------------------------------------------------------------------------------------
# Plane strain: 2D Hertz and Hunter (1961), a rigid cylinder rolling on a viscoelastic
# half-space. Derivation: docs/derivations.md, section "Plane strain: line contact".


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

    def pressure(self, x):
        """``p0 sqrt(1 - x^2 / b^2)`` (Pa, compressive) at ``x`` (m), 0 for ``|x| >= b``."""
        return self.peak_pressure * _disc(x, self.half_width, np.sqrt)


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
    """
    P = _positive("load", load, "N/m")
    R = _positive("radius", radius, "m")
    G = _positive("shear_modulus", shear_modulus, "Pa")
    b = math.sqrt(P * R / (math.pi * G))
    return HertzLineContact(P, R, G, b, 2 * P / (math.pi * b))


@dataclass(frozen=True)
class HunterRollingContact:
    """Steady rolling of a rigid cylinder on an incompressible three-parameter (standard
    linear solid) viscoelastic half-space, frictionless, per unit length (Hunter 1961).

    Inputs as :func:`hunter_rolling_contact`; lengths in m, measured in the frame of the
    cylinder with ``x > 0`` ahead (the direction of motion).

    Attributes
    ----------
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
        return self.centre - self.half_width

    @property
    def leading_edge(self) -> float:
        return self.centre + self.half_width

    @property
    def pressure_centroid_x(self) -> float:
        b = self.coefficients
        second = b[1] if b.size > 1 else 0.0
        return self.centre + self.half_width**2 * math.pi * second / (4 * self.load)

    @property
    def rolling_resistance(self) -> float:
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

    def _series(self, theta):
        """``sum_n beta_n sin(n theta) = Im sum_n beta_n exp(i n theta)``, by Horner."""
        z = np.exp(1j * np.asarray(theta, dtype=float))
        return np.polynomial.polynomial.polyval(z, np.concatenate([[0.0], self.coefficients])).imag

    def pressure(self, x):
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
    from scipy.special import ive

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
    P = _positive("load", load, "N/m")
    R = _positive("radius", radius, "m")
    G0 = _positive("G0", G0, "Pa")
    tau = _positive("tau", tau, "s")
    f = _number("f", f, "(dimensionless)")
    if f < 0:
        raise ValueError(f"f must be >= 0, got {f!r}")
    V = _number("speed", speed, "m/s")
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


__all__ += ["HertzLineContact", "hertz_line_contact", "HunterRollingContact", "hunter_rolling_contact"]
