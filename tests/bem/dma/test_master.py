"""Time-temperature superposition recovers the shift law and the moduli it was made from.

Synthetic isotherms ``G*(omega; T) = b_T G*_ref(a_T omega)`` of a known Prony series
under a known WLF or Arrhenius law go in; the fitted shift factors must match the known
``a_T`` within 1 % and the master curve (its points, its Prony fit) the known moduli
within 1 % over the data's range.
"""

from __future__ import annotations

import numpy as np
import pytest

from bem.dma import Arrhenius, ShiftError, WLF, build_master_curve
from bem.materials import MasterCurveTable, Prony

T_REF = 273.15 + 20.0
WLF_TRUE = WLF(8.86, 101.6, T_REF)
T_WLF = 273.15 + np.arange(-20.0, 61.0, 5.0)
ARR_TRUE = Arrhenius(150e3, T_REF)
T_ARR = 273.15 + np.arange(0.0, 91.0, 10.0)


def _rel(a, b):
    return np.abs(a / b - 1.0)


def _build(synthetic, law, temperatures, name, **kw):
    return build_master_curve(synthetic(law, temperatures), T_REF, name, **kw)


@pytest.mark.parametrize("quantity", ["modulus", "both"])
def test_wlf_round_trip_recovers_shift_factors_within_1_percent(synthetic, quantity):
    master = _build(synthetic, WLF_TRUE, T_WLF, "wlf", quantity=quantity)
    assert isinstance(master.law, WLF)
    assert np.max(_rel(10 ** master.log_aT, 10 ** WLF_TRUE.log_aT(T_WLF))) < 0.01  # each isotherm
    T = np.linspace(T_WLF[0], T_WLF[-1], 50)
    assert np.max(_rel(10 ** master.log_shift(T), 10 ** WLF_TRUE.log_aT(T))) < 0.01  # the fitted law
    assert master.law.C1 == pytest.approx(8.86, rel=0.01)
    assert master.law.C2 == pytest.approx(101.6, rel=0.01)


def test_wlf_round_trip_master_points_and_prony_fit_match_the_true_moduli(synthetic):
    master = _build(synthetic, WLF_TRUE, T_WLF, "wlf")
    true = synthetic.TRUE.modulus(master.omega)
    assert np.max(_rel(master.storage, true.real)) < 0.01
    assert np.max(_rel(master.loss, true.imag)) < 0.01
    fit = master.fit_prony()
    assert isinstance(fit.material, Prony)
    w = np.geomspace(master.omega[0], master.omega[-1], 300)
    g, t = fit.material.modulus(w), synthetic.TRUE.modulus(w)
    assert np.max(_rel(g.real, t.real)) < 0.01
    assert np.max(_rel(g.imag, t.imag)) < 0.01
    assert fit.max_error < 0.01


@pytest.mark.parametrize("quantity", ["modulus", "both", "tan_delta"])
def test_arrhenius_round_trip_recovers_activation_energy_and_shifts(synthetic, quantity):
    master = _build(synthetic, ARR_TRUE, T_ARR, "arrhenius", quantity=quantity)
    assert isinstance(master.law, Arrhenius)
    assert master.law.activation_energy == pytest.approx(150e3, rel=0.01)
    assert np.max(_rel(10 ** master.log_aT, 10 ** ARR_TRUE.log_aT(T_ARR))) < 0.01
    true = synthetic.TRUE.modulus(master.omega)
    assert np.max(_rel(master.storage, true.real)) < 0.01
    assert np.max(_rel(master.loss, true.imag)) < 0.01


def test_given_law_shifts_every_isotherm_by_the_law_exactly(synthetic):
    master = build_master_curve(synthetic(WLF_TRUE, T_WLF), law=WLF_TRUE)
    assert np.array_equal(master.log_aT, WLF_TRUE.log_aT(T_WLF))
    true = synthetic.TRUE.modulus(master.omega)
    np.testing.assert_allclose(master.storage, true.real, rtol=1e-9)
    np.testing.assert_allclose(master.loss, true.imag, rtol=1e-9)


