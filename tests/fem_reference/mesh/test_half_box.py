"""The half-box mesh of the 3D rolling model: every named side on its own plane, the
candidate half disk inside its radius, the mesh its own mirror image about x = 0, and
the volumes tiling the box."""

import types

import numpy as np
import pytest

H = 5e-3


@pytest.mark.parametrize("length", [0.0386])
def test_half_box_mesh_names_every_side_and_is_its_mirror_image(length):
    """Every named side holds facets on its own plane (on a short box, where a
    bounding-box tolerance below OCC's padding would lose them all), and the mesh is its
    own mirror image about x = 0 with positive volumes."""
    from fem_reference.mesh.half_box import NAMES, half_box_mesh

    Z, lat = 8.585e-3, 0.0386
    mesh = half_box_mesh(H, Z, length, lat,
                         types.SimpleNamespace(mesh_size=2e-3, grading=0.5, far_size=H))
    planes = {"base": (2, 0.0), "inflow": (0, length), "outflow": (0, -length), "sym_y": (1, 0.0),
              "lateral": (1, lat), "zone": (2, H), "free": (2, H)}
    for name in NAMES:
        pts = mesh.p[:, mesh.facets[:, mesh.boundaries[name]]]
        axis, value = planes[name]
        assert pts.size and np.allclose(pts[axis], value, atol=1e-12)
    zone = mesh.p[:, mesh.facets[:, mesh.boundaries["zone"]]]
    assert np.all(np.hypot(zone[0], zone[1]) <= Z * (1 + 1e-9))
    mirrored = {tuple(np.round(c, 12)) for c in (mesh.p * [[-1], [1], [1]]).T}
    assert mirrored == {tuple(np.round(c, 12)) for c in mesh.p.T}
    cent = mesh.p[:, mesh.t].mean(axis=1)
    assert np.sum(cent[0] > 0) == np.sum(cent[0] < 0) == mesh.t.shape[1] // 2
    e1, e2, e3 = (mesh.p[:, mesh.t[k]] - mesh.p[:, mesh.t[0]] for k in (1, 2, 3))
    vol = np.einsum("ij,ij->j", np.cross(e1.T, e2.T).T, e3) / 6.0
    assert np.all(vol > 0) or np.all(vol < 0)
    assert abs(np.sum(np.abs(vol)) - 2 * length * lat * H) < 1e-9 * length * lat * H
