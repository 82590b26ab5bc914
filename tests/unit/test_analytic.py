"""Tests of the analytic references in :mod:`verification.analytic` (fast)."""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import spherical_jn

from verification import analytic as an

G = 3.0e6  # Pa, paper sec. 10


# ---------------------------------------------------------------------------------------
# Hertz


def test_effective_modulus_from_shear():
    assert an.effective_modulus_from_shear(G) == pytest.approx(4 * G, rel=1e-15)
    nu = 0.3
    E = 2 * G * (1 + nu)
    assert an.effective_modulus_from_shear(G, nu) == pytest.approx(E / (1 - nu**2), rel=1e-14)


@pytest.mark.parametrize("P", [1e-3, 1.0, 100.0, 1e4])
def test_hertz_inverse_pair(P):
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


# ---------------------------------------------------------------------------------------
# kernel L of eq. 68 and b_m of eq. 67


def _L_mp(w, nu):
    w, kap = mp.mpf(w), 3 - 4 * mp.mpf(nu)
    return (2 * kap * mp.sinh(2 * w) - 4 * w) / (2 * kap * mp.cosh(2 * w) + 4 * w * w + kap * kap + 1)


@pytest.mark.parametrize("nu", [0.5, 0.3, -0.5])
def test_kernel_against_high_precision(nu):
    w = np.concatenate([[0.0], np.logspace(-6, 2.5, 60), [0.999999, 1.0, 1.000001]])
    with mp.workdps(320):  # 1 - L ~ exp(-2w) needs the digits at w = 316
        ref = np.array([float(_L_mp(x, nu)) for x in w])
        ref_c = np.array([float(1 - _L_mp(x, nu)) for x in w])
    L = an.bonded_layer_kernel(w, nu)
    np.testing.assert_allclose(L, ref, rtol=1e-13, atol=0)
    np.testing.assert_allclose(an.bonded_layer_kernel_complement(w, nu), ref_c, rtol=1e-13, atol=0)
    assert L[0] == 0.0 and an.bonded_layer_kernel_complement(0.0, nu) == 1.0


def test_kernel_complement_decays():
    """1 - L -> 0 like exp(-2w): the b_m integrals converge as printed."""
    w = np.array([10.0, 20.0, 40.0])
    c = an.bonded_layer_kernel_complement(w)
    np.testing.assert_allclose(c * np.exp(2 * w) / (4 * w * w + 4 * w + 2), 1.0, rtol=1e-6)
    assert an.bonded_layer_kernel(1e4) == 1.0


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


# ---------------------------------------------------------------------------------------
# Jaffar (2008), thick layer


def test_thick_paper_value():
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
def test_thick_tends_to_hertz(nu):
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


def test_thick_pressure_integrates_to_load():
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


def test_thick_too_thin_raises():
    with pytest.raises(ValueError, match="no thick-layer solution"):
        an.jaffar_thick_layer_contact(100.0, 0.02, 1e-4, G)


# ---------------------------------------------------------------------------------------
# Jaffar (1997), thin layer


def _thin():
    return an.jaffar_thin_layer_contact(10.0, 80.0, 1e-4, G)


def test_thin_paper_value():
    """Paper sec. 10.2: 3.7 mm (two digits: +-0.05 mm); eq. 70 at nu = 1/2 is the 32 form."""
    c = _thin()
    assert abs(c.contact_radius - 3.7e-3) <= 0.05e-3
    assert c.contact_radius**6 == pytest.approx(32 * 10.0 * 80.0 * 1e-12 / (math.pi * G), rel=1e-13)
    assert c.thickness_ratio < 0.03


def test_thin_pressure_integrates_to_load():
    c = _thin()
    total, _ = quad(lambda r: 2 * math.pi * r * c.pressure(r), 0, c.contact_radius, epsabs=0, epsrel=1e-12)
    assert total == pytest.approx(10.0, rel=1e-10)
    assert c.pressure(0.0) == pytest.approx(3 * 10.0 / (math.pi * c.contact_radius**2), rel=1e-15)
    np.testing.assert_array_equal(c.pressure([c.contact_radius, 3 * c.contact_radius]), 0.0)


def test_thin_profile_solves_the_lubrication_equation():
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


def test_thin_work_equals_stored_energy():
    """d ~ P^(1/3), so the work is P d / 4; Clapeyron: (1/2) int p u dA is the same."""
    c = _thin()
    c8 = an.jaffar_thin_layer_contact(80.0, 80.0, 1e-4, G)
    assert c8.indentation == pytest.approx(2 * c.indentation, rel=1e-13)
    energy, _ = quad(
        lambda r: 0.5 * c.pressure(r) * (c.indentation - r * r / (2 * c.radius)) * 2 * math.pi * r,
        0, c.contact_radius, epsabs=0, epsrel=1e-12,
    )
    assert energy == pytest.approx(c.load * c.indentation / 4, rel=1e-9)


