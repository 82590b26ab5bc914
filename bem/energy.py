"""Power dissipated in the layer, computed in Fourier space from its loss modulus.

In steady state the layer's stored energy does not change, so the power it dissipates is
the power of the surface tractions on the surface velocity seen by the material,
``Du/Dt = -V d/dx`` (eq. 6):

    P_visc = -V  integral  t . du/dx  dA                                  (W)

over one period, with ``t = (sigma_z, tau_xz, tau_yz)`` the traction on the layer and
``u = (w, u, v)`` its surface displacement. With the Fourier series of both fields
(``u_mn = C_mn t_mn``, eq. 50) and Parseval's identity,

    P_visc = -V L_x L_y sum_mn i nu_x t_mn^H C_mn t_mn
           = 2 V L_x L_y sum_{m > 0, n} nu_x Im(t_mn^H C_mn t_mn),

because the terms ``(m, n)`` and ``(-m, -n)`` are complex conjugates
(``C(-nu) = conj C(nu)`` for a real relaxation function). Only the anti-Hermitian part
of ``C_mn``, the loss, contributes: an elastic layer (with or without inertia) dissipates
nothing, and :func:`viscous_dissipation` returns an exact 0 without summing when the
modulus is real at every frequency the modes feel (or the speed is 0). The traction of a nodal force spread on its patch (eq. 52) has the coefficients
of eqs. 56-59. This is independent of the contact solver's nodal collocation and of the
upwind derivative: it integrates the layer's own continuous fields.

Cost: with normal forces alone only ``C_ww`` is needed (``t^H C t = |t_z|^2 C_ww``), and
it comes from the outer-grid normal compliance, fast for the many half-space modes. The
isotropic layer is symmetric under ``y -> -y``, so
``C(nu_x, -nu_y) = D C(nu_x, nu_y) D`` with ``D = diag(1, 1, -1)`` (``v`` and ``tau_yz``
change sign; checked to round-off against the closed form); the compliance is evaluated
for ``n >= 0`` only and serves both halves.
"""

from __future__ import annotations

import numpy as np

from .grid import Grid
from .layer import Layer, normal_compliance_outer, surface_compliance

__all__ = ["viscous_dissipation"]

_CHUNK = 64


def viscous_dissipation(grid: Grid, layer: Layer, speed: float, force_z: np.ndarray,
                        force_x: np.ndarray, force_y: np.ndarray) -> float:
    """Power (W) dissipated in the layer by the nodal surface forces, in steady motion.

    Parameters
    ----------
    grid : Grid
        Nodes and Fourier truncation (the sum runs over ``|m| <= N_tx``, ``|n| <= N_ty``).
    layer : Layer
    speed : float
        ``V`` (m/s).
    force_z, force_x, force_y : ndarray, shape ``(K_y, K_x)``
        Nodal forces on the layer (N): ``force_z`` positive in tension (upwards, the
        paper's ``F_W``), ``force_x, force_y`` along ``+x, +y`` (``F_U, F_V``).
    """
    g = grid
    F = [np.asarray(f, float).reshape(g.shape) for f in (force_z, force_x, force_y)]
    m = np.arange(1, g.truncation_x + 1)
    n = np.arange(0, g.truncation_y + 1)
    nu_x = 2 * np.pi * m / g.period_x
    nu_y = 2 * np.pi * n / g.period_y
    G = np.asarray(layer.material.modulus(-nu_x * speed), dtype=complex)
    if speed == 0 or not G.imag.any():
        return 0.0  # no loss at any mode felt: C_mn is Hermitian and every term vanishes
    rho_V2 = layer.inertia(speed)
    wx = np.sinc(m * g.spacing_x / g.period_x) / g.period_x
    wy = np.sinc(n * g.spacing_y / g.period_y) / g.period_y
    e_pos = np.exp(-1j * np.outer(g.y, nu_y)) * wy  # (K_y, n), n >= 0
    e_neg = np.exp(1j * np.outer(g.y, nu_y[1:])) * wy[1:]  # (K_y, n), -n < 0
    if not (F[1].any() or F[2].any()):
        return _normal_dissipation(g, layer, speed, F[0], nu_x, nu_y, G, rho_V2, wx, e_pos, e_neg)
    flip = np.array([1.0, 1.0, -1.0])  # D = diag(1, 1, -1)
    total = 0.0
    for s in range(0, m.size, _CHUNK):
        sl = slice(s, s + _CHUNK)
        ex = np.exp(-1j * np.outer(nu_x[sl], g.x)) * wx[sl, None]  # (m, K_x)
        rows = [ex @ f.T for f in F]
        t = np.stack([r @ e_pos for r in rows], axis=-1)  # (m, n >= 0, 3)
        tn = np.stack([r @ e_neg for r in rows], axis=-1) * flip  # D t at (m, -n), n >= 1
        C = surface_compliance(nu_x[sl, None], nu_y[None, :], G[sl, None], rho_V2, layer.thickness)
        quad = np.einsum("mni,mnij,mnj->mn", t.conj(), C, t)
        quad_n = np.einsum("mni,mnij,mnj->mn", tn.conj(), C[:, 1:], tn)
        total += float((nu_x[sl, None] * quad.imag).sum() + (nu_x[sl, None] * quad_n.imag).sum())
    return 2 * speed * g.period_x * g.period_y * total


def _normal_dissipation(g: Grid, layer: Layer, speed: float, Fz, nu_x, nu_y, G, rho_V2, wx, e_pos, e_neg) -> float:
    """:func:`viscous_dissipation` of normal forces alone: ``t^H C t = |t_z|^2 C_ww``, and
    ``C_ww`` (even in ``nu_y``) from the fast outer-grid normal compliance."""
    ex = np.exp(-1j * np.outer(nu_x, g.x)) * wx[:, None]  # (m, K_x)
    rows = ex @ Fz.T  # (m, K_y)
    power = np.abs(rows @ e_pos) ** 2  # (m, n >= 0)
    power[:, 1:] += np.abs(rows @ e_neg) ** 2  # the modes (m, -n)
    C_ww = normal_compliance_outer(nu_x, nu_y, G, rho_V2, layer.thickness)
    return 2 * speed * g.period_x * g.period_y * float(np.sum(nu_x[:, None] * C_ww.imag * power))
