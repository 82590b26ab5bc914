"""A roller of finite length (bem.indenters.Cylinder with rounded ends) through bem.solve:
its mid-plane against the plane-strain line contact, steady rolling without and with
friction in every loading mode, and the case file's rule on the edge radius.

References are independent of the roller's code: the plane-strain solver (its own
kernel, bem.plane) for the mid-plane, each loading mode's equilibrium (its definition)
and the energy balance (the layer's dissipation from the loss modulus, a separate sum).
"""

import math

import numpy as np
import pytest

import bem
import casefile
from bem import Cylinder, Elastic, Friction, Grid, Layer, LineCylinder, LineGrid, Loading, Problem
from bem.case import problem_from_config
from bem.materials import ThreeParameterSolid

R = 0.02


def test_a_long_stationary_roller_carries_the_line_contact_pressure_at_mid_length():
    """An elastic 20 mm layer (G = 3 MPa), a roller of R = 2 cm, L = 30 mm, r_e = 2 mm at
    500 N/m nominal: b = 1.03 mm, L / b = 29. The plane-strain BEM at the mid-plane's own load
    per unit length (the 3D pressure on y = 0 summed over x) gives the same pressure on the
    inner 90% of the contact: RMS 1.2e-4 of the peak measured at a = 0.125 mm (b / 8) and
    N_t = L / (2 a) (1.4e-4 at 3 L / (2 a): not the truncation's; 1.9e-3 at L = 10 mm,
    L / b = 9, where the ends reach the mid-plane): gated at 3e-4. The mid-plane carries
    more than the nominal 500 N/m (the ends carry less): 505 N/m measured."""
    a, L = 1.25e-4, 0.03
    layer = Layer(0.02, Elastic(3e6))
    grid = Grid.centred((a, a), (0.2, 0.2), (800, 800), (2e-3, L / 2 + a))
    res = bem.solve(Problem(layer, Cylinder(R, L, 0.002), grid, Loading(0.0, load=500.0 * L)), energy=False)
    row = grid.shape[0] // 2
    assert grid.y[row] == 0.0
    p3 = res.pressure[row]
    per_length = p3.sum() * a
    assert 500.0 < per_length < 520.0
    line_problem = Problem(layer, LineCylinder(R), LineGrid.centred(a, 0.2, 800, 2e-3), Loading(0.0, load=per_length))
    line = bem.solve(line_problem, energy=False)
    p2 = line.pressure_profile
    np.testing.assert_array_equal(line.x, grid.x)
    inner = np.abs(grid.x) <= 0.9 * line.contact_radius
    rms = math.sqrt(np.mean((p3 - p2)[inner] ** 2)) / p2.max()
    assert rms < 3e-4, rms


@pytest.mark.parametrize("multiple, bound", [(1, 1e-3), (3, 3e-5)])
def test_a_long_roller_has_no_odd_even_row_loads_far_from_its_ends(multiple, bound):
    """A roller 20 H long (H = 10 mm, a_y = 2 mm = 10 a_x, N_t = multiple x L / (2 a) in x
    and y). On the nodes the modes n and n + L / a_y are one lattice frequency; with the
    end modes |n| = N_t at half weight every lattice frequency takes the same number of
    them (docs/derivations.md, section 8, "End modes"), and the odd-even (Nyquist) part of
    the row loads, excited by the ends, decays along y. Its amplitude over the row load
    (binomial high pass (1, -4, 6, -4, 1) / 16: gain 1 at (-1)^j, blind to cubics), at 5 H
    and more from the ends: measured 5.2e-4 and 7.8e-6 (the truncation's kink at Nyquist,
    which falls fast with N_t); both end modes in full gave a plateau of 7.6e-3 and 5.4e-4."""
    ax, ay, L, H, length = 2e-4, 2e-3, 0.4, 0.01, 0.2
    N = (round(L / (2 * ax)), round(L / (2 * ay)))
    grid = Grid.centred((ax, ay), (L, L), (multiple * N[0], multiple * N[1]), (3e-3, length / 2 + ay))
    res = bem.solve(Problem(Layer(H, Elastic(1e6)), Cylinder(0.05, length, 4e-3), grid,
                            Loading(0.0, load=250.0 * length)), energy=False)
    rows = res.force.sum(axis=1)
    j = np.arange(2, rows.size - 2)
    odd = (-1.0) ** j * (rows[:-4] - 4 * rows[1:-3] + 6 * rows[2:-2] - 4 * rows[3:-1] + rows[4:]) / 16
    far = np.abs(grid.y[j]) <= length / 2 - 5 * H
    assert far.sum() > 40
    assert np.abs(odd[far] / rows[j[far]]).max() < bound


