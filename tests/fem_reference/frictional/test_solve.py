"""The frictional FEM solve on a viscoelastic layer: the frictionless limit, the energy
balance, and the loading modes as inverses of one another."""

import math

import numpy as np
import pytest

from fem_reference.frictional import RollingFriction, solve_frictional
from fem_reference.rolling import solve_rolling
from tests.fem_reference.frictional.layers import assert_coulomb, viscous, viscous_problem


def test_no_friction_is_the_frictionless_fem_solution():
    """mu = 0 gives the frictionless FEM rolling solve: the same compliance and profile
    ("exact" kinematics), so indentation and pressures agree to the solves' rounding, and
    sum N x / R is its rolling resistance; mu = 1e-6 moves them by O(mu)."""
    problem, comp = viscous(2e-4)
    ref = solve_rolling(problem)
    for mu, tol in ((0.0, 1e-10), (1e-6, 1e-5)):
        r = solve_frictional(problem, RollingFriction(mu, creepage=0.0, kinematics="exact"), compliance=comp)
        assert_coulomb(r)
        assert math.isclose(r.indentation, ref.indentation, rel_tol=tol)
        assert np.allclose(r.pressure, ref.pressure, rtol=0, atol=tol * ref.pressure.max())
        assert math.isclose(float(r.normal @ r.x) / r.radius, ref.rolling_resistance, rel_tol=tol)
        assert abs(r.rolling_resistance_friction) <= 10 * mu * ref.rolling_resistance


@pytest.mark.parametrize("friction, tol", [
    # measured balance at h = 0.2 / 0.1 / 0.05 mm: +1.10e-2 / +3.40e-3 / +1.53e-3
    (RollingFriction(0.5, creepage=2e-3, kinematics="exact"), 5e-3),
    # measured -6.4e-3 / +1.4e-3 / -1.6e-5
    (RollingFriction(0.5, "pushed_at_top", kinematics="exact"), 2e-3),
    # measured -5.8e-3 / +1.5e-3 / -6.4e-5
    (RollingFriction(0.5, "towed"), 2e-3),
])
def test_energy_balance(friction, tol):
    """R_r V = bulk dissipation (the FEM's dashpot power) + friction power sum S w, to the
    discretization error (docstring of fem_reference.frictional.solve); h = 0.1 mm,
    tolerance 1.5x the measured error."""
    problem, comp = viscous(1e-4)
    r = solve_frictional(problem, friction, compliance=comp)
    assert_coulomb(r)
    assert r.dissipation > 0 and r.friction_power >= 0
    assert abs(r.energy_balance) < tol


def test_force_mode_inverts_the_omega_mode():
    """The driving force Q' that a creepage produces, given back in mode "force", gives
    back that creepage and the same state."""
    problem, comp = viscous(2e-4)
    a = solve_frictional(problem, RollingFriction(0.5, creepage=1e-3), compliance=comp)
    assert a.stick.any() and a.slip.any()
    b = solve_frictional(problem, RollingFriction(0.5, "force", driving_force=a.driving_force), compliance=comp)
    assert_coulomb(b)
    assert math.isclose(b.creepage, 1e-3, rel_tol=1e-8)
    assert np.allclose(b.tangential, a.tangential, atol=1e-9 * a.normal.max())


def test_equilibrium_rows_of_the_modes():
    """Towed: no torque; pushed at the top: T' = Q' R; force: Q' as given."""
    problem, comp = viscous(2e-4)
    scale = problem.loading.load * 1e-10
    r = solve_frictional(problem, RollingFriction(0.5, "towed"), compliance=comp)
    assert abs(r.torque) < scale * r.radius
    r = solve_frictional(problem, RollingFriction(0.5, "pushed_at_top"), compliance=comp)
    assert abs(r.torque - r.driving_force * r.radius) < scale * r.radius
    r = solve_frictional(problem, RollingFriction(0.5, "force", driving_force=1.0), compliance=comp)
    assert abs(r.driving_force - 1.0) < scale
