"""``[friction] kinematics``: the rolling geometry of each choice
(:func:`bem.kinematics.rolling_geometry`) against its definition, and bad input."""

from pathlib import Path

import numpy as np
import pytest

from bem.cli import main
from casefile.schema import section
from bem.frictional import Friction
from bem.indenters import Cylinder, Paraboloid, Sphere
from bem.kinematics import DEFAULT_KINEMATICS, KINEMATICS, rolling_geometry

R = 0.02
X, Y = np.meshgrid(np.linspace(-4e-3, 4e-3, 9), np.linspace(-3e-3, 3e-3, 7))
CASE = str(Path(__file__).resolve().parents[3] / "examples" / "paper-section11-friction.toml")


def test_paper_is_eq14_with_the_arm_x_over_R_on_the_exact_sphere():
    g, arm, ell = rolling_geometry(Sphere(R), X, Y, "paper")
    np.testing.assert_allclose(g, R - np.sqrt(R**2 - X**2 - Y**2), rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(arm, X / R, rtol=1e-15)
    np.testing.assert_allclose(ell, np.sqrt(R**2 - Y**2), rtol=1e-15)


def test_small_slope_solves_the_sphere_as_its_paraboloid():
    g, arm, ell = rolling_geometry(Sphere(R), X, Y, "small_slope")
    g2, arm2, ell2 = rolling_geometry(Paraboloid(R), X, Y, "small_slope")
    np.testing.assert_allclose(g, (X**2 + Y**2) / (2 * R), rtol=1e-15)
    np.testing.assert_array_equal(g, g2)
    np.testing.assert_array_equal(arm, arm2)
    np.testing.assert_array_equal(ell, np.full(X.shape, R))
    np.testing.assert_array_equal(ell2, np.full(X.shape, R))


@pytest.mark.parametrize("body", [Sphere(R), Cylinder(R, 0.01, edge_radius=2e-3), Cylinder(R, 0.01, crown_radius=0.05)])
def test_exact_arm_is_the_profile_slope_and_ell_the_depth_below_the_axis(body):
    g, arm, ell = rolling_geometry(body, X, Y, "exact")
    np.testing.assert_array_equal(g, body.profile(X, Y))
    np.testing.assert_allclose(ell, R - g, rtol=1e-15)
    # dg/dx by a centred difference (error h^2 g''' / 6, about 1e-9 of the slope here)
    h = 1e-7
    slope = (body.profile(X + h, Y) - body.profile(X - h, Y)) / (2 * h)
    np.testing.assert_allclose(arm, slope, rtol=1e-6, atol=1e-12)


def test_exact_sphere_arm_and_rolling_radius_in_closed_form():
    g, arm, ell = rolling_geometry(Sphere(R), X, Y, "exact")
    zeta = np.sqrt(R**2 - X**2 - Y**2)
    np.testing.assert_allclose(ell, zeta, rtol=1e-14)
    np.testing.assert_allclose(arm, X / zeta, rtol=1e-14)


def test_small_slope_roller_keeps_its_axial_drop_with_x2_over_2R():
    body = Cylinder(R, 0.01, edge_radius=2e-3)
    g, arm, ell = rolling_geometry(body, X, Y, "small_slope")
    np.testing.assert_allclose(g, X**2 / (2 * R) + body.axial_drop(Y), rtol=1e-15)
    np.testing.assert_allclose(arm, X / R, rtol=1e-15)


def test_paraboloid_exact_is_its_small_slope_geometry():
    for a, b in zip(rolling_geometry(Paraboloid(R), X, Y, "exact"), rolling_geometry(Paraboloid(R), X, Y, "small_slope")):
        np.testing.assert_array_equal(a, b)


def test_default_and_bad_kinematics():
    assert DEFAULT_KINEMATICS == "paper" and Friction(0.2).kinematics == "paper"
    schema_default = next(k.default for k in section("friction").keys if k.name == "kinematics")
    assert schema_default == DEFAULT_KINEMATICS  # the case file and the API agree
    assert set(KINEMATICS) == {"paper", "small_slope", "exact"}
    with pytest.raises(ValueError, match="kinematics must be one of paper, small_slope, exact, got 'flat'"):
        Friction(0.2, kinematics="flat")
    with pytest.raises(ValueError, match="kinematics must be one of"):
        rolling_geometry(Sphere(R), X, Y, "flat")


def test_cli_unknown_kinematics_exits_2(capsys):
    code = main(["solve", CASE, "--quiet", "--set", "grid.spacing=1e-3", "--set", "grid.truncation=500",
                 "--set", "friction.kinematics=flat"])
    err = capsys.readouterr().err
    assert code == 2
    assert "kinematics" in err and "flat" in err


def test_result_names_its_kinematics():
    from bem import Grid, Layer, Loading, Problem, ThreeParameterSolid
    from bem.frictional import solve_friction

    layer = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
    grid = Grid.centred((1e-3, 1e-3), (0.2, 0.2), (100, 100), (5e-3, 5e-3))
    p = Problem(layer, Sphere(R), grid, Loading(0.05, load=150.0))
    res, _ = solve_friction(p, Friction(0.2, kinematics="small_slope"), energy=False)
    assert res.kinematics == "small_slope" and res.summary()["kinematics"] == "small_slope"
