"""The coarse level of the contact solvers' multilevel starts: its grid, the fields and
kernel read on it, and the way back (masks upsampled, values interpolated).

Along an odd-sized axis of ``K`` nodes the coarse level keeps every other node (``(K +
1) / 2``, the same positions); along an even-sized one it puts a node in the middle of
each pair ``(2k, 2k + 1)`` (``K / 2``, so the grid stays centred). Either way the
offsets between coarse nodes are even numbers of fine spacings, so the kernel table read
at even offsets (:func:`coarse_kernel`) is the exact compliance between them. The
frictional solver keeps to odd-sized grids (:func:`coarse_grid`); the frictionless one
coarsens both (:func:`coarse_level`).
"""

from __future__ import annotations

import numpy as np

from .grid import Grid

__all__ = ["coarse_grid", "coarse_level", "restricted", "coarse_kernel", "upsampled", "prolonged"]


def coarse_grid(grid: Grid) -> Grid | None:
    """Every other node of ``grid`` (same period and truncation), or ``None`` when the grid
    is small (< 625 nodes, or < 9 a side) or even-sized: the coarse level of the frictional
    solver's multilevel start (the frictionless one also coarsens even-sized grids,
    :func:`coarse_level`)."""
    Ky, Kx = grid.shape
    if Kx % 2 == 0 or Ky % 2 == 0:
        return None
    return coarse_level(grid)


def coarse_level(grid: Grid) -> Grid | None:
    """The coarse level of the frictionless solver's multilevel start: along an odd-sized
    axis every other node (the same positions), along an even-sized one a node at the
    middle of each pair of neighbours ``(2k, 2k + 1)`` (the grid stays centred); the
    spacing (m) doubled, period (m) and truncation kept. ``None`` when the grid is small (< 625
    nodes, or < 9 a side)."""
    Ky, Kx = grid.shape
    if Kx * Ky < 625 or min(Kx, Ky) < 9:
        return None
    return Grid(2 * grid.spacing_x, 2 * grid.spacing_y, grid.period_x, grid.period_y,
                grid.truncation_x, grid.truncation_y, (Kx + 1) // 2, (Ky + 1) // 2)


def restricted(values: np.ndarray) -> np.ndarray:
    """Nodal values ``(K_y, K_x)`` (a profile in m, say) on :func:`coarse_level`'s nodes,
    in their unit: every other value along an odd-sized axis, the mean of each pair along
    an even-sized one (``inf`` where either is)."""
    out = np.asarray(values, dtype=float)
    for axis in (0, 1):
        a, b = (slice(None),) * axis + (slice(0, None, 2),), (slice(None),) * axis + (slice(1, None, 2),)
        out = out[a] if out.shape[axis] % 2 else 0.5 * (out[a] + out[b])
    return out


def coarse_kernel(kernel: np.ndarray) -> np.ndarray:
    """The kernel table ``(2 K_y - 1, 2 K_x - 1)`` (m/N) at the even node offsets, the offsets of
    :func:`coarse_level`'s nodes (from the middle entry, offset 0: every other entry when
    ``K`` is odd, the odd-indexed ones when it is even)."""
    Ky, Kx = (kernel.shape[0] + 1) // 2, (kernel.shape[1] + 1) // 2
    return kernel[(Ky + 1) % 2::2, (Kx + 1) % 2::2]


def upsampled(coarse: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """A coarse mask on the grid of ``shape``: each coarse node on the fine node it stands
    for (odd-sized axis) or on both of its pair (even-sized axis)."""
    out = np.asarray(coarse, dtype=bool)
    for axis, n in enumerate(shape):
        if n % 2:
            up = np.zeros(out.shape[:axis] + (n,) + out.shape[axis + 1:], dtype=bool)
            up[(slice(None),) * axis + (slice(0, None, 2),)] = out
            out = up
        else:
            out = np.repeat(out, 2, axis=axis)
    return out


def prolonged(coarse: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Nodal values on :func:`coarse_level`'s nodes interpolated linearly along each axis
    onto the grid of ``shape``, in their unit (beyond the outermost coarse nodes, their
    values; nodal forces in N need the area ratio, 1/4, on top)."""
    out = np.asarray(coarse, dtype=float)
    for axis, n in enumerate(shape):
        m = out.shape[axis]
        pos = np.arange(n) / 2.0 if n % 2 else (np.arange(n) - 0.5) / 2.0  # in coarse nodes
        pos = np.clip(pos, 0.0, m - 1.0)
        lo = np.minimum(np.floor(pos).astype(int), m - 1)
        hi = np.minimum(lo + 1, m - 1)
        w = (pos - lo).reshape((-1,) + (1,) * (out.ndim - axis - 1))
        out = out.take(lo, axis=axis) * (1 - w) + out.take(hi, axis=axis) * w
    return out
