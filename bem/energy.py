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
of eqs. 56-59; its series is not truncated, while the displacement's is the kernels'
``u_mn = e_m e_n C_mn t_mn`` for ``|m| <= N_tx, |n| <= N_ty`` (``e`` the
:func:`bem.spectral.end_weights`: 1/2 on end modes that alias onto the lattice's Nyquist
frequency), so Parseval keeps the same modes with the same weights ``e_m e_n``, once.
This is independent of the contact solver's nodal collocation and of the upwind
derivative: it integrates the layer's own continuous fields.

Cost: with normal forces alone only ``C_ww`` is needed (``t^H C t = |t_z|^2 C_ww``), and
it comes from the outer-grid normal compliance, fast for the many half-space modes. The
isotropic layer is symmetric under ``y -> -y``, so
``C(nu_x, -nu_y) = D C(nu_x, nu_y) D`` with ``D = diag(1, 1, -1)`` (``v`` and ``tau_yz``
change sign; checked to round-off against the closed form); the compliance is evaluated
for ``n >= 0`` only and serves both halves.
"""

from __future__ import annotations

import numpy as np

from . import fft as sfft

from .grid import Grid
from .layer import Layer, normal_compliance_outer, surface_compliance
from .spectral import end_weights

__all__ = ["dissipates", "viscous_dissipation", "dissipation_from_tables", "power_key", "layer_power"]

_CHUNK = 64


def power_key(block: str) -> str:
    """The key of ``block``'s power table in a kernel dict (:func:`bem.problem.compute_kernels`)."""
    return f"{block}:power"


def dissipates(grid: Grid, layer: Layer, speed: float) -> bool:
    """Whether the layer can absorb power at ``speed`` (m/s): moving, with a loss modulus
    at some mode's frequency ``omega_m = -nu_x V`` (``0 < m <= N_tx``)."""
    if speed == 0:
        return False
    nu_x = 2 * np.pi * np.arange(1, grid.truncation_x + 1) / grid.period_x
    return bool(np.asarray(layer.material.modulus(-nu_x * speed), dtype=complex).imag.any())