def test_table_at_a_service_temperature_is_the_reference_table_shifted(synthetic):
    master = build_master_curve(synthetic(WLF_TRUE, T_WLF), law=WLF_TRUE)
    ref, hot = master.table(), master.table(273.15 + 40.0)
    assert isinstance(hot, MasterCurveTable)
    a = 10 ** WLF_TRUE.log_aT(273.15 + 40.0)
    np.testing.assert_allclose(hot.omega, np.array(ref.omega) / a, rtol=1e-12)
    np.testing.assert_allclose(hot.storage, ref.storage, rtol=1e-12)
    # at its nodes the table is the true modulus at T: G*(omega; T) = G*_ref(a_T omega)
    true = synthetic.TRUE.modulus(np.array(hot.omega) * a)
    assert np.max(_rel(np.array(hot.storage), true.real)) < 0.01
    assert np.max(_rel(np.array(hot.loss), true.imag)) < 0.01


def test_density_vertical_shift_divides_by_T_rho_over_Tref_rho_ref(synthetic):
    # b_T = T / T_ref for a constant density: moduli scale with absolute temperature
    data = synthetic(WLF_TRUE, T_WLF, log_b=np.log10(T_WLF / T_REF))
    master = build_master_curve(data, law=WLF_TRUE, vertical="density", density=1100.0)
    np.testing.assert_allclose(master.log_bT, np.log10(T_WLF / T_REF), rtol=1e-12)
    true = synthetic.TRUE.modulus(master.omega)
    np.testing.assert_allclose(master.storage, true.real, rtol=1e-9)
    hot = master.points_at(273.15 + 40.0)
    assert hot[1][0] == pytest.approx(master.storage[0] * (273.15 + 40.0) / T_REF, rel=1e-12)


def test_fitted_vertical_shift_recovers_a_linear_log_b(synthetic):
    slope = 0.004  # log10 b_T per K
    data = synthetic(WLF_TRUE, T_WLF, log_b=slope * (T_WLF - T_REF))
    master = build_master_curve(data, T_REF, "wlf", vertical="fit")
    assert master.vertical_slope == pytest.approx(slope, rel=0.05)
    assert np.max(np.abs(master.log_bT - slope * (T_WLF - T_REF))) < 0.005
    # a free vertical shift competes with the horizontal one where log G is nearly
    # straight in log omega (glassy end here), so the horizontal shifts are looser: 3 %
    assert np.max(_rel(10 ** master.log_aT, 10 ** WLF_TRUE.log_aT(T_WLF))) < 0.03


def test_density_column_gives_the_vertical_shift(tmp_path):
    from bem.dma import read_dma_csv

    path = tmp_path / "rho.csv"
    rows = ["temperature_K,omega_rad_s,G_storage_Pa,G_loss_Pa,density_kg_m3"]
    for T, rho in ((300.0, 1000.0), (330.0, 980.0)):
        rows += [f"{T},{w},{1e6 * T * rho},{1e5 * T * rho}" for w in (1.0, 10.0, 100.0)]
        rows[-3:] = [r + f",{rho}" for r in rows[-3:]]
    data = read_dma_csv(_write(path, rows))
    master = build_master_curve(data, law=Arrhenius(100e3, 300.0), vertical="density")
    # moduli proportional to T rho collapse onto the reference: G / b_T = 1e6 T_ref rho_ref
    np.testing.assert_allclose(master.storage, 1e6 * 300.0 * 1000.0, rtol=1e-12)
    np.testing.assert_allclose(master.log_bT, [0.0, np.log10(330.0 * 980.0 / (300.0 * 1000.0))], rtol=1e-12)


def test_density_must_be_positive(synthetic):
    with pytest.raises(ShiftError, match=r"density must be a finite number > 0 kg/m\^3, got -1.0"):
        build_master_curve(synthetic(WLF_TRUE, T_WLF), law=WLF_TRUE, vertical="density", density=-1.0)


def _write(path, rows):
    path.write_text("\n".join(rows) + "\n")
    return path
