"""The nodal compliance operator of one block (eq. 51), applied by FFT or assembled dense.

Entries depend on the node offset only, so the operator is block-Toeplitz with Toeplitz
blocks: it is applied by a circulant embedding of size about ``(2 K_y) x (2 K_x)`` at
``O(N log N)`` cost and ``O(N)`` memory, and assembled densely only on request (small
grids, or a node subset).

The contact solvers' preconditioner (:meth:`ComplianceOperator.circulant_inverse`) is the
inverse of another circulant: the kernel wrapped onto a period of at most ``2 K - 2``
nodes a side, every offset within half a period at its true value (the compliance of the
layer made periodic with that period; :func:`periodic_size`). The zero-padded embedding,
exact for the product, is a poor one to invert: its kernel drops to zero at the table's
border, and on a thick layer, whose kernel is still large there, the jump puts
eigenvalues near zero and below it into its spectrum (the thick elastic layer of
``benchmarks/bem_viscoelastic_rolling.py`` at 77 x 77: real parts down to -3.7e-4 of the
largest, six negative; four eigenvalues near -30 in the preconditioned contact system).
A viscoelastic kernel keeps a long tail along the rolling direction (``V tau`` = 12.5 mm
on that case), so its jump is larger: real parts down to -2.3e-3 of the largest, 23
negative, and eigenvalues of the preconditioned system at 0.04 and 0.09. Wrapped, the
kernel is not cut, and its spectrum keeps the positive real part of a passive layer's
symbol (``G' > 0``; measured at least 1.5e-3 of the largest on that case's kernels at
39 x 39). GMRES from zero to 1e-11 on that case's converged contact sets, zero-padded ->
wrapped: elastic 16 -> 11 (77 x 77), 17 -> 13 (155 x 155); viscoelastic 38 -> 15,
49 -> 16; the inverse of the whole grid's matrix restricted to the contact gives 11 and
14 at 77 x 77, so the wrapped circulant is about as good as that ideal. On a thin layer
(section 11's, ``H = 5 mm``, 21 x 21 nodes, elastic at rest and rolling) the kernel has
decayed at the border and both spectra stay positive.
"""

from __future__ import annotations

import sys
import threading
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
from . import fft as sfft

from .grid import Grid
from .threads import cores

__all__ = ["ComplianceOperator", "THREADED_FROM", "IMPORT_PAYS_FROM", "fft_workers", "one_worker", "periodic_size",
           "spectrum_of", "values_of", "wrapped", "BLOCKS_KEPT", "Block"]

#: FFTs of an embedding with this many points or more run on every core, smaller ones on
#: one (a small transform costs less than handing it over), once scipy.fft, which runs the
#: threads (:mod:`bem.fft`), is loaded. Measured, whole solves with the two settings
#: alternated in one process (median of the pairs' ratios, one thread / every core): the
#: frictionless solver, the CONTACT comparison case at 61 x 61 (embedding 128 x 128) 0.65,
#: 121 x 121 0.72, section 11 41 x 41 0.57, 129 x 129 (258 x 258) 0.76, 257 x 257
#: (514 x 514) 1.20; the frictional one (on the contact's box) 61 x 61 (108 x 108) 0.84,
#: 121 x 121 0.93, 41 x 41 0.85, 129 x 129 (225 x 216) 0.99, 257 x 257 (450 x 405) 0.95
#: and 1.06. Measured again on 2026-11-28 (scipy.fft loaded, 5 pairs), the frictionless
#: solver at 257 x 257 0.80 and 385 x 385 (770 x 770) 0.92: one thread now wins there, so
#: this threshold is open to question for the frictionless solver. The frictional one
#: needs it: section 11 with friction at 513 x 513 (a whole ``bem solve``, one run each)
#: 10.9 s with threads from here on, 12.1 s with none below 1 000 000 points (its coarse
#: levels' boxes).
THREADED_FROM = 100_000
#: scipy.fft's import costs a process 0.135 s, which a run's threads pay back only where it
#: transforms embeddings of this many points (a grid of about 500 x 500 nodes): below, the
#: transforms stay on one thread until scipy.fft is loaded. Whole ``bem solve`` runs as a
#: user starts them (two cores, no thread variables; paired runs, median wall time),
#: against threads from :data:`THREADED_FROM` on regardless: the viscoelastic half-space of
#: ``benchmarks/bem_viscoelastic_rolling.py`` (155 x 155 nodes, embedding 320 x 320) 0.246
#: against 0.387 s, the paraboloid with friction at 0.05 mm (241 x 241) 1.55 against 1.60 s,
#: section 11 with friction at 257 x 257 2.12 against 2.40 s and frictionless 0.43 against
#: 0.63 s (514 x 514); frictionless at 385 x 385 (770 x 770) 0.72 against 0.86 s. From
#: here on threads pay: frictionless at 513 x 513 (1026 x 1026) 1.14 against 1.18 s on one
#: thread, at 1025 x 1025 9.29 against 9.72 s.
IMPORT_PAYS_FROM = 1_000_000
#: :meth:`ComplianceOperator.block` keeps the operators of this many block shapes
BLOCKS_KEPT = 8
_BLOCKS_LOCK = threading.Lock()


