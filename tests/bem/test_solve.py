"""bem.solve: one entry point for every problem, and the rolling figures its results carry
(dissipation, the pressure's power, the contact's edges on y = 0), each recomputed here
from its definition with the returned forces."""

import math

import numpy as np
import pytest

import bem
from bem import Elastic, Friction, Grid, Layer, LineCylinder, LineGrid, Loading, Problem, Sphere, ThreeParameterSolid
from bem.energy import viscous_dissipation
from bem.frictional import FrictionalContact
from bem.plane import LineContact, contact_edges, edges_along, line_dissipation, line_kernel
from bem.problem import compute_kernels
from bem.result import ROLLING_SCALARS, NormalContact

SECTION11 = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5.5e-3, 5.5e-3))  # 23 x 23
R = 0.02


def _rolling(speed=0.05, grid=GRID, load=150.0):
    return Problem(SECTION11, Sphere(R), grid, Loading(speed, load=load))


@pytest.fixture(scope="module")
def rolling():
    return bem.solve(_rolling())


def test_the_package_has_one_entry_point():
    assert "solve" in bem.__all__ and bem.solve.__module__ == "bem.driver"
    for old in ("solve_frictionless", "solve_normal", "solve_line", "solve_friction"):
        assert old not in bem.__all__ and not hasattr(bem, old)


def test_rolling_figures_are_what_they_say(rolling):
    """``dissipation`` is the layer's loss-modulus sum of the returned forces,
    ``pressure_power`` is ``V sum F ds/dx`` with the sphere's exact slope
    ``x / sqrt(R^2 - r^2)`` (the central difference's error, about ``h^2 / 2 R^2`` = 3e-10
    with ``h`` a thousandth of the spacing, within 1e-9), the edges are those
    of the row y = 0, the energy figure is ``dissipation / V``; the summary says the same."""
    res, V = rolling, 0.05
    assert type(res) is NormalContact and res.speed == V
    F = res.force
    zero = np.zeros_like(F)
    assert res.dissipation == pytest.approx(viscous_dissipation(GRID, SECTION11, V, -F, zero, zero), rel=1e-12)
    assert res.dissipation > 0
    X, Y = GRID.coordinates()
    on = F > 0
    slope = X[on] / np.sqrt(R * R - X[on] ** 2 - Y[on] ** 2)
    assert res.pressure_power == pytest.approx(V * float(np.sum(F[on] * slope)), rel=1e-9)
    row = GRID.shape[0] // 2
    assert GRID.y[row] == 0.0
    assert (res.trailing_edge, res.leading_edge) == edges_along(GRID.x, GRID.spacing_x, F[row], res.gap[row])
    assert -0.005 < res.trailing_edge < 0 < res.leading_edge < 0.005
    assert res.leading_edge > -res.trailing_edge  # the contact shifts towards the leading edge
    assert res.rolling_resistance_energy == res.dissipation / V
    summary = res.summary()
    assert all(summary[k] == getattr(res, k) for k in ROLLING_SCALARS)


def test_the_pressure_power_balances_the_dissipation(rolling):
    """Steady rolling: the power the pressure puts in is the power the layer dissipates,
    up to the discretization (measured 2.5e-3 at a = 0.5 mm, 6.4e-4 at 0.25 mm); the
    small-slope ``R_r V`` is about ``r^2 / 2 R^2`` lower (1.7 % here)."""
    res = rolling
    assert abs(res.pressure_power / res.dissipation - 1) < 4e-3
    assert 0.005 < 1 - res.rolling_resistance * res.speed / res.pressure_power < 0.03


def test_the_record_has_the_times_of_the_stages(rolling):
    times = rolling.record.times
    assert set(times) == {"kernel_s", "solve_s", "energy_s"}
    assert times["kernel_s"] > 0 and times["solve_s"] > 0 and times["energy_s"] >= 0


def test_at_rest_nothing_is_dissipated():
    """V = 0: no power in or out, no energy figure; an elastic layer's contact is symmetric."""
    res = bem.solve(Problem(Layer(5e-3, Elastic(3e6)), Sphere(R), GRID, Loading(0.0, load=150.0)))
    assert res.speed == 0.0 and res.dissipation == 0.0 and res.pressure_power == 0.0
    assert math.isnan(res.rolling_resistance_energy)
    assert res.trailing_edge == pytest.approx(-res.leading_edge, rel=1e-9)


