"""Speeds the model cannot take: at or above the shear-wave speed (with inertia), and
absurdly large ones (without inertia), which must give the fast limit or a clear error,
never NaN."""

import math

import numpy as np
import pytest

from bem import solve
from bem.frictional import Friction
from bem.grid import Grid
from bem.indenters import Sphere
from bem.layer import Layer
from bem.materials import Elastic, MasterCurveTable, Prony, ThreeParameterSolid
from bem.problem import Loading, Problem, check_subsonic
from bem.spectral import influence_kernels

# examples/paper-section11-frictionless.toml: G0 = 3 MPa, rho = 1000 kg/m^3, so
# c_s = sqrt(3e6 / 1000) = 54.77 m/s
SOLID = ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0)
SECTION11 = Layer(5e-3, SOLID, 1000.0)
NO_INERTIA = Layer(5e-3, SOLID, 0.0)
GRID = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (2000, 2000), (5e-3, 5e-3))  # 41 x 41, as the example

SUPERSONIC = ("is at or above the layer's shear-wave speed c_s = sqrt(G(0) / rho) = "
              "sqrt(3e+06 Pa / 1000 kg/m^3) = 54.8 m/s: steady motion is subsonic only for speed < c_s "
              "(faster, the steady state radiates waves that the periodic model would only imitate, "
              "with results that depend on the period); use a loading.speed below 54.8 m/s, or "
              "layer.density = 0 to neglect inertia")


class _FastLimit:
    """The README's fast limit: G(inf) for every moving mode, G(0) for the modes uniform
    along x (omega_m = 0 at any speed)."""

    def modulus(self, omega):
        omega = np.asarray(omega, float)
        return np.where(omega == 0, SOLID.relaxed_modulus, SOLID.glassy_modulus).astype(complex)


def _problem(layer, speed, grid=GRID, load=150.0):
    return Problem(layer, Sphere(0.02), grid, Loading(speed, load=load))


def test_shear_wave_speed():
    assert SECTION11.shear_wave_speed == pytest.approx(math.sqrt(3000.0), rel=1e-15)
    assert NO_INERTIA.shear_wave_speed == math.inf


@pytest.mark.parametrize("speed", [60.0, 100.0, math.sqrt(3000.0)])
def test_a_speed_at_or_above_the_shear_wave_speed_is_rejected(speed):
    with pytest.raises(ValueError) as err:
        _problem(SECTION11, speed)
    assert str(err.value) == f"loading.speed = {speed:g} m/s " + SUPERSONIC
    with pytest.raises(ValueError, match="54.8 m/s"):  # the check the solvers call before forming kernels
        check_subsonic(SECTION11, speed)


def test_a_speed_below_the_shear_wave_speed_solves():
    """50 m/s (0.91 c_s): R_r = 4.468e-3 N (measured), far on the glassy side of the loss
    peak (omega_1 tau = 393)."""
    res = solve(_problem(SECTION11, 50.0))
    # GMRES (rtol 1e-11, above DENSE_LIMIT nodes) meets the load row to 7.5e-12 measured
    assert res.load == pytest.approx(150.0, rel=3e-11)
    assert 0 < res.rolling_resistance < 0.01
    assert res.record.residual < 1e-10


def test_without_inertia_there_is_no_speed_limit():
    res = solve(_problem(NO_INERTIA, 100.0))
    assert np.isfinite(res.force).all() and res.load == pytest.approx(150.0, rel=3e-11)  # GMRES, as above


@pytest.mark.parametrize("speed", [1e150, 1e300])
def test_absurd_speeds_give_the_fast_limit(speed):
    """Without inertia the moving modes see the glassy modulus; the x-uniform modes keep
    G(0) (README, "The fast limit"). Measured: identical to the last bit at both speeds
    (the moduli there are G0 (1 + f) + i O(1e-144) Pa); before, omega tau = 1e154 was
    squared into inf / inf and the load printed as nan."""
    res = solve(_problem(NO_INERTIA, speed))
    ref = solve(Problem(Layer(5e-3, _FastLimit(), 0.0), Sphere(0.02), GRID, Loading(1.0, load=150.0)))
    assert np.isfinite(res.force).all() and math.isfinite(res.indentation)
    assert res.load == pytest.approx(150.0, rel=3e-11)  # GMRES, as above
    assert abs(res.indentation / ref.indentation - 1) < 1e-12
    np.testing.assert_allclose(res.force, ref.force, rtol=0, atol=1e-12 * ref.force.max())


def test_absurd_speed_with_friction_gives_the_fast_limit():
    """The frictional solve at 1e150 m/s (GMRES path) against the fast-limit material at
    1 m/s: the same kernels, so the same answer up to round-off (measured 2.4e-14 on R_r,
    2e-14 on the tangential forces). Before, the free Omega (~ V / R) was solved for
    unscaled and GMRES failed from about 1e50 m/s on."""
    grid = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (500, 500), (5e-3, 5e-3))
    friction = Friction(0.2, dense_limit=0)
    ref = solve(Problem(Layer(5e-3, _FastLimit(), 0.0), Sphere(0.02), grid, Loading(1.0, load=20.0)),
                friction, energy=False)
    res = solve(_problem(NO_INERTIA, 1e150, grid, load=20.0), friction)
    assert res.record.linear_solver == "gmres"
    assert all(math.isfinite(v) for v in (res.rolling_resistance, res.omega, res.indentation,
                                          res.rolling_resistance_energy))
    assert abs(res.rolling_resistance / ref.rolling_resistance - 1) < 1e-12
    assert abs(res.omega / 1e150 / ref.omega - 1) < 1e-12
    np.testing.assert_array_equal(res.stick, ref.stick)
    np.testing.assert_allclose(res.force_x, ref.force_x, rtol=0, atol=1e-12 * np.abs(ref.force_x).max())


