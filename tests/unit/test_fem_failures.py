"""Bad input and failed solves end in clear errors; the CLI reports them."""

import json

import numpy as np

import gmsh
import pytest

from fem_reference import (ContactProblem, ContactZoneError, ElasticMaterial, FemSettings,
                           Indenter, Layer, Loading, MeshError, solve)
from fem_reference.cli import main


def _thick(**fem):
    return ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", 0.02),
                          Loading(load=100.0), FemSettings(**fem))


def test_load_too_large_for_the_refined_zone():
    # contact radius ~4.5 mm, candidate zone 3 mm
    with pytest.raises(ContactZoneError, match="raise fem.contact_zone"):
        solve(_thick(element_size=2e-4, contact_zone=3e-3))


def test_a_mesh_that_fails(monkeypatch):
    def broken(dim=3):
        raise Exception("no elements in volume")

    monkeypatch.setattr(gmsh.model.mesh, "generate", broken)
    with pytest.raises(MeshError, match="gmsh failed to mesh the layer: no elements"):
        solve(_thick(element_size=4e-4))


def test_indentation_control_inverts_load_control():
    by_load = solve(_thick(element_size=2e-4))
    by_disp = solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6),
                                   Indenter("paraboloid", 0.02),
                                   Loading(indentation=by_load.indentation),
                                   FemSettings(element_size=2e-4, contact_zone=7e-3)))
    assert by_disp.load == pytest.approx(100.0, rel=1e-8)
    assert by_disp.contact_radius == pytest.approx(by_load.contact_radius, rel=1e-8)


def test_cli_json_plot_vtu(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text('[layer]\nthickness = 5e-3\n[material]\nmodel = "elastic"\n'
                    'shear_modulus = 3e6\n[indenter]\nshape = "sphere"\nradius = 0.02\n'
                    '[loading]\nspeed = 0.0\nload = 100.0\n[grid]\nspacing = 0.25e-3\n')
    png, vtu = tmp_path / "p.png", tmp_path / "f.vtu"
    code = main(["solve", str(case), "--json", "--set", "fem.element_size=2e-4",
                 "--plot", str(png), "--vtu", str(vtu)])
    out = capsys.readouterr()
    assert code == 0
    data = json.loads(out.out)
    assert {"contact_radius", "indentation", "load", "peak_pressure", "mesh", "solver"} <= set(data)
    assert data["load"] == pytest.approx(100.0)
    # against the BEM on the same layer, converged (0.2/0.1/0.05 mm grids: 4.5077, 4.5139,
    # 4.5151 mm -> 4.5154 mm; peak 2.42851 MPa; indentation 0.59831 mm): the FEM at
    # h = 0.2 mm measured -0.31% in radius, +0.014% in peak pressure, -0.04% in
    # indentation; gates at about twice that (the former 4.3-4.7 mm was +-4.4%)
    assert abs(data["contact_radius"] / 4.5154e-3 - 1) < 6e-3
    assert abs(data["peak_pressure"] / 2.42851e6 - 1) < 5e-4
    assert abs(data["indentation"] / 0.59831e-3 - 1) < 1e-3
    assert "contact iteration" in out.err
    assert png.stat().st_size > 0 and vtu.stat().st_size > 0
    # the VTU's fields, not only its size: the hydrostatic pressure under the indenter is
    # compressive (> 0) and of the order of the contact pressure at the top of the axis;
    # the displacement there is the indentation, downwards
    import meshio

    fields = meshio.read(vtu)
    top_axis = np.flatnonzero((np.abs(fields.points[:, 0]) < 1e-12) & np.isclose(fields.points[:, 1], 5e-3))
    assert top_axis.size == 1
    p_top = fields.point_data["pressure"][top_axis[0]]
    assert 0.5 * data["peak_pressure"] < p_top < 1.5 * data["peak_pressure"]
    uz_top = fields.point_data["displacement"][top_axis[0]][1]
    assert abs(uz_top + data["indentation"]) < 1e-3 * data["indentation"]
    assert main(["solve", str(case), "--set", "loading.speed=0.1"]) == 2
    assert "speed must be 0 m/s: fem-reference solves stationary contact only" in capsys.readouterr().err


def test_indentation_that_reaches_no_node_is_an_error_naming_the_gap():
    """Displacement control below the first multiplier node: the rigid indenter touches
    no node, the contact problem's unique solution is lam = 0 (load 0), which used to be
    returned as a result. It raises, naming the indentation and the gap to close.

    The gap named is the smallest weighted gap q_j / m_j of a node; at the axis node of
    the axisymmetric zone (hat function 1 - r / r1 on [0, r1], weight r dr, paraboloid
    s = r^2 / (2 R)) it is (r1^4 / (40 R)) / (r1^2 / 6) = 3 r1^2 / (20 R) exactly (the
    facet quadrature, order 6, is exact for this degree-4 integrand). Just above it the
    solve carries a load, just below it raises: the named value is the threshold."""
    import re

    from fem_reference import InputError

    R = 0.02

    def by_indentation(d):
        return solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", R),
                                    Loading(indentation=d),
                                    FemSettings(element_size=4e-4, contact_zone=3e-3)))

    with pytest.raises(InputError, match=r"loading.indentation = 1e-09 m reaches no node") as info:
        by_indentation(1e-9)
    message = str(info.value)
    assert "raise loading.indentation" in message and "fem.element_size" in message
    gap = float(re.search(r"would need to close ([0-9.e+-]+) m", message).group(1))
    with pytest.raises(InputError, match="reaches no node"):
        by_indentation(0.99 * gap)
    touching = by_indentation(1.02 * gap)
    assert touching.load > 0
    r1 = touching.radius[1]  # the first node off the axis (the radii are sorted)
    assert gap == pytest.approx(3.0 * r1 ** 2 / (20.0 * R), rel=1e-4)  # 5 digits printed


def _small_3d():
    """The mutation run's settings whose quarter cylinder lost its faces x = 0 and z = H:
    domain radius 10 mm, so the old face tolerance 1e-5 r_d = 1e-7 m equalled the padding
    OCC adds to every bounding box."""
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
    from fem_reference.discretization import resolve
    from fem_reference.mesh_3d import quarter_cylinder_mesh

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
    from fem_reference import mesh_3d

    real = mesh_3d.mesh_with_gmsh

    def lose_sym_x(build, kind, dim):
        mesh = real(build, kind, dim)
        kept = {k: v for k, v in mesh.boundaries.items() if k != "sym_x"}
        return type(mesh)(mesh.p, mesh.t, _boundaries=kept)

    monkeypatch.setattr(mesh_3d, "mesh_with_gmsh", lose_sym_x)
    with pytest.raises(MeshError, match=r"no facet on the boundary 'sym_x' \(the symmetry plane "
                                        r"x = 0\).*fem.domain_radius = 0.01 m"):
        solve(_small_3d())
