"""Structured, graded triangle mesh of the plane-strain layer section (x, z).

The rectangle [-downstream, upstream] x [0, H] is cut by horizontal node lines z_j into
rows; the top line carries the vertical node lines x_i: uniform spacing ``h`` on the
candidate zone |x| <= Z, growing as h + grading * distance outside it, capped at
``far_x`` (along x). The rows are h tall in a band of depth ``band`` under the top
surface and grow as h + grading * depth below it, capped at ``far_z``.

Every row of element edges is aligned with x, the flow direction of the rolling
material, so the element x-extent (the SUPG length) is known per element. Below the
band the x-spacing follows the row height: going down, a node line drops every other
node wherever the merged spacing would still be at most ``aspect`` times the height of
the row above it (a 2:1 transition row: each coarse interval under two fine ones is
cut into three triangles, a fan from the middle top node). The number of unknowns then
grows like log(H / h) instead of (number of zone columns) x log(H / h): a deep layer
costs little more than a shallow one. ``aspect = None`` keeps every x line through the
whole depth (the tensor-product mesh).

Quadrilaterals are cut along the diagonal that rises towards x = 0 and the transitions
are made outward from x = 0 on both sides, so the mesh is the mirror image of itself
about x = 0 wherever the node lines are (the candidate zone and its grading): a
symmetric load gives a symmetric answer (one diagonal direction everywhere gave a
spurious R_r of 1e-5 of P b / R on an elastic layer).

Named boundaries: ``base`` (z = 0, bonded), ``inflow`` (x = upstream: material
enters), ``outflow`` (x = -downstream: material leaves), ``zone`` (z = H, |x| <= Z:
the candidate contact zone) and ``free`` (z = H, |x| > Z). Lengths in m.
"""

from __future__ import annotations

import numpy as np
from skfem import MeshTri

__all__ = ["ASPECT", "coarsen_line", "graded_nodes", "plane_mesh"]


def graded_nodes(start: float, stop: float, h: float, grading: float, far: float) -> np.ndarray:
    """Node positions from ``start`` to ``stop`` (m, either order) with spacings
    h + grading * distance from ``start``, capped at ``far``; the last spacing is
    merged into the one before when it would be shorter than half of it."""
    sign = 1.0 if stop >= start else -1.0
    length = abs(stop - start)
    pos = [0.0]
    while pos[-1] < length:
        step = min(h + grading * pos[-1], far)
        if pos[-1] + 1.5 * step >= length:
            if length - pos[-1] < 0.5 * step and len(pos) > 1:
                pos[-1] = length
            else:
                pos.append(length)
            break
        pos.append(pos[-1] + step)
    return start + sign * np.asarray(pos)


def _axis(center_lo, center_hi, h, lo, hi, grading, far_lo, far_hi):
    n = max(int(np.ceil((center_hi - center_lo) / h - 1e-9)), 1)
    mid = np.linspace(center_lo, center_hi, n + 1)
    left = graded_nodes(center_lo, lo, h, grading, far_lo)[::-1] if lo < center_lo else np.array([lo])
    right = graded_nodes(center_hi, hi, h, grading, far_hi) if hi > center_hi else np.array([hi])
    return np.unique(np.concatenate([left[:-1], mid, right[1:]]))


#: default largest x-spacing over the height of the row above a node line (-): below the
#: band a line drops every other node where the merged spacing stays under this. Measured
#: (H = 160 b0, h = b0 / 30, band Z / 2, V tau / b0 = 1; R_r against Hunter, of its
#: peak): every x line -0.102% (97 984 unknowns), ASPECT 0.5 -0.114% (74 772), 1 -0.150%
#: (70 990), 2 -0.357% (66 724): the SUPG-advected viscous strains want the x-spacing
#: well under the depth they vary over
ASPECT = 0.5
_MODULE_ASPECT = object()  # plane_mesh's default: ASPECT as it is at the call


def _coarsen_half(xs: np.ndarray, target: float) -> np.ndarray:
    """Indices (into ``xs``, ordered outward from its first entry, which is kept) of the
    nodes a coarser line keeps: walking outward, the next node is skipped when the two
    intervals it separates together span at most ``target`` (m); the last node stays."""
    keep = [0]
    i, n = 0, len(xs) - 1
    while i < n:
        if i + 2 <= n and abs(xs[i + 2] - xs[i]) <= target * (1 + 1e-12):
            i += 2
        else:
            i += 1
        keep.append(i)
    return np.asarray(keep)


def coarsen_line(x: np.ndarray, target: float) -> np.ndarray:
    """Boolean mask of the nodes of the sorted line ``x`` (m) kept on the line below:
    every other node dropped where two merged intervals span at most ``target`` (m),
    outward from x = 0 on each side (mirror-symmetric where ``x`` is); the end nodes and
    the node at x = 0 (or both ends of the interval across it) are kept."""
    n = len(x)
    tol = 1e-9 * (x[-1] - x[0])
    k = int(np.argmin(np.abs(x)))
    if abs(x[k]) <= tol:
        right0, left0 = k, k
    else:  # no node at 0: the interval across it is kept whole
        right0 = k if x[k] > 0 else k + 1
        left0 = right0 - 1
    mask = np.zeros(n, bool)
    if right0 < n:
        mask[right0 + _coarsen_half(x[right0:], target)] = True
    if left0 >= 0:
        mask[left0 - _coarsen_half(x[left0::-1], target)] = True
    return mask


