"""Inverses of the Toeplitz blocks that a run of contact nodes on one grid row sees, for
every run length at once (:class:`RowInverses`, from :func:`levinson`'s columns by
Gohberg-Semencul's formula), and the second thread their solves and the line
preconditioner share (:func:`second_thread`).

On a grid row the compliance between two nodes depends on their distance alone, so a run
of ``m`` contiguous contact nodes sees Toeplitz blocks: ``C_ww`` in its gap rows and the
upwind-differenced ``a_x C_uu``, ``a_x C_vv`` in its stick rows. The inverse of a Toeplitz
matrix is fixed by its first and last columns (two products of triangular Toeplitz
matrices, ``O(m log m)`` by FFT), and Levinson's recursion gives those columns for every
length up to the longest run at once (``O(M^2)``, once a grid); up to ``dense_upto``
nodes (:class:`~bem.frictional.options.SolverOptions`) the runs take the inverses
themselves, built by bordering for the lengths present and applied one product per length (:class:`GroupedRuns`). Their use, the slip rows by
Woodbury's identity: :mod:`bem.frictional.preconditioner`.
"""

from __future__ import annotations

import os

import numpy as np
from .. import fft as sfft

from .options import SolverOptions

__all__ = ["RowInverses", "GroupedRuns", "levinson", "second_thread"]


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
    (stick rows), from the first and last columns ``x, y`` of ``T^{-1}`` (:func:`levinson`)
    by Gohberg-Semencul's formula

        ``T^{-1} = (L(x) U(J y) - L(Z y) U(Z J x)) / x_0``

    (``L(a)`` and ``U(a)`` the lower and upper triangular Toeplitz matrices with first
    column or row ``a``, ``J`` the reversal, ``Z`` the shift down by one). Two ways to apply
    them:

    * ``dense`` (default: ``M <= dense_upto``): the inverses themselves, built for
      the run lengths asked for (:meth:`inverse`, by bordering from the same columns,
      :meth:`_build`) and kept; the runs of one length are solved by one matrix product
      (:class:`GroupedRuns`);
    * else by transforms of length ``F >= 2 M - 1``: ``U`` is a correlation, ``L`` a
      convolution, each a product of spectra.

    Attributes
    ----------
    M, F : int
        The longest run and the transform length.
    dense : bool
        Whether the inverses are applied themselves.
    spectra : ndarray, shape ``(3, 4, M, F // 2 + 1)``, or None
        Per block (``ww``, ``uu``, ``vv``) and length ``n`` (index ``n - 1``) the spectra of
        ``J y`` and ``Z J x`` (conjugated: correlations) and of ``x / x_0``, ``Z y / x_0``;
        ``None`` when ``dense``.
    units : ndarray, shape ``(M, F // 2 + 1)``, or None
        The spectra of the unit vectors ``e_0 ... e_{M - 1}``; ``None`` when ``dense``.
    batched_upto : int
        :class:`GroupedRuns` pads every run to ``M x M`` up to this ``M``.

    ``dense_upto`` and ``batched_upto``: :class:`~bem.frictional.options.SolverOptions`'
    fields of those names.
    """

    BLOCKS = ("ww", "duu", "dvv")

    def __init__(self, ops, M: int, dense: bool | None = None, *, dense_upto: int = SolverOptions.dense_upto,
                 batched_upto: int = SolverOptions.batched_upto):
        Ky, Kx = ops.grid.shape
        self.batched_upto = batched_upto
        self.M = M = min(M, Kx)
        self.F = F = sfft.next_fast_len(2 * M - 1, real=True)
        ax = ops.grid.spacing_x
        self.dense = M <= dense_upto if dense is None else dense
        # the three blocks' grid rows, in one Levinson recursion and one formula
        t = np.stack([(1.0 if name == "ww" else ax) * ops.tables[name][Ky - 1, Kx - M:Kx - 1 + M]
                      for name in self.BLOCKS])
        try:
            x, y = levinson(t, M)  # (3, M, M)
        except np.linalg.LinAlgError as exc:
            raise np.linalg.LinAlgError(f"{exc} (block {self.BLOCKS[exc.system][-2:]} on a grid row)") from exc
        self._levinson = (x, y)
        self._inverses: dict = {}  # n -> (3, n, n) T_n^{-1}, double
        self._cast: dict = {}
        self._grouped: dict = {}
        self.spectra = self.units = None
        if not self.dense:
            i = np.arange(M)
            src = i[:, None] - i[None, :]  # row n - 1, entry i: entry n - 1 - i of the columns
            rev = src >= 0
            at = np.broadcast_to(np.where(rev, src, 0), x.shape)
            Jx = np.where(rev, np.take_along_axis(x, at, 2), 0.0)
            Jy = np.where(rev, np.take_along_axis(y, at, 2), 0.0)
            ZJx, Zy = np.zeros_like(x), np.zeros_like(y)
            ZJx[:, :, 1:] = np.where(rev[:, 1:], Jx[:, :, :-1], 0.0)
            Zy[:, :, 1:] = np.where(rev[:, 1:], y[:, :, :-1], 0.0)
            x0 = x[:, :, :1]
            spec = sfft.rfft(np.stack([Jy, ZJx, x / x0, Zy / x0], 1), F)
            spec[:, :2] = np.conj(spec[:, :2])
            self.spectra = spec  # (3, 4, M, F // 2 + 1)
            self.units = np.exp(-2j * np.pi / F * np.outer(i, np.arange(F // 2 + 1)))

    def inverse(self, n: int) -> np.ndarray:
        """``T_n^{-1}`` of the three blocks, ``(3, n, n)``, double (built and kept)."""
        n = int(n)
        if not 1 <= n <= self.M:
            raise ValueError(f"a run of {n} nodes: the inverses are for 1 to {self.M}")
        if n not in self._inverses:
            self._build(np.array([n]))
        return self._inverses[n]

    def _build(self, lengths: np.ndarray) -> None:
        """The inverses of the run ``lengths`` not built yet, by bordering: ``T_{n+1}`` is
        ``T_n`` with a row and a column added, and its inverse is ``T_n^{-1}`` (padded
        with 0) plus ``y (J x)^T / x_0``, ``x, y`` the first and last columns of
        ``T_{n+1}^{-1}`` (:func:`levinson`; its last row is ``J x`` and its last diagonal
        entry ``x_0``, a Toeplitz inverse being persymmetric): one rank-one update a
        length, up to the longest asked for, ``O(m^3)`` in all (a few ms at ``m = 112``,
        against 15-25 ms for the lengths of the elastic paraboloid at 121 x 121 one by one by
        Gohberg-Semencul's formula)."""
        todo = {int(n) for n in lengths} - set(self._inverses)
        if not todo:
            return
        m = max(todo)
        x, y = self._levinson
        G = np.zeros((3, m, m))
        for n in range(1, m + 1):
            G[:, :n, :n] += y[:, n - 1, :n, None] * (x[:, n - 1, n - 1::-1] / x[:, n - 1, :1])[:, None, :]
            if n in todo:
                self._inverses[n] = G[:, :n, :n].copy()

    def _transposed(self, n: int, blocks: tuple, dtype) -> np.ndarray:
        """``T_n^{-T}`` of ``blocks``, ``(B, n, n)`` contiguous in ``dtype`` (kept)."""
        key = (n, blocks, np.dtype(dtype))
        if key not in self._cast:
            self._cast[key] = np.ascontiguousarray(self.inverse(n)[list(blocks)].transpose(0, 2, 1), dtype)
        return self._cast[key]

    def operand(self, blocks, lens: np.ndarray, dtype):
        """What :meth:`solve` needs for ``blocks`` (an index or a tuple of them; 0: ``ww``,
        1: ``uu``, 2: ``vv``) on runs of ``lens`` nodes, in real ``dtype``: a
        :class:`GroupedRuns` (``dense``), or the :attr:`spectra` ``(4, B R, F // 2 + 1)``
        in the matching complex type, the blocks one after the other along the runs."""
        blocks = (int(blocks),) if np.ndim(blocks) == 0 else tuple(int(b) for b in blocks)
        lens = np.asarray(lens)
        if self.dense:
            # the distinct lengths (np.unique would import numpy.ma, 8-10 ms of a small run)
            self._build(np.flatnonzero(np.bincount(lens)))
            # kept for the last runs of each blocks and dtype (the contact set's runs repeat
            # over a solve's active-set iterations)
            key = (blocks, np.dtype(dtype))
            last = self._grouped.get(key)
            if last is None or not np.array_equal(last[0], lens):
                self._grouped[key] = last = (lens.copy(), GroupedRuns(self, blocks, lens, dtype))
            return last[1]
        dtype = np.dtype(dtype)
        if dtype not in self._cast:
            self._cast[dtype] = self.spectra.astype(np.result_type(dtype, np.complex64))
        table = self._cast[dtype]
        return np.concatenate([table[b][:, lens - 1] for b in blocks], 1)

    def solve(self, operand, v: np.ndarray, threads: bool = False) -> np.ndarray:
        """``T^{-1} v`` for each row of ``v`` ``(B R, M)`` (a run's values in its first ``n``
        entries, 0 after them; the runs of each block of the operand one after the other),
        ``operand`` the runs' :meth:`operand`; the first ``n`` entries of each result row
        are the run's. With ``threads`` the work is split between two threads (the
        transforms and products release the GIL)."""
        if isinstance(operand, GroupedRuns):
            return operand.apply(v, threads)
        rows = v.shape[0]
        if not threads or rows < 2:
            return self._transform(operand, v)
        half = rows // 2
        job = second_thread().submit(self._transform, operand[:, half:], v[half:])
        first = self._transform(operand[:, :half], v[:half])
        return np.concatenate([first, job.result()])

    def columns(self, b: int, lens: np.ndarray, pos: np.ndarray, dtype) -> np.ndarray:
        """The columns ``pos`` ``(L, P)`` of the inverses of block ``b`` for runs of ``lens``
        (``L``) nodes, as rows ``(L, P, M)`` in real ``dtype`` (0 beyond the run, and for a
        place at or beyond its end)."""
        if self.dense:
            out = np.zeros((len(lens), pos.shape[1], self.M), dtype)
            for i, n in enumerate(lens):
                inside = pos[i] < n
                # rows of T^{-T}, from the stacks the solves read (blocks 0, then 1 and 2)
                GT = self._transposed(int(n), (1, 2), dtype)[b - 1] if b else self._transposed(int(n), (0,), dtype)[0]
                out[i, inside, :n] = GT[pos[i][inside]]
            return out
        spec = self.operand(b, lens, dtype)[:, :, None]
        return self._transform(spec, None, self.units[pos].astype(spec.dtype))

    def _transform(self, spectra, v, unit=None):
        """Gohberg-Semencul by transforms (``unit``: the spectra of ``v``, then not read)."""
        F, M = self.F, self.M
        V = sfft.rfft(v, F) if unit is None else unit
        w = sfft.irfft(np.stack([spectra[0] * V, spectra[1] * V]), F)
        W = sfft.rfft(w[..., :M], F)
        W[0] *= spectra[2]
        W[1] *= spectra[3]
        return sfft.irfft(W[0] - W[1], F)[..., :M]


class GroupedRuns:
    """The dense inverses of :class:`RowInverses` for runs of ``lens`` nodes and ``blocks``:
    for ``M <=`` ``inv.batched_upto`` each run's inverse padded to ``M x M``, one batched
    product for all runs; above it the runs grouped by length, one matrix product per
    length present (``(B, k, n) x (B, n, n)`` for its ``k`` runs; a grid row and its mirror
    have one length, and a contact's rows take few lengths) instead of ``M x M`` per run.
    Measured, the three blocks in single precision: elastic paraboloid at 121 x 121 (101 runs of
    31 lengths, ``M = 112``) 0.51 ms grouped against 1.73 ms by transforms; at 61 x 61 (51
    runs of 16 lengths, ``M = 61``) 0.07 ms batched against 0.13-0.17 ms grouped."""

    def __init__(self, inv: RowInverses, blocks: tuple, lens: np.ndarray, dtype):
        self.blocks, self.dtype, self.runs = len(blocks), np.dtype(dtype), lens.size
        order = np.argsort(lens, kind="stable")
        ordered = lens[order]
        cuts = np.flatnonzero(np.r_[True, ordered[1:] != ordered[:-1], True])
        groups = [(int(a), int(b), int(ordered[a]), inv._transposed(int(ordered[a]), blocks, dtype))
                  for a, b in zip(cuts[:-1], cuts[1:])]
        self.stack = None
        if inv.M <= inv.batched_upto:
            # every run's T^{-T}, padded (rows in the runs' own order)
            M = inv.M
            self.stack = np.zeros((len(blocks), lens.size, M, M), dtype)
            for a, b, n, G in groups:
                self.stack[:, order[a:b], :n, :n] = G[:, None]
            self.groups, self.order = [], None
            self.nbytes = self.stack.nbytes
        else:
            self.groups, self.order = groups, order
            self.nbytes = sum(G.nbytes for *_, G in groups)

    def apply(self, v: np.ndarray, threads: bool = False) -> np.ndarray:
        """``T^{-1} v`` for the rows of ``v`` ``(B R, M)`` (see :meth:`RowInverses.solve`)."""
        B, R = self.blocks, self.runs
        if self.stack is not None:
            vb = v.reshape(B, R, 1, -1)
            if not threads or R < 2:
                return np.matmul(vb, self.stack).reshape(v.shape)
            half = R // 2
            job = second_thread().submit(np.matmul, vb[:, half:], self.stack[:, half:])
            first = np.matmul(vb[:, :half], self.stack[:, :half])
            return np.concatenate([first, job.result()], 1).reshape(v.shape)
        vb = v.reshape(B, R, -1)[:, self.order]
        out = np.zeros_like(vb)

        def part(groups):
            for a, b, n, G in groups:
                np.matmul(vb[:, a:b, :n], G, out=out[:, a:b, :n])

        if threads and len(self.groups) > 1:
            # the longest runs' groups on the second thread, about half the products
            work = np.cumsum([(b - a) * n * n for a, b, n, _ in self.groups])
            cut = int(np.searchsorted(work, work[-1] / 2)) + 1
            job = second_thread().submit(part, self.groups[cut:])
            part(self.groups[:cut])
            job.result()
        else:
            part(self.groups)
        res = np.empty_like(out)
        res[:, self.order] = out
        return res.reshape(v.shape)


def second_thread():
    """One worker thread (a ``concurrent.futures.ThreadPoolExecutor``), started on first
    use and kept (a forked child starts its own: the parent's thread does not exist there,
    and work handed to it would never run)."""
    global _POOL
    if _POOL is None:
        from concurrent.futures import ThreadPoolExecutor  # loaded by the first run on two threads

        _POOL = ThreadPoolExecutor(1, thread_name_prefix="line-preconditioner")
    return _POOL


def _forget_pool() -> None:
    global _POOL
    _POOL = None


_POOL = None
os.register_at_fork(after_in_child=_forget_pool)
