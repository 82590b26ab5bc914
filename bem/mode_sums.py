"""Sums over Fourier modes to node offsets: the transforms the kernel tables are made of.

``h(j) = sum_n c(n) exp(2 pi i ratio n j)`` over the truncated modes ``n`` for the node
offsets ``j``, with ``ratio = a / L`` (spacing over period): by Bluestein's chirp-z
identity (:func:`chirp_sum`, any ``a / L``, ``O(N log N)``), by discrete cosine and sine
transforms of type I when ``L = 2 Q a`` for an integer ``Q >= N_t`` (:func:`lattice_half`,
:func:`cos_sums`, :func:`sin_sums`: the phases are then ``pi n j / Q``, one real transform a
row) or, for a few offsets, by matrix products with trigonometric tables (:func:`over_n`,
:func:`over_m`), phases reduced modulo one turn. :mod:`bem.spectral` and :mod:`bem.plane`
build their kernels with them.
"""

from __future__ import annotations

import functools

import numpy as np
from . import fft as sfft

from .batches import in_batches

__all__ = ["chirp_sum", "turns", "circle_table", "trig_table", "over_n", "over_m", "over_m_mirrored", "lattice_half",
           "cos_sums", "sin_sums"]


def chirp_sum(c: np.ndarray, ratio: float, j0: int, count: int, weight: np.ndarray | None = None,
              workers: int = 1) -> np.ndarray:
    """``sum_n c[..., n] w[n] exp(2 pi i ratio n j)`` for ``j = j0 .. j0 + count - 1`` (``w`` the
    ``weight``, 1 without); the inverse transform on ``workers`` threads (-1: every core,
    in scipy.fft; threads share out the rows of ``c``, so a few rows, as a line contact's
    kernels and dissipation have, gain nothing from them and one thread spares the
    process scipy.fft's import, 0.135 s).

    Bluestein's identity ``n j = (n^2 + j^2 - (j - n)^2) / 2`` turns the sum into a
    convolution done by FFT; phases are reduced modulo one turn before use.
    """
    size, pre, chirp_spectrum, post = _chirp_factors(float(ratio), c.shape[-1], j0, count)
    spec = sfft.fft(c * (pre if weight is None else pre * weight), size, axis=-1)
    spec *= chirp_spectrum
    return sfft.ifft(spec, axis=-1, workers=workers)[..., :count] * post


@functools.lru_cache(maxsize=16)
def _chirp_factors(ratio: float, N: int, j0: int, count: int):
    """What :func:`chirp_sum` multiplies by, the same for every batch of rows: the FFT
    length (2, 3 and 5 its only factors: 1.3 times faster than with 7s and 11s), the
    chirp of the terms, the spectrum of the convolution's chirp and that of the results
    (read-only)."""
    n = np.arange(N, dtype=float)
    t = np.arange(count, dtype=float)
    lag = np.arange(-(N - 1), count, dtype=float)

    def turn(x):
        return np.exp(2j * np.pi * np.mod(ratio * x, 1.0))

    size = sfft.next_fast_len(N + count - 1, True)
    b = np.zeros(size, dtype=complex)
    chirp = turn(-lag * lag / 2)
    b[:count] = chirp[N - 1 :]
    b[size - (N - 1) :] = chirp[: N - 1]
    factors = turn(n * j0 + n * n / 2), sfft.fft(b), turn(t * t / 2)
    for f in factors:
        f.flags.writeable = False
    return (size, *factors)


