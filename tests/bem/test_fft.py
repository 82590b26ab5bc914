"""bem.fft: NumPy's transforms on one thread, SciPy's on more, the same numbers either way
(that a small solve never imports scipy.fft: tests/bem/test_startup.py)."""

import numpy as np
import pytest
import scipy.fft

from bem import fft

RNG = np.random.default_rng(7)


def test_next_fast_len_is_scipys_rule():
    for real in (True, False):
        for n in range(1, 3001):
            assert fft.next_fast_len(n, real) == scipy.fft.next_fast_len(n, real=real), (n, real)
    with pytest.raises(ValueError, match="length must be >= 1, got 0"):
        fft.next_fast_len(0)


@pytest.mark.parametrize("workers", [1, 2])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_transforms_equal_scipys(workers, dtype):
    x = RNG.standard_normal((3, 12, 10)).astype(dtype)
    z = (x + 1j * RNG.standard_normal(x.shape)).astype(np.result_type(dtype, np.complex64))
    tol = 1e-13 if dtype == np.float64 else 2e-5
    pairs = [
        (fft.rfft2(x, (16, 20), workers=workers), scipy.fft.rfft2(x, (16, 20))),
        (fft.irfft2(z, (12, 18), workers=workers), scipy.fft.irfft2(z, (12, 18))),
        (fft.rfft(x, 16, workers=workers), scipy.fft.rfft(x, 16)),
        (fft.irfft(z, 14, workers=workers), scipy.fft.irfft(z, 14)),
        (fft.fft(z, 15, -2, workers=workers), scipy.fft.fft(z, 15, -2)),
        (fft.ifft(z, None, -2, workers=workers), scipy.fft.ifft(z, None, -2)),
    ]
    for ours, theirs in pairs:
        assert ours.dtype == theirs.dtype
        assert np.abs(ours - theirs).max() <= tol * np.abs(theirs).max()


def test_the_library_by_threads():
    """One worker: numpy.fft in either precision and at any size; more: scipy.fft."""
    small, large = np.ones((3, 40, 40)), np.ones((3, 250, 250))
    for x in (small, large):
        for dtype in (np.float64, np.float32, np.complex128, np.complex64):
            assert fft._lib(x.astype(dtype), 1)[0] is np.fft, (x.shape, dtype)
            assert fft._lib(x.astype(dtype), 2)[0] is scipy.fft, (x.shape, dtype)
    assert fft._lib(small, -1)[0] is scipy.fft
    assert fft.in_numpy(1) and not fft.in_numpy(2)


@pytest.mark.parametrize("shape, args", [((3, 90, 90), ("rfft", 128, -1)), ((3, 90, 90), ("rfft", None, 0)),
                                         ((2, 108, 55), ("fft", None, -2)), ((2, 108, 55), ("fft", 125, 1)),
                                         ((3, 40, 30), ("rfft2", (50, 64)))])
def test_single_precision_forward_transforms_are_unnormalised(shape, args):
    """numpy.fft's single-precision forward transforms run with the scale 1/n as a float32
    and are multiplied back by n (bem.fft's docstring): the unnormalised transform, to
    single precision, of the length asked for (padded or cut), complex64 out; into
    ``out`` when given."""
    name, *rest = args
    x = RNG.standard_normal(shape).astype(np.float32)
    if name == "fft":
        x = (x + 1j * RNG.standard_normal(shape)).astype(np.complex64)
    ours = getattr(fft, name)(x, *rest)
    exact = getattr(scipy.fft, name)(x.astype(np.complex128 if name == "fft" else np.float64), *rest)
    assert ours.dtype == np.complex64 and ours.shape == exact.shape
    assert np.abs(ours - exact).max() <= 1e-6 * np.abs(exact).max()
    if name != "rfft2":
        out = np.zeros(exact.shape, np.complex64)
        assert getattr(fft, name)(x, *rest, out=out) is out
        np.testing.assert_array_equal(out, ours)


@pytest.mark.parametrize("workers", [1, 2])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_pruned_embedding_transforms_are_the_zero_padded_2d_ones(workers, dtype):
    """bem.operator.spectrum_of and values_of, one axis at a time (in numpy.fft a padded
    spectrum written in place, in scipy.fft the plain calls), against scipy.fft's rfft2 of
    the zero-padded fields and the first rows of its irfft2: the same numbers to rounding,
    in both libraries (one worker: numpy.fft; two: scipy.fft), and in single precision."""
    from bem.operator import spectrum_of, values_of

    x = RNG.standard_normal((3, 9, 11)).astype(dtype)
    tol = 1e-13 if dtype == np.float64 else 2e-6
    F = spectrum_of(x, (20, 24), workers)
    theirs = scipy.fft.rfft2(x, (20, 24))
    assert F.dtype == theirs.dtype and F.shape == (3, 20, 13)
    assert np.abs(F - theirs).max() <= tol * np.abs(theirs).max()
    back = values_of(F, 9, (20, 24), workers)
    assert back.shape == (3, 9, 24)
    np.testing.assert_allclose(back[..., :11], x, rtol=0, atol=tol * 10 * np.abs(x).max())
    assert np.abs(back[..., 11:]).max() <= tol * 10 * np.abs(x).max()  # the padding comes back as zeros
