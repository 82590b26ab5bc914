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
