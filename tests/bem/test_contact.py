"""Frictionless contact: physical identities and limits of the rolling solution."""

import math

import numpy as np
import pytest

from bem import solve
from bem.contact import ContactAtEdge, solve_normal
from bem.grid import Grid
from bem.indenters import Paraboloid, Sphere
from bem.layer import Layer
from bem.materials import Elastic, ThreeParameterSolid
from bem.problem import Loading, Problem

SOLID = ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0)
SPHERE = Sphere(0.02)
COARSE = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (500, 500), (5.5e-3, 5.5e-3))


def run(material, speed, density=1000.0, grid=COARSE, indenter=SPHERE, thickness=5e-3, **load):
    load = load or {"load": 150.0}
    problem = Problem(Layer(thickness, material, density), indenter, grid, Loading(speed, **load))
    return solve(problem)


def test_elastic_layer_has_no_rolling_resistance():
    """An elastic layer (with inertia) gives a pressure symmetric in x: R_r = 0."""
    r = run(Elastic(3e6), 0.5)
    assert abs(r.rolling_resistance) < 1e-12 * r.load
    np.testing.assert_allclose(r.force, r.force[:, ::-1], rtol=0, atol=1e-12 * r.force.max())


@pytest.mark.parametrize("speed", [0.002, 0.05, 1.0, 20.0])
def test_viscoelastic_layer_resists_rolling(speed):
    """Passive material: positive rolling resistance, pressure shifted to the leading edge."""
    r = run(SOLID, speed)
    assert r.rolling_resistance > 0
    assert r.pressure_centroid_x > 0
    assert r.record.residual < 1e-10


def test_slow_limit_is_the_relaxed_elastic_solution():
    """V -> 0: elastic with G(0) = G0; the deviation is O(omega tau) ~ 1e-7 at 1e-9 m/s."""
    r = run(SOLID, 1e-9, density=0.0)
    e = run(Elastic(SOLID.relaxed_modulus), 0.0, density=0.0)
    assert abs(r.indentation / e.indentation - 1) < 1e-6
    assert abs(r.rolling_resistance) < 1e-6 * run(SOLID, 0.05).rolling_resistance
    np.testing.assert_allclose(r.force, e.force, rtol=0, atol=1e-6 * e.force.max())


class _FastLimit:
    """G(inf) for every moving mode, G(0) for the x-uniform modes (omega_m = 0 at any V)."""

    def modulus(self, omega):
        omega = np.asarray(omega, float)
        return np.where(omega == 0, SOLID.relaxed_modulus, SOLID.glassy_modulus).astype(complex)


def test_fast_limit_is_glassy_except_for_the_static_modes():
    """V -> inf (no inertia): in the periodic model the modes m = 0 are uniform along x and
    static in the material at any speed, so they keep G(0); every other mode stiffens to
    G(inf). Exact up to O(1 / (omega_1 tau)) ~ 1e-8 at V = 1e7 m/s."""
    r = run(SOLID, 1e7, density=0.0)
    e = run(_FastLimit(), 1.0, density=0.0)
    assert abs(r.indentation / e.indentation - 1) < 1e-7
    np.testing.assert_allclose(r.force, e.force, rtol=0, atol=1e-7 * e.force.max())


def test_fast_limit_tends_to_the_glassy_solution_as_the_period_grows():
    """The static m = 0 modes carry the x-average of the response over one period, so
    the gap to the glassy elastic solution falls like 1/L."""
    gaps = []
    for L in (0.2, 0.4):
        grid = Grid.centred((0.5e-3, 0.5e-3), (L, 0.2), (int(L / 1e-3) + 1, 500), (5.5e-3, 5.5e-3))
        r = run(SOLID, 1e7, density=0.0, grid=grid)
        e = run(Elastic(SOLID.glassy_modulus), 0.0, density=0.0, grid=grid)
        gaps.append(r.indentation / e.indentation - 1)
    assert 0 < gaps[1] < gaps[0] < 0.02  # measured 1.55% and 0.78%
    assert 1.9 < gaps[0] / gaps[1] < 2.1


def test_thick_layer_gives_hertz():
    """H = 30 mm, contact radius 2.3 mm: Jaffar's thick-layer correction to the radius is
    O((a/H)^3) ~ 1e-4; the rest is discretization (0.1 mm nodes)."""
    G, P, R = 3e6, 10.0, 0.02
    grid = Grid.centred((0.1e-3, 0.1e-3), (0.2, 0.2), (1000, 1000), (2.8e-3, 2.8e-3))
    r = run(Elastic(G), 0.0, density=0.0, grid=grid, indenter=Paraboloid(R), thickness=0.03, load=P)
    a = (3 * P * R / (16 * G)) ** (1 / 3)  # E* = 4 G
    p0 = 3 * P / (2 * math.pi * a**2)
    assert abs(r.contact_radius / a - 1) < 0.001  # measured 0.03%; node counting noise, 3x margin
    assert abs(r.peak_pressure / p0 - 1) < 0.001  # measured 0.03%, 3x margin
    X, Y = grid.coordinates()
    inner = X**2 + Y**2 < (0.8 * a) ** 2
    hertz = p0 * np.sqrt(1 - (X[inner] ** 2 + Y[inner] ** 2) / a**2)
    assert np.abs(r.pressure[inner] - hertz).max() < 0.003 * p0  # measured 0.14%, 2x margin


def test_displacement_control_inverts_load_control():
    r = run(SOLID, 0.05)
    d = run(SOLID, 0.05, indentation=r.indentation)
    assert abs(d.load / r.load - 1) < 1e-10
    np.testing.assert_allclose(d.force, r.force, rtol=0, atol=1e-9 * r.force.max())


def test_gmres_path_matches_dense_path():
    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (400, 400), (5.5e-3, 5.5e-3))
    problem = Problem(Layer(5e-3, SOLID, 1000.0), SPHERE, grid, Loading(0.05, load=150.0))
    it = solve(problem)  # the default: GMRES above DENSE_LIMIT (300) nodes
    from bem.operator import ComplianceOperator
    from bem.spectral import influence_kernels

    op = ComplianceOperator(grid, influence_kernels(grid, problem.layer, 0.05)["ww"])
    X, Y = grid.coordinates()
    dense = solve_normal(op, SPHERE.profile(X, Y), load=150.0, arm=SPHERE.rolling_arm(X, Y), dense_limit=5000)
    assert it.record.linear_solver == "gmres" and dense.record.linear_solver == "dense"
    np.testing.assert_array_equal(it.contact, dense.contact)
    assert abs(it.rolling_resistance - dense.rolling_resistance) < 1e-8


def test_contact_at_the_edge_is_an_error():
    small = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (500, 500), (3e-3, 3e-3))
    with pytest.raises(ContactAtEdge, match="increase grid.half_width"):
        run(SOLID, 0.05, grid=small)


def test_bad_loading_is_rejected():
    with pytest.raises(ValueError, match="load must be > 0 N, got -1"):
        Loading(0.05, load=-1.0)
    with pytest.raises(ValueError, match="exactly one"):
        Loading(0.05, load=1.0, indentation=1e-4)
    with pytest.raises(ValueError, match="speed must be >= 0 m/s"):
        Loading(-1.0, load=1.0)
    with pytest.raises(ValueError, match="thickness must be > 0 m, got -0.005"):
        Layer(-0.005, SOLID)
