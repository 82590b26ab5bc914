"""Shift laws: their identities, their fits, and the errors of impossible shifting."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bem.dma import (Arrhenius, DMAData, ShiftError, WLF, build_master_curve, fit_arrhenius,
                     fit_wlf, overlap_shifts)
from bem.dma.shift import GAS_CONSTANT


def test_wlf_is_zero_at_T_ref_and_matches_its_formula():
    law = WLF(17.44, 51.6, 373.0)
    assert law.log_aT(373.0) == 0.0
    assert law.log_aT(383.0) == pytest.approx(-17.44 * 10 / 61.6)
    assert law.log_aT(363.0) > 0  # colder: slower, a_T > 1


def test_arrhenius_slope_is_activation_energy_over_R_ln10():
    law = Arrhenius(100e3, 300.0)
    assert law.log_aT(300.0) == 0.0
    T = np.array([280.0, 320.0])
    slope = np.diff(law.log_aT(T)) / np.diff(1 / T)
    assert slope[0] == pytest.approx(100e3 / (GAS_CONSTANT * math.log(10)))


def test_wlf_singularity_is_refused_at_and_below_T_ref_minus_C2():
    law = WLF(8.86, 101.6, 293.15)
    pattern = r"temperature 191.55 K is at or below the WLF singularity T_ref - C2 = 293.15 - 101.6 = 191.55 K"
    with pytest.raises(ShiftError, match=pattern):
        law.log_aT([300.0, 293.15 - 101.6])
    with pytest.raises(ShiftError, match="at or below the WLF singularity"):
        law.log_aT(150.0)
    assert np.isfinite(law.log_aT(191.56))


def test_wlf_singularity_is_refused_for_an_isotherm_and_a_service_temperature():
    law = WLF(8.86, 30.0, 293.15)
    data = DMAData.from_arrays([250.0, 300.0], [[1.0, 2.0]] * 2, [[1.0, 2.0]] * 2, [[0.1, 0.2]] * 2)
    with pytest.raises(ShiftError, match=r"temperature 250 K is at or below the WLF singularity"):
        build_master_curve(data, law=law)
    ok = DMAData.from_arrays([280.0, 300.0], [[1.0, 2.0]] * 2, [[1.0, 2.0]] * 2, [[0.1, 0.2]] * 2)
    master = build_master_curve(ok, law=law)
    with pytest.raises(ShiftError, match=r"temperature 263.15 K is at or below the WLF singularity"):
        master.table(263.15)


@pytest.mark.parametrize("kwargs, pattern", [
    (dict(C1=-1.0, C2=50.0, T_ref=300.0), r"WLF.C1 must be a finite number > 0"),
    (dict(C1=8.0, C2=0.0, T_ref=300.0), r"WLF.C2 must be a finite number > 0 K, got 0.0"),
    (dict(C1=8.0, C2=50.0, T_ref=math.inf), r"WLF.T_ref must be a finite number > 0 K, got inf"),
])
def test_wlf_constants_are_validated(kwargs, pattern):
    with pytest.raises(ShiftError, match=pattern):
        WLF(**kwargs)


def test_arrhenius_constants_are_validated():
    with pytest.raises(ShiftError, match=r"Arrhenius.activation_energy must be a finite number > 0 J/mol, got -5"):
        Arrhenius(-5, 300.0)


def test_law_fits_recover_exact_constants_with_and_without_offset():
    T = np.linspace(260.0, 360.0, 9)
    wlf = WLF(8.86, 101.6, 293.15)
    law, c = fit_wlf(T, wlf.log_aT(T) + 0.7, 293.15, offset=True)
    assert (law.C1, law.C2, c) == pytest.approx((8.86, 101.6, 0.7), rel=1e-6)
    law, c = fit_wlf(T, wlf.log_aT(T), 293.15)
    assert (law.C1, law.C2, c) == pytest.approx((8.86, 101.6, 0.0), rel=1e-6)
    arr = Arrhenius(120e3, 300.0)
    law, c = fit_arrhenius(T, arr.log_aT(T) - 2.0, 300.0, offset=True)
    assert (law.activation_energy, c) == pytest.approx((120e3, -2.0), rel=1e-9)


def test_wlf_fit_of_straight_arrhenius_like_shifts_is_refused():
    T = np.linspace(260.0, 360.0, 9)
    with pytest.raises(ShiftError, match="no WLF curvature"):
        fit_wlf(T, -0.05 * (T - 300.0), 300.0, offset=True)


def test_a_single_isotherm_cannot_be_shifted():
    data = DMAData.from_arrays([300.0], [[1.0, 2.0, 3.0]], [[1.0, 2.0, 3.0]], [[0.1, 0.2, 0.3]], source="one.csv")
    with pytest.raises(ShiftError, match=r"one.csv: shifting needs at least 2 isotherms, got 1 \(at 300.00 K\)"):
        build_master_curve(data, 300.0, "wlf")
    with pytest.raises(ShiftError, match="at least 2 isotherms"):
        overlap_shifts(data)
    # with a given law there is nothing to fit: one isotherm is fine
    assert build_master_curve(data, law=WLF(8.0, 100.0, 300.0)).log_aT[0] == 0.0


def test_too_short_isotherms_cannot_overlap():
    data = DMAData.from_arrays([300.0, 310.0], [[1.0, 2.0]] * 2, [[1.0, 2.0]] * 2, [[0.1, 0.2]] * 2)
    with pytest.raises(ShiftError, match=r"cannot overlap by min_overlap = 0.5 decades"):
        overlap_shifts(data)


@pytest.mark.parametrize("kwargs, pattern", [
    (dict(law="williams"), r"law must be 'wlf', 'arrhenius', a WLF or an Arrhenius, got 'williams'"),
    (dict(law="wlf", T_ref=None), r"T_ref must be given as a temperature > 0 K to fit a wlf law, got None"),
    (dict(law="wlf", vertical="up"), r"vertical must be None, 'density' or 'fit', got 'up'"),
    (dict(law=WLF(8.0, 100.0, 300.0), T_ref=310.0), r"T_ref = 310.0 K differs from the given law's T_ref = 300.0 K"),
    (dict(law=WLF(8.0, 100.0, 300.0), vertical="fit"), r"vertical='fit' fits shifts from the data"),
    (dict(law="wlf", vertical="density"), r"needs the density argument or a density_kg_m3 column"),
    (dict(law="wlf", quantity="phase"), r"quantity must be 'both', 'modulus' or 'tan_delta', got 'phase'"),
])
def test_bad_master_curve_options_are_named(kwargs, pattern):
    data = DMAData.from_arrays([290.0, 300.0, 310.0], [[1.0, 10.0, 100.0]] * 3, [[1.0, 2.0, 3.0]] * 3,
                               [[0.1, 0.2, 0.3]] * 3)
    kwargs = {"T_ref": 300.0, **kwargs}
    with pytest.raises(ShiftError, match=pattern):
        build_master_curve(data, **kwargs)