_ONE_WORKER = 0  # depth of the one_worker() blocks open


def fft_workers(shape: tuple[int, int]) -> int:
    """Threads for the transforms of an embedding of ``shape``: every core the process may
    use (:func:`bem.threads.cores`) from :data:`THREADED_FROM` points on once scipy.fft is
    loaded, from :data:`IMPORT_PAYS_FROM` points on before; 1 below, and 1 inside
    :func:`one_worker`."""
    points = shape[0] * shape[1]
    if _ONE_WORKER or points < THREADED_FROM or points < IMPORT_PAYS_FROM and "scipy.fft" not in sys.modules:
        return 1
    return cores()


def periodic_size(nodes: int) -> int:
    """Period (nodes) of the wrapped circulant that :meth:`ComplianceOperator.circulant_inverse`
    inverts on a grid of ``nodes`` a side: the largest transform-friendly length (factors
    2, 3, 5) up to ``2 nodes - 2``, the longest period whose every offset within half a
    period is in the kernel table, and never less than ``nodes`` (a power of two lies in
    ``[nodes, 2 nodes - 2]``); 1 for a single node (a line contact's one row)."""
    if nodes < 2:
        return 1
    n = 2 * nodes - 2
    while sfft.next_fast_len(n, real=True) != n:
        n -= 1
    return n