MATERIALS = [
    Elastic(3e6),
    SOLID,
    Prony(2e6, (1e6, 3e6), (1e-3, 10.0)),
    MasterCurveTable((1.0, 10.0, 100.0), (3e6, 4e6, 6e6), (1e5, 3e5, 2e5)),
]


@pytest.mark.parametrize("material", MATERIALS, ids=lambda m: type(m).__name__)
def test_moduli_are_finite_at_every_frequency(material):
    """|omega tau| up to 1e300 and beyond (omega tau overflowing to inf): the glassy modulus,
    real in the limit."""
    omega = np.array([1e150, 1e300, 1.7e308, np.inf])
    for w in (omega, -omega):
        G = material.modulus(w)
        assert np.isfinite(G).all()
        np.testing.assert_allclose(G.real, material.glassy_modulus, rtol=1e-14)
        assert np.all(np.abs(G.imag) <= 1e-100 * material.glassy_modulus)


@pytest.mark.parametrize("material", [SOLID, Prony(2e6, (1e6, 3e6), (1e-3, 10.0))], ids=lambda m: type(m).__name__)
def test_moduli_are_the_printed_formula_on_both_sides_of_omega_tau_1(material):
    """Below |omega tau| = 1 the fractions are written in omega tau, above in 1 / (omega tau):
    both agree with the formula as printed where it does not overflow."""
    omega = np.concatenate([-np.logspace(-4, 6, 301), np.logspace(-4, 6, 301)])
    if isinstance(material, ThreeParameterSolid):
        wt, f = omega * material.tau, material.f
        g = material.G0 * (1 + f)
        printed = g * ((1 + f) + wt**2) / ((1 + f) ** 2 + wt**2) + 1j * g * f * wt / ((1 + f) ** 2 + wt**2)
    else:
        iwt = 1j * omega[:, None] * np.asarray(material.tau)
        printed = material.G_inf + (np.asarray(material.G) * iwt / (1 + iwt)).sum(axis=1)
    np.testing.assert_allclose(material.modulus(omega), printed, rtol=1e-14)


class _Broken:
    """A material model that breaks down above 1e6 rad/s."""

    def modulus(self, omega):
        omega = np.asarray(omega, float)
        return np.where(np.abs(omega) > 1e6, np.nan, 3e6).astype(complex)


@pytest.mark.filterwarnings("ignore:invalid value:RuntimeWarning")  # the NaN on its way to the check
def test_non_finite_kernels_are_an_error_naming_the_speed_and_the_grid():
    with pytest.raises(ValueError) as err:
        influence_kernels(GRID, Layer(5e-3, _Broken(), 0.0), 1e3)
    assert str(err.value) == (
        "the influence kernels ww are not finite at speed = 1000 m/s on the grid of 41 x 41 nodes "
        "(a = 0.00025 x 0.00025 m, L = 0.2 x 0.2 m, N_t = 2000 x 2000): the material's modulus or "
        "the layer's compliance is not finite at some of the modes' frequencies |omega_m| = "
        "2 pi m V / L_x <= 6.28e+07 rad/s; use a lower loading.speed or check the material model")
    with pytest.raises(ValueError, match="not finite at speed = 1000 m/s"):
        solve(_problem(Layer(5e-3, _Broken(), 0.0), 1e3))


def test_a_speed_must_be_finite():
    with pytest.raises(ValueError, match="speed must be >= 0 m/s, got inf"):
        Loading(math.inf, load=1.0)
    with pytest.raises(ValueError, match="speed must be finite and >= 0 m/s, got nan"):
        influence_kernels(GRID, NO_INERTIA, math.nan)


def test_a_lossless_layer_is_limited_at_its_rayleigh_speed():
    """An elastic layer resonates at the Rayleigh speed c_R = 0.9553 c_s (52.3 m/s for
    G = 3 MPa, rho = 1000 kg/m^3), where the contact solve used to end without saying why;
    just below it, it solves."""
    from bem.problem import RAYLEIGH_RATIO

    xi = RAYLEIGH_RATIO
    assert (2 - xi * xi) ** 4 == pytest.approx(16 * (1 - xi * xi), rel=1e-14) and 0.955 < xi < 0.956
    elastic = Layer(5e-3, Elastic(3.0e6), 1000.0)
    with pytest.raises(ValueError, match=r"Rayleigh speed c_R = 0.9553 c_s = 52.3 m/s .*below 52.3 m/s"):
        _problem(elastic, 52.4)
    coarse = Grid.centred((1e-3, 1e-3), (0.2, 0.2), (100, 100), (8e-3, 8e-3))
    at_rest = solve(_problem(elastic, 0.0, coarse))
    fast = solve(_problem(elastic, 52.0, coarse))
    # inertia softens the layer (7.5% deeper at 52 m/s) without any resonance yet
    assert 1.0 < fast.indentation / at_rest.indentation < 1.1 and fast.load == pytest.approx(150.0)


def test_the_energy_figure_is_finite_at_an_absurd_speed():
    """rho V^2 is exactly 0 without inertia in the dissipation too (it overflowed at 1e300 m/s)."""
    from bem.energy import viscous_dissipation

    coarse = Grid.centred((1e-3, 1e-3), (0.2, 0.2), (100, 100), (6e-3, 6e-3))
    force = np.zeros(coarse.shape)
    force[coarse.shape[0] // 2, coarse.shape[1] // 2] = 1.0
    for speed in (1e150, 1e300):
        assert math.isfinite(viscous_dissipation(coarse, NO_INERTIA, speed, force, 0 * force, 0 * force))
