"""Jaffar's (1997) thin incompressible layer (:mod:`verification.analytic.jaffar_thin`):
the paper's 3.7 mm and eq. 70 at ``nu = 1/2``, the load balance, the profile as a solution
of the lubrication equation with the derived indentation, and the work against the stored
energy."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from verification import analytic as an

G = 3.0e6  # Pa, paper sec. 10


def _thin():
    return an.jaffar_thin_layer_contact(10.0, 80.0, 1e-4, G)


def test_thin_layer_gives_the_papers_3_7_mm_and_eq70_at_nu_half():
    """Paper sec. 10.2: 3.7 mm (two digits: +-0.05 mm); eq. 70 at nu = 1/2 is the 32 form."""
    c = _thin()
    assert abs(c.contact_radius - 3.7e-3) <= 0.05e-3
    assert c.contact_radius**6 == pytest.approx(32 * 10.0 * 80.0 * 1e-12 / (math.pi * G), rel=1e-13)
    assert c.thickness_ratio < 0.03


def test_thin_layer_pressure_integrates_to_the_load():
    c = _thin()
    total, _ = quad(lambda r: 2 * math.pi * r * c.pressure(r), 0, c.contact_radius, epsabs=0, epsrel=1e-12)
    assert total == pytest.approx(10.0, rel=1e-10)
    assert c.pressure(0.0) == pytest.approx(3 * 10.0 / (math.pi * c.contact_radius**2), rel=1e-15)
    np.testing.assert_array_equal(c.pressure([c.contact_radius, 3 * c.contact_radius]), 0.0)


def test_thin_layer_profile_solves_the_lubrication_equation():
    """-(H^3 / 3G) lap p = d - r^2 / (2R) inside the contact, with d = r_c^2 / (4R)."""
    c = _thin()
    a, H, R = c.contact_radius, c.thickness, c.radius
    r = np.linspace(0.05, 0.95, 19) * a
    h = 1e-3 * a
    p = c.pressure
    lap = (p(r + h) - 2 * p(r) + p(r - h)) / h**2 + (p(r + h) - p(r - h)) / (2 * h * r)
    u = -(H**3) / (3 * G) * lap
    np.testing.assert_allclose(u, c.indentation - r * r / (2 * R), rtol=0, atol=1e-6 * c.indentation)
    assert c.indentation == pytest.approx(a * a / (4 * R), rel=1e-13)
    assert c.indentation == pytest.approx(8 * H**3 * c.peak_pressure / (3 * G * a * a), rel=1e-15)


def test_thin_layer_work_equals_stored_energy():
    """d ~ P^(1/3), so the work is P d / 4; Clapeyron: (1/2) int p u dA is the same."""
    c = _thin()
    c8 = an.jaffar_thin_layer_contact(80.0, 80.0, 1e-4, G)
    assert c8.indentation == pytest.approx(2 * c.indentation, rel=1e-13)
    energy, _ = quad(
        lambda r: 0.5 * c.pressure(r) * (c.indentation - r * r / (2 * c.radius)) * 2 * math.pi * r,
        0, c.contact_radius, epsabs=0, epsrel=1e-12,
    )
    assert energy == pytest.approx(c.load * c.indentation / 4, rel=1e-9)
