"""The nine compliance blocks of a grid for frictional rolling, applied by FFT or read
densely on node subsets (SI units: kernels in m/N, differenced kernels in 1/N)."""

from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np
from .. import fft as sfft

from ..grid import Grid
from ..kinematics import upwind_table
from ..operator import ComplianceOperator, fft_workers, periodic_size, spectrum_of, values_of, wrapped
from ..plane import LineGrid
from .options import SolverOptions

__all__ = ["RollingOperators", "DIFFERENCED", "FIELDS"]

#: blocks whose upwind x-difference enters the slip velocity (rows u and v)
DIFFERENCED = ("uw", "uu", "uv", "vw", "vu", "vv")
#: the signed blocks of :meth:`RollingOperators.fields`: deflection, then the upwind strains
FIELDS = (((1, "ww"), (-1, "wu"), (-1, "wv")),
          ((-1, "duw"), (1, "duu"), (1, "duv")),
          ((-1, "dvw"), (1, "dvu"), (1, "dvv")))


class RollingOperators:
    """The nine kernel tables of a grid and the upwind-differenced ``u, v`` rows
    (``"d" + block``, :func:`bem.kinematics.upwind_table`), their FFT operators (built on
    demand) and dense blocks on node subsets.

    Parameters
    ----------
    grid : Grid or LineGrid
        A :class:`bem.plane.LineGrid` (plane strain, one row) takes the tables of
        :func:`bem.plane.line_kernels` (per unit length, m/(N/m)).
    kernels : dict
        The nine blocks of :func:`bem.spectral.influence_kernels` for ``grid`` (m/N).
    tables : dict, optional
        The kernel and differenced tables when already known (a :meth:`window`'s).
    """

    def __init__(self, grid: Grid, kernels: dict, tables: dict | None = None):
        self.grid = grid
        self.kernels = kernels
        if tables is None:
            tables = {b: kernels[b] for b in ("ww", "wu", "wv")}
            for b in DIFFERENCED:
                tables["d" + b] = upwind_table(kernels[b], grid.spacing_x)
        self.tables = tables
        self._ops: dict = {}
        self._stacked: dict = {}
        self._filters: dict = {}
        self._placing: dict = {}
        self._windows: dict = {}

    @property
    def diagonal(self) -> float:
        """``C_ww`` of a node on itself (m/N), the scale of the rows written in metres."""
        g = self.grid
        return float(self.tables["ww"][g.nodes_y - 1, g.nodes_x - 1])

    def op(self, name: str) -> ComplianceOperator:
        """The FFT operator of block ``name`` (a kernel or a differenced table)."""
        if name not in self._ops:
            table = self.tables[name] if name in self.tables else self.kernels[name]
            self._ops[name] = ComplianceOperator(self.grid, table)
        return self._ops[name]

    def dense(self, name: str, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """Block ``name`` between flat node indices ``rows`` and ``cols``."""
        Ky, Kx = self.grid.shape
        jr, ir = np.divmod(rows, Kx)
        jc, ic = np.divmod(cols, Kx)
        table, di = self.tables[name], (ir[:, None] - ic[None, :]) + Kx - 1
        if jr.size and jc.size and jr.min() == jr.max() and jc.min() == jc.max():
            # rows and columns each on one grid row (a line of the preconditioner): one row
            # of the table, read 5x faster than by two index arrays
            return table[jr[0] - jc[0] + Ky - 1][di]
        return table[(jr[:, None] - jc[None, :]) + Ky - 1, di]

    def _convolve(self, names, f):
        """``sum_j sign_j K_j * f_j`` for each row of ``names`` (block names with signs,
        ``-`` for the normal force ``-N``) and the stacked force fields ``f`` ``(3, K_y,
        K_x)``: one batched forward transform, the signed spectra (stacked once per set of
        rows) multiplied in, one batched inverse transform; an array ``(rows, K_y, E_x)``
        whose first ``K_x`` columns are the grid's (``E_x`` the embedding's width); in single
        precision when ``f`` is ``float32``."""
        key = (names, f.dtype)
        spectra = self._stacked.get(key)
        if spectra is None:
            spectra = np.stack([np.stack([sign * self.op(name).spectrum for sign, name in row]) for row in names])
            spectra = self._stacked[key] = spectra.astype(np.complex64 if f.dtype == np.float32 else np.complex128,
                                                          copy=False)
        workers = self._workers()
        F = self._forward(f, workers)
        acc = spectra[:, 0] * F[0]
        acc += spectra[:, 1] * F[1]
        acc += spectra[:, 2] * F[2]
        return self._inverse(acc, workers)

    def _workers(self) -> int:
        """Threads of the transforms (:func:`bem.operator.fft_workers` of the embedding)."""
        return fft_workers(self.op("ww").embedding)

    # the 2-D transforms one axis at a time, skipping the embedding's zero rows on the way
    # in and the rows off the grid on the way out (40-55 % less work than rfft2), on the
    # callers' threads
    def _forward(self, f, workers):
        return spectrum_of(f, self.op("ww").embedding, workers)

    def _inverse(self, F, workers):
        return values_of(F, self.grid.nodes_y, self.op("ww").embedding, workers)

    @functools.cached_property
    def filter_size(self) -> tuple[int, int]:
        """The period ``(E_y, E_x)`` of :meth:`row_filter` and :meth:`filter_on`: per axis
        the transform-friendly length (factors 2, 3, 5) from ``1.5 K`` nodes on, at most
        :func:`bem.operator.periodic_size` (at most ``2 K - 2``, at least ``K``)."""
        return tuple(min(sfft.next_fast_len(-(-3 * K // 2), real=True), periodic_size(K))
                     for K in self.grid.shape)

    def row_filter(self, power: float, dtype=np.complex128, *, long: float | None = None,
                   waves: float = SolverOptions.filter_waves) -> np.ndarray:
        """The spectra ``(3, E_y, E_x / 2 + 1)`` of ``(C_row / C) ** q`` for the blocks
        ``ww, uu, vv`` on the period ``(E_y, E_x)`` = :attr:`filter_size` (-): ``C`` the
        symbol of the block's kernel wrapped onto that period (every offset within half a
        period at its true value, as the circulant of :meth:`bem.operator.
        ComplianceOperator.circulant_inverse`), ``C_row`` that of its row through the
        origin (``C`` averaged over ``k_y``), what a solve on lines along ``x`` sees. Where
        ``|C|`` is below 1e-3 of its largest it is taken as that floor. The exponent ``q``
        is ``power``; with ``long`` it runs from ``long`` on the longest waves to ``power``
        on the short ones, ``q = power + (long - power) exp(-(n / waves)^2)``, ``n`` the
        number of waves across this grid (``hypot(f_x K_x, f_y K_y)``, ``f`` in cycles a
        node, ``K`` the nodes a side). Computed in double precision, kept per exponent and
        ``dtype``; see :mod:`bem.frictional.preconditioner`, which has the figures of the
        wrapped period against the products' zero-padded embedding."""
        key = (power, long, waves, np.dtype(dtype))
        if key not in self._filters:
            Ky, Kx = self.grid.shape
            Ey, width = self.filter_size
            q = power
            if long is not None:
                n = np.hypot(np.fft.rfftfreq(width)[None, :] * Kx, np.fft.fftfreq(Ey)[:, None] * Ky)
                q = power + (long - power) * np.exp(-(n / waves) ** 2)
            out = []
            for name in ("ww", "uu", "vv"):
                table = self.tables[name] if name in self.tables else self.kernels[name]
                table = wrapped(wrapped(table, 0, Ey), 1, width)
                full = sfft.rfft2(table)
                mag = np.abs(full)
                full = np.where(mag < 1e-3 * mag.max(), 1e-3 * mag.max(), full)
                # the row through the origin: its transform along x is C averaged over k_y
                out.append((sfft.rfft(table[0]) / full) ** q)
            self._filters[key] = np.stack(out).astype(dtype)
        return self._filters[key]

    def _stack(self, N, Sx, Sy):
        Ky, Kx = self.grid.shape
        f = np.empty((3, Ky, Kx))
        for i, a in enumerate((N, Sx, Sy)):
            f[i] = np.asarray(a, float).reshape(Ky, Kx)
        return f

    def fields(self, N, Sx, Sy):
        """Downward deflection (m) and upwind strains ``du/dx, dv/dx`` (-) on the grid from
        the normal forces ``N`` (compressive) and tangential forces ``S_x, S_y`` (N)."""
        return self._convolve(FIELDS, self._stack(N, Sx, Sy))[:, :, :self.grid.nodes_x]

    def fields_on(self, nodes: np.ndarray, forces: np.ndarray, dtype=np.float64) -> np.ndarray:
        """:meth:`fields` ``(3, k)`` at the flat node indices ``nodes`` (``k``) of the forces
        ``forces = (N, S_x, S_y)`` ``(3, k)`` on those nodes, 0 elsewhere: the product of
        an iterative solve, without full-grid copies in and out; transformed and
        multiplied in ``dtype`` (``float32``: single precision, about half the time)."""
        return self._gather(self._convolve(FIELDS, self._scatter(nodes, forces, dtype)), nodes)

    def filter_on(self, nodes: np.ndarray, values: np.ndarray, spectra: np.ndarray) -> np.ndarray:
        """The three rows of ``values`` ``(3, k)`` on the flat node indices ``nodes`` (``k``),
        0 elsewhere, each multiplied in Fourier space by its row of ``spectra`` on the
        period :attr:`filter_size` (:meth:`row_filter`), read back at ``nodes``; in single
        precision when ``spectra`` is ``complex64``."""
        real = np.float32 if spectra.dtype == np.complex64 else np.float64
        size = self.filter_size
        workers = fft_workers(size)
        F = spectrum_of(self._scatter(nodes, values, real, size[1]), size, workers)
        F *= spectra
        return self._gather(values_of(F, self.grid.nodes_y, size, workers), nodes, size[1])

    def _scatter(self, nodes, values, dtype=np.float64, width=None):
        """``values`` ``(3, k)`` at the flat grid indices ``nodes``, 0 elsewhere, in rows
        ``width`` wide ``(3, K_y, width)``, by default the embedding's: the forward
        transform along ``x`` then reads them without a zero-padded copy."""
        Ky, width = self.grid.nodes_y, width or self.op("ww").embedding[1]
        f = np.zeros((3, Ky * width), dtype)
        flat, mask = self._placed(nodes, width)
        if mask is None:
            f[:, flat] = values
        else:  # sorted nodes: a boolean mask per row, 5x faster than the fancy-indexed copy
            for row, vals in zip(f, values):
                row[mask] = vals
        return f.reshape(3, Ky, width)

    def _gather(self, out, nodes, width=None):
        """``out`` ``(rows, K_y, width)`` (by default the embedding's width) read at the flat
        grid indices ``nodes``."""
        return np.take(out.reshape(out.shape[0], -1), self._placed(nodes, width)[0], axis=1)

    def _placed(self, nodes, width=None):
        """For the flat grid indices ``nodes``: their flat positions in rows ``width`` wide
        (by default the embedding's) and, when they increase, the boolean mask of those
        positions (else ``None``); kept per width for the last ``nodes`` array (the same one
        in every product of a solve)."""
        width = width or self.op("ww").embedding[1]
        last = self._placing.get(width)
        if last is None or last[0] is not nodes:
            j, i = np.divmod(nodes, self.grid.nodes_x)
            mask = None
            flat = j * width + i
            if np.all(np.diff(nodes) > 0):
                mask = np.zeros(self.grid.nodes_y * width, bool)
                mask[flat] = True
            last = self._placing[width] = (nodes, (flat, mask))
        return last[1]

    def displacements(self, N, Sx, Sy):
        """Horizontal surface displacements ``u, v`` (m)."""
        return self._convolve((((-1, "uw"), (1, "uu"), (1, "uv")),
                               ((-1, "vw"), (1, "vu"), (1, "vv"))), self._stack(N, Sx, Sy))[:, :, :self.grid.nodes_x]

    def window(self, shape: tuple[int, int]) -> "RollingOperators":
        """The operators of a box of ``shape = (K_y', K_x')`` nodes of the grid: the tables
        read at the offsets such a box spans (every table, the differenced ones included,
        as the whole grid's). By translation invariance :meth:`fields` of forces inside the
        box, read inside the box, equals the whole grid's there, on an embedding of about
        ``(2 K_y') x (2 K_x')`` instead of ``(2 K_y) x (2 K_x)``; kept per shape."""
        Ky, Kx = self.grid.shape
        By, Bx = shape
        if not (1 <= By <= Ky and 1 <= Bx <= Kx):
            raise ValueError(f"a window of {shape} nodes must fit in the grid's {self.grid.shape}")
        if (By, Bx) == (Ky, Kx):
            return self
        if shape not in self._windows:
            cut = (slice(Ky - By, Ky + By - 1), slice(Kx - Bx, Kx + Bx - 1))
            box = replace(self.grid, nodes=Bx) if isinstance(self.grid, LineGrid) else \
                replace(self.grid, nodes_x=Bx, nodes_y=By)
            self._windows[shape] = RollingOperators(box,
                                                    {b: k[cut] for b, k in self.kernels.items()},
                                                    {b: t[cut] for b, t in self.tables.items()})
        return self._windows[shape]

    def window_around(self, rows: np.ndarray, cols: np.ndarray) -> tuple["RollingOperators", int, int]:
        """The :meth:`window` of a box holding the nodes at grid ``rows`` and ``cols`` (index
        arrays), and the box's first row and column. Each side is widened to the longest
        one with the same transform length (``(E + 1) // 2`` nodes for an embedding of ``E``,
        within the grid; the box moved back inside it where it would leave): the products
        cost the same, and the contact sets of one solve, whose bounding boxes differ by a
        node or two, share one window instead of building nine spectra each."""
        Ky, Kx = self.grid.shape

        def side(idx, K):
            lo = int(idx.min())
            n = int(idx.max()) - lo + 1
            n = min(K, (sfft.next_fast_len(2 * n - 1, real=True) + 1) // 2)  # >= n: the length is >= 2 n - 1
            return n, min(lo, K - n)

        (By, j0), (Bx, i0) = side(rows, Ky), side(cols, Kx)
        return self.window((By, Bx)), j0, i0

    def coarse(self, grid: Grid) -> "RollingOperators":
        """The operators of every other node (``grid`` from :func:`bem.contact.coarse_grid`):
        the kernel tables read at even offsets."""
        return RollingOperators(grid, {b: k[::2, ::2] for b, k in self.kernels.items()})
