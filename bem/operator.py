"""The nodal compliance operator of one block (eq. 51), applied by FFT or assembled dense.

Entries depend on the node offset only, so the operator is block-Toeplitz with Toeplitz
blocks: it is applied by a circulant embedding of size about ``(2 K_y) x (2 K_x)`` at
``O(N log N)`` cost and ``O(N)`` memory, and assembled densely only on request (small
grids, or a node subset).
"""

from __future__ import annotations

import numpy as np
import scipy.fft as sfft

from .grid import Grid

__all__ = ["ComplianceOperator"]


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
        self._hat = sfft.rfft2(circ, workers=-1)

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
        out = sfft.irfft2(sfft.rfft2(f, s=self._size, workers=-1) * self._hat, s=self._size, workers=-1)
        return out[:Ky, :Kx]

    def apply_transpose(self, forces: np.ndarray) -> np.ndarray:
        """``C^T f`` (the operator is not symmetric in steady rolling): the conjugate
        spectrum of the real kernel turns the circular convolution into a correlation."""
        Ky, Kx = self.grid.shape
        f = np.asarray(forces, dtype=float).reshape(Ky, Kx)
        out = sfft.irfft2(sfft.rfft2(f, s=self._size, workers=-1) * np.conj(self._hat), s=self._size, workers=-1)
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
        out = sfft.irfft2(sfft.rfft2(f, s=self._size, workers=-1) * self._inv_hat, s=self._size, workers=-1)
        return out[:Ky, :Kx]

    def dense(self, nodes: np.ndarray | None = None) -> np.ndarray:
        """Dense matrix ``C[M, N]`` (m/N) on the flat node indices ``nodes`` (all if None)."""
        Ky, Kx = self.grid.shape
        idx = np.arange(Kx * Ky) if nodes is None else np.asarray(nodes)
        j, i = np.divmod(idx, Kx)
        return self.kernel[(j[:, None] - j[None, :]) + Ky - 1, (i[:, None] - i[None, :]) + Kx - 1]
