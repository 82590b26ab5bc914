"""bem.frictional.options: SolverOptions' validation messages whole, its defaults, and that
passing the defaults explicitly is the solve without options, bit for bit."""

import dataclasses
import math

import numpy as np
import pytest

from bem import Grid, Layer, Loading, Problem, Sphere, ThreeParameterSolid
from bem.frictional import Friction, SolverOptions, solve_friction

LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (6.0e-3, 6.0e-3))  # 25 x 25: a coarse level


@pytest.mark.parametrize("kwargs, message", [
    ({"loose_reduction": 0.0}, "SolverOptions.loose_reduction must be a finite number in (0, 1), got 0.0"),
    ({"tight_reduction": 1.0}, "SolverOptions.tight_reduction must be a finite number in (0, 1), got 1.0"),
    ({"start_rtol": math.nan}, "SolverOptions.start_rtol must be a finite number in (0, 1), got nan"),
    ({"settled": -1e-5}, "SolverOptions.settled must be a finite number >= 0, got -1e-05"),
    ({"slope_floor": math.inf}, "SolverOptions.slope_floor must be a finite number >= 0, got inf"),
    ({"filter_power": "0.5"}, "SolverOptions.filter_power must be a finite number >= 0, got '0.5'"),
    ({"settle_changes": 1.5}, "SolverOptions.settle_changes must be a finite number in [0, 1], got 1.5"),
    ({"filter_waves": 0.0}, "SolverOptions.filter_waves must be a finite number > 0, got 0.0"),
    ({"continuation_mu": 0}, "SolverOptions.continuation_mu must be a finite number > 0, got 0"),
    ({"filter_long": -0.1}, "SolverOptions.filter_long must be a finite number >= 0 or None, got -0.1"),
    ({"coarse_settle": math.nan}, "SolverOptions.coarse_settle must be a finite number >= 0 or None, got nan"),
    ({"restart": 0}, "SolverOptions.restart must be an integer >= 1, got 0"),
    ({"max_cycles": 2.0}, "SolverOptions.max_cycles must be an integer >= 1, got 2.0"),
    ({"local_window": True}, "SolverOptions.local_window must be an integer >= 1, got True"),
    ({"local_from": -1}, "SolverOptions.local_from must be an integer >= 0, got -1"),
    ({"dense_upto": 1e3}, "SolverOptions.dense_upto must be an integer >= 0, got 1000.0"),
])
def test_bad_options_are_refused_with_field_value_and_rule(kwargs, message):
    with pytest.raises(ValueError) as info:
        SolverOptions(**kwargs)
    assert str(info.value) == message


def test_options_are_frozen_and_none_turns_off_the_blend_and_the_early_coarse_end():
    o = SolverOptions(filter_long=None, coarse_settle=None, filter_power=0, local_from=0)
    assert o.filter_long is None and o.coarse_settle is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        o.restart = 10
    assert dataclasses.replace(o, restart=10).restart == 10
    edge = SolverOptions(filter_long=0.0, coarse_settle=0.0, filter_waves=0.5, filter_power=0.0, settle_changes=1.0)
    assert (edge.filter_long, edge.coarse_settle, edge.filter_waves) == (0.0, 0.0, 0.5)


def test_defaults_are_the_measured_ones():
    """The defaults docs/frictional-solver.md justifies (a change there is a change here)."""
    o = SolverOptions()
    assert (o.loose_reduction, o.loose_until, o.settled, o.start_reduction, o.settle_changes) == (
        3e-3, 1e-2, 1e-5, 1e-5, 0.01)
    assert (o.few_changes, o.local_from, o.slope_floor, o.slip_creep, o.cone_tol, o.penetration_tol) == (
        20, 20_000, 1e-3, 1e-2, 1e-10, 1e-12)
    assert (o.tight_reduction, o.residual_floor, o.single_from, o.single_start, o.restart, o.max_cycles) == (
        1e-10, 1e-15, 1e-4, 1e-4, 200, 10)
    assert (o.local_window, o.local_rounds) == (8, 8)
    assert (o.filter_power, o.filter_long, o.filter_waves, o.thread_from, o.chunk, o.compose_upto) == (
        0.5, 0.7, 5.0, 4_000_000, 2048, 16)
    assert (o.dense_upto, o.batched_upto) == (128, 64)
    assert (o.coarse_settle, o.start_rtol, o.frictionless_rtol, o.overlap_from, o.continuation_mu) == (
        0.3, 1e-8, 1e-11, 4000, 0.2)