def viscous_dissipation(grid: Grid, layer: Layer, speed: float, force_z: np.ndarray,
                        force_x: np.ndarray, force_y: np.ndarray) -> float:
    """Power (W) dissipated in the layer by the nodal surface forces, in steady motion.

    Parameters
    ----------
    grid : Grid
        Nodes and Fourier truncation (the sum runs over ``|m| <= N_tx``, ``|n| <= N_ty``,
        the end modes with the kernels' :func:`bem.spectral.end_weights`).
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
    if not dissipates(grid, layer, speed):
        return 0.0  # no loss at any mode felt: C_mn is Hermitian and every term vanishes
    rho_V2 = layer.inertia(speed)
    wx = np.sinc(m * g.spacing_x / g.period_x) / g.period_x
    wy = np.sinc(n * g.spacing_y / g.period_y) / g.period_y
    e_pos = np.exp(-1j * np.outer(g.y, nu_y)) * wy  # (K_y, n), n >= 0
    e_neg = np.exp(1j * np.outer(g.y, nu_y[1:])) * wy[1:]  # (K_y, n), -n < 0
    # nu_x times the end weights of (m, +-n): the displacement's truncation, once
    nu_e = nu_x[:, None] * np.outer(end_weights(g.truncation_x, g.spacing_x, g.period_x)[1:],
                                    end_weights(g.truncation_y, g.spacing_y, g.period_y))
    if not (F[1].any() or F[2].any()):
        return _normal_dissipation(g, layer, speed, F[0], nu_x, nu_y, nu_e, G, rho_V2, wx, e_pos, e_neg)
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
        total += float((nu_e[sl] * quad.imag).sum() + (nu_e[sl, 1:] * quad_n.imag).sum())
    return 2 * speed * g.period_x * g.period_y * total


def _normal_dissipation(g: Grid, layer: Layer, speed: float, Fz, nu_x, nu_y, nu_e, G, rho_V2, wx, e_pos,
                        e_neg) -> float:
    """:func:`viscous_dissipation` of normal forces alone: ``t^H C t = |t_z|^2 C_ww``, and
    ``C_ww`` (even in ``nu_y``) from the fast outer-grid normal compliance; ``nu_e`` is
    ``nu_x`` times the end weights, ``(m, n >= 0)``."""
    ex = np.exp(-1j * np.outer(nu_x, g.x)) * wx[:, None]  # (m, K_x)
    rows = ex @ Fz.T  # (m, K_y)
    power = np.abs(rows @ e_pos) ** 2  # (m, n >= 0)
    power[:, 1:] += np.abs(rows @ e_neg) ** 2  # the modes (m, -n)
    C_ww = normal_compliance_outer(nu_x, nu_y, G, rho_V2, layer.thickness)
    return 2 * speed * g.period_x * g.period_y * float(np.sum(nu_e * C_ww.imag * power))


def dissipation_from_tables(tables: dict, speed: float, force_z: np.ndarray, force_x: np.ndarray,
                            force_y: np.ndarray) -> float:
    """:func:`viscous_dissipation` (W) by FFTs, from the power tables of
    :func:`bem.spectral.kernels_with_power`: ``-V sum_PQ F_P . (W_PQ * F_Q)``, the same
    truncated mode sum to rounding, at the cost of a few transforms of the nodal grid.

    ``tables``: block name -> table; a block missing from it must meet a zero force
    (normal forces alone need ``"ww"`` only). Forces as in :func:`viscous_dissipation`.
    """
    F = {"w": np.asarray(force_z, float), "u": np.asarray(force_x, float), "v": np.asarray(force_y, float)}
    need = tuple(2 * k - 1 for k in F["w"].shape)
    bad = {b: np.shape(t) for b, t in tables.items() if np.shape(t) != need}
    if bad:
        raise ValueError(f"power tables of shape {bad} cannot serve forces on {F['w'].shape[1]} x "
                         f"{F['w'].shape[0]} nodes (a table of that grid has shape {need})")
    ky, kx = F["w"].shape
    shape = [sfft.next_fast_len(2 * k - 1 + k - 1, real=True) for k in (ky, kx)]
    spectra = {c: sfft.rfft2(f, shape) for c, f in F.items() if f.any()}
    total = 0.0
    for p in spectra:  # u_p = sum_q W_pq * F_q: one inverse transform per component
        acc = 0
        for q in spectra:
            if p + q not in tables:
                raise ValueError(f"the power table {p + q} is needed for these forces but was not computed")
            # contiguous: a table cut from a wider one (a view) gives the bits of its copy
            acc = acc + sfft.rfft2(np.ascontiguousarray(tables[p + q]), shape) * spectra[q]
        u = sfft.irfft2(acc, shape)[ky - 1: 2 * ky - 1, kx - 1: 2 * kx - 1]  # the valid part: offsets of the grid
        total += float(np.sum(F[p] * u))
    return -speed * total


def layer_power(grid: Grid, layer: Layer, speed: float, kernels: dict | None, force_z: np.ndarray,
                force_x: np.ndarray, force_y: np.ndarray) -> float:
    """The power (W) the layer absorbs: by FFTs when ``kernels`` carry the power tables the
    forces need (:func:`bem.problem.compute_kernels` with ``power``), by the mode sum of
    :func:`viscous_dissipation` otherwise. The two agree to rounding."""
    F = (force_z, force_x, force_y)
    need = [p + q for p in "wuv" for q in "wuv" if np.any(F["wuv".index(p)]) and np.any(F["wuv".index(q)])]
    if kernels and need and all(power_key(b) in kernels for b in need):
        return dissipation_from_tables({b: kernels[power_key(b)] for b in need}, speed, *F)
    return viscous_dissipation(grid, layer, speed, *F)
