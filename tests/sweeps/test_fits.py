"""The fitted laws and their 95 % intervals, the peak finder, and the paper's tables."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from sweeps import fit_power, fit_two_exponential
from sweeps.paper import TABLE2, TABLE3, friction_effect, friction_share_max, law_gap, paper_fit, peak_position


def test_power_law_recovers_exact_data():
    P = np.linspace(10, 150, 15)
    fit = fit_power(P, 2.88e-3 * P ** 1.394)
    assert fit.values == pytest.approx((2.88e-3, 1.394), rel=1e-9)
    assert fit.r2 == pytest.approx(1.0, abs=1e-12)
    assert (fit.n, fit.x_min, fit.x_max) == (15, 10.0, 150.0)


def test_power_law_interval_is_the_t_interval_of_the_jacobian():
    """The interval against an independent computation: ``s^2 (J^T J)^-1`` with the
    Jacobian of ``a P^b`` written by hand and Student's t with n - 2 degrees of freedom."""
    rng = np.random.default_rng(3)
    P = np.linspace(10, 150, 12)
    R = 2.7e-3 * P ** 1.4 * (1 + 0.01 * rng.standard_normal(P.size))
    fit = fit_power(P, R)
    a, b = fit.values
    J = np.column_stack([P ** b, a * P ** b * np.log(P)])
    res = R - a * P ** b
    cov = (res @ res) / (P.size - 2) * np.linalg.inv(J.T @ J)
    half = stats.t.ppf(0.975, P.size - 2) * np.sqrt(np.diag(cov))
    np.testing.assert_allclose(np.array(fit.upper) - np.array(fit.values), half, rtol=1e-5)
    np.testing.assert_allclose(np.array(fit.values) - np.array(fit.lower), half, rtol=1e-5)
    assert fit.lower[1] < 1.4 < fit.upper[1]


def test_two_exponential_recovers_table3():
    """Data drawn from the midpoints of Table 3 (P = 50 N) over 1-30 mm come back."""
    law = paper_fit(TABLE3, 50.0, (1e-3, 30e-3))
    H = np.array([1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 15, 20, 25, 30]) * 1e-3
    fit = fit_two_exponential(H, law(H))
    np.testing.assert_allclose(fit.values, law.values, rtol=1e-6)
    assert law_gap(fit, law, 1e-3, 30e-3) < 1e-9
    assert law(5e-3) == pytest.approx(0.666, abs=2e-3)  # R_r(5 mm) of the paper's curve at 50 N


def test_paper_tables_agree_with_each_other():
    """Tables 2 and 3 describe the same points (H = 5, 30 mm at P = 50, 125 N): their laws
    must agree there within their own scatter (a check of the transcription)."""
    for P in (50.0, 125.0):
        t3 = paper_fit(TABLE3, P, (1e-3, 30e-3))
        for H in (5e-3, 30e-3):
            t2 = paper_fit(TABLE2, H, (10, 150))
            assert float(t2(P)) == pytest.approx(float(t3(H)), rel=0.02), (P, H)


def test_peak_position():
    x = np.linspace(2e-3, 12e-3, 11)
    y = 1 - (x - 6.7e-3) ** 2 * 1e4
    assert peak_position(x, y) == pytest.approx(6.7e-3, rel=1e-9)
    V = np.geomspace(1e-3, 1, 13)
    R = 3 - (np.log10(V) - np.log10(0.037)) ** 2
    assert peak_position(V, R, log=True) == pytest.approx(0.037, rel=1e-9)
    assert peak_position(x, x) == x[-1]  # a maximum at the end of the range
    with pytest.raises(ValueError, match="at least 3"):
        peak_position([1.0, 2.0], [1.0, 2.0])


def test_friction_share_max():
    rows = [{"status": "ok", "loading.load": "100", "friction_share": "0.01"},
            {"status": "ok", "loading.load": "150", "friction_share": "0.012"},
            {"status": "ok", "loading.load": "200", "friction_share": "0.5"},
            {"status": "failed", "loading.load": "50", "friction_share": ""},
            {"status": "ok", "loading.load": "50", "friction_share": ""}]
    assert friction_share_max(rows) == 0.012


def test_friction_effect_pairs_the_two_cases():
    rows = [{"status": "ok", "case": c, "layer.thickness": h, "rolling_resistance": str(v)}
            for c, h, v in [("base-friction", "0.005", 1.02), ("base-frictionless", "0.005", 1.0),
                            ("base-friction", "0.01", 2.2), ("base-frictionless", "0.01", 2.0),
                            ("base-friction", "0.02", 3.0)]]
    x, effect = friction_effect(rows, "layer.thickness")
    np.testing.assert_allclose(x, [0.005, 0.01])
    np.testing.assert_allclose(effect, [0.02, 0.1], rtol=1e-12)


def test_findings_on_tables_drawn_from_the_papers_laws():
    """Rows made from the paper's own laws give back its laws (gap ~ 0), the share's and
    the speed peak's positions, through the same function a verification case calls."""
    from sweeps.paper import findings

    loads = [{"status": "ok", "layer.thickness": repr(H), "loading.load": repr(float(P)), "friction_share": "0.01",
              "rolling_resistance_energy": repr(float(paper_fit(TABLE2, H, (10, 150))(P)))}
             for H in TABLE2 for P in np.linspace(10, 150, 8)]
    Hs = np.array([1, 2, 3, 4, 5, 6, 7, 8, 10, 15, 30]) * 1e-3
    thick = [{"status": "ok", "layer.thickness": repr(float(H)), "loading.load": repr(P),
              "friction_share": repr(float(0.01 - (H - 7e-3) ** 2)),
              "rolling_resistance_energy": repr(float(paper_fit(TABLE3, P, (1e-3, 30e-3))(H)))}
             for P in TABLE3 for H in Hs]
    V = np.geomspace(1e-3, 1, 9)
    speed = [{"status": "ok", "layer.thickness": "0.001", "loading.speed": repr(float(v)),
              "rolling_resistance_energy": repr(float(2 - (np.log10(v) + 1.6) ** 2))} for v in V]
    f = findings(loads, thick, speed)
    assert all(f["table2"][H]["gap"] < 1e-6 for H in TABLE2)
    assert all(f["table3"][P]["gap"] < 1e-5 for P in TABLE3)
    assert f["friction_share_max"] == 0.01
    assert f["share_peak_thickness"][50.0] == pytest.approx(7e-3, rel=1e-9)
    assert f["peak_speed"][(("layer.thickness", "0.001"),)] == pytest.approx(10 ** -1.6, rel=1e-9)
