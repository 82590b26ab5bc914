"""bem.kinematics against closed forms: the upwind difference of a quadratic, the
difference of a convolution against the convolution with the differenced kernel (a second
algorithm), the indenter's radius and the distance to the axis of rotation (Pythagoras).
Tolerances are a few ulps of the compared quantities (stated per test).
"""

import math

import numpy as np
import pytest
from scipy.signal import convolve2d

from bem.indenters import Cylinder, HeightMap, Paraboloid, Sphere
from bem.kinematics import indenter_radius, rolling_radius, upwind_field, upwind_table


def test_upwind_difference_of_a_quadratic_is_the_slope_half_a_step_upstream():
    """f = x^2: (f_{i+1} - f_i) / a = 2 x_i + a exactly (the forward, upwind difference;
    the downwind one would give 2 x_i - a, a centred one 2 x_i). The last column (the
    leading edge) repeats its neighbour. Rounding of the differences of f ~ 3.5e-3 over
    a = 2.5e-4 gives ~3e-15 (measured 1.3e-15); 1e-13 is still 2500 times smaller than
    the a = 2.5e-4 that tells the upwind difference from the others."""
    a = 0.25e-3
    x = np.arange(-6, 7) * a
    y = np.arange(-2, 3) * a
    X, Y = np.meshgrid(x, y)
    f = X**2 + 7.0 * Y  # the y dependence must not leak into d/dx
    d = upwind_field(f, a)
    expect = 2 * X[:, :-1] + a
    np.testing.assert_allclose(d[:, :-1], expect, rtol=0, atol=1e-13)
    np.testing.assert_array_equal(d[:, -1], d[:, -2])
    assert d.shape == f.shape
    dt = upwind_table(f, a)
    np.testing.assert_allclose(dt[:, :-1], expect, rtol=0, atol=1e-13)
    np.testing.assert_array_equal(dt[:, -1], dt[:, -2])
    assert dt.shape == f.shape


def test_upwind_field_accepts_lists_of_integers():
    """A nodal field given as integers is differenced in floating point (no truncation)."""
    np.testing.assert_allclose(upwind_field([[0, 1, 4]], 0.3), [[1 / 0.3, 3 / 0.3, 3 / 0.3]], rtol=1e-15, atol=0)


def test_differenced_kernel_applied_is_the_difference_of_the_applied_kernel():
    """A second algorithm: differencing the displacement u = K * F (a convolution) must
    equal convolving F with the differenced kernel Kd, at every node off the leading edge
    whose stencil stays inside the table. Random data; 1e-12 relative (measured 2e-16)."""
    rng = np.random.default_rng(3)
    Ky, Kx = 5, 7
    K = rng.normal(size=(2 * Ky - 1, 2 * Kx - 1))
    F = rng.normal(size=(Ky, Kx))
    a = 0.37
    u = convolve2d(F, K, mode="full")[Ky - 1 : 2 * Ky - 1, Kx - 1 : 2 * Kx - 1]
    Kd = upwind_table(K, a)
    ud = convolve2d(F, Kd, mode="full")[Ky - 1 : 2 * Ky - 1, Kx - 1 : 2 * Kx - 1]
    du = upwind_field(u, a)
    np.testing.assert_allclose(ud[:, :-1], du[:, :-1], rtol=1e-12, atol=1e-12 * np.abs(du).max())


def test_indenter_radius_override_then_own_radius_then_error():
    assert indenter_radius(Sphere(0.02)) == 0.02
    assert indenter_radius(Sphere(0.02), 0.05) == 0.05
    r = indenter_radius(Sphere(0.02), 1)
    assert r == 1.0 and type(r) is float
    x = np.linspace(0, 1, 3)
    with pytest.raises(ValueError, match=r"^this indenter has no radius: give friction\.radius \(m\), the distance "
                       r"from its axis of rotation to its lowest point$"):
        indenter_radius(HeightMap(x, x, np.zeros((3, 3))))
    assert indenter_radius(HeightMap(x, x, np.zeros((3, 3))), 0.3) == 0.3
    for bad in (0.0, -1.0, math.inf, math.nan):
        with pytest.raises(ValueError, match=r"^radius must be > 0 m, got "):
            indenter_radius(Sphere(0.02), bad)


def test_rolling_radius_is_the_distance_to_the_axis():
    """Sphere/paraboloid: sqrt(R^2 - y^2) (Pythagoras), 0 beyond the sphere; a cylinder,
    or any body given only a radius, R everywhere. Exact to 1 ulp."""
    R = 0.02
    Y = np.array([[0.0, 0.006, -0.012], [0.016, 0.02, 0.03]])
    expect = np.array([[0.02, math.sqrt(R**2 - 0.006**2), 0.016], [0.012, 0.0, 0.0]])
    for body in (Sphere(R), Paraboloid(R)):
        got = rolling_radius(body, Y)
        assert got.shape == Y.shape
        np.testing.assert_allclose(got, expect, rtol=1e-15, atol=1e-18)
    np.testing.assert_array_equal(rolling_radius(Cylinder(R, 0.01), Y), np.full(Y.shape, R))
    np.testing.assert_array_equal(rolling_radius(Sphere(R), Y, 0.05), np.full(Y.shape, 0.05))
    np.testing.assert_array_equal(rolling_radius(Sphere(R), [0.001, 0.002], 0.05), [0.05, 0.05])
