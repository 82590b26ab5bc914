"""The discrete Fourier transforms of :mod:`bem`: NumPy's on one thread, SciPy's on more.

numpy.fft and scipy.fft are the same library (pocketfft). Best of three repetitions, one
thread, at the sizes the solvers use, a forward and inverse pair in double precision by
NumPy took 0.88-1.27 times SciPy's (0.97-1.06 from 128 x 128 points on; the extra at
64 x 64 is 10 us of call overhead); in single precision 3.0-3.4 times (the frictional
solver's fields of 3 x 61 x 61 and 3 x 121 x 121 nodes: SciPy vectorises over rows).
SciPy adds threads (``workers``), which pay from :data:`bem.operator.THREADED_FROM`
points on, and its import costs a process about 0.17 s (it loads scipy.special and the
array-API layer), a third of a small ``bem solve``. So a transform runs in numpy.fft
when it is asked of one thread and is in double precision or smaller than
:data:`SINGLE_FROM` values; otherwise scipy.fft runs it, imported by the first such
transform. Measured, the frictional solve of ``examples/elastic-paraboloid-creepage.toml``
against every transform in scipy.fft (9 alternated pairs, loaded machine): 1.05 times as
long at 61 x 61 (every transform in numpy.fft), 1.03 at 121 x 121 (single precision in
scipy.fft; 1.14 with numpy.fft throughout).

Only the calls and arguments that :mod:`bem` uses are here; ``workers`` is keyword-only.
"""

from __future__ import annotations

import functools

import numpy as np

__all__ = ["fft", "ifft", "rfft", "irfft", "rfft2", "irfft2", "in_numpy", "next_fast_len", "SINGLE_FROM"]


#: single-precision transforms of this many input values or more run in scipy.fft (module
#: docstring): the frictional solver's fields from about 82 x 82 nodes on (3 fields)
SINGLE_FROM = 20_000


def _lib(x, workers: int):
    """The module that runs a transform of ``x`` on ``workers`` threads, the keyword it
    takes, and ``x`` as an array."""
    x = np.asarray(x)
    single = x.dtype in (np.float32, np.complex64)
    if workers == 1 and (not single or x.size < SINGLE_FROM):
        return np.fft, {}, x
    import scipy.fft

    return scipy.fft, {"workers": workers}, x


def in_numpy(x, workers: int = 1) -> bool:
    """Whether a transform of ``x`` on ``workers`` threads runs in numpy.fft (see above)."""
    return _lib(x, workers)[0] is np.fft


def _run(name, x, args, workers):
    """Transform ``name`` of ``x`` with the positional ``args`` on ``workers`` threads."""
    lib, kw, x = _lib(x, workers)
    return getattr(lib, name)(x, *args, **kw)


def fft(x, n=None, axis=-1, *, workers=1):
    return _run("fft", x, (n, axis), workers)


def ifft(x, n=None, axis=-1, *, workers=1):
    return _run("ifft", x, (n, axis), workers)


def rfft(x, n=None, axis=-1, *, workers=1):
    return _run("rfft", x, (n, axis), workers)


def irfft(x, n=None, axis=-1, *, workers=1):
    return _run("irfft", x, (n, axis), workers)


def rfft2(x, s=None, *, workers=1):
    return _run("rfft2", x, (s,), workers)


def irfft2(x, s=None, *, workers=1):
    return _run("irfft2", x, (s,), workers)


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
