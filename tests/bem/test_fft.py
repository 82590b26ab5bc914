"""bem.fft: NumPy's transforms on one thread, SciPy's on more, the same numbers either way,
and a small solve that never imports scipy.fft (its import is a third of a small run)."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.fft

from bem import fft

RNG = np.random.default_rng(7)
CASE = Path(__file__).resolve().parents[2] / "examples" / "elastic-paraboloid-creepage.toml"


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
    # into a given array: a view of a larger one, and the input itself
    padded = np.zeros((3, 16, 9), z.dtype)
    rows = fft.rfft(x, 16, workers=workers, out=padded[:, :12])
    assert np.shares_memory(rows, padded)
    np.testing.assert_allclose(padded[:, :12], scipy.fft.rfft(x, 16), rtol=0, atol=tol * 40)
    assert not padded[:, 12:].any()
    full = fft.fft(padded, None, -2, workers=workers, out=padded)
    assert np.shares_memory(full, padded)
    theirs = scipy.fft.fft(scipy.fft.rfft(x, 16), 16, -2)
    assert np.abs(padded - theirs).max() <= tol * np.abs(theirs).max()


def test_the_library_by_threads_precision_and_size():
    small, large = np.ones((3, 40, 40)), np.ones((3, 90, 90))  # 4800 and 24 300 values
    assert large.size >= fft.SINGLE_FROM > small.size
    for x, workers, lib in [(small, 1, np.fft), (large, 1, np.fft), (small.astype(np.float32), 1, np.fft),
                            (large.astype(np.float32), 1, scipy.fft), (large.astype(np.complex64), 1, scipy.fft),
                            (large.astype(np.complex128), 1, np.fft), (small, 2, scipy.fft), (small, -1, scipy.fft)]:
        assert fft._lib(x, workers)[0] is lib, (x.shape, x.dtype, workers)
    big = RNG.standard_normal((3, 90, 90)).astype(np.float32)
    np.testing.assert_array_equal(fft.rfft(big, 128), scipy.fft.rfft(big, 128))


def test_a_small_frictional_solve_does_not_import_scipy_fft():
    code = ("import sys\n"
            "from bem.cli import main\n"
            f"assert main(['solve', {str(CASE)!r}, '--quiet', "
            "'--no-error-estimate', '--set', 'grid.spacing=0.4e-3', '--set', 'grid.truncation=750']) == 0\n"
            "print(sorted(m for m in ('scipy.fft', 'scipy.ndimage', 'scipy.special', 'scipy.sparse') "
            "if m in sys.modules))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.splitlines()[-1] == "[]"
