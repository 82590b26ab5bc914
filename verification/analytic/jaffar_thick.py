r"""Frictionless contact of a rigid sphere with a thick elastic layer bonded to a rigid
base: Jaffar (2008) as quoted by Zehil and Gavin (2013), sec. 10.1, eqs. 64-68.

The pressure keeps Hertz's shape; the contact radius ``r_c`` solves eq. 65 with the
correction ``D(gamma)`` of eq. 66, whose coefficients ``b_m`` (eq. 67) are integrals of
the kernel ``1 - L`` of :mod:`.bonded_layer`. Re-derived in
:func:`jaffar_thick_layer_contact`.

Transcription notes (checked in ``tests/verification/analytic/test_jaffar_thick.py``):

* Next to eq. 64 the text reads ``gamma = r/r_c <= 0.9``. ``D`` (eq. 66) is a constant,
  so ``gamma`` cannot depend on ``r``: it is ``gamma = r_c / H``, the contact radius over
  the layer thickness. Re-deriving eq. 66 gives exactly this, and it reproduces the
  paper's 4.56 mm. ``gamma <= 0.9`` is the validity range; for ``nu = 1/2`` the truncated
  ``D(gamma)`` is stationary at ``gamma = 0.906``.
* Eqs. 67-68 are right as printed: ``L(w) -> 1`` as ``w -> inf``, ``1 - L`` decays like
  ``(4 w^2 + 4 w + kappa^2 + 1) exp(-2 w) / kappa``; ``b_1 < 0 < b_2``.
* Eq. 64 prints the pressure as ``sigma_z``, although the paper's convention elsewhere is
  ``sigma_z`` positive in tension; the pressure here is compressive and positive
  (``p = -sigma_z``).

SI units: N, m, Pa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq

from ._checks import disc, poisson, positive
from .bonded_layer import bonded_layer_kernel_complement

__all__ = ["ThickLayerContact", "jaffar_b_coefficient", "jaffar_thick_layer_contact"]


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
    nu = poisson(poisson_ratio)
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

    def pressure(self, r) -> np.ndarray:
        """Eq. 64: ``3 P / (2 pi r_c^2) sqrt(1 - r^2/r_c^2)`` (Pa, compressive), 0 outside.

        ``r`` (m) is the distance from the axis (array_like).
        """
        return self.peak_pressure * disc(r, self.contact_radius, np.sqrt)


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
        Invalid inputs, or no root (use :func:`.jaffar_thin.jaffar_thin_layer_contact` for
        thin layers).

    Notes
    -----
    Valid for a thick layer, ``gamma = r_c / H <~ 0.9`` (the paper's "gamma = r/r_c <= 0.9"
    is a transcription slip). With ``R = 2 cm, H = 5 mm, P = 100 N, G = 3 MPa, nu = 0.5``
    it gives ``r_c = 4.559 mm`` (``gamma = 0.912``), the paper's 4.56 mm.
    """
    P = positive("load", load, "N")
    R = positive("radius", radius, "m")
    H = positive("thickness", thickness, "m")
    G = positive("shear_modulus", shear_modulus, "Pa")
    nu = poisson(poisson_ratio)
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
