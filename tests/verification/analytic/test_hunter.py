"""Hunter's (1961) rigid cylinder rolling on a standard-linear-solid half-space
(:mod:`verification.analytic.hunter`).

Checked against its own limits (relaxed 2D Hertz as V -> 0, glassy 2D Hertz as V -> inf,
R_r -> 0 at both ends and positive between) and against the integral equation it solves,
evaluated by direct quadrature of the Cauchy integral rather than by the Chebyshev series
the solution is built from. The comparison with the plane-strain BEM is in
``tests/bem/test_plane.py``.
"""

import functools
import math

import numpy as np
import pytest
from scipy.integrate import quad

from verification.analytic import hertz_line_contact, hunter_rolling_contact

G0, TAU, F, R = 1e6, 1.0, 2.0, 1.0
B0 = 1e-3  # relaxed Hertz half-width (m)
P = math.pi * G0 * B0**2 / R  # N/m
BG = B0 / math.sqrt(1 + F)  # glassy Hertz half-width


@functools.lru_cache(maxsize=None)
def _hunter(s):
    """Hunter at V tau / b0 = s."""
    return hunter_rolling_contact(P, R, G0, TAU, F, s * B0 / TAU)


def _theta_quad(h, fn, n=400):
    """integral over the contact of fn(x) p(x) dx, by Gauss-Legendre in theta (x = c + a cos theta)."""
    t, w = np.polynomial.legendre.leggauss(n)
    th = (t + 1) * math.pi / 2
    x = h.centre + h.half_width * np.cos(th)
    return float(np.sum(w * fn(x) * h.pressure(x) * h.half_width * np.sin(th)) * math.pi / 2)

@pytest.mark.parametrize("s", [1e-3, 0.3, 1.0, 3.0, 1e3, 1e5])
def test_hunter_balances_the_load_and_its_moment(s):
    """The series pressure integrates to P (the closed-form load condition) and its moment
    about the axis is the closed-form R_r (beta_2); it is >= 0 and vanishes at both edges."""
    h = _hunter(s)
    assert _theta_quad(h, lambda x: 1.0) == pytest.approx(P, rel=1e-10)
    assert _theta_quad(h, lambda x: x / R) == pytest.approx(h.rolling_resistance, rel=1e-8, abs=1e-14 * P)
    x = np.linspace(h.trailing_edge, h.leading_edge, 2001)
    p = h.pressure(x)
    assert p.min() >= -1e-9 * p.max()
    assert max(p[0], p[-1]) <= 1e-6 * p.max()  # the edges as c -/+ a, rounded: 4e-8 measured
    assert h.pressure(np.array([h.trailing_edge - 1e-9, h.leading_edge + 1e-9])).tolist() == [0.0, 0.0]


def test_hunter_slow_limit_is_relaxed_hertz():
    """As V -> 0 the contact tends to relaxed 2D Hertz, linearly in V (measured at
    V tau / b0 = 1e-3: a / b0 - 1 = -3.33e-4, c / b0 = 3.33e-4, i.e. V tau / (3 b0), and
    ten times that at 1e-2); the pressure differs only in a boundary layer of width
    V tau / (1 + f) at the leading edge."""
    hz = hertz_line_contact(P, R, G0)
    slow, slower = _hunter(1e-2), _hunter(1e-3)
    dev = [h.half_width / hz.half_width - 1 for h in (slow, slower)]
    assert -1e-3 < dev[1] < 0 and dev[0] / dev[1] == pytest.approx(10, rel=0.01)
    assert 0 < slower.centre < 1e-3 * B0 and slow.centre / slower.centre == pytest.approx(10, rel=0.01)
    x = np.linspace(-0.9 * B0, 0.9 * B0, 101)  # outside the boundary layer
    assert np.abs(slower.pressure(x) - hz.pressure(x)).max() < 2e-3 * hz.peak_pressure
    assert 0 < slower.rolling_resistance_coefficient < slow.rolling_resistance_coefficient < 1e-5


def test_hunter_fast_limit_is_glassy_hertz():
    """As V -> inf the contact tends to glassy 2D Hertz (G0 (1 + f)); measured at
    V tau / b0 = 1e5: a / b_g - 1 = 1e-10, c = 4e-5 b0, R_r / P = 4e-8."""
    h, hz = _hunter(1e5), hertz_line_contact(P, R, G0 * (1 + F))
    assert h.half_width / hz.half_width == pytest.approx(1.0, abs=1e-8)
    assert 0 < h.centre < 1e-4 * B0
    x = np.linspace(-0.99 * BG, 0.99 * BG, 101)  # measured 5e-4 of p0 at 0.99 a (the offset c)
    assert np.abs(h.pressure(x) - hz.pressure(x)).max() < 1e-3 * hz.peak_pressure
    assert 0 < h.rolling_resistance_coefficient < 1e-7


