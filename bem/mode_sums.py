"""Sums over Fourier modes to node offsets: the transforms the kernel tables are made of.

``h(j) = sum_n c(n) exp(2 pi i ratio n j)`` over the truncated modes ``n`` for the node
offsets ``j``, with ``ratio = a / L`` (spacing over period): by Bluestein's chirp-z
identity (:func:`chirp_sum`, any ``a / L``, ``O(N log N)``) or, for a few offsets, by
matrix products with trigonometric tables (:func:`over_n`, :func:`over_m`), phases
reduced modulo one turn. :mod:`bem.spectral` and :mod:`bem.plane` build their kernels
with them.
"""

from __future__ import annotations

import functools

import numpy as np
from . import fft as sfft

__all__ = ["chirp_sum", "turns", "over_n", "over_m"]


def chirp_sum(c: np.ndarray, ratio: float, j0: int, count: int) -> np.ndarray:
    """``sum_n c[..., n] exp(2 pi i ratio n j)`` for ``j = j0 .. j0 + count - 1``.

    Bluestein's identity ``n j = (n^2 + j^2 - (j - n)^2) / 2`` turns the sum into a
    convolution done by FFT; phases are reduced modulo one turn before use.
    """
    N = c.shape[-1]
    n = np.arange(N, dtype=float)
    t = np.arange(count, dtype=float)
    lag = np.arange(-(N - 1), count, dtype=float)

    def turn(x):
        return np.exp(2j * np.pi * np.mod(ratio * x, 1.0))

    size = sfft.next_fast_len(N + count - 1)
    a = c * turn(n * j0 + n * n / 2)
    b = np.zeros(size, dtype=complex)
    chirp = turn(-lag * lag / 2)
    b[:count] = chirp[N - 1 :]
    b[size - (N - 1) :] = chirp[: N - 1]
    conv = sfft.ifft(sfft.fft(a, size, axis=-1) * sfft.fft(b), axis=-1, workers=-1)
    return conv[..., :count] * turn(t * t / 2)


def turns(ratio: float, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Phase ``2 pi ratio a b`` reduced modulo a turn (``a b`` exact integers)."""
    return 2 * np.pi * np.mod(ratio * np.outer(a, b).astype(float), 1.0)


def over_n(r: np.ndarray, odd: bool, ratio: float, count: int, chirp: bool,
            weight_n: np.ndarray | None = None) -> np.ndarray:
    """``h(m, dy) = sum_{|n| <= N_t} g(m, n) exp(2 pi i ratio n dy)`` for ``|dy| < count``
    (complex, ``(rows, 2 count - 1)``) of ``g(m, n) = r(m, n) w(n)`` for ``n >= 0`` (``r``
    real or complex, ``w`` the ``weight_n``, 1 without) and ``g(m, -n) = -g(m, n)``
    (``odd``) or ``+g(m, n)``."""
    if chirp:
        r = r if weight_n is None else r * weight_n
        coef = 2 * r.astype(complex)
        coef[:, 0] = 0 if odd else r[:, 0]
        S = chirp_sum(coef, ratio, -(count - 1), 2 * count - 1)
        return 0.5 * (S - S[:, ::-1]) if odd else 0.5 * (S + S[:, ::-1])
    T = _trig_table(ratio, r.shape[1], count, odd)
    if weight_n is not None:
        T = weight_n[:, None] * T
    h = (r.real @ T + 1j * (r.imag @ T)) if np.iscomplexobj(r) else (r @ T).astype(complex)
    if odd:
        h = 1j * h
        return np.concatenate([-h[:, :0:-1], h], axis=1)
    return np.concatenate([h[:, :0:-1], h], axis=1)


@functools.lru_cache(maxsize=8)
def _trig_table(ratio: float, modes: int, count: int, odd: bool) -> np.ndarray:
    """``2 sin`` (``odd``) or ``2 cos`` (first row 1) of the phases ``2 pi ratio n dy``,
    ``0 <= n < modes``, ``0 <= dy < count``: the same table for every batch and block
    (read-only)."""
    ph = turns(ratio, np.arange(modes), np.arange(count))
    if odd:  # sum_n g (e^{i..} - e^{-i..}) = 2 i sum_{n>0} g sin
        T = 2 * np.sin(ph)
    else:
        T = 2 * np.cos(ph)
        T[0] = 1.0
    T.flags.writeable = False
    return T


def over_m(h: np.ndarray, ratio: float, count: int, chirp: bool) -> np.ndarray:
    """``K(dy, dx) = Re sum_{|m| <= N_t} h(m, dy) exp(2 pi i ratio m dx)``, ``|dx| < count``,
    from ``h`` on ``m >= 0`` (``h(-m) = conj h(m)``): real, ``(2 K_y - 1, 2 count - 1)``."""
    m = np.arange(h.shape[0])
    if chirp:
        cm = 2 * h.T
        cm[:, 0] = h[0]
        return chirp_sum(cm, ratio, -(count - 1), 2 * count - 1).real
    phx = turns(ratio, np.arange(-(count - 1), count), m)  # (dx, m)
    wm = np.full(m.size, 2.0)
    wm[0] = 1.0
    return ((np.cos(phx) * wm) @ h.real - (np.sin(phx) * wm) @ h.imag).T
