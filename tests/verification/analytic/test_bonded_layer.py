"""The bonded layer's Fourier-space compliance (:mod:`verification.analytic.bonded_layer`):
the kernel ``L`` of eq. 68 and its complement against high-precision arithmetic, their
decay, and the static compliance against high precision and its thin-layer and
half-space limits, without overflow."""

import mpmath as mp
import numpy as np
import pytest

from verification import analytic as an

G = 3.0e6  # Pa, paper sec. 10


def _L_mp(w, nu):
    w, kap = mp.mpf(w), 3 - 4 * mp.mpf(nu)
    return (2 * kap * mp.sinh(2 * w) - 4 * w) / (2 * kap * mp.cosh(2 * w) + 4 * w * w + kap * kap + 1)


@pytest.mark.parametrize("nu", [0.5, 0.3, -0.5])
def test_kernel_and_complement_match_320_digit_arithmetic(nu):
    w = np.concatenate([[0.0], np.logspace(-6, 2.5, 60), [0.999999, 1.0, 1.000001]])
    with mp.workdps(320):  # 1 - L ~ exp(-2w) needs the digits at w = 316
        ref = np.array([float(_L_mp(x, nu)) for x in w])
        ref_c = np.array([float(1 - _L_mp(x, nu)) for x in w])
    L = an.bonded_layer_kernel(w, nu)
    np.testing.assert_allclose(L, ref, rtol=1e-13, atol=0)
    np.testing.assert_allclose(an.bonded_layer_kernel_complement(w, nu), ref_c, rtol=1e-13, atol=0)
    assert L[0] == 0.0 and an.bonded_layer_kernel_complement(0.0, nu) == 1.0


def test_kernel_complement_decays_like_exp_minus_2w():
    """1 - L -> 0 like exp(-2w): the b_m integrals converge as printed."""
    w = np.array([10.0, 20.0, 40.0])
    c = an.bonded_layer_kernel_complement(w)
    np.testing.assert_allclose(c * np.exp(2 * w) / (4 * w * w + 4 * w + 2), 1.0, rtol=1e-6)
    assert an.bonded_layer_kernel(1e4) == 1.0


def _compliance_mp(k, H, G):
    with mp.workdps(50):
        t = mp.mpf(k) * H
        v = (mp.sinh(2 * t) - 2 * t) / (mp.cosh(2 * t) + 2 * t * t + 1) / (2 * G * mp.mpf(k))
        return float(v)


def test_compliance_matches_50_digit_arithmetic_and_is_positive():
    H = 5e-3
    k = np.concatenate([np.logspace(-4, 4.5, 80), [0.999999 / H, 1 / H, 1.000001 / H]]) / H
    ref = np.array([_compliance_mp(x, H, G) for x in k])
    C = an.layer_normal_compliance_static(k, H, G)
    np.testing.assert_allclose(C, ref, rtol=1e-13, atol=0)
    assert np.all(C > 0)  # sigma_z tension-positive, w upward: pulling lifts the surface
    np.testing.assert_allclose(C, an.bonded_layer_kernel(k * H) / (2 * G * k), rtol=1e-13)


def test_compliance_tends_to_its_thin_layer_and_halfspace_limits():
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