def test_hunter_rolling_resistance_rises_and_falls():
    """R_r > 0 at every speed, rising from V = 0 to one peak near V tau / b0 ~ 1 and falling
    again; the contact shrinks monotonically from b0 to the glassy half-width and its middle
    moves ahead (c > 0)."""
    s = np.logspace(-3, 5, 17)
    runs = [_hunter(v) for v in s]
    rr = np.array([h.rolling_resistance for h in runs])
    a = np.array([h.half_width for h in runs])
    assert (rr > 0).all()
    peak = int(np.argmax(rr))
    assert 0 < peak < s.size - 1 and 0.3 < s[peak] < 3
    assert (np.diff(rr[: peak + 1]) > 0).all() and (np.diff(rr[peak:]) < 0).all()
    assert (np.diff(a) < 0).all() and BG < a.min() and a.max() < B0
    assert all(h.centre > 0 for h in runs)
    assert rr[1] / rr[0] == pytest.approx(s[1] / s[0], rel=1e-2)  # R_r ~ V at low speed


def test_hunter_without_relaxation_or_at_rest_is_relaxed_hertz():
    for h in (hunter_rolling_contact(P, R, G0, TAU, 0.0, 1.0), hunter_rolling_contact(P, R, G0, TAU, F, 0.0)):
        assert h.half_width == pytest.approx(B0, rel=1e-14) and h.rolling_resistance == 0.0


def _check_integral_equation(s, points, rtol):
    """The cylinder's slope -x/R equals the viscoelastic surface slope at ``points`` (in
    units of a from the contact's middle), with the unit-modulus slope
    phi = (1/2 pi) int p(s)/(s - x) ds computed by adaptive quadrature (Cauchy weight
    inside), not by the series, and the memory of the material ahead:
    u' = J_g phi(x) + (dJ / V tau) int_x^inf exp(-(xi - x)/(V tau)) phi(xi) dxi.
    The solution imposes this only through its derivative inside and at the leading edge."""
    h = _hunter(s)
    lam = s * B0
    Jg, dJ = 1 / (G0 * (1 + F)), F / (G0 * (1 + F))
    c1, c2 = h.trailing_edge, h.leading_edge

    def phi(x):
        if c1 < x < c2:
            val, _ = quad(h.pressure, c1, c2, weight="cauchy", wvar=x, limit=200, epsabs=0, epsrel=rtol)
        else:
            val, _ = quad(lambda t: h.pressure(t) / (t - x), c1, c2, limit=200, epsabs=0, epsrel=rtol)
        return val / (2 * math.pi)

    gl, wl = np.polynomial.legendre.leggauss(48)

    def gauss(fn, hi):  # int_0^hi fn(r) dr, 48-point Gauss-Legendre
        return sum(w * fn(r) for r, w in zip(hi * (gl + 1) / 2, wl * hi / 2))

    def slope(x):
        # memory over [x, c2] in r = sqrt(c2 - t) and ahead in v = sqrt((t - c2) / lam):
        # phi has a square-root cusp at the edge, smooth in r and v
        inside = gauss(lambda r: math.exp(-(c2 - r * r - x) / lam) * phi(c2 - r * r) * 2 * r, math.sqrt(c2 - x))
        ahead = gauss(lambda v: math.exp(-v * v) * phi(c2 + lam * v * v) * 2 * v * lam, 8.0)
        return Jg * phi(x) + dJ / lam * (inside + math.exp(-(c2 - x) / lam) * ahead)

    scale = h.half_width / R
    return [abs(slope(h.centre + t * h.half_width) + (h.centre + t * h.half_width) / R) / scale for t in points]


def test_hunter_satisfies_the_rolling_integral_equation():
    # measured: 2.8e-10 of a / R at the middle, V tau / b0 = 1 (quadrature tolerance 1e-6)
    assert max(_check_integral_equation(1.0, (0.0,), 1e-6)) < 1e-7


@pytest.mark.slow
@pytest.mark.parametrize("s", [0.1, 10.0])
def test_hunter_satisfies_the_rolling_integral_equation_across_the_contact(s):
    # measured: <= 4.2e-13 (V tau / b0 = 0.1) and 6.6e-13 (10) of a / R
    assert max(_check_integral_equation(s, (-0.8, 0.2, 0.7), 1e-8)) < 1e-10


def test_hunter_rejects_negative_speed_or_f_and_zero_tau():
    with pytest.raises(ValueError, match="speed must be >= 0"):
        hunter_rolling_contact(P, R, G0, TAU, F, -1.0)
    with pytest.raises(ValueError, match="f must be >= 0"):
        hunter_rolling_contact(P, R, G0, TAU, -0.5, 1.0)
    with pytest.raises(ValueError, match="tau must be > 0 s"):
        hunter_rolling_contact(P, R, G0, 0.0, F, 1.0)
