"""bem.indenters against closed forms: each profile and rolling arm compared with a value
computed here from the geometry (a circle, a parabola, a plane, a bilinear surface),
never with the module's own output; the rules of their inputs, with their messages.
Tolerances are a few ulps of the compared quantities (stated per test).
"""

import math

import numpy as np
import pytest

from bem.indenters import Cylinder, HeightMap, LineCylinder, Paraboloid, Sphere


def test_sphere_profile_is_the_circle_and_its_arm_is_x_over_r():
    """g = R - sqrt(R^2 - r^2) from Pythagoras in long double arithmetic (the module uses
    the cancellation-free form); relative 1e-14."""
    R = 0.02
    X = np.array([0.0, 0.003, -0.011, 0.0])
    Y = np.array([0.0, 0.004, 0.002, 0.0199])
    r2 = np.longdouble(X) ** 2 + np.longdouble(Y) ** 2
    expect = (np.longdouble(R) - np.sqrt(np.longdouble(R) ** 2 - r2)).astype(float)
    np.testing.assert_allclose(Sphere(R).profile(X, Y), expect, rtol=1e-14, atol=0)
    np.testing.assert_allclose(Sphere(R).rolling_arm(X, Y), X / R, rtol=1e-15)
    with pytest.raises(ValueError, match=r"^the grid reaches 0\.02 m from the axis, beyond the sphere's radius 0\.02 m: reduce grid\.half_width$"):
        Sphere(R).profile(np.array([0.0, 0.02]), np.array([0.0, 0.0]))  # r = R exactly is refused


def test_paraboloid_profile_is_r2_over_2r_and_its_arm_is_x_over_r():
    R = 0.05
    X, Y = np.array([0.0, 0.01, -0.02]), np.array([0.0, -0.003, 0.004])
    np.testing.assert_allclose(Paraboloid(R).profile(X, Y), (X**2 + Y**2) / 0.1, rtol=1e-15, atol=0)
    np.testing.assert_allclose(Paraboloid(R).rolling_arm(X, Y), X / R, rtol=1e-15)


def test_cylinder_is_a_circle_in_x_and_infinite_beyond_its_ends():
    """Circle in x, independent of y inside |y| <= L/2 (the end itself still touches),
    +inf beyond; arm x / R (a roller's lever arm about its axis)."""
    R, L = 0.02, 0.006
    X = np.array([0.0, 0.005, -0.012, 0.005, 0.005])
    Y = np.array([0.0, 0.003, -0.003, 0.0031, -0.0031])
    expect = np.array([R - math.sqrt(R * R - x * x) for x in X])
    got = Cylinder(R, L).profile(X, Y)
    np.testing.assert_allclose(got[:3], expect[:3], rtol=1e-12, atol=0)
    assert np.all(np.isinf(got[3:])) and np.all(got[3:] > 0)
    np.testing.assert_allclose(Cylinder(R, L).rolling_arm(X, Y), X / R, rtol=1e-15)
    np.testing.assert_allclose(Cylinder(R, L).profile(0.005, np.zeros((2, 2))), np.full((2, 2), expect[1]), rtol=1e-12)
    with pytest.raises(ValueError, match=r"^the grid reaches beyond the cylinder's radius 0\.02 m: reduce grid\.half_width$"):
        Cylinder(R, L).profile(np.array([0.02]), np.array([0.0]))
    for bad in (0.0, -1.0, math.nan, "1"):
        with pytest.raises(ValueError, match=r"^length must be finite and > 0 m, got "):
            Cylinder(R, bad)
    assert Cylinder(R, 1).length == 1


def test_line_cylinder_is_a_circle_in_x_whatever_y():
    R = 0.01
    X = np.array([0.0, 0.004, -0.0099])
    expect = np.array([R - math.sqrt(R * R - x * x) for x in X])
    np.testing.assert_allclose(LineCylinder(R).profile(X), expect, rtol=1e-12, atol=0)
    np.testing.assert_allclose(LineCylinder(R).profile(X, np.ones(3)), expect, rtol=1e-12, atol=0)
    np.testing.assert_allclose(LineCylinder(R).rolling_arm(X), X / R, rtol=1e-15)
    np.testing.assert_allclose(LineCylinder(R).rolling_arm([0.002], None), [0.2], rtol=1e-15)
    with pytest.raises(ValueError, match=r"^the grid reaches \|x\| = 0\.01 m, beyond the cylinder's radius 0\.01 m: reduce grid\.half_width$"):
        LineCylinder(R).profile([0.0, -0.01])