def spectrum_of(f: np.ndarray, size: tuple[int, int], workers: int = 1) -> np.ndarray:
    """The 2-D real transform ``(..., E_y, E_x / 2 + 1)`` of fields ``f`` ``(..., K_y, K_x)``
    zero-padded to ``size`` ``(E_y, E_x)``, one axis at a time: the rows (the padding's
    zero rows skipped), then the columns. In numpy.fft the rows go straight into a
    zero-padded spectrum whose columns are then transformed in place: 107 against 146 us
    at 61 x 61 nodes (embedding 125 x 125, with :func:`values_of`) than ``rfft2`` and
    ``irfft2``, and 106 against 129 us for 3 x 54 x 54 single-precision fields (108 x 108)
    than padding inside the columns' transform; scipy.fft (on more threads: :mod:`bem.fft`)
    pads inside, 0.75 ms against 1.6 ms the other way for 3 x 218 x 218 fields (450 x 450)
    on two threads. Single precision for ``float32`` fields."""
    Ey, Ex = size
    if not sfft.in_numpy(workers):
        return sfft.fft(sfft.rfft(f, Ex, workers=workers), Ey, -2, workers=workers)
    F = np.zeros(f.shape[:-2] + (Ey, Ex // 2 + 1), np.result_type(f.dtype, np.complex64))
    sfft.rfft(f, Ex, out=F[..., :f.shape[-2], :])
    return sfft.fft(F, None, -2, out=F)


def values_of(F: np.ndarray, rows: int, size: tuple[int, int], workers: int = 1) -> np.ndarray:
    """The inverse of :func:`spectrum_of` on the first ``rows`` rows, all ``E_x`` columns
    (``(..., rows, E_x)``): the columns, then only those rows."""
    return sfft.irfft(sfft.ifft(F, None, -2, workers=workers)[..., :rows, :], size[1], workers=workers)


def wrapped(table: np.ndarray, axis: int, period: int) -> np.ndarray:
    """The kernel ``table`` (offsets ``-(K-1) .. K-1`` along ``axis``) wrapped onto
    ``period`` (at most ``2 K - 2``): offset ``d`` at index ``d mod period`` for ``|d| <=
    period / 2``, the two ends of an even period averaged (they share an index)."""
    centre = (table.shape[axis] - 1) // 2
    d = np.arange(period)
    d = np.where(d > period // 2, d - period, d)
    out = table.take(centre + d, axis=axis)
    if period % 2 == 0 and period > 1:
        half = [slice(None)] * table.ndim
        half[axis] = period // 2
        ends = table.take(centre + period // 2, axis=axis) + table.take(centre - period // 2, axis=axis)
        out[tuple(half)] = 0.5 * ends
    return out


@dataclass(frozen=True)
class Block:
    """The nodes of a block of a grid, for the operator of :meth:`ComplianceOperator.block`:
    ``nodes_x`` columns and ``nodes_y`` rows (positions do not enter the operator)."""

    nodes_x: int
    nodes_y: int

    @property
    def shape(self) -> tuple[int, int]:
        """Field shape ``(nodes_y, nodes_x)``."""
        return (self.nodes_y, self.nodes_x)


@contextmanager
def one_worker():
    """Every transform on one thread while the block runs, on every thread: for two threads
    that solve side by side (the frictional solver's coarse levels and its frictionless
    start), each then on its own core instead of four transform threads on two cores.
    What it saves (section 11 at 513 x 513): :func:`bem.frictional.solve._first_solves`."""
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
        Or anything with its ``shape`` ``(K_y, K_x)`` and ``nodes_x``, ``nodes_y``
        (:class:`bem.plane.LineGrid`, :class:`Block`).
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
        F = spectrum_of(f, self._size, self._workers)
        F *= self._hat
        return values_of(F, Ky, self._size, self._workers)[:, :Kx]

    def apply_transpose(self, forces: np.ndarray) -> np.ndarray:
        """``C^T f`` (the operator is not symmetric in steady rolling): the conjugate
        spectrum of the real kernel turns the circular convolution into a correlation."""
        Ky, Kx = self.grid.shape
        f = np.asarray(forces, dtype=float).reshape(Ky, Kx)
        F = spectrum_of(f, self._size, self._workers)
        F *= np.conj(self._hat)
        return values_of(F, Ky, self._size, self._workers)[:, :Kx]

    @property
    def has_circulant_inverse(self) -> bool:
        """Whether the wrapped circulant of :meth:`circulant_inverse` is safely invertible
        (its smallest eigenvalue modulus above 1e-12 of the largest); computes and keeps
        its inverse spectrum."""
        if not hasattr(self, "_inv_hat"):
            Ky, Kx = self.grid.shape
            self._period = (periodic_size(Ky), periodic_size(Kx))
            table = wrapped(wrapped(self.kernel, 0, self._period[0]), 1, self._period[1])
            self._periodic_hat = sfft.rfft2(table, workers=fft_workers(self._period))
            mag = np.abs(self._periodic_hat)
            self._inv_hat = 1.0 / self._periodic_hat if mag.min() > 1e-12 * mag.max() else None
        return self._inv_hat is not None

    @property
    def periodic_spectrum(self) -> np.ndarray:
        """Eigenvalues (m/N) of the wrapped circulant that :meth:`circulant_inverse` inverts
        (its kernel's ``rfft2``, period :func:`periodic_size` a side), read-only."""
        self.has_circulant_inverse
        out = self._periodic_hat.view()
        out.flags.writeable = False
        return out

    def circulant_inverse(self, values: np.ndarray) -> np.ndarray:
        """The inverse of the kernel's wrapped circulant (period :func:`periodic_size` a
        side, at least the grid's; see the module docstring) applied to ``values``
        (deflections, m, shape ``(K_y, K_x)``, zero-padded to the period), read back on the
        grid (forces, N).

        An approximate inverse of ``C`` restricted to a node set, cheap (two FFTs of the
        period) and spectrally close to it: a preconditioner for Krylov solves on contact
        sets. Raises ``ZeroDivisionError`` if the circulant is (nearly) singular.
        """
        if not self.has_circulant_inverse:
            raise ZeroDivisionError("the wrapped circulant of the compliance is nearly singular")
        Ky, Kx = self.grid.shape
        f = np.asarray(values, dtype=float).reshape(Ky, Kx)
        workers = fft_workers(self._period)
        F = spectrum_of(f, self._period, workers)
        F *= self._inv_hat
        return values_of(F, Ky, self._period, workers)[:, :Kx]

    def block(self, shape: tuple[int, int]) -> "ComplianceOperator":
        """The operator between the nodes of a block of ``shape`` = ``(rows, columns)`` nodes
        anywhere on the grid (entries depend on the node offset only: its kernel is the
        middle of this one's), for products and preconditioners on a contact set's bounding
        box; this operator itself for the whole grid. It is of this operator's class, its
        ``grid`` a :class:`Block`. The last :data:`BLOCKS_KEPT` shapes asked for are kept."""
        Ky, Kx = self.grid.shape
        by, bx = shape
        if not (1 <= by <= Ky and 1 <= bx <= Kx):
            raise ValueError(f"a block of {shape} nodes does not fit in the grid's {self.grid.shape}")
        if (by, bx) == (Ky, Kx):
            return self
        with _BLOCKS_LOCK:  # solves on two threads may share an operator
            kept = self.__dict__.setdefault("_blocks", {})
            op = kept.pop((by, bx), None)
            if op is None:
                op = type(self)(Block(bx, by), self.kernel[Ky - by:Ky + by - 1, Kx - bx:Kx + bx - 1])
            kept[(by, bx)] = op  # the last asked for at the end
            while len(kept) > BLOCKS_KEPT:
                kept.pop(next(iter(kept)))
        return op

    def dense(self, nodes: np.ndarray | None = None) -> np.ndarray:
        """Dense matrix ``C[M, N]`` (m/N) on the flat node indices ``nodes`` (all if None)."""
        Ky, Kx = self.grid.shape
        idx = np.arange(Kx * Ky) if nodes is None else np.asarray(nodes)
        j, i = np.divmod(idx, Kx)
        return self.kernel[(j[:, None] - j[None, :]) + Ky - 1, (i[:, None] - i[None, :]) + Kx - 1]
