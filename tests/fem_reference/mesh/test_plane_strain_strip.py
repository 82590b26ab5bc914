"""The structured plane-strain strip: the x lines that thin out with depth (pairs merged
outward from x = 0), a conforming mesh that tiles the section and is its own mirror image
about x = 0 near the contact, and vertices that grow like the log of the depth.

Numbers from benchmarks/fem_rolling_deep.py; each tolerance is the measured value with a
stated margin.
"""

import math

import numpy as np
import pytest

import fem_reference as fr
from fem_reference.mesh import plane_strain_strip
from fem_reference.mesh.plane_strain_strip import coarsen_line, plane_mesh
from fem_reference.rolling.plane_strain.discretization import resolve_plane

G0, TAU, F = 3.0e6, 0.25, 1.0
R, P = 0.02, 1000.0
B0 = math.sqrt(P * R / (math.pi * G0))  # 2D Hertz half-width, relaxed modulus (m)


def _problem(depth, material=None, speed=0.0, density=0.0, **fem):
    material = material or fr.ThreeParameterMaterial(G0, TAU, F)
    return fr.ContactProblem(fr.Layer(depth * B0, density), material, fr.Indenter("line", R),
                             fr.Loading(load=P, speed=speed), fr.FemSettings(**fem))


def _mesh(depth, aspect=plane_strain_strip.ASPECT, band=None, size=30.0):
    d = resolve_plane(_problem(depth, speed=B0 / TAU, element_size=B0 / size))
    return plane_mesh(depth * B0, d.contact_zone, d.upstream, d.downstream, d.mesh_size,
                      d.band if band is None else band, d.grading, d.far_x_up, d.far_x_down,
                      d.far_z, aspect=aspect), d


def test_coarsen_line_merges_pairs_outward_from_zero():
    """Uniform unit spacing, target 2: every other node from x = 0 outwards on both sides,
    the ends kept (the last interval stays single)."""
    x = np.arange(-5.0, 6.0)
    assert x[coarsen_line(x, 2.0)].tolist() == [-5, -4, -2, 0, 2, 4, 5]
    assert coarsen_line(x, 1.9).all()  # two intervals span 2 > 1.9: nothing merges
    # no node at 0: the interval across it is kept, the halves merge from its ends
    y = np.arange(-2.5, 3.0)
    assert y[coarsen_line(y, 2.0)].tolist() == [-2.5, -0.5, 0.5, 2.5]


def test_mesh_is_conforming_mirrored_and_fills_the_section():
    """The transition rows leave no hanging node: every edge lies on two triangles except
    those on the rectangle's sides; the triangles tile the section (areas sum to it, none
    degenerate) and, on the candidate zone and its grading, are the mirror image of
    themselves about x = 0."""
    (mesh, x, z), d = _mesh(160, size=10.0)
    H = 160 * B0
    p, t = mesh.p, mesh.t
    a = 0.5 * ((p[0, t[1]] - p[0, t[0]]) * (p[1, t[2]] - p[1, t[0]])
               - (p[0, t[2]] - p[0, t[0]]) * (p[1, t[1]] - p[1, t[0]]))
    assert np.abs(a).min() > 0
    assert np.abs(a).sum() == pytest.approx((d.upstream + d.downstream) * H, rel=1e-12)
    fb = mesh.facets[:, mesh.boundary_facets()]
    ends = p[:, fb]  # (2, 2, n): both ends of each boundary facet
    tol = 1e-9 * H
    on_side = ((np.abs(ends[1]) < tol) | (np.abs(ends[1] - H) < tol)).all(axis=0) | \
              ((np.abs(ends[0] - d.upstream) < tol) | (np.abs(ends[0] + d.downstream) < tol)).all(axis=0)
    assert on_side.all()
    # mirror symmetry where the x lines are symmetric: up to 10 b0 on each side
    key = lambda pts: set(tuple(sorted(map(tuple, np.round(tri.T / (1e-6 * B0)).astype(int))))
                          for tri in pts)
    near = np.abs(p[0, t]).max(axis=0) < 10 * B0
    tris = p[:, t[:, near]].transpose(2, 0, 1)  # (n, 2, 3)
    mirrored = tris * np.array([-1.0, 1.0])[None, :, None]
    assert key(tris) == key(mirrored)
    # below the band the x lines thin out: the deepest line keeps far fewer nodes
    assert np.sum(np.abs(p[1]) < tol) < 0.5 * len(x)


def test_unknowns_grow_like_the_log_of_the_depth():
    """Vertices at H / b0 = 40, 160, 640, 2560 (h = b0 / 30): each factor 4 in depth adds
    about the same number (measured 580, 653, 635 to 3 015: log growth; the
    tensor-product mesh, every x line through the depth with a band of Z / 2, has 2.4
    times the vertices at 160 b0)."""
    counts = [_mesh(depth)[0][0].p.shape[1] for depth in (40, 160, 640, 2560)]
    steps = np.diff(counts)
    assert (steps > 0).all() and steps.max() < 1.25 * steps.min()
    assert counts[-1] < 1.7 * counts[0]
    (tensor, _, _), d = _mesh(160, aspect=None, band=0.75 * B0)
    assert tensor.p.shape[1] > 2 * counts[1]
