"""Structured, graded triangle mesh of the plane-strain layer section (x, z).

The rectangle [-downstream, upstream] x [0, H] is cut by vertical lines x_i and
horizontal lines z_j into quadrilaterals, each split into two triangles (skfem
mirrored about x = 0): every row of element edges is aligned with x, the flow
direction of the rolling material, and the element x-extent is known per element.
The node spacing is uniform (``element_size`` h) on the candidate zone |x| <= Z and in
a band of depth ``band`` under the top surface; away from them it grows as
h + grading * distance, capped at ``far_x`` (along x) and ``far_z`` (along z).

Named boundaries: ``base`` (z = 0, bonded), ``inflow`` (x = upstream: material
enters), ``outflow`` (x = -downstream: material leaves), ``zone`` (z = H, |x| <= Z:
the candidate contact zone) and ``free`` (z = H, |x| > Z). Lengths in m.
"""

from __future__ import annotations

import numpy as np
from skfem import MeshTri

__all__ = ["graded_nodes", "plane_mesh"]


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


def _mirrored_tensor_mesh(x: np.ndarray, z: np.ndarray) -> MeshTri:
    """Triangles of the tensor grid x by z, each quadrilateral cut along the diagonal that
    rises towards x = 0: the mesh is the mirror image of itself about x = 0 wherever the
    node lines are (the candidate zone and its grading), so a symmetric load gives a
    symmetric answer (one diagonal direction everywhere gave a spurious R_r of 1e-5 of
    P b / R on an elastic layer)."""
    nx, nz = len(x), len(z)
    X, Z = np.meshgrid(x, z, indexing="ij")
    p = np.vstack([X.ravel(), Z.ravel()])
    idx = np.arange(nx * nz).reshape(nx, nz)
    n00, n10 = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    n01, n11 = idx[:-1, 1:].ravel(), idx[1:, 1:].ravel()
    left = np.repeat(0.5 * (x[:-1] + x[1:]) < 0, nz - 1)
    t1 = np.where(left, [n00, n10, n11], [n00, n10, n01])
    t2 = np.where(left, [n00, n11, n01], [n10, n11, n01])
    return MeshTri(p, np.hstack([t1, t2]))


def plane_mesh(thickness: float, zone: float, upstream: float, downstream: float, h: float,
               band: float, grading: float, far_x_up: float, far_x_down: float, far_z: float):
    """The mesh (skfem ``MeshTri``) and its vertical and horizontal node lines (module
    docstring). ``far_x_up`` and ``far_x_down``: largest x spacings (m) ahead of and
    behind the zone."""
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
    mesh = _mirrored_tensor_mesh(x, z)
    tol = 1e-9 * max(upstream + downstream, H)
    mesh = mesh.with_boundaries({
        "base": lambda p: np.abs(p[1]) < tol,
        "inflow": lambda p: np.abs(p[0] - upstream) < tol,
        "outflow": lambda p: np.abs(p[0] + downstream) < tol,
        "zone": lambda p: (np.abs(p[1] - H) < tol) & (np.abs(p[0]) <= zone + tol),
        "free": lambda p: (np.abs(p[1] - H) < tol) & (np.abs(p[0]) > zone + tol),
    })
    return mesh, x, z
