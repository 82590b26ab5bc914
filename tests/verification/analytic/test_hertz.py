"""Hertz in 3D and in plane strain (:mod:`verification.analytic.hertz`): the contact
modulus, the load and indentation forms as an inverse pair, the pressure against the load
and the work against the stored energy (Clapeyron), and the line contact's formulas."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from verification import analytic as an
from verification.analytic import hertz_line_contact

G = 3.0e6  # Pa, paper sec. 10
G0, R = 1e6, 1.0  # the line contact: shear modulus (Pa), cylinder radius (m)
P = math.pi * G0 * 1e-3**2 / R  # N/m: a half-width of 1 mm


def test_effective_modulus_is_2G_over_1_minus_nu():
    assert an.effective_modulus_from_shear(G) == pytest.approx(4 * G, rel=1e-15)
    nu = 0.3
    E = 2 * G * (1 + nu)
    assert an.effective_modulus_from_shear(G, nu) == pytest.approx(E / (1 - nu**2), rel=1e-14)


@pytest.mark.parametrize("P", [1e-3, 1.0, 100.0, 1e4])
def test_hertz_from_load_and_from_indentation_are_inverse(P):
    Es = an.effective_modulus_from_shear(G)
    c = an.hertz_contact(P, 0.02, Es)
    back = an.hertz_contact_from_indentation(c.indentation, 0.02, Es)
    assert back.load == pytest.approx(P, rel=1e-13)
    for f in ("contact_radius", "indentation", "peak_pressure", "mean_pressure"):
        assert getattr(back, f) == pytest.approx(getattr(c, f), rel=1e-13)
    assert c.indentation == pytest.approx(c.contact_radius**2 / c.radius, rel=1e-14)
    assert c.mean_pressure == pytest.approx(2 * c.peak_pressure / 3, rel=1e-14)


def test_hertz_pressure_integrates_to_load_and_vanishes_outside():
    c = an.hertz_contact(100.0, 0.02, 4 * G)
    a = c.contact_radius
    total, _ = quad(lambda r: 2 * math.pi * r * c.pressure(r), 0, a, epsabs=0, epsrel=1e-12)
    assert total == pytest.approx(100.0, rel=1e-9)
    assert c.pressure(0.0) == c.peak_pressure
    np.testing.assert_array_equal(c.pressure([a, -1.5 * a, 2 * a]), 0.0)
    assert c.pressure(-0.5 * a) == c.pressure(0.5 * a)


def test_hertz_work_equals_stored_energy():
    """int_0^d P(delta) d delta = (1/2) int p (d - r^2/2R) dA = (2/5) P d (Clapeyron)."""
    R, Es = 0.02, 4 * G
    c = an.hertz_contact(100.0, R, Es)
    work, _ = quad(lambda s: an.hertz_contact_from_indentation(s, R, Es).load, 1e-300, c.indentation)
    energy, _ = quad(
        lambda r: 0.5 * c.pressure(r) * (c.indentation - r * r / (2 * R)) * 2 * math.pi * r,
        0, c.contact_radius, epsabs=0, epsrel=1e-12,
    )
    assert work == pytest.approx(energy, rel=1e-8)
    assert work == pytest.approx(0.4 * c.load * c.indentation, rel=1e-8)


def test_hertz_line_contact_formulas():
    hz = hertz_line_contact(P, R, G0)
    assert hz.half_width == pytest.approx(math.sqrt(4 * P * R / (math.pi * 4 * G0)), rel=1e-15)  # E* = 4 G
    assert hz.peak_pressure == pytest.approx(2 * G0 * hz.half_width / R, rel=1e-14)
    x = np.linspace(-hz.half_width, hz.half_width, 200001)
    assert np.trapezoid(hz.pressure(x), x) == pytest.approx(P, rel=1e-6)
    with pytest.raises(ValueError, match="load must be > 0 N/m"):
        hertz_line_contact(-1.0, R, G0)
