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


# --- the roller's ends: rounded (edge radius) or crowned --------------------------------


def _arc_drop(radius, s):
    """radius - sqrt(radius^2 - s^2) (m) in long double: the drop of a circular arc."""
    r, s = np.longdouble(radius), np.longdouble(s)
    return (r - np.sqrt(r * r - s * s)).astype(float)


def test_rounded_roller_is_flat_then_an_arc_square_to_the_end_face():
    """e(y) = 0 up to y0 = L/2 - r_e, then the arc r_e - sqrt(r_e^2 - (|y| - y0)^2), reaching
    r_e at the end face; g = e + R - sqrt((R - e)^2 - x^2) (circle of the row's radius),
    +inf beyond; relative 1e-13."""
    R, L, re = 0.02, 0.008, 0.002
    roller = Cylinder(R, L, re)
    Y = np.array([0.0, -0.0015, 0.002, 0.0025, -0.0031, 0.004, -0.004])
    s = np.clip(np.abs(Y) - 0.002, 0, None)
    e = _arc_drop(re, s)
    np.testing.assert_allclose(roller.axial_drop(Y), e, rtol=1e-13, atol=0)
    assert roller.axial_drop(0.004) == pytest.approx(re, rel=1e-15)
    X = np.full(Y.shape, 0.0013)
    rho = np.longdouble(R) - np.longdouble(e)
    expect = (np.longdouble(e) + rho - np.sqrt(rho * rho - np.longdouble(X) ** 2)).astype(float)
    np.testing.assert_allclose(roller.profile(X, Y), expect, rtol=1e-13, atol=0)
    assert np.isposinf(roller.profile(0.0, 0.00401))
    np.testing.assert_allclose(roller.rolling_arm(X, Y), X / R, rtol=1e-15)


def test_rounded_end_blends_tangentially_into_the_flat():
    """At y0 = L/2 - r_e the drop and its slope are 0 on both sides (e(y0 - d) = 0 and e(y0 + d)
    = d^2 / 2 r_e + O(d^4): the one-sided slopes e / d -> 0 linearly, d / 2 r_e); the curvature
    jumps from 0 to 1 / r_e."""
    L, re = 0.01, 0.003
    y0 = L / 2 - re
    roller = Cylinder(0.05, L, re)
    for d in (1e-4, 1e-5, 1e-6):
        assert roller.axial_drop(y0 - d) == 0.0
        right = roller.axial_drop(y0 + d)
        assert right / d == pytest.approx(d / (2 * re), rel=2 * (d / re) ** 2)  # slope -> 0
        assert 2 * right / d**2 == pytest.approx(1 / re, rel=(d / re) ** 2)  # curvature 1 / r_e


def test_edge_radius_to_zero_is_the_flat_ended_cylinder():
    """The drop is at most r_e and only on the last r_e of each end: the gap grows by e times
    d g / d e = rho / sqrt(rho^2 - x^2) <= (R - r_e) / sqrt((R - r_e)^2 - x^2) (the row's circle
    of radius rho = R - e; 1.021 at |x| = R / 5),
    so r_e = 1e-9 m moves no node's gap by more than 1.03e-9 m; r_e = 0 is the flat-ended
    cylinder exactly."""
    R, L = 0.02, 0.006
    X, Y = np.meshgrid(np.linspace(-0.004, 0.004, 17), np.linspace(-0.003, 0.003, 25))
    flat = Cylinder(R, L).profile(X, Y)
    np.testing.assert_array_equal(Cylinder(R, L, 0.0).profile(X, Y), flat)
    for re in (1e-4, 1e-6, 1e-9):
        diff = Cylinder(R, L, re).profile(X, Y) - flat
        assert np.all(diff >= 0) and np.all(diff <= re * (R - re) / np.sqrt((R - re) ** 2 - X * X) * (1 + 1e-9))
        assert np.all(diff[np.abs(Y) < L / 2 - re] == 0)


@pytest.mark.parametrize("kwargs", [dict(edge_radius=0.002), dict(crown_radius=1e4), dict()])
def test_a_long_roller_has_the_line_profile_on_every_row(kwargs):
    """L -> infinity: on |y| <= 0.05 m of a 100 m roller every row is the line contact's circle
    (exact for flat and rounded ends; for a 10 km crown within e dg/de <= y^2 / 2 R_c R / sqrt(R^2
    - x^2) = 1.25e-7 m x 1.155 at |x| = R / 2)."""
    R = 0.02
    X, Y = np.meshgrid(np.linspace(-0.01, 0.01, 21), np.linspace(-0.05, 0.05, 11))
    line = LineCylinder(R).profile(X)
    got = Cylinder(R, 100.0, **kwargs).profile(X, Y)
    atol = 0.05**2 / (2 * kwargs["crown_radius"]) * 1.1548 if "crown_radius" in kwargs else 0
    np.testing.assert_allclose(got, line, rtol=1e-13, atol=atol)


def test_crowned_roller_drops_along_one_arc():
    """e = R_c - sqrt(R_c^2 - y^2) over the whole length (y^2 / 2 R_c to small slope); relative 1e-13."""
    R, L, Rc = 0.02, 0.01, 0.2
    Y = np.array([0.0, 0.001, -0.003, 0.005])
    np.testing.assert_allclose(Cylinder(R, L, crown_radius=Rc).axial_drop(Y), _arc_drop(Rc, Y), rtol=1e-13, atol=0)
    assert Cylinder(R, L, crown_radius=Rc).axial_drop(0.004) == pytest.approx(0.004**2 / (2 * Rc), rel=2e-4)


@pytest.mark.parametrize("args, kwargs, message", [
    ((0.02, 0.006, 0.0031), {}, r"^edge_radius must be <= length / 2 = 0\.003 m \(the two end roundings meet at "
                                r"mid-length\), got 0\.0031$"),
    ((0.02, 0.006, -0.001), {}, r"^edge_radius must be finite and >= 0 m, got -0\.001$"),
    ((0.02, 0.006, math.nan), {}, r"^edge_radius must be finite and >= 0 m, got nan$"),
    ((0.002, 0.006, 0.002), {}, r"^edge_radius must be < radius = 0\.002 m \(an end rounding within the roller\), "
                                r"got 0\.002$"),
    ((0.02, 0.006), dict(crown_radius=0.0029), r"^crown_radius must be >= length / 2 = 0\.003 m \(an arc of radius "
                                               r"R_c spans at most 2 R_c\), got 0\.0029$"),
    ((0.02, 0.006), dict(crown_radius=-1.0), r"^crown_radius must be finite and > 0 m, got -1\.0$"),
    ((0.02, 0.006, 0.001), dict(crown_radius=1.0), r"^give crown_radius or edge_radius, not both"),
])
def test_bad_roller_ends_are_refused_naming_the_key(args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        Cylinder(*args, **kwargs)
    assert Cylinder(0.02, 0.006, 0.003).edge_radius == 0.003  # r_e = L / 2: the ends meet at mid-length