@pytest.mark.parametrize("radius", [0.0, -0.01, math.inf, math.nan, "0.02", None])
def test_a_radius_that_is_not_a_positive_number_is_refused(radius):
    for cls in (Sphere, Paraboloid, LineCylinder):
        with pytest.raises(ValueError, match=r"^radius must be > 0 m, got "):
            cls(radius)
    with pytest.raises(ValueError, match=r"^radius must be > 0 m, got "):
        Cylinder(radius, 0.01)


def test_integer_radius_is_accepted():
    assert Sphere(1).radius == 1 and Paraboloid(2).radius == 2


def test_height_map_of_a_bilinear_surface_interpolates_exactly():
    """h = c + b x + d y + e x y is reproduced exactly by bilinear interpolation between
    table nodes; its x-slope from centred differences is b + e y exactly (np.gradient is
    exact on linear data, one-sided at the ends too). Outside the table: +inf height,
    zero arm."""
    x = np.array([-1.0, -0.2, 0.5, 1.5]) * 1e-3
    y = np.array([-1.0, 0.0, 2.0]) * 1e-3
    X, Y = np.meshgrid(x, y)

    def h(X, Y):
        return 1e-4 + 0.02 * X + 0.01 * Y + 30.0 * X * Y + 2e-4

    hm = HeightMap(x, y, h(X, Y))
    Xq = np.array([-0.9, 0.0, 0.3, 1.4, 1.6, 0.0]) * 1e-3
    Yq = np.array([-0.5, 1.5, 0.7, -0.9, 0.0, 2.5]) * 1e-3
    inside = slice(0, 4)
    np.testing.assert_allclose(hm.profile(Xq, Yq)[inside], h(Xq, Yq)[inside], rtol=1e-13, atol=0)
    assert np.all(np.isposinf(hm.profile(Xq, Yq)[4:]))
    np.testing.assert_allclose(hm.rolling_arm(Xq, Yq)[inside], (0.02 + 30.0 * Yq)[inside], rtol=1e-12, atol=0)
    np.testing.assert_array_equal(hm.rolling_arm(Xq, Yq)[4:], 0.0)
    assert hm.profile(0.0, np.zeros(2)).shape == (2,)  # broadcast scalar x against array y
    assert hm.rolling_arm(0.0, np.zeros(2)).shape == (2,)


@pytest.mark.parametrize(
    "x, y, h, message",
    [
        ([0.0, 1.0], [0.0, 1.0, 2.0], np.zeros((2, 2)), r"^h must have shape \(len\(y\), len\(x\)\) = \(3, 2\), got \(2, 2\)$"),
        ([0.0, 1.0], [0.0, 1.0], np.zeros((2, 2, 1)), r"^h must have shape"),
        (np.zeros((2, 2)), [0.0, 1.0], np.zeros((2, 2)), r"^h must have shape"),
        ([0.0, 1.0], [[0.0, 1.0]], np.zeros((1, 2)), r"^h must have shape"),
        ([0.0], [0.0, 1.0], np.zeros((2, 1)), r"^x must be strictly increasing with >= 2 values$"),
        ([0.0, 0.0], [0.0, 1.0], np.zeros((2, 2)), r"^x must be strictly increasing with >= 2 values$"),
        ([0.0, 1.0], [1.0, 0.0], np.zeros((2, 2)), r"^y must be strictly increasing with >= 2 values$"),
        # the first offending entry, as a plain number (not np.float64(...)), with its place
        ([0.0, 1.0], [0.0, 2.0], [[0.0, -1e-9], [-2.0, 0.0]],
         r"^h must be finite and >= 0 m, got h\[0, 1\] = -1e-09 at x = 1\.0 m, y = 0\.0 m$"),
        ([0.0, 1.0], [0.0, 2.0], [[0.0, 0.0], [np.nan, 0.0]],
         r"^h must be finite and >= 0 m, got h\[1, 0\] = nan at x = 0\.0 m, y = 2\.0 m$"),
        ([0.0, 1.0], [0.0, 2.0], [[0.0, np.inf], [0.0, 0.0]],
         r"^h must be finite and >= 0 m, got h\[0, 1\] = inf at x = 1\.0 m, y = 0\.0 m$"),
        ([0.0, 1.0], [0.0, 2.0], [[0.0, 0.0], [0.0, -np.inf]],
         r"^h must be finite and >= 0 m, got h\[1, 1\] = -inf at x = 1\.0 m, y = 2\.0 m$"),
    ],
)
def test_height_map_refuses_a_bad_table_naming_the_entry(x, y, h, message):
    with pytest.raises(ValueError, match=message):
        HeightMap(np.asarray(x), np.asarray(y), np.asarray(h))


