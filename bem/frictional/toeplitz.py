"""Inverses of the Toeplitz blocks that a run of contact nodes on one grid row sees, for
every run length at once (:class:`RowInverses`, from :func:`levinson`'s columns by
Gohberg-Semencul's formula), and the second thread their solves and the line
preconditioner share (:func:`second_thread`).

On a grid row the compliance between two nodes depends on their distance alone, so a run
of ``m`` contiguous contact nodes sees Toeplitz blocks: ``C_ww`` in its gap rows and the
upwind-differenced ``a_x C_uu``, ``a_x C_vv`` in its stick rows. The inverse of a Toeplitz
matrix is fixed by its first and last columns (two products of triangular Toeplitz
matrices, ``O(m log m)`` by FFT), and Levinson's recursion gives those columns for every
length up to the longest run at once (``O(M^2)``, once a grid); runs of up to
:data:`DENSE_UPTO` nodes take the inverses themselves, from the same formula. Their use,
the slip rows by Woodbury's identity: :mod:`bem.frictional.preconditioner`.
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import scipy.fft as sfft

__all__ = ["RowInverses", "levinson", "second_thread", "DENSE_UPTO"]

#: when the longest run (rounded up to 16 nodes) has at most this many nodes, every run is
#: solved by its inverse itself (:attr:`RowInverses.matrices`, ``24 M^3`` bytes), else by
#: transforms. Measured (one application against the former dense line inverses, alternated
#: 40 times, new / old): issue case 61 x 61 1.15 by inverses, 1.71 by transforms; runs of up
#: to 112 nodes (121 x 121, 129 x 129) 1.12-1.25 by inverses, 0.98-1.21 by transforms
DENSE_UPTO = 96


def levinson(t: np.ndarray, M: int) -> tuple[np.ndarray, np.ndarray]:
    """The first and last columns of ``T_n^{-1}`` for ``n = 1 ... M``, ``T_n`` the ``n x n``
    Toeplitz matrix ``T_n[i, j] = t[M - 1 + i - j]`` (``t``: ``2 M - 1`` values, offsets
    ``-(M - 1) ... M - 1``): two arrays ``(M, M)`` whose row ``n - 1`` holds them in its
    first ``n`` entries. Levinson's recursion for a nonsymmetric matrix, ``O(M^2)``: with
    ``x, y`` the columns of size ``n``, ``[x; 0]`` and ``[0; y]`` solve ``T_{n+1}`` up to one
    residual entry each, and their two combinations that cancel it are the columns of size
    ``n + 1``. ``t`` may hold several matrices, ``(B, 2 M - 1)``: all run in the same loop
    and the arrays are ``(B, M, M)``. Raises :class:`numpy.linalg.LinAlgError` when a leading
    block is singular to working precision (the recursion needs every one regular); with
    several matrices its ``system`` attribute is the index of the first such one."""
    t = np.asarray(t, float)
    T = t.reshape(-1, t.shape[-1])
    B, c = T.shape[0], M - 1
    first, last = np.zeros((B, M, M)), np.zeros((B, M, M))

    def check(bad, message):
        if bad.any():
            exc = np.linalg.LinAlgError(message)
            exc.system = int(np.flatnonzero(bad)[0])
            raise exc

    check(T[:, c] == 0, "Levinson's recursion: zero diagonal")
    first[:, 0, 0] = last[:, 0, 0] = 1.0 / T[:, c]
    for n in range(1, M):
        x, y = first[:, n - 1, :n], last[:, n - 1, :n]
        ex = np.einsum("bj,bj->b", T[:, c + n:c:-1], x)  # row n of T_{n+1} on [x; 0]
        ey = np.einsum("bj,bj->b", T[:, c - 1::-1][:, :n], y)  # row 0 of T_{n+1} on [0; y]
        den = 1.0 - ex * ey
        check(np.abs(den) < 1e-12, f"Levinson's recursion: the leading {n + 1} x {n + 1} block is singular")
        first[:, n, :n] = x
        first[:, n, 1:n + 1] -= ex[:, None] * y
        last[:, n, 1:n + 1] = y
        last[:, n, :n] -= ey[:, None] * x
        first[:, n, :n + 1] /= den[:, None]
        last[:, n, :n + 1] /= den[:, None]
    return (first[0], last[0]) if t.ndim == 1 else (first, last)


class RowInverses:
    """The inverses of the Toeplitz blocks of a run of ``n`` contact nodes on a grid row,
    ``n = 1 ... M``: ``C_ww`` (gap rows) and ``a_x C_uu``, ``a_x C_vv`` upwind-differenced
    (stick rows), as the spectra of Gohberg-Semencul's formula

        ``T^{-1} = (L(x) U(J y) - L(Z y) U(Z J x)) / x_0``

    (``x, y`` the first and last columns of ``T^{-1}`` from :func:`levinson`, ``L(a)`` and
    ``U(a)`` the lower and upper triangular Toeplitz matrices with first column or row
    ``a``, ``J`` the reversal, ``Z`` the shift down by one) on transforms of length ``F >= 2 M
    - 1``: ``U`` is a correlation, ``L`` a convolution, each a product of spectra.

    Attributes
    ----------
    M, F : int
        The longest run and the transform length.
    spectra : ndarray, shape ``(3, 4, M, F // 2 + 1)``, or None
        Per block (``ww``, ``uu``, ``vv``) and length ``n`` (index ``n - 1``) the spectra of
        ``J y`` and ``Z J x`` (conjugated: correlations) and of ``x / x_0``, ``Z y / x_0``;
        ``None`` with ``matrices`` (not read then).
    units : ndarray, shape ``(M, F // 2 + 1)``, or None
        The spectra of the unit vectors ``e_0 ... e_{M - 1}``; ``None`` with ``matrices``.
    matrices : ndarray, shape ``(3, M, M, M)``, or None
        With ``dense`` (default: ``M <=`` :data:`DENSE_UPTO`) the inverses themselves, per
        block and length (``T_n^{-1}`` in the leading ``n x n`` of index ``n - 1``, 0
        around it), from the same formula: runs this short are applied faster by batched
        products than by transforms.
    """

    BLOCKS = ("ww", "duu", "dvv")

    def __init__(self, ops, M: int, dense: bool | None = None):
        Ky, Kx = ops.grid.shape
        self.M = M = min(M, Kx)
        self.F = F = sfft.next_fast_len(2 * M - 1, real=True)
        ax = ops.grid.spacing_x
        i = np.arange(M)
        src = i[:, None] - i[None, :]  # row n - 1, entry i: entry n - 1 - i of the columns
        rev = src >= 0
        src = np.where(rev, src, 0)
        dense = M <= DENSE_UPTO if dense is None else dense
        self.spectra = None
        self.matrices = np.empty((3, M, M, M)) if dense else None
        # the three blocks' grid rows, in one Levinson recursion and one formula
        t = np.stack([(1.0 if name == "ww" else ax) * ops.tables[name][Ky - 1, Kx - M:Kx - 1 + M]
                      for name in self.BLOCKS])
        try:
            x, y = levinson(t, M)  # (3, M, M)
        except np.linalg.LinAlgError as exc:
            raise np.linalg.LinAlgError(f"{exc} (block {self.BLOCKS[exc.system][-2:]} on a grid row)") from exc
        at = np.broadcast_to(src, x.shape)
        Jx = np.where(rev, np.take_along_axis(x, at, 2), 0.0)
        Jy = np.where(rev, np.take_along_axis(y, at, 2), 0.0)
        ZJx, Zy = np.zeros_like(x), np.zeros_like(y)
        ZJx[:, :, 1:] = np.where(rev[:, 1:], Jx[:, :, :-1], 0.0)
        Zy[:, :, 1:] = np.where(rev[:, 1:], y[:, :, :-1], 0.0)
        x0 = x[:, :, :1]
        if not dense:
            spec = sfft.rfft(np.stack([Jy, ZJx, x / x0, Zy / x0], 1), F)
            spec[:, :2] = np.conj(spec[:, :2])
            self.spectra = spec  # (3, 4, M, F // 2 + 1)
        else:
            # the formula entry by entry: T^{-1}[i, j] = T^{-1}[i - 1, j - 1] + D[i, j],
            # D = (x (J y)^T - (Z y) (Z J x)^T) / x_0 (0 beyond each length)
            D = x[..., None] * Jy[:, :, None, :]
            D -= Zy[..., None] * ZJx[:, :, None, :]
            D /= x0[..., None]
            G = self.matrices
            G[:, :, 0] = D[:, :, 0]
            for r in range(1, M):
                G[:, :, r, 0] = D[:, :, r, 0]
                np.add(G[:, :, r - 1, :-1], D[:, :, r, 1:], out=G[:, :, r, 1:])
            G *= rev[:, :, None] & rev[:, None, :]  # the sums run on along the diagonals
        self.units = None if dense else np.exp(-2j * np.pi / F * np.outer(i, np.arange(F // 2 + 1)))
        self._cast: dict = {}

    def operand(self, b: int, lens: np.ndarray, dtype) -> np.ndarray:
        """What :meth:`solve` needs for block ``b`` (0: ``ww``, 1: ``uu``, 2: ``vv``) on
        runs of ``lens`` nodes, in real ``dtype``: their :attr:`matrices` ``(R, M, M)``, or
        their :attr:`spectra` ``(4, R, F // 2 + 1)`` in the matching complex type."""
        dtype = np.dtype(dtype)
        if dtype not in self._cast:
            self._cast[dtype] = (self.matrices if self.matrices is not None else self.spectra).astype(
                dtype if self.matrices is not None else np.result_type(dtype, np.complex64))
        table = self._cast[dtype][b]
        return table[lens - 1] if self.matrices is not None else table[:, lens - 1]

    def solve(self, operand: np.ndarray, v: np.ndarray, threads: bool = False) -> np.ndarray:
        """``T^{-1} v`` for each row of ``v`` ``(R, M)`` (a run's values in its first ``n``
        entries, 0 after them), ``operand`` the runs' :meth:`operand`; the first ``n``
        entries of each result row are the run's. With ``threads`` the rows are split
        between two threads (the transforms and products release the GIL)."""
        dense = self.matrices is not None
        rows = v.shape[0]
        if not threads or rows < 2:
            return self._apply(operand, v, dense)
        half = rows // 2
        lo, hi = ((operand[:half], operand[half:]) if dense else (operand[:, :half], operand[:, half:]))
        job = second_thread().submit(self._apply, hi, v[half:], dense)
        first = self._apply(lo, v[:half], dense)
        return np.concatenate([first, job.result()])

    def _apply(self, operand, v, dense):
        return np.matmul(operand, v[:, :, None])[:, :, 0] if dense else self._transform(operand, v)

    def columns(self, b: int, lens: np.ndarray, pos: np.ndarray, dtype, threads: bool = False) -> np.ndarray:
        """The columns ``pos`` ``(L, P)`` of the inverses of block ``b`` for runs of ``lens``
        (``L``) nodes, as rows ``(L, P, M)`` in real ``dtype``."""
        if self.matrices is not None:
            mats = self.operand(b, lens, dtype)
            return np.take_along_axis(mats, pos[:, None, :], 2).swapaxes(1, 2)
        spec = self.operand(b, lens, dtype)[:, :, None]
        unit = self.units[pos].astype(spec.dtype)
        if not threads or len(lens) < 2:
            return self._transform(spec, None, unit)
        half = len(lens) // 2
        job = second_thread().submit(self._transform, spec[:, half:], None, unit[half:])
        first = self._transform(spec[:, :half], None, unit[:half])
        return np.concatenate([first, job.result()])

    def _transform(self, spectra, v, unit=None):
        """Gohberg-Semencul by transforms (``unit``: the spectra of ``v``, then not read)."""
        F, M = self.F, self.M
        V = sfft.rfft(v, F) if unit is None else unit
        w = sfft.irfft(np.stack([spectra[0] * V, spectra[1] * V]), F)
        W = sfft.rfft(w[..., :M], F)
        W[0] *= spectra[2]
        W[1] *= spectra[3]
        return sfft.irfft(W[0] - W[1], F)[..., :M]


def second_thread() -> ThreadPoolExecutor:
    """One worker thread, started on first use and kept (a forked child starts its own:
    the parent's thread does not exist there, and work handed to it would never run)."""
    global _POOL
    if _POOL is None:
        _POOL = ThreadPoolExecutor(1, thread_name_prefix="line-preconditioner")
    return _POOL


def _forget_pool() -> None:
    global _POOL
    _POOL = None


_POOL: ThreadPoolExecutor | None = None
os.register_at_fork(after_in_child=_forget_pool)