def test_without_energy_the_dissipation_is_not_computed():
    res = bem.solve(_rolling(), energy=False)
    assert math.isnan(res.dissipation) and math.isnan(res.rolling_resistance_energy)
    assert res.pressure_power > 0 and math.isfinite(res.leading_edge)


def test_a_grid_without_a_row_on_y_0_has_no_edges():
    """20 rows of nodes: y = +/- a/2, ... but no y = 0; the edges are not defined there."""
    grid = Grid(0.5e-3, 0.5e-3, 0.2, 0.2, 200, 200, 21, 20)
    res = bem.solve(_rolling(grid=grid, load=20.0))
    assert not (grid.y == 0).any()
    assert math.isnan(res.trailing_edge) and math.isnan(res.leading_edge)
    assert res.dissipation > 0 and res.pressure_power > 0


def test_given_kernels_are_reused_and_checked():
    kernels, _ = compute_kernels(_rolling(), ("ww",))
    reused = bem.solve(_rolling(), kernels=kernels, energy=False)
    own = bem.solve(_rolling(), energy=False)
    assert reused.record.times["kernel_s"] == 0.0
    np.testing.assert_array_equal(reused.force, own.force)
    small = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5e-3, 5e-3))
    with pytest.raises(ValueError, match=r"^kernels\['ww'\] has shape \(45, 45\), a grid of 21 x 21 nodes needs "
                                         r"\(41, 41\)$"):
        bem.solve(_rolling(grid=small), kernels=kernels)


def test_plane_strain_is_a_line_contact_with_its_figures():
    """A LineCylinder on a LineGrid: a LineContact per unit length, its dissipation the 1-D
    sum (:func:`bem.plane.line_dissipation`), its edges those of :func:`contact_edges`."""
    grid = LineGrid.centred(2.5e-5, 0.1, 2000, 1.25e-3)
    layer = Layer(1e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0))
    res = bem.solve(Problem(layer, LineCylinder(R), grid, Loading(5e-3, load=750.0)))
    assert type(res) is LineContact and res.speed == 5e-3
    assert res.dissipation == line_dissipation(grid, layer, 5e-3, res.force) > 0
    assert (res.trailing_edge, res.leading_edge) == contact_edges(grid, res.force, res.gap)
    assert res.rolling_resistance_energy == res.dissipation / 5e-3
    assert abs(res.pressure_power / res.dissipation - 1) < 1e-3  # measured 1.6e-4
    assert res.summary()["model"] == "plane strain" and res.summary()["dissipation"] == res.dissipation
    table = line_kernel(grid, layer, 5e-3)
    again = bem.solve(Problem(layer, LineCylinder(R), grid, Loading(5e-3, load=750.0)), kernels={"ww": table})
    assert again.record.times["kernel_s"] == 0.0
    np.testing.assert_array_equal(again.force, res.force)


def test_friction_goes_to_the_frictional_solver():
    """With a Friction the result is the frictional solver's, its record with the times."""
    grid = Grid.centred((1e-3, 1e-3), (0.2, 0.2), (100, 100), (5e-3, 5e-3))
    res = bem.solve(_rolling(grid=grid), Friction(0.2))
    assert type(res) is FrictionalContact
    assert set(res.record.times) == {"kernel_s", "solve_s", "energy_s"}
    assert math.isfinite(res.rolling_resistance_energy)
    quiet = bem.solve(_rolling(grid=grid), Friction(0.2), energy=False)
    assert set(quiet.record.times) == {"kernel_s", "solve_s"} and math.isnan(quiet.rolling_resistance_energy)


def test_options_that_do_not_apply_are_refused():
    with pytest.raises(ValueError, match=r"^grow widens the region of a frictionless solve only"):
        bem.solve(_rolling(), Friction(0.2), grow=True)
    with pytest.raises(ValueError, match=r"^options tune the frictional solver: give them with friction$"):
        bem.solve(_rolling(), options=object())
