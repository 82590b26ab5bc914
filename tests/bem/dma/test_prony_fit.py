"""The Prony fit: exact on a three-parameter solid, passive, errors reported honestly."""

from __future__ import annotations

import numpy as np
import pytest

from bem.dma import PronyFitError, fit_prony
from bem.materials import Prony, ThreeParameterSolid

PAPER_SOLID = ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0)  # paper section 11.1
W = np.logspace(-3, 3, 121)


@pytest.mark.parametrize("terms_per_decade", [1, 3])
def test_three_parameter_solid_is_recovered_within_1e_6(terms_per_decade):
    g = PAPER_SOLID.modulus(W)
    fit = fit_prony(W, g.real, g.imag, terms_per_decade=terms_per_decade)
    assert isinstance(fit.material, Prony)
    w = np.logspace(-4, 4, 400)  # beyond the data too: the solid is one Maxwell branch
    got, want = fit.material.modulus(w), PAPER_SOLID.modulus(w)
    np.testing.assert_allclose(got.real, want.real, rtol=1e-6)
    np.testing.assert_allclose(got.imag, want.imag, rtol=1e-6)
    # the equivalent one-term series: G_inf = G0, sum G_i = G0 f, relaxation time tau / (1 + f)
    assert fit.material.G_inf == pytest.approx(3.0e6, rel=1e-6)
    assert sum(fit.material.G) == pytest.approx(3.0e6, rel=1e-6)
    assert fit.max_error_storage < 1e-6 and fit.max_error_loss < 1e-6
    assert fit.omega_min == pytest.approx(1e-3) and fit.omega_max == pytest.approx(1e3)


def test_nnls_alone_reports_its_larger_error_and_stays_passive():
    g = PAPER_SOLID.modulus(W)
    fit = fit_prony(W, g.real, g.imag, terms_per_decade=2, refine=False)
    got = fit.material.modulus(W)
    e_s = np.abs(got.real / g.real - 1)
    e_l = np.abs(got.imag / g.imag - 1)
    assert fit.max_error_storage == pytest.approx(e_s.max(), rel=1e-9)
    assert fit.rms_error_storage == pytest.approx(np.sqrt(np.mean(e_s**2)), rel=1e-9)
    assert fit.max_error_loss == pytest.approx(e_l.max(), rel=1e-9)
    assert fit.rms_error_loss == pytest.approx(np.sqrt(np.mean(e_l**2)), rel=1e-9)
    assert 1e-3 < fit.max_error < 0.5
    assert min(fit.material.G) > 0 and fit.material.G_inf > 0


def test_fit_is_passive_at_every_frequency():
    rng = np.random.default_rng(3)
    g = PAPER_SOLID.modulus(W)
    noisy = g * (1 + 0.05 * rng.standard_normal(W.size))  # 5 % noise on both parts
    fit = fit_prony(W, noisy.real, np.abs(noisy.imag), terms_per_decade=3)
    w = np.concatenate([np.logspace(-12, 12, 2001), [0.0, np.inf]])
    loss = fit.material.modulus(w).imag
    assert np.all(loss >= 0)
    assert np.all(fit.material.modulus(-w[:-1]).imag <= 0)  # G*(-omega) = conj G*(omega)
    assert all(G > 0 for G in fit.material.G) and fit.material.G_inf > 0


def test_unreachable_tolerance_raises_naming_errors_and_tolerance():
    g = PAPER_SOLID.modulus(W)
    rng = np.random.default_rng(0)
    noisy = g * (1 + 0.05 * rng.standard_normal(W.size))
    with pytest.raises(PronyFitError, match=r"cannot reach tolerance = 0\.001: max relative error of G' is"):
        fit_prony(W, noisy.real, np.abs(noisy.imag), tolerance=1e-3)
    assert fit_prony(W, g.real, g.imag, tolerance=1e-3).max_error < 1e-3  # reachable: no error


def test_zero_relaxed_modulus_raises():
    # a Maxwell fluid: G' -> 0 at low frequency, no rubbery plateau
    x = W * 0.1
    with pytest.raises(PronyFitError, match="relaxed modulus G_inf is 0"):
        fit_prony(W, 1e6 * x * x / (1 + x * x), 1e6 * x / (1 + x * x))


@pytest.mark.parametrize("bad", [0, -1, float("nan")])
def test_terms_per_decade_must_be_positive(bad):
    g = PAPER_SOLID.modulus(W)
    with pytest.raises(PronyFitError, match="terms_per_decade must be > 0"):
        fit_prony(W, g.real, g.imag, terms_per_decade=bad)


def test_repeated_frequencies_from_overlapping_isotherms_are_fitted():
    w = np.concatenate([W, W[::10]])  # a master curve may hold the same reduced frequency twice
    g = PAPER_SOLID.modulus(w)
    fit = fit_prony(w, g.real, g.imag)
    assert fit.max_error < 1e-6
