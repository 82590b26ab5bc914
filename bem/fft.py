"""The discrete Fourier transforms of :mod:`bem`: NumPy's on one thread, SciPy's on more.

numpy.fft and scipy.fft are the same library (pocketfft). SciPy adds threads
(``workers``), which pay from :data:`bem.operator.THREADED_FROM` points on, and its import
from :data:`~bem.operator.IMPORT_PAYS_FROM`: the import costs a process 0.135 s (it loads
scipy.special and the array-API layer; median of five, after numpy), a quarter of
a ``bem solve`` at 0.1 mm (0.45 s). So a transform runs in numpy.fft when
it is asked of one thread, in scipy.fft (imported by the first such transform) when asked
of more. On one thread the two take the same time: the frictional products' pruned
transforms (:func:`bem.operator.spectrum_of`, :func:`~bem.operator.values_of`) of three
single-precision fields from 61 x 61 to 241 x 241 nodes, NumPy's forward 0.99-1.01 times
SciPy's and inverse 1.02-1.07 (best of five, malloc's thresholds raised so that no
transform meets fresh pages); in double precision 0.88-1.27 (0.97-1.06 from 128 x 128
points on; the extra at 64 x 64 is 10 us of call overhead).

NumPy's unnormalised single-precision forward transforms (``fft``, ``rfft``, ``rfft2``
with the default ``norm``) pass the scale as the Python number 1, and its transform
ufuncs then take their double-precision loop, casting the data in and out through
buffers (numpy 2.4): the columns' ``fft`` of 3 x 108 x 55 complex64 values took 65 us
against 38 us in the single-precision loop. With ``norm="forward"`` the scale is a
float32 and the single-precision loop runs, so :func:`fft`, :func:`rfft` and
:func:`rfft2` ask for that and multiply the result by the transform's length (rounding of
single precision, about 1e-7). The inverse transforms' default scale, ``1 / n``, is a
float32 already.

NumPy also pads a transform of ``n`` values longer than its input slowly (per
transform, inside its loop): the rows' ``rfft`` of 363 x 121 values padded to 243 took
338 us in single precision and 299 us in double, against 133 and 180 us for the same
transform of an array padded beforehand and 130 and 189 us by SciPy; the columns'
``fft`` of 3 x 61 x 63 complex values to 125, 123 against 101 us (SciPy 91). So
:func:`fft` and :func:`rfft` pad in an array of their own first.

Only the calls and arguments that :mod:`bem` uses are here; ``workers`` and ``out`` (the
result's array) are keyword-only.
"""

from __future__ import annotations

import functools

import numpy as np

__all__ = ["fft", "ifft", "rfft", "irfft", "rfft2", "irfft2", "in_numpy", "next_fast_len"]


#: numpy.fft's forward transforms, run in single precision by a float32 scale (module docstring)
_FORWARD = ("fft", "rfft", "rfft2")


def _lib(x, workers: int):
    """The module that runs a transform of ``x`` on ``workers`` threads, the keyword it
    takes, and ``x`` as an array."""
    x = np.asarray(x)
    if in_numpy(workers):
        return np.fft, {}, x
    import scipy.fft

    return scipy.fft, {"workers": workers}, x


def in_numpy(workers: int = 1) -> bool:
    """Whether a transform on ``workers`` threads runs in numpy.fft (see above)."""
    return workers == 1


def _run(name, x, args, workers, out=None):
    """Transform ``name`` of ``x`` with the positional ``args`` on ``workers`` threads,
    into ``out`` when given (numpy.fft writes there, scipy.fft's result is copied)."""
    lib, kw, x = _lib(x, workers)
    if lib is not np.fft:
        y = getattr(lib, name)(x, *args, **kw)
        if out is None:
            return y
        out[...] = y
        return out
    if name in ("fft", "rfft") and args[0] is not None and args[0] > x.shape[args[1]]:
        x, args = _padded(x, *args), (None, args[1])  # zero-padded here (module docstring)
    if name not in _FORWARD or x.dtype not in (np.float32, np.complex64):
        return getattr(np.fft, name)(x, *args, out=out)
    # the single-precision loop by a float32 scale (module docstring), then times the length
    y = getattr(np.fft, name)(x, *args, norm="forward", out=out)
    if name == "rfft2":
        s = args[0] if args[0] is not None else x.shape[-2:]
        y *= np.float32(s[0] * s[1])
    else:
        n, axis = args
        y *= np.float32(x.shape[axis] if n is None else n)
    return y


def _padded(x, n, axis):
    """``x`` zero-padded to ``n`` values along ``axis`` (``np.pad`` took 28 against 11 us for
    400 x 128 values padded to 256: its checks cost more than the copy)."""
    shape = list(x.shape)
    shape[axis] = n
    out = np.zeros(shape, x.dtype)
    out[(slice(None),) * (axis % x.ndim) + (slice(0, x.shape[axis]),)] = x
    return out


def fft(x, n=None, axis=-1, *, workers=1, out=None):
    return _run("fft", x, (n, axis), workers, out)


def ifft(x, n=None, axis=-1, *, workers=1):
    return _run("ifft", x, (n, axis), workers)


def rfft(x, n=None, axis=-1, *, workers=1, out=None):
    return _run("rfft", x, (n, axis), workers, out)


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
