"""Jaffar's (2008) thick-layer contact (:mod:`verification.analytic.jaffar_thick`): the
coefficients ``b_m`` of eq. 67 against mpmath, the paper's 4.56 mm with ``gamma = r_c / H``
and eqs. 65-66, the Hertz limit of a thick layer, the load balance, eq. 66 as the
small-``gamma`` expansion of the full curvature match, and the refusal of a layer too thin
for the expansion."""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import spherical_jn

from verification import analytic as an

G = 3.0e6  # Pa, paper sec. 10


def _L_mp(w, nu):
    w, kap = mp.mpf(w), 3 - 4 * mp.mpf(nu)
    return (2 * kap * mp.sinh(2 * w) - 4 * w) / (2 * kap * mp.cosh(2 * w) + 4 * w * w + kap * kap + 1)


@pytest.mark.parametrize("nu", [0.5, 0.25])
def test_b_coefficients_against_mpmath(nu):
    with mp.workdps(30):
        for m in (1, 2):
            ref = mp.quad(lambda w: (1 - _L_mp(w, nu)) * w ** (2 * m), [0, 1, 5, 20, mp.inf])
            assert an.jaffar_b_coefficient(m, nu) == pytest.approx(float((-0.25) ** m * ref), rel=1e-11)


def test_b_coefficient_values_and_signs():
    b1, b2 = an.jaffar_b_coefficient(1), an.jaffar_b_coefficient(2)
    assert b1 == pytest.approx(-0.957769288898, abs=1e-11)  # regression, computed once
    assert b2 == pytest.approx(1.749436123750, abs=1e-11)
    for nu in (0.5, 0.0, -0.9):
        assert an.jaffar_b_coefficient(1, nu) < 0 < an.jaffar_b_coefficient(2, nu)


def test_thick_layer_gives_the_papers_4_56_mm_and_satisfies_eqs_65_66():
    """Paper sec. 10.1: 4.56 mm (three digits: +-0.005 mm), with gamma = r_c / H."""
    c = an.jaffar_thick_layer_contact(100.0, 0.02, 5e-3, G, 0.5)
    assert abs(c.contact_radius - 4.56e-3) <= 0.005e-3
    assert c.gamma == pytest.approx(c.contact_radius / c.thickness, rel=1e-15)
    lhs = c.contact_radius**3
    rhs = c.load * c.radius * c.D * (1 - c.poisson_ratio) / (8 * math.pi * c.shear_modulus)
    assert lhs == pytest.approx(rhs, rel=1e-12)  # eq. 65
    D = 3 * math.pi + 8 * c.gamma**3 * (c.b1 + 0.4 * c.b2 * c.gamma**2)
    assert c.D == pytest.approx(D, rel=1e-15)  # eq. 66


@pytest.mark.parametrize("nu", [0.5, 0.3])
def test_thick_layer_tends_to_hertz_as_the_layer_thickens(nu):
    """H -> inf: D -> 3 pi and r_c^3 -> 3 P R (1 - nu) / (8 G), Hertz with E* = 2G/(1-nu)."""
    hz = an.hertz_contact(100.0, 0.02, an.effective_modulus_from_shear(G, nu))
    if nu == 0.5:
        assert hz.contact_radius**3 == pytest.approx(3 * 100.0 * 0.02 / (16 * G), rel=1e-14)
    prev = None
    for H in (0.05, 0.5, 5.0, 500.0):
        c = an.jaffar_thick_layer_contact(100.0, 0.02, H, G, nu)
        err = hz.contact_radius / c.contact_radius - 1
        assert err > 0  # a bonded layer is stiffer than the half-space
        if prev is not None:
            assert err == pytest.approx(prev * 1e-3, rel=0.01)  # O(gamma^3)
        prev = err
    assert err < 1e-11
    assert c.D == pytest.approx(3 * math.pi, rel=1e-11)


def test_thick_layer_pressure_integrates_to_the_load():
    c = an.jaffar_thick_layer_contact(100.0, 0.02, 5e-3, G)
    total, _ = quad(lambda r: 2 * math.pi * r * c.pressure(r), 0, c.contact_radius, epsabs=0, epsrel=1e-12)
    assert total == pytest.approx(100.0, rel=1e-9)
    assert c.pressure(0.0) == pytest.approx(3 * 100.0 / (2 * math.pi * c.contact_radius**2), rel=1e-15)


def _phi(x):
    """Hankel transform of the unit Hertz profile over a^2: j1(x)/x (1/3 at 0)."""
    return 1 / 3 - x * x / 30 if x < 1e-3 else spherical_jn(1, x) / x


@pytest.mark.parametrize("gamma", [0.1, 0.2, 0.3])
def test_eq66_is_the_small_gamma_expansion(gamma):
    """Independent re-derivation of eq. 66: matching the centre curvature of the layer's
    deflection under a Hertz profile (kernel L, Hankel quadrature) gives
    D_full = 3 pi - 6 gamma^3 int j1(gamma t)/(gamma t) (1 - L(t)) t^2 dt. Eq. 66 is its
    expansion to gamma^5; the gap is the next term -6 gamma^7 I_3 / 840 + O(gamma^9)."""
    f = lambda t: _phi(gamma * t) * an.bonded_layer_kernel_complement(t) * t * t
    Phi, _ = quad(f, 0, np.inf, epsabs=0, epsrel=1e-13, limit=200)
    D_full = 3 * math.pi - 6 * gamma**3 * Phi
    b1, b2 = an.jaffar_b_coefficient(1), an.jaffar_b_coefficient(2)
    D_66 = 3 * math.pi + 8 * gamma**3 * (b1 + 0.4 * b2 * gamma**2)
    I3 = -64 * an.jaffar_b_coefficient(3)
    next_term = -6 * gamma**7 * I3 / 840
    assert D_full - D_66 == pytest.approx(next_term, rel=gamma**2)  # observed 0.4 gamma^2


def test_thick_layer_refuses_a_layer_too_thin_for_the_load():
    with pytest.raises(ValueError, match="no thick-layer solution"):
        an.jaffar_thick_layer_contact(100.0, 0.02, 1e-4, G)
