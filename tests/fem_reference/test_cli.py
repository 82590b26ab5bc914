"""The ``fem-reference`` command line on a stationary case: the JSON result against the
converged BEM, the figure and the VTU written with their fields (the pressure and the
displacement at the top of the axis), and a speed refused with exit status 2. (Rolling
cases through the command line are checked with their models.)"""

import json

import numpy as np
import pytest

from fem_reference.cli import main


def test_cli_json_plot_and_vtu_of_a_stationary_case(tmp_path, capsys):
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
    # indentation; gates at about twice that
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
