"""bem.fft: NumPy's transforms on one thread, SciPy's on more, the same numbers either way."""

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