def turns(ratio: float, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Phase ``2 pi ratio a b`` reduced modulo a turn (``a b`` exact integers)."""
    return 2 * np.pi * np.mod(ratio * np.outer(a, b).astype(float), 1.0)


def circle_table(ratio: float, a: np.ndarray, b: np.ndarray, odd: bool) -> np.ndarray:
    """``sin`` (``odd``) or ``cos`` of the phases ``2 pi ratio a b`` (``a b`` exact integers),
    ``(a.size, b.size)``. Where ``ratio = 1 / P`` (to 1e-12) for an integer ``P`` no larger
    than the table (the nodes on the transform's lattice, ``N_t = L / 2a``: ``P = 2 N_t``),
    each entry is read from the ``P`` values at ``2 pi k / P`` at the exact residue ``k = a b
    mod P``: about 0.9 ms for a table of 1501 x 61 against 2.4 ms by reducing and evaluating
    every phase (:func:`turns`), which carries the rounding of ``ratio`` (7e-14 here)."""
    P = round(1 / ratio) if ratio > 0 else 0
    if P < 1 or P > a.size * b.size or abs(ratio * P - 1) > 1e-12:
        return (np.sin if odd else np.cos)(turns(ratio, a, b))
    k = np.outer(a, b)
    np.remainder(k, P, out=k)
    return (np.sin if odd else np.cos)((2 * np.pi / P) * np.arange(P))[k]


def over_n(r: np.ndarray, odd: bool, ratio: float, count: int, chirp: bool,
            weight_n: np.ndarray | None = None) -> np.ndarray:
    """``h(m, dy) = sum_{|n| <= N_t} g(m, n) exp(2 pi i ratio n dy)`` for ``|dy| < count``
    (complex, ``(rows, 2 count - 1)``) of ``g(m, n) = r(m, n) w(n)`` for ``n >= 0`` (``r``
    real or complex, ``w`` the ``weight_n``, 1 without) and ``g(m, -n) = -g(m, n)``
    (``odd``) or ``+g(m, n)``."""
    if chirp:
        w = np.full(r.shape[1], 2.0) if weight_n is None else 2.0 * weight_n
        w[0] = 0.0 if odd else 0.5 * w[0]
        S = chirp_sum(r, ratio, -(count - 1), 2 * count - 1, w, workers=1)  # called in batches
        return 0.5 * (S - S[:, ::-1]) if odd else 0.5 * (S + S[:, ::-1])
    T = trig_table(ratio, r.shape[1], count, odd)
    if weight_n is not None:
        T = weight_n[:, None] * T
    h = (r.real @ T + 1j * (r.imag @ T)) if np.iscomplexobj(r) else (r @ T).astype(complex)
    if odd:
        h = 1j * h
        return np.concatenate([-h[:, :0:-1], h], axis=1)
    return np.concatenate([h[:, :0:-1], h], axis=1)


@functools.lru_cache(maxsize=8)
def trig_table(ratio: float, modes: int, count: int, odd: bool) -> np.ndarray:
    """``2 sin`` (``odd``) or ``2 cos`` (first row 1) of the phases ``2 pi ratio n dy``,
    ``0 <= n < modes``, ``0 <= dy < count``: the same table for every batch and block
    (read-only)."""
    # odd: sum_n g (e^{i..} - e^{-i..}) = 2 i sum_{n>0} g sin; even: the mode n = 0 once
    T = 2 * circle_table(ratio, np.arange(modes), np.arange(count), odd)
    if not odd:
        T[0] = 1.0
    T.flags.writeable = False
    return T


_COLUMNS = 64  # columns of partial sums a chirp-z transform over m takes at once


def over_m(h: np.ndarray, ratio: float, count: int, chirp: bool) -> np.ndarray:
    """``K(dy, dx) = Re sum_{|m| <= N_t} h(m, dy) exp(2 pi i ratio m dx)``, ``|dx| < count``,
    from ``h`` on ``m >= 0`` (``h(-m) = conj h(m)``): real, ``(2 K_y - 1, 2 count - 1)``.
    A real or imaginary ``h`` (of a real symbol) takes one matrix product, not two."""
    if chirp:
        Q = lattice_half(ratio, h.shape[0], count)
        if Q:
            re, im = h.real, h.imag
            C = cos_sums(re, Q, count, axis=0) if re.any() else np.zeros((count, h.shape[1]))
            S = sin_sums(im, Q, count, axis=0) if im.any() else np.zeros((count, h.shape[1]))
            return np.concatenate([(C + S)[:0:-1], C - S]).T
        w = np.full(h.shape[0], 2.0)
        w[0] = 1.0
        out = np.empty((h.shape[1], 2 * count - 1))

        def columns(c: int) -> None:  # a block of columns at a time: in cache
            block = np.ascontiguousarray(h[:, c : c + _COLUMNS].T)
            out[c : c + _COLUMNS] = chirp_sum(block, ratio, -(count - 1), 2 * count - 1, w, workers=1).real

        in_batches(h.shape[1], columns, _COLUMNS)
        return out
    cos, sin = _x_tables(ratio, h.shape[0], count)
    re, im = h.real, h.imag
    if not im.any():
        return (cos @ re).T
    if not re.any():
        return -(sin @ im).T
    return (cos @ re - sin @ im).T


def over_m_mirrored(h: np.ndarray, ratio: float, count: int, chirp: bool, sign: float) -> np.ndarray:
    """:func:`over_m` of the partial sums of the offsets ``dy >= 0`` alone (``h`` of ``(rows,
    K_y)``), the rows ``dy < 0`` of the table ``(2 K_y - 1, 2 count - 1)`` by its parity
    ``sign`` in ``dy`` (1 even, -1 odd): the same numbers as from every column (each
    column's sum is its own), for half the transforms."""
    K = over_m(h, ratio, count, chirp)
    return np.concatenate([sign * K[:0:-1], K])


@functools.lru_cache(maxsize=8)
def _x_tables(ratio: float, modes: int, count: int) -> tuple[np.ndarray, np.ndarray]:
    """``w_m cos`` and ``w_m sin`` of the phases ``2 pi ratio m dx``, ``|dx| < count``,
    ``0 <= m < modes``, ``w_m = 2`` but ``w_0 = 1``: ``(2 count - 1, modes)``, read-only."""
    dx, m = np.arange(-(count - 1), count), np.arange(modes)
    wm = np.full(modes, 2.0)
    wm[0] = 1.0
    tables = circle_table(ratio, dx, m, False) * wm, circle_table(ratio, dx, m, True) * wm
    for t in tables:
        t.flags.writeable = False
    return tables


def lattice_half(ratio: float, modes: int, count: int) -> int | None:
    """``Q`` if ``ratio = a / L = 1 / (2 Q)`` (to 1e-12) for an integer ``Q`` with ``modes - 1 =
    N_t <= Q`` (no two kept modes alias but the two end ones) and ``count <= Q`` offsets;
    else ``None``. Then ``2 pi ratio n j = pi n j / Q``: :func:`cos_sums`, :func:`sin_sums`."""
    if not ratio > 0:
        return None
    Q = round(0.5 / ratio)
    return Q if Q >= max(modes - 1, count, 1) and abs(2 * ratio * Q - 1) <= 1e-12 else None


def cos_sums(x: np.ndarray, Q: int, count: int, axis: int = -1, weight: np.ndarray | None = None) -> np.ndarray:
    """``x(0) + 2 sum_{n >= 1} x(n) cos(pi n j / Q)``, ``0 <= j < count``, along ``axis`` of
    real ``x`` (``n = 0 .. N_t``, ``N_t <= Q``) times ``weight`` (of ``n``, 1 without): the even
    sum ``sum_{|n| <= N_t} x(|n|) exp(i pi n j / Q)``, a DCT-I of ``Q + 1`` points (``y_j =
    x_0 + (-1)^j x_Q + 2 sum_{0 < n < Q} x_n cos(pi n j / Q)``, so ``x_Q`` enters twice),
    taken as the real part of the real transform of the even extension ``x_0 .. x_Q,
    x_{Q-1} .. x_1`` (``2 Q`` points; what pocketfft's DCT-I computes, in numpy.fft, whose
    import a process has already paid: scipy.fft's costs 0.135 s)."""
    x = np.moveaxis(x, axis, -1)
    n = x.shape[-1]
    w = np.ones(n) if weight is None else np.array(weight, float)
    if w.size == Q + 1:
        w[Q] *= 2
    k = min(n, Q)  # x_1 .. x_{k-1} appear twice, x_Q once
    e = np.zeros(x.shape[:-1] + (2 * Q,))
    np.multiply(x, w, out=e[..., :n])
    e[..., 2 * Q - k + 1:] = e[..., k - 1:0:-1]
    return np.moveaxis(sfft.rfft(e)[..., :count].real, -1, axis)


def sin_sums(x: np.ndarray, Q: int, count: int, axis: int = -1) -> np.ndarray:
    """``2 sum_{n >= 1} x(n) sin(pi n j / Q)``, ``0 <= j < count``, along ``axis`` of real
    ``x`` (``n = 0 .. N_t <= Q``): the odd sum ``sum_{|n| <= N_t} sign(n) x(|n|) exp(i pi n j /
    Q)`` over ``i``, a DST-I of ``Q - 1`` points (``x(0)`` and ``x(Q)`` have no sine), taken as
    minus the imaginary part of the real transform of the odd extension ``0, x_1 .. x_{Q-1},
    0, -x_{Q-1} .. -x_1`` (``2 Q`` points, as :func:`cos_sums`)."""
    x = np.moveaxis(x, axis, -1)
    k = min(x.shape[-1], Q)  # x_1 .. x_{k-1}
    z = np.zeros(x.shape[:-1] + (2 * Q,))
    z[..., 1:k] = x[..., 1:k]
    z[..., 2 * Q - k + 1:] = -z[..., k - 1:0:-1]
    return np.moveaxis(-sfft.rfft(z)[..., :count].imag, -1, axis)
