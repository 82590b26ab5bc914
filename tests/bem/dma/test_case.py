"""``[material] model = "dma"`` in a case: the fitted series as if typed by hand, the
time-temperature identity through the whole solve, the frequency band check."""

from __future__ import annotations

import math

import numpy as np
import pytest

import bem
from bem.case import problem_from_config, read_case
from bem.dma import DMAError
from bem.dma.case import check_band, dma_material, frequency_band
from bem.materials import MasterCurveTable, Prony


def _solve(path, overrides=()):
    problem, _ = problem_from_config(read_case(path, list(overrides)))
    return bem.solve(problem)


def test_dma_case_at_the_reference_temperature_equals_its_fitted_prony_typed_by_hand(kit):
    dma = kit.write(kit.case(kit.material()), "dma.toml")
    cm = dma_material(read_case(dma)["material"], kit.folder)
    assert isinstance(cm.material, Prony) and cm.material == cm.fit.material  # a_T = b_T = 1 at T_ref
    m = cm.fit.material
    typed = kit.write(kit.case({"model": "prony", "G_inf": m.G_inf, "G": list(m.G), "tau": list(m.tau)}), "prony.toml")
    a, b = _solve(dma), _solve(typed)
    assert a.rolling_resistance > 0
    assert a.rolling_resistance == b.rolling_resistance and a.indentation == b.indentation
    np.testing.assert_array_equal(a.pressure, b.pressure)


@pytest.mark.parametrize("form", ["prony", "table"])
def test_a_case_at_temperature_T_equals_the_case_at_T_ref_with_speed_times_a_T(kit, form):
    """G*(omega; T) = G*_ref(a_T omega) without vertical shift, and the layer is loaded
    at omega = nu_x V: without inertia R_r(V, T) = R_r(a_T V, T_ref) on the same grid.
    The law is given (C1, C2), so a_T is known independently of the code."""
    path = kit.write(kit.case(kit.material(form=form, C1=8.86, C2=101.6)))
    V = 0.01
    for T in (273.15, 313.15):  # a_T = 10^1.44 and 10^-1.46
        a_T = 10.0 ** (-8.86 * (T - kit.T_REF) / (101.6 + T - kit.T_REF))
        hot = _solve(path, [f"material.temperature={T!r}", f"loading.speed={V!r}"])
        ref = _solve(path, [f"loading.speed={a_T * V!r}"])
        # the two differ only in the rounding of (a_T tau_i) nu V against tau_i nu (a_T V):
        # measured 1e-15 in R_r and 1.5e-14 of the peak in the pressure
        assert hot.rolling_resistance == pytest.approx(ref.rolling_resistance, rel=1e-12)
        assert hot.indentation == pytest.approx(ref.indentation, rel=1e-12)
        assert np.allclose(hot.pressure, ref.pressure, rtol=0, atol=1e-12 * ref.pressure.max())
    # and the temperature matters: 40 K apart, the resistance differs by more than 10 %
    cold = _solve(path, ["material.temperature=273.15"]).rolling_resistance
    warm = _solve(path, ["material.temperature=313.15"]).rolling_resistance
    assert abs(cold / warm - 1) > 0.1


def test_the_shifted_prony_is_the_law_applied_to_the_fit(kit, synthetic):
    """The material at T is the T_ref fit at a_T omega, and close to the generating
    series there (the data's own law, within the fit's error over the data)."""
    sec = read_case(kit.write(kit.case(kit.material(temperature=313.15))))["material"]
    cm = dma_material(sec, kit.folder)
    a_T = 10.0 ** float(kit.law.log_aT(313.15))
    assert cm.log_aT == pytest.approx(math.log10(a_T), abs=2e-3)  # the fitted law
    w = np.geomspace(cm.omega_min, cm.omega_max, 50)
    np.testing.assert_allclose(cm.material.modulus(w), cm.fit.material.modulus(10.0 ** cm.log_aT * w), rtol=1e-12)
    g, g0 = cm.material.modulus(w[10:-10]), synthetic.TRUE.modulus(a_T * w[10:-10])  # the generating series
    assert np.max(np.abs(g / g0 - 1)) < 0.02