@pytest.fixture(scope="module")
def rolling_roller():
    """The section 11 solid (G0 = 3 MPa, tau = 0.25 s, f = 1) on a 5 mm layer, a roller of R =
    2 cm, L = 8 mm, r_e = 2 mm at 8 N (1000 N/m) rolling at 5 mm/s (V tau / b = 0.9, near the
    loss peak), on a = 0.25 mm."""
    layer = Layer(5e-3, ThreeParameterSolid(G0=3e6, tau=0.25, f=1.0))
    grid = Grid.centred((2.5e-4, 2.5e-4), (0.1, 0.1), (200, 200), (2.5e-3, 4.5e-3))
    return Problem(layer, Cylinder(R, 0.008, 0.002), grid, Loading(0.005, load=8.0))


def test_rolling_roller_without_friction_resists_and_balances_its_energy(rolling_roller):
    """R_r > 0 (the pressure's centroid ahead of the axis), and the pressure's work rate sum F
    ds/dx over V equals the layer's dissipation over V (from the loss modulus, a separate sum):
    measured 8.7e-3 on this grid, converging at second order (2.0e-3 at a = 0.125 mm, 4.9e-4
    at 0.0625 mm: the steep pressure where the rounded ends begin needs fine modes), gated at
    1.5e-2; R_r itself moves by 5e-4 over those grids."""
    res = bem.solve(rolling_roller)
    assert res.rolling_resistance > 0.05
    assert res.pressure_centroid_x > 0
    work, energy = res.pressure_power / res.speed, res.dissipation / res.speed
    assert abs(work - energy) / energy < 1.5e-2
    assert res.load == pytest.approx(8.0, rel=1e-9)


@pytest.mark.parametrize("mode", ["pushed_at_top", "towed", "torque", "omega"])
def test_rolling_roller_with_friction_solves_in_every_loading_mode(rolling_roller, mode):
    """mu = 0.5: each mode's own equilibrium holds (pushed at the top T = Q R, towed T = 0,
    driven by a torque Q = 0, Omega as given); the roller turns at nearly V / R (the
    rolling radius is R on every row: creep below 1%); R_r stays within 3% of the
    frictionless one (2.5% measured in the omega mode, whose Omega is prescribed 0.1% below
    V / R) and a stick zone exists."""
    V = rolling_roller.loading.speed
    omega = 0.999 * V / R if mode == "omega" else None
    free = bem.solve(rolling_roller, energy=False)
    res = bem.solve(rolling_roller, friction=Friction(0.5, mode, omega=omega))
    scale = res.rolling_resistance * R  # N m
    if mode == "pushed_at_top":
        assert res.driving_torque == pytest.approx(res.driving_force * R, abs=1e-9 * scale)
    elif mode == "towed":
        assert abs(res.driving_torque) <= 1e-9 * scale
    elif mode == "torque":
        assert abs(res.driving_force) <= 1e-9 * res.rolling_resistance
    else:
        assert res.omega == omega
    assert res.omega == pytest.approx(V / R, rel=1e-2)
    assert res.rolling_resistance == pytest.approx(free.rolling_resistance, rel=3e-2)
    assert res.stick.sum() > 0
    assert res.load == pytest.approx(8.0, rel=1e-9)


def _case(**indenter):
    return {"layer": {"thickness": 5e-3}, "material": {"model": "elastic", "shear_modulus": 3e6},
            "indenter": {"shape": "cylinder", "radius": R, "length": 0.006, **indenter},
            "loading": {"load": 6.0}, "grid": {"spacing": 2.5e-4, "period": 0.1, "truncation": 200}}


@pytest.mark.parametrize("indenter, message", [
    (dict(edge_radius=0.0031), r"^\[indenter\] edge_radius must be <= length / 2 = 0\.003 m \(the two end roundings "
                               r"meet at mid-length\), got 0\.0031$"),
    (dict(edge_radius=0.001, crown_radius=1.0), r"^\[indenter\] give crown_radius or edge_radius, not both"),
    (dict(crown_radius=0.002), r"^\[indenter\] crown_radius must be >= length / 2 = 0\.003 m"),
    (dict(edge_radius=-1e-3), r"\[indenter\] edge_radius must be >= 0 m, got -0\.001$"),
])
def test_a_case_with_bad_roller_ends_is_refused_naming_the_key(indenter, message):
    with pytest.raises(casefile.CaseFileError, match=message):
        problem_from_config(_case(**indenter))


def test_a_case_roller_has_its_ends():
    problem, _ = problem_from_config(_case(edge_radius=0.001))
    assert problem.indenter == Cylinder(R, 0.006, 0.001)
    problem, _ = problem_from_config(_case(crown_radius=0.5))
    assert problem.indenter == Cylinder(R, 0.006, crown_radius=0.5)
