"""The discrete Fourier transforms of :mod:`bem`: NumPy's on one thread, SciPy's on more.

numpy.fft and scipy.fft are the same library (pocketfft). Best of three repetitions, one
thread, at the sizes the solvers use, a forward and inverse pair by NumPy took 0.88-1.27
times SciPy's (0.97-1.06 from 128 x 128 points on; the extra at 64 x 64 is 10 us of call
overhead). SciPy adds threads (``workers``), which pay from
:data:`bem.operator.THREADED_FROM` points on, and its import costs a process about
0.17 s (it loads scipy.special and the array-API layer), a third of a small
``bem solve``. So a transform asked of one thread runs in numpy.fft, and scipy.fft is
imported by the first transform asked of more (``workers`` other than 1; -1 is every
core).

Only the calls and arguments that :mod:`bem` uses are here; ``workers`` is keyword-only.
"""

from __future__ import annotations

import functools

import numpy as np

__all__ = ["fft", "ifft", "rfft", "irfft", "rfft2", "irfft2", "next_fast_len"]


def _lib(workers: int):
    """The module that runs a transform on ``workers`` threads and the keyword it takes."""
    if workers == 1:
        return np.fft, {}
    import scipy.fft

    return scipy.fft, {"workers": workers}


def fft(x, n=None, axis=-1, *, workers=1):
    lib, kw = _lib(workers)
    return lib.fft(x, n, axis, **kw)


def ifft(x, n=None, axis=-1, *, workers=1):
    lib, kw = _lib(workers)
    return lib.ifft(x, n, axis, **kw)


def rfft(x, n=None, axis=-1, *, workers=1):
    lib, kw = _lib(workers)
    return lib.rfft(x, n, axis, **kw)


def irfft(x, n=None, axis=-1, *, workers=1):
    lib, kw = _lib(workers)
    return lib.irfft(x, n, axis, **kw)


def rfft2(x, s=None, *, workers=1):
    lib, kw = _lib(workers)
    return lib.rfft2(x, s, **kw)


def irfft2(x, s=None, *, workers=1):
    lib, kw = _lib(workers)
    return lib.irfft2(x, s, **kw)


@functools.lru_cache(maxsize=256)
def next_fast_len(n: int, real: bool = False) -> int:
    """The smallest length ``>= n`` whose prime factors are all at most 5 (``real``) or
    11: lengths that pocketfft transforms fastest (the rule of ``scipy.fft.next_fast_len``)."""
    if n < 1:
        raise ValueError(f"a transform length must be >= 1, got {n!r}")
    primes = (2, 3, 5) if real else (2, 3, 5, 7, 11)
    while True:
        k = n
        for p in primes:
            while k % p == 0:
                k //= p
        if k == 1:
            return n
        n += 1