def test_frequency_band_is_nu_x_V_from_the_first_mode_to_the_grid_nyquist():
    lo, hi = frequency_band(2.0, 1.0e-4, 0.1)
    assert lo == pytest.approx(2 * math.pi * 2.0 / 0.1) and hi == pytest.approx(math.pi * 2.0 / 1.0e-4)


def test_band_inside_the_data_passes_and_outside_raises_naming_both_ranges(kit):
    sec = read_case(kit.write(kit.case(kit.material())))["material"]
    cm = dma_material(sec, kit.folder)
    lo, hi = check_band(cm, 0.01, 5e-5, 0.05)  # 1.26-628 rad/s, inside 2e-3 to 3e8 rad/s
    assert cm.omega_min < lo < hi < cm.omega_max
    slow = 2e-6  # m/s: the band starts at 2 pi V / L = 2.5e-4 rad/s, 0.9 decades below the data
    with pytest.raises(DMAError) as err:
        check_band(cm, slow, 5e-5, 0.05)
    msg = str(err.value)
    assert f"from {2 * math.pi * slow / 0.05:.3g} to {math.pi * slow / 5e-5:.3g} rad/s" in msg
    assert f"cover {cm.omega_min:.3g} to {cm.omega_max:.3g} rad/s" in msg
    assert "decades below" in msg and "rubbery" in msg and "extrapolate = true" in msg
    with pytest.raises(DMAError, match="omega = 0"):
        check_band(cm, 0.0, 5e-5, 0.05)  # stationary: the relaxed modulus
    quiet = dma_material({**sec, "extrapolate": True}, kit.folder)
    assert check_band(quiet, slow, 5e-5, 0.05) == pytest.approx((2 * math.pi * slow / 0.05, math.pi * slow / 5e-5))
    table = dma_material({**sec, "form": "table"}, kit.folder)
    assert isinstance(table.material, MasterCurveTable)
    assert (table.omega_min, table.omega_max) == (cm.omega_min, cm.omega_max)
    with pytest.raises(DMAError, match="not physical"):
        check_band(table, slow, 5e-5, 0.05)


def test_problem_from_config_checks_the_band_at_the_service_temperature(kit):
    path = kit.write(kit.case(kit.material()))
    problem_from_config(read_case(path, ["material.temperature=253.15"]))  # -20 degC: the coldest isotherm
    # 40 K below the coldest isotherm the data end 27 decades below the band (log10 a_T = 32.8):
    # the band reaches 27 decades above them
    with pytest.raises(DMAError, match=r"temperature = 213\.15 K .* decades above"):
        problem_from_config(read_case(path, ["material.temperature=213.15"]))
    problem_from_config(read_case(path, ["material.temperature=213.15", "material.extrapolate=true"]))


def test_material_temperature_is_a_sweep_axis(kit, capsys):
    from sweeps.cli import main as sweep_main
    from sweeps.spec import expand, read_sweep

    kit.write(kit.case(kit.material()), "base.toml")
    sweep = kit.folder / "over-temperature.toml"
    sweep.write_text('case = "base.toml"\n\n[[axis]]\nkey = "material.temperature"\n'
                     "values = [253.15, 293.15, 213.15]\n")
    points = expand(read_sweep(sweep))
    assert [p.config["material"]["temperature"] for p in points] == [253.15, 293.15, 213.15]
    assert sweep_main([str(sweep), "--check"]) == 0
    out = capsys.readouterr().out
    assert "3 points over material.temperature (3)" in out
    # the third point (-60 degC) leaves the data: named with its band and the data's range
    assert "point 2 {'material.temperature': 213.15}: [material] model = \"dma\": this case loads" in out
    assert "point 0" not in out and "point 1" not in out