# ---------------------------------------------------------------------------------------
# Fourier-space compliance


def _compliance_mp(k, H, G):
    with mp.workdps(50):
        t = mp.mpf(k) * H
        v = (mp.sinh(2 * t) - 2 * t) / (mp.cosh(2 * t) + 2 * t * t + 1) / (2 * G * mp.mpf(k))
        return float(v)


def test_compliance_against_high_precision():
    H = 5e-3
    k = np.concatenate([np.logspace(-4, 4.5, 80), [0.999999 / H, 1 / H, 1.000001 / H]]) / H
    ref = np.array([_compliance_mp(x, H, G) for x in k])
    C = an.layer_normal_compliance_static(k, H, G)
    np.testing.assert_allclose(C, ref, rtol=1e-13, atol=0)
    assert np.all(C > 0)  # sigma_z tension-positive, w upward: pulling lifts the surface
    np.testing.assert_allclose(C, an.bonded_layer_kernel(k * H) / (2 * G * k), rtol=1e-13)


def test_compliance_limits():
    H = 5e-3
    t = np.logspace(-4, -1, 7)
    ratio = an.layer_normal_compliance_static(t / H, H, G) / an.thin_layer_normal_compliance_static(t / H, H, G)
    assert np.all(np.abs(ratio - (1 - 1.8 * t**2)) <= 5 * t**4)  # L = (2t^3/3)(1 - 9t^2/5 + O(t^4))
    t = np.array([10.0, 20.0, 40.0, 1e6])
    ratio = an.layer_normal_compliance_static(t / H, H, G) / an.halfspace_normal_compliance_static(t / H, G)
    np.testing.assert_allclose(ratio, 1 - (4 * t * t + 4 * t + 2) * np.exp(-2 * t), rtol=1e-12)
    assert an.layer_normal_compliance_static(0.0, H, G) == 0.0  # no motion under uniform pressure
    assert an.halfspace_normal_compliance_static(0.0, G) == np.inf


def test_compliance_shape_and_no_overflow():
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        C = an.layer_normal_compliance_static(np.array([[0.0, 1.0], [1e3, 1e12]]), 5e-3, G)
    assert C.shape == (2, 2) and np.all(np.isfinite(C))


# ---------------------------------------------------------------------------------------
# validation


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: an.hertz_contact(100.0, -1, 4 * G), "radius must be > 0 m, got -1"),
        (lambda: an.hertz_contact(0.0, 0.02, 4 * G), "load must be > 0 N, got 0.0"),
        (lambda: an.hertz_contact(1.0, 0.02, -5.0), "effective_modulus must be > 0 Pa, got -5.0"),
        (lambda: an.hertz_contact_from_indentation(-1e-4, 0.02, 4 * G), "indentation must be > 0 m, got -0.0001"),
        (lambda: an.effective_modulus_from_shear(G, 0.7), r"poisson_ratio must be in \(-1, 0.5\], got 0.7"),
        (lambda: an.jaffar_thick_layer_contact(1.0, 0.02, -0.005, G), "thickness must be > 0 m, got -0.005"),
        (lambda: an.jaffar_thick_layer_contact(1.0, 0.02, 0.005, 0), "shear_modulus must be > 0 Pa, got 0"),
        (lambda: an.jaffar_thin_layer_contact(1.0, 1.0, 1e-4, G, 0.3), "poisson_ratio must be 0.5"),
        (lambda: an.layer_normal_compliance_static([1.0, -2.0], 0.005, G), "wavenumber must be >= 0 rad/m"),
        (lambda: an.hertz_contact(float("nan"), 0.02, 4 * G), "load must be finite, got nan"),
        (lambda: an.jaffar_b_coefficient(-1), "m must be an integer >= 0, got -1"),
    ],
)
def test_validation_messages(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_rejects_non_numbers():
    with pytest.raises(TypeError, match="radius must be a real number in m"):
        an.hertz_contact(1.0, "2 cm", 4 * G)
    with pytest.raises(TypeError, match="load"):
        an.hertz_contact(True, 0.02, 4 * G)


def test_results_are_frozen():
    c = an.hertz_contact(1.0, 0.02, 4 * G)
    with pytest.raises(AttributeError):
        c.load = 2.0
