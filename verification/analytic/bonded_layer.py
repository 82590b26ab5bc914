r"""The normal surface compliance of an elastic layer bonded to a rigid base, in Fourier
space: the kernel ``L(kH)`` of Zehil and Gavin (2013), eq. 68, and the static compliance
of an incompressible layer with its two asymptotes.

* :func:`bonded_layer_kernel`, :func:`bonded_layer_kernel_complement`: ``L(w)`` and
  ``1 - L(w)``, ``w = k H`` (-), any Poisson's ratio; the thick-layer reference
  (:mod:`.jaffar_thick`) integrates ``1 - L``.
* :func:`layer_normal_compliance_static`: ``w / sigma_z = L(kH) / (2 G k)`` (m/Pa) at
  ``nu = 1/2``, the quantity the boundary-element kernel tabulates;
  :func:`halfspace_normal_compliance_static` (``kH -> inf``) and
  :func:`thin_layer_normal_compliance_static` (``kH -> 0``, lubrication) are its limits.

SI units: wavenumbers in rad/m, lengths in m, moduli in Pa, compliances in m/Pa.
``sigma_z`` is positive in tension and ``w`` positive away from the base.
"""

from __future__ import annotations

import numpy as np

from ._checks import poisson, positive, wavenumbers

__all__ = [
    "bonded_layer_kernel",
    "bonded_layer_kernel_complement",
    "halfspace_normal_compliance_static",
    "layer_normal_compliance_static",
    "thin_layer_normal_compliance_static",
]


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


def bonded_layer_kernel(w, poisson_ratio: float = 0.5) -> np.ndarray:
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

    Returns
    -------
    ndarray
        ``L(w)`` (-), in [0, 1), same shape as ``w``.
    """
    kap = 3.0 - 4.0 * poisson(poisson_ratio)
    w = wavenumbers(w)
    small = w <= 1.0
    ws = np.where(small, w, 0.0)
    num_s = 2 * kap * _sinh2_minus(ws) + 4 * (kap - 1) * ws
    den_s = 2 * kap * np.cosh(2 * ws) + 4 * ws * ws + kap * kap + 1
    wl = np.where(small, 1.0, w)
    e2 = np.exp(-2 * wl)
    num_l = kap * (1 - e2 * e2) - 4 * wl * e2
    den_l = kap * (1 + e2 * e2) + (4 * wl * wl + kap * kap + 1) * e2
    return np.where(small, num_s / den_s, num_l / den_l)


def bonded_layer_kernel_complement(w, poisson_ratio: float = 0.5) -> np.ndarray:
    """``1 - L(w)`` (eq. 67's integrand without ``w^(2m)``), evaluated from positive terms.

    ``1 - L = (2 kappa e^{-4w} + (4w^2 + 4w + kappa^2 + 1) e^{-2w})
    / (kappa (1 + e^{-4w}) + (4w^2 + kappa^2 + 1) e^{-2w})``; it is 1 at ``w = 0`` and
    decays like ``e^{-2w}``, so the ``b_m`` integrals converge.

    Parameters
    ----------
    w : array_like
        Dimensionless wavenumber ``k H`` (-), >= 0.
    poisson_ratio : float
        ``nu`` (-), in (-1, 0.5].

    Returns
    -------
    ndarray
        ``1 - L(w)`` (-), in (0, 1], same shape as ``w``.
    """
    kap = 3.0 - 4.0 * poisson(poisson_ratio)
    w = wavenumbers(w)
    e2 = np.exp(-2 * w)
    e4 = e2 * e2
    return (2 * kap * e4 + (4 * w * w + 4 * w + kap * kap + 1) * e2) / (
        kap * (1 + e4) + (4 * w * w + kap * kap + 1) * e2
    )


def layer_normal_compliance_static(wavenumber, thickness: float, shear_modulus: float) -> np.ndarray:
    r"""Normal surface compliance ``w / sigma_z`` (m/Pa) of an incompressible bonded layer.

    For a surface traction ``sigma_z exp(i k x)`` (positive in tension, no shear) on a
    layer of thickness ``H`` bonded to a rigid base, the surface moves by
    ``w exp(i k x)``, ``w`` positive upwards (away from the base):

    .. math:: \frac{w}{\sigma_z} = \frac{1}{2 G k}\,
              \frac{\sinh 2kH - 2kH}{\cosh 2kH + 2(kH)^2 + 1} = \frac{L(kH)}{2 G k}

    (``L`` of eq. 68 at ``nu = 1/2``). It is positive: pulling lifts the surface, and a
    compressive pressure ``p = -sigma_z`` pushes it down by ``p L / (2 G k)``. Limits:
    ``k^2 H^3 / (3 G)`` for ``kH -> 0`` (lubrication, see
    :func:`.jaffar_thin.jaffar_thin_layer_contact`) and ``1 / (2 G k)`` for ``kH -> inf``
    (half-space, ``(1 - nu) / (G k)``). At ``k = 0`` it is exactly 0: a bonded incompressible layer does
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
    H = positive("thickness", thickness, "m")
    G = positive("shear_modulus", shear_modulus, "Pa")
    t = wavenumbers(wavenumber) * H
    tt = np.where(t > 0, t, 1.0)
    return np.where(t > 0, H / (2 * G) * bonded_layer_kernel(t) / tt, 0.0)


def halfspace_normal_compliance_static(wavenumber, shear_modulus: float) -> np.ndarray:
    """``w / sigma_z = 1 / (2 G k)`` (m/Pa) of an incompressible half-space (``inf`` at
    ``k = 0``); conventions of :func:`layer_normal_compliance_static`. ``k`` in rad/m,
    ``G`` in Pa."""
    G = positive("shear_modulus", shear_modulus, "Pa")
    k = wavenumbers(wavenumber)
    with np.errstate(divide="ignore"):
        return 1.0 / (2 * G * k)


def thin_layer_normal_compliance_static(wavenumber, thickness: float, shear_modulus: float) -> np.ndarray:
    """``w / sigma_z = k^2 H^3 / (3 G)`` (m/Pa), the lubrication limit ``kH -> 0`` of
    :func:`layer_normal_compliance_static`. ``k`` in rad/m, ``H`` in m, ``G`` in Pa."""
    H = positive("thickness", thickness, "m")
    G = positive("shear_modulus", shear_modulus, "Pa")
    k = wavenumbers(wavenumber)
    return k * k * H**3 / (3 * G)
