"""The quarter-cylinder mesh of the stationary 3D model: every named boundary present with
the area of its face at a scale where a bounding-box tolerance would lose faces, and a
mesh that lost a symmetry face stops the solve with a MeshError naming it."""

import numpy as np
import pytest

from fem_reference import (ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading,
                           MeshError, solve)


def _small_3d():
    """A quarter cylinder of domain radius 10 mm: a face tolerance of 1e-5 r_d = 1e-7 m
    would equal the padding OCC adds to every bounding box and lose the faces x = 0 and
    z = H."""
    return ContactProblem(Layer(2e-3), ElasticMaterial(3e6), Indenter("sphere", 0.02),
                          Loading(load=100.0), FemSettings(model="3d", domain_radius=10e-3,
                                                           grading=1.0, element_size=1e-3))


def _areas(mesh):
    """Area (m^2) of every named boundary of a tetrahedral mesh."""
    out = {}
    for name, facets in mesh.boundaries.items():
        a, b, c = (mesh.p[:, mesh.facets[k, facets]] for k in range(3))
        out[name] = 0.5 * np.linalg.norm(np.cross(b - a, c - a, axis=0), axis=0).sum()
    return out


def test_quarter_cylinder_names_every_face_at_any_scale():
    """Every named boundary of the quarter cylinder is there and has the area of its
    face: the planes exactly (base pi r_d^2 / 4, x = 0 and y = 0 r_d H), the curved
    faces to their chords (zone pi Z^2 / 4 and outer pi r_d H / 2 within 1%: a chord of
    the 1 mm elements on r = 7 and 10 mm cuts 1 - sin(t)/t ~ t^2/6 < 0.4%)."""
    from fem_reference.mesh.quarter_cylinder import quarter_cylinder_mesh
    from fem_reference.stationary.discretization import resolve

    problem = _small_3d()
    disc = resolve(problem)
    H, Z, rd = 2e-3, disc.contact_zone, disc.domain_radius
    areas = _areas(quarter_cylinder_mesh(H, disc))
    assert set(areas) == {"base", "sym_x", "sym_y", "outer", "zone", "free"}
    assert areas["base"] == pytest.approx(np.pi * rd ** 2 / 4, rel=1e-2)
    assert areas["sym_x"] == pytest.approx(rd * H, rel=1e-12)
    assert areas["sym_y"] == pytest.approx(rd * H, rel=1e-12)
    assert areas["zone"] == pytest.approx(np.pi * Z ** 2 / 4, rel=1e-2)
    assert areas["zone"] + areas["free"] == pytest.approx(areas["base"], rel=1e-12)
    assert areas["outer"] == pytest.approx(np.pi * rd * H / 2, rel=1e-2)


def test_a_3d_mesh_that_loses_a_symmetry_face_names_it(monkeypatch):
    """A quarter cylinder without its face x = 0 cannot carry the symmetry condition
    u_x = 0: a MeshError naming the boundary and the settings that shape it, not
    scikit-fem's raw ValueError at the boundary condition."""
    from fem_reference.mesh import quarter_cylinder

    real = quarter_cylinder.mesh_with_gmsh

    def lose_sym_x(build, kind, dim):
        mesh = real(build, kind, dim)
        kept = {k: v for k, v in mesh.boundaries.items() if k != "sym_x"}
        return type(mesh)(mesh.p, mesh.t, _boundaries=kept)

    monkeypatch.setattr(quarter_cylinder, "mesh_with_gmsh", lose_sym_x)
    with pytest.raises(MeshError, match=r"no facet on the boundary 'sym_x' \(the symmetry plane "
                                        r"x = 0\).*fem.domain_radius = 0.01 m"):
        solve(_small_3d())
