"""Figure 9's measures: the rise of the friction share towards thin layers and the grid
estimate of a figure from two or three grids."""

import math

import numpy as np
import pytest

from sweeps.paper import findings, grid_estimate, share_rise


def _rows(shares, **other):
    return [{"status": "ok", "layer.thickness": repr(H), "friction_share": repr(s), **other} for H, s in shares]


def test_share_rise_is_the_thick_share_over_the_thin_one():
    rows = _rows([(1e-3, 0.10), (2e-3, 0.02), (5e-3, 0.005), (7e-3, 0.006)], **{"loading.load": "50.0"})
    rows += _rows([(1e-3, 0.20), (5e-3, 0.01)], **{"loading.load": "125.0"})
    assert share_rise(rows, **{"loading.load": 50.0}) == pytest.approx(0.05, rel=1e-12)
    assert share_rise(rows, **{"loading.load": 125.0}) == pytest.approx(0.05, rel=1e-12)
    assert share_rise(rows, thin=2e-3, thick=7e-3, **{"loading.load": 50.0}) == pytest.approx(0.3, rel=1e-12)


def test_share_rise_without_either_thickness_is_nan():
    assert math.isnan(share_rise(_rows([(1e-3, 0.1), (4e-3, 0.01)])))
    failed = _rows([(1e-3, 0.1)]) + [{"status": "failed", "layer.thickness": "0.005", "friction_share": ""}]
    assert math.isnan(share_rise(failed))


def test_findings_report_the_share_rise_per_load():
    Hs = np.array([1, 2, 3, 5, 7, 10]) * 1e-3
    thick = [{"status": "ok", "layer.thickness": repr(float(H)), "loading.load": repr(P),
              "friction_share": repr(float(1e-4 / H)), "rolling_resistance_energy": "1.0"}
             for P in (50.0, 125.0) for H in Hs]
    f = findings([], thick, [])
    assert f["share_rise"] == {50.0: pytest.approx(0.2, rel=1e-12), 125.0: pytest.approx(0.2, rel=1e-12)}


@pytest.mark.parametrize("order", [1.0, 2.0])
def test_grid_estimate_recovers_the_limit_of_a_power_law_in_the_spacing(order):
    """q(a) = q* + c a^p on grids halved in turn: two grids give q* exactly at p = 1 (the
    order assumed), three give it at any p in [0.5, 5] with the observed order."""
    limit, c, a = 0.0123, 0.4, np.array([0.5e-3, 0.25e-3, 0.125e-3])
    q = limit + c * (a / a[0]) ** order * 1e-3
    three = grid_estimate(q)
    assert three.order == pytest.approx(order, rel=1e-9) and three.asymptotic
    assert three.extrapolated == pytest.approx(limit, rel=1e-9)
    assert three.error_finest == pytest.approx(abs(q[-1] - limit), rel=1e-9)
    two = grid_estimate(q[:2])
    assert (two.order, two.asymptotic) == (1.0, False)
    if order == 1.0:
        assert two.extrapolated == pytest.approx(limit, rel=1e-9)
    assert two.error_finest == pytest.approx(abs(q[1] - q[0]), rel=1e-12)


def test_grid_estimate_needs_two_grids():
    with pytest.raises(ValueError, match="at least 2 grids, got 1"):
        grid_estimate([0.1])


def test_the_figure_9_study_files_check_and_halve_the_spacing_at_one_truncation():
    """examples/sweeps/fig9-kinematics/: four grids halved in turn at one Nt, the same
    thicknesses and loads on every grid, and the three kinematics on each frictional one."""
    from pathlib import Path

    from sweeps.spec import read_sweep

    folder = Path(__file__).resolve().parents[2] / "examples" / "sweeps" / "fig9-kinematics"
    spacing, axes = {}, set()
    for f in sorted(folder.glob("*.toml")):
        sweep = read_sweep(f)
        sets = dict(item.split("=") for item in sweep.overrides)
        assert sets["grid.truncation"] == "1600", f
        spacing.setdefault(f.stem.split("-")[0], []).append(float(sets["grid.spacing"]))
        values = {a.key: tuple(a.values) for a in sweep.axes}
        axes.add((values["loading.load"], values["layer.thickness"]))
        if f.stem.startswith("share"):
            assert values["friction.kinematics"] == ("paper", "small_slope", "exact"), f
    assert len(axes) == 1
    for kind in ("share", "frictionless"):
        a = sorted(spacing[kind], reverse=True)
        np.testing.assert_allclose(a, [0.5e-3, 0.25e-3, 0.125e-3, 0.0625e-3], rtol=1e-12)
