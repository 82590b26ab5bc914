"""The nodal compliance operator of one block (eq. 51), applied by FFT or assembled dense.

Entries depend on the node offset only, so the operator is block-Toeplitz with Toeplitz
blocks: it is applied by a circulant embedding of size about ``(2 K_y) x (2 K_x)`` at
``O(N log N)`` cost and ``O(N)`` memory, and assembled densely only on request (small
grids, or a node subset).
"""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np
import scipy.fft as sfft

from .grid import Grid

__all__ = ["ComplianceOperator", "THREADED_FROM", "fft_workers", "one_worker"]

#: FFTs of an embedding with this many points or more run on every core, smaller ones on
#: one (a small transform costs less than handing it over). Measured, whole solves with the
#: two settings alternated in one process (median of the pairs' ratios, one thread / every
#: core): the frictionless solver, the CONTACT comparison case at 61 x 61 (embedding
#: 128 x 128) 0.65, 121 x 121 0.72, section 11 41 x 41 0.57, 129 x 129 (258 x 258) 0.76,
#: 257 x 257 (514 x 514) 1.20; the frictional one (on the contact's box) 61 x 61 (108 x 108) 0.84, 121 x 121 0.93,
#: 41 x 41 0.85, 129 x 129 (225 x 216) 0.99, 257 x 257 (450 x 405) 0.95 and 1.06
THREADED_FROM = 100_000


_ONE_WORKER = 0  # depth of the one_worker() blocks open


def fft_workers(shape: tuple[int, int]) -> int:
    """Threads for the transforms of an embedding of ``shape``: ``-1`` (every core) from
    :data:`THREADED_FROM` points on, 1 below, and 1 inside :func:`one_worker`."""
    return -1 if shape[0] * shape[1] >= THREADED_FROM and not _ONE_WORKER else 1


@contextmanager
def one_worker():
    """Every transform on one thread while the block runs, on every thread: for two threads
    that solve side by side (the frictional solver's coarse levels and its frictionless
    start), each then on its own core instead of four transform threads on two cores.
    Measured (section 11 at 513 x 513, whole frictional solves alternated with and without,
    ``benchmarks/bem_friction_rolling.py``): see ``BENCHMARKS.md``, seventeenth pass."""
    global _ONE_WORKER
    _ONE_WORKER += 1
    try:
        yield
    finally:
        _ONE_WORKER -= 1


class ComplianceOperator:
    """Displacements (m) at the nodes from nodal forces (N), for one block of ``C``.

    Parameters
    ----------
    grid : Grid
    kernel : ndarray, shape ``(2 K_y - 1, 2 K_x - 1)``
        Kernel table from :func:`bem.spectral.influence_kernels` (m/N).
    """

    def __init__(self, grid: Grid, kernel: np.ndarray):
        Ky, Kx = grid.shape
        if kernel.shape != (2 * Ky - 1, 2 * Kx - 1):
            raise ValueError(f"kernel shape must be {(2 * Ky - 1, 2 * Kx - 1)} for grid {grid.shape}, got {kernel.shape}")
        self.grid = grid
        self.kernel = kernel
        self._size = (sfft.next_fast_len(2 * Ky - 1, real=True), sfft.next_fast_len(2 * Kx - 1, real=True))
        circ = np.zeros(self._size)
        dy = np.arange(-(Ky - 1), Ky) % self._size[0]
        dx = np.arange(-(Kx - 1), Kx) % self._size[1]
        circ[np.ix_(dy, dx)] = kernel
        self._hat = sfft.rfft2(circ, workers=self._workers)

    @property
    def _workers(self) -> int:
        """Threads of this embedding's transforms, :func:`fft_workers` at each call."""
        return fft_workers(self._size)

    @property
    def embedding(self) -> tuple[int, int]:
        """Shape of the circulant embedding (rows, columns)."""
        return self._size

    @property
    def spectrum(self) -> np.ndarray:
        """Eigenvalues of the circulant embedding (its kernel's ``rfft2``), read-only."""
        out = self._hat.view()
        out.flags.writeable = False
        return out

    @property
    def shape(self) -> tuple[int, int]:
        n = self.grid.nodes_x * self.grid.nodes_y
        return (n, n)

    def apply(self, forces: np.ndarray) -> np.ndarray:
        """``C f`` for nodal forces of shape ``(K_y, K_x)`` (N); returns m, same shape."""
        Ky, Kx = self.grid.shape
        f = np.asarray(forces, dtype=float).reshape(Ky, Kx)
        out = sfft.irfft2(sfft.rfft2(f, s=self._size, workers=self._workers) * self._hat, s=self._size, workers=self._workers)
        return out[:Ky, :Kx]

    def apply_transpose(self, forces: np.ndarray) -> np.ndarray:
        """``C^T f`` (the operator is not symmetric in steady rolling): the conjugate
        spectrum of the real kernel turns the circular convolution into a correlation."""
        Ky, Kx = self.grid.shape
        f = np.asarray(forces, dtype=float).reshape(Ky, Kx)
        out = sfft.irfft2(sfft.rfft2(f, s=self._size, workers=self._workers) * np.conj(self._hat), s=self._size, workers=self._workers)
        return out[:Ky, :Kx]

    @property
    def has_circulant_inverse(self) -> bool:
        """Whether the circulant embedding is safely invertible (its smallest eigenvalue
        modulus above 1e-12 of the largest); computes and keeps the inverse spectrum."""
        if not hasattr(self, "_inv_hat"):
            mag = np.abs(self._hat)
            self._inv_hat = 1.0 / self._hat if mag.min() > 1e-12 * mag.max() else None
        return self._inv_hat is not None

    def circulant_inverse(self, values: np.ndarray) -> np.ndarray:
        """Exact inverse of the circulant embedding of ``C`` applied to ``values``
        (shape ``(K_y, K_x)``, zero-padded to the embedding), read back on the grid.

        An approximate inverse of ``C`` restricted to a node set, cheap (two FFTs) and
        spectrally close to it: a preconditioner for Krylov solves on contact sets. Raises
        ``ZeroDivisionError`` if the embedding is (nearly) singular.
        """
        if not self.has_circulant_inverse:
            raise ZeroDivisionError("the circulant embedding of the compliance is nearly singular")
        Ky, Kx = self.grid.shape
        f = np.asarray(values, dtype=float).reshape(Ky, Kx)
        out = sfft.irfft2(sfft.rfft2(f, s=self._size, workers=self._workers) * self._inv_hat, s=self._size, workers=self._workers)
        return out[:Ky, :Kx]

    def dense(self, nodes: np.ndarray | None = None) -> np.ndarray:
        """Dense matrix ``C[M, N]`` (m/N) on the flat node indices ``nodes`` (all if None)."""
        Ky, Kx = self.grid.shape
        idx = np.arange(Kx * Ky) if nodes is None else np.asarray(nodes)
        j, i = np.divmod(idx, Kx)
        return self.kernel[(j[:, None] - j[None, :]) + Ky - 1, (i[:, None] - i[None, :]) + Kx - 1]