def _row_triangles(top: np.ndarray, bottom: np.ndarray, x_top: np.ndarray, x_bottom: np.ndarray):
    """Triangles (3, m) of one row between a node line with ids ``top`` at ``x_top`` and
    the line under it with ids ``bottom`` at ``x_bottom`` (a subset of ``x_top``): under
    each bottom interval one top interval (a quadrilateral, cut along the diagonal rising
    towards x = 0) or two (three triangles fanning from the middle top node)."""
    pos = np.searchsorted(x_top, x_bottom)
    tris = []
    for m in range(len(bottom) - 1):
        i0, i1 = pos[m], pos[m + 1]
        b0, b1 = bottom[m], bottom[m + 1]
        if i1 - i0 == 1:
            t0, t1 = top[i0], top[i1]
            if 0.5 * (x_top[i0] + x_top[i1]) < 0:
                tris += [(b0, b1, t1), (b0, t1, t0)]
            else:
                tris += [(b0, b1, t0), (b1, t1, t0)]
        elif i1 - i0 == 2:
            t0, tm, t1 = top[i0], top[i0 + 1], top[i1]
            tris += [(b0, tm, t0), (b0, b1, tm), (b1, t1, tm)]
        else:  # pragma: no cover - coarsen_line merges pairs only
            raise AssertionError("a transition row may merge two intervals at most")
    return np.asarray(tris).T


def _transition_mesh(x: np.ndarray, z: np.ndarray, fixed_rows: int, aspect) -> MeshTri:
    """Triangles of the rows between the node lines ``z`` (increasing; the top line
    carries all of ``x``), the x-lines thinned going down (module docstring); the top
    ``fixed_rows`` rows keep every x line. ``aspect`` None: no thinning."""
    nz = len(z)
    masks = [None] * nz
    masks[-1] = np.ones(len(x), bool)
    for j in range(nz - 2, -1, -1):  # line j under row (j, j + 1)
        mask = masks[j + 1].copy()
        if aspect is not None and j < nz - 1 - fixed_rows:
            xs = x[mask]
            mask[np.flatnonzero(mask)] = coarsen_line(xs, aspect * (z[j + 1] - z[j]))
        masks[j] = mask
    ids, start, pts = [], 0, []
    for j in range(nz):
        cols = np.flatnonzero(masks[j])
        ids.append(np.arange(start, start + len(cols)))
        start += len(cols)
        pts.append(np.vstack([x[cols], np.full(len(cols), z[j])]))
    tris = [_row_triangles(ids[j + 1], ids[j], x[masks[j + 1]], x[masks[j]]) for j in range(nz - 1)]
    return MeshTri(np.ascontiguousarray(np.hstack(pts)), np.ascontiguousarray(np.hstack(tris)))


def plane_mesh(thickness: float, zone: float, upstream: float, downstream: float, h: float,
               band: float, grading: float, far_x_up: float, far_x_down: float, far_z: float,
               aspect=_MODULE_ASPECT):
    """The mesh (skfem ``MeshTri``), the x node line of its top surface and its
    horizontal node lines z (module docstring). ``far_x_up`` and ``far_x_down``: largest
    x spacings (m) ahead of and behind the zone; ``aspect`` (-): the largest x spacing
    over the height of the row above a line below the band, where the x lines are
    thinned (None: every x line runs through the whole depth; default the module's
    ``ASPECT`` at the call)."""
    if aspect is _MODULE_ASPECT:
        aspect = ASPECT
    H = thickness
    x = _axis(-zone, zone, h, -downstream, upstream, grading, far_x_down, far_x_up)
    top_band = min(band, H)
    nb = max(int(np.ceil(top_band / h - 1e-9)), 1)
    zb = np.linspace(H - top_band, H, nb + 1)
    if top_band < H:
        below = graded_nodes(H - top_band, 0.0, h, grading, far_z)[::-1]
        z = np.unique(np.concatenate([below[:-1], zb]))
    else:
        z = zb
    mesh = _transition_mesh(x, z, nb, aspect)
    tol = 1e-9 * max(upstream + downstream, H)
    mesh = mesh.with_boundaries({
        "base": lambda p: np.abs(p[1]) < tol,
        "inflow": lambda p: np.abs(p[0] - upstream) < tol,
        "outflow": lambda p: np.abs(p[0] + downstream) < tol,
        "zone": lambda p: (np.abs(p[1] - H) < tol) & (np.abs(p[0]) <= zone + tol),
        "free": lambda p: (np.abs(p[1] - H) < tol) & (np.abs(p[0]) > zone + tol),
    })
    return mesh, x, z