def test_the_defaults_given_explicitly_are_the_solve_without_options():
    """GMRES on both levels (dense_limit 0): the same forces and record, bit for bit; a
    tighter loose reduction takes another path to the same state."""
    problem = Problem(LAYER, Sphere(0.02), GRID, Loading(0.05, load=20.0))
    friction = Friction(0.3, dense_limit=0)
    plain, _ = solve_friction(problem, friction, energy=False)
    given, _ = solve_friction(problem, friction, energy=False, options=SolverOptions())
    for a, b in ((plain.force, given.force), (plain.force_x, given.force_x), (plain.force_y, given.force_y)):
        np.testing.assert_array_equal(a, b)
    assert plain.record == given.record
    other, _ = solve_friction(problem, friction, energy=False, options=SolverOptions(loose_reduction=1e-6))
    assert other.record.linear_iterations != plain.record.linear_iterations
    assert np.array_equal(other.stick, plain.stick)
    np.testing.assert_allclose(other.force_x, plain.force_x, rtol=0, atol=1e-8 * plain.force.max())


def test_the_linear_solves_take_their_settings_from_the_options():
    from bem.frictional.active_set import LinearSolves

    o = SolverOptions(tight_reduction=1e-9, restart=50, max_cycles=3, residual_floor=1e-14, single_from=1e-3,
                      single_start=1e-5, filter_power=0.25)
    solves = LinearSolves(123, o)
    s = solves.solver
    assert (s.dense_limit, s.rtol, s.restart, s.maxiter, s.floor, s.single_from, s.single_start) == (
        123, 1e-9, 50, 3, 1e-14, 1e-3, 1e-5)
    assert s.correction and solves.options is o and solves.lines.options is o
    d = LinearSolves(7).solver
    assert (d.rtol, d.restart, d.maxiter, d.floor, d.single_from, d.single_start) == (1e-10, 200, 10, 1e-15, 1e-4, 1e-4)


@pytest.mark.parametrize("change", [{"loose_until": 0.1}, {"cone_tol": 0.5}, {"slope_floor": 0.3},
                                    {"loose_reduction": 1e-6}])
def test_each_active_set_option_reaches_the_iteration(change):
    """Solved by GMRES on both levels (dense_limit 0), Omega = 0.99 V / R: a change of one
    active-set option changes the path (the history of contact, stick, misfit and
    Omega), so the option is read where the iteration decides."""
    problem = Problem(LAYER, Sphere(0.02), GRID, Loading(0.05, load=20.0))
    friction = Friction(0.3, "omega", omega=0.99 * 0.05 / 0.02, dense_limit=0)
    plain, _ = solve_friction(problem, friction, energy=False)
    other, _ = solve_friction(problem, friction, energy=False, options=SolverOptions(**change))
    assert other.record.history != plain.record.history


def test_the_local_row_options_reach_the_local_solves():
    """With local rows on every contact (``local_from`` 1), a window of 1 node takes
    another path than the default 8 (Omega = 0.99 V / R, 25 N: local rows on the fine
    level too, GMRES on both levels)."""
    problem = Problem(LAYER, Sphere(0.02), GRID, Loading(0.05, load=25.0))
    friction = Friction(0.3, "omega", omega=0.99 * 0.05 / 0.02, dense_limit=0)
    lines = []
    wide, _ = solve_friction(problem, friction, energy=False, options=SolverOptions(local_from=1),
                             progress=lines.append)
    narrow, _ = solve_friction(problem, friction, energy=False, options=SolverOptions(local_from=1, local_window=1))
    assert any(line.startswith("  local rows") for line in lines)
    assert narrow.record.history != wide.record.history
