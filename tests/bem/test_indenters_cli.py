"""Indenters other than the sphere, and the `bem solve` command line."""

import json

import numpy as np
import pytest

from bem import Cylinder, Elastic, Grid, HeightMap, Layer, Loading, Paraboloid, Problem, solve
from bem.cli import main

GRID = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (500, 500), (5.5e-3, 5.5e-3))
LAYER = Layer(5e-3, Elastic(3e6))


def test_height_map_of_a_paraboloid_is_the_paraboloid():
    """Table nodes on the grid nodes: bilinear interpolation is exact there, so the
    contact is the same to rounding."""
    x = np.arange(-12, 13) * 0.5e-3
    X, Y = np.meshgrid(x, x)
    table = HeightMap(x, x, (X**2 + Y**2) / (2 * 0.02))
    ref = solve(Problem(LAYER, Paraboloid(0.02), GRID, Loading(0.0, load=100.0)))
    got = solve(Problem(LAYER, table, GRID, Loading(0.0, load=100.0)))
    np.testing.assert_allclose(got.force, ref.force, rtol=0, atol=1e-12 * ref.force.max())
    # the rolling arm of a height map is its slope dh/dx = x / R for a paraboloid
    inner = np.abs(GRID.coordinates()[0]) < 5e-3
    np.testing.assert_allclose(table.rolling_arm(*GRID.coordinates())[inner],
                               Paraboloid(0.02).rolling_arm(*GRID.coordinates())[inner], rtol=1e-12)


def test_short_roller_contact_spans_its_length():
    roller = Cylinder(radius=0.02, length=6e-3)
    res = solve(Problem(LAYER, roller, GRID, Loading(0.0, load=100.0)))
    X, Y = GRID.coordinates()
    assert not res.contact[np.abs(Y) > 3e-3].any()
    assert res.contact[np.abs(Y) <= 3e-3].any()
    np.testing.assert_allclose(res.force, res.force[::-1], rtol=0, atol=1e-12 * res.force.max())
    centre_row = res.pressure[GRID.shape[0] // 2]
    end_row = res.pressure[np.argmin(np.abs(GRID.y - 3e-3))]
    assert end_row.max() > centre_row.max()  # the flat ends concentrate the pressure
    with pytest.raises(ValueError, match="length must be finite and > 0 m, got inf"):
        Cylinder(0.02, float("inf"))


def test_cli_json_overrides_and_fields(tmp_path, capsys):
    fields = tmp_path / "f.npz"
    code = main(["solve", "examples/paper-section11-frictionless.toml", "--json", "--quiet",
                 "--set", "grid.spacing=1e-3", "--set", "grid.truncation=500", "--fields", str(fields)])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(out["rolling_resistance"] - 3.1129) < 1e-4  # Table 1, a = 1 mm, Nt = 500
    for key in ("indentation", "contact_radius", "load", "peak_pressure"):
        assert out[key] > 0
    assert abs(out["load"] - 150.0) < 1e-9
    assert np.load(fields)["pressure"].shape == (11, 11)


def test_cli_reports_bad_input(capsys):
    code = main(["solve", "examples/paper-section11-frictionless.toml", "--quiet", "--set", "layer.thickness=-0.005"])
    assert code == 2
    assert "thickness must be > 0 m, got -0.005" in capsys.readouterr().err
    code = main(["solve", "examples/paper-section11-frictionless.toml", "--quiet", "--set", "grid.half_width=2e-3"])
    assert code == 1  # the solve ran and failed
    assert "increase grid.half_width" in capsys.readouterr().err


def test_automatic_region_is_sized(tmp_path, capsys):
    """Without grid.half_width the region comes from an elastic estimate (Table 1,
    a = 1 mm, Nt = 500)."""
    text = open("examples/paper-section11-frictionless.toml").read().replace("half_width = 5.0e-3", "")
    case = tmp_path / "auto.toml"
    case.write_text(text)
    code = main(["solve", str(case), "--json", "--quiet", "--set", "grid.spacing=1e-3", "--set", "grid.truncation=500"])
    assert code == 0
    assert abs(json.loads(capsys.readouterr().out)["rolling_resistance"] - 3.1129) < 1e-4


def test_a_region_too_small_grows_when_automatic():
    """grow=True widens a region the contact reaches by half until it fits, and gives the
    answer of a large enough region; without it the edge contact is an error."""
    from bem import Sphere, ThreeParameterSolid
    from bem.contact import ContactAtEdge

    layer = Layer(5e-3, ThreeParameterSolid(3.0e6, 0.25, 1.0), 1000.0)
    small = Grid.centred((1e-3, 1e-3), (0.2, 0.2), (500, 500), (3e-3, 3e-3))
    problem = Problem(layer, Sphere(0.02), small, Loading(0.05, load=150.0))
    lines = []
    grown = solve(problem, progress=lines.append, grow=True)
    assert any("widening" in line for line in lines)
    assert abs(grown.rolling_resistance - 3.1129) < 1e-4
    with pytest.raises(ContactAtEdge):
        solve(problem)