def test_height_map_accepts_zero_and_two_point_tables():
    hm = HeightMap(np.array([0.0, 1.0]), np.array([0.0, 1.0]), np.zeros((2, 2)))
    assert hm.profile(0.5, 0.5) == 0.0


def test_single_precision_coordinates_are_computed_in_double():
    """Coordinates in float32 give the float64 answer for the same (float32) values: the
    profiles and arms are evaluated in double precision (float32 arithmetic would err by
    ~1e-7 relative), and a roller's end y = L/2 is decided in double: float32(0.003) is
    0.0030000000261 > L/2, beyond the end."""
    R = 0.02
    X32 = np.array([0.0011, -0.0047, 0.0093], dtype=np.float32)
    X64 = X32.astype(float)
    Y32 = np.zeros(3, dtype=np.float32)
    Y32b = np.array([0.0021, 0.0003, -0.0011], dtype=np.float32)
    for body, args32, args64 in (
        (Cylinder(R, 0.006), (X32, Y32), (X64, Y32.astype(float))),
        (LineCylinder(R), (X32,), (X64,)),
        (Sphere(R), (X32, Y32b), (X64, Y32b.astype(float))),
        (Paraboloid(R), (X32, Y32b), (X64, Y32b.astype(float))),
    ):
        for f32, f64 in ((body.profile(*args32), body.profile(*args64)),
                         (body.rolling_arm(*args32), X64 / R)):
            assert f32.dtype == np.float64, (type(body).__name__, f32.dtype)
            np.testing.assert_allclose(f32, f64, rtol=1e-15, atol=0)
    # float32 arithmetic would be off by ~1e-8 relative: the check above can tell
    assert np.max(np.abs((X32 / np.float32(R)).astype(float) / (X64 / R) - 1)) > 1e-9
    p32 = Sphere(R).profile(X64, Y32b.astype(float)).astype(np.float32).astype(float)
    assert np.max(np.abs(p32 / Sphere(R).profile(X64, Y32b.astype(float)) - 1)) > 1e-9
    end = np.array([np.float32(0.003)])
    assert float(end[0]) > 0.003
    assert np.isposinf(Cylinder(R, 0.006).profile(np.array([0.001]), end)[0])


def test_height_map_slope_of_a_single_precision_table_is_computed_in_double():
    x = np.array([-1.0, -0.2, 0.5, 1.5]) * 1e-3
    y = np.array([0.0, 1.0]) * 1e-3
    h32 = (np.array([[1.1, 2.3, 0.7, 5.9], [0.3, 0.1, 0.2, 0.9]]) * 1e-4).astype(np.float32)
    a, b = HeightMap(x, y, h32), HeightMap(x, y, h32.astype(float))
    q = (np.array([-0.9e-3, 0.1e-3, 1.2e-3]), np.array([0.2e-3, 0.5e-3, 0.9e-3]))
    np.testing.assert_allclose(a.rolling_arm(*q), b.rolling_arm(*q), rtol=1e-13, atol=0)
    np.testing.assert_allclose(a.profile(*q), b.profile(*q), rtol=1e-15, atol=0)


def test_height_map_on_a_grid_of_nodes():
    """The solver calls profile and rolling_arm on (K_y, K_x) node arrays: the result has
    that shape, and equals the plane's height and slope node by node."""
    x = np.linspace(-2e-3, 2e-3, 5)
    y = np.linspace(-1e-3, 1e-3, 3)
    Xt, Yt = np.meshgrid(x, y)
    hm = HeightMap(x, y, 1e-4 + 0.02 * Xt + 0.01 * Yt + 2e-4)
    X, Y = np.meshgrid(np.linspace(-1.5e-3, 1.5e-3, 4), np.linspace(-0.5e-3, 0.5e-3, 2))
    np.testing.assert_allclose(hm.profile(X, Y), 3e-4 + 0.02 * X + 0.01 * Y, rtol=1e-13, atol=0)
    np.testing.assert_allclose(hm.rolling_arm(X, Y), np.full(X.shape, 0.02), rtol=1e-13, atol=0)


@pytest.mark.parametrize("x, y", [([[0.0, 1.0]], [0.0, 1.0]), ([0.0, 1.0], [[0.0, 1.0]])])
def test_height_map_axes_must_be_one_dimensional(x, y):
    """A 2-D axis whose size still matches h's shape is refused on its own account."""
    with pytest.raises(ValueError, match=r"^h must have shape \(len\(y\), len\(x\)\) = \(2, 2\), got \(2, 2\)$"):
        HeightMap(np.asarray(x), np.asarray(y), np.zeros((2, 2)))
