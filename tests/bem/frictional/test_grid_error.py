"""Richardson estimates of the frictional figures (:mod:`bem.frictional.grid_error`)."""

import math

import pytest

from bem import Grid, Layer, LineGrid, Loading, Problem, Sphere, ThreeParameterSolid
from bem.frictional import Friction, solve_friction
from bem.frictional.grid_error import SCALARS, coarsened_grid, estimate_grid_error


def test_coarsened_grid_keeps_region_periods_and_the_modes_per_node():
    """The coarse level is the case written on the coarser grid: its truncation divided by
    the factor, so ``N_t a`` is the fine grid's (rounded to whole modes)."""
    g = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.3), (500, 750), (5e-3, 5e-3))
    for factor, nodes, modes in ((1, 41, (500, 750)), (2, 21, (250, 375)), (4, 11, (125, 188))):
        c = coarsened_grid(g, factor)
        assert (c.nodes_x, c.nodes_y) == (nodes, nodes)
        assert c.spacing_x == g.spacing_x * factor and c.x[-1] == pytest.approx(g.x[-1], rel=1e-12)
        assert (c.period_x, c.period_y) == (g.period_x, g.period_y)
        assert (c.truncation_x, c.truncation_y) == modes
    line = LineGrid.centred(0.1e-3, 0.2, 3000, 4e-3)
    assert coarsened_grid(line, 4).truncation == 750 and coarsened_grid(line, 4).nodes == 21
    with pytest.raises(ValueError, match="factor must be an integer >= 1, got 0"):
        coarsened_grid(g, 0)


def test_estimate_on_the_section11_example_at_a_coarse_truncation():
    """Levels 1, 0.5, 0.25 mm (Nt = 500): the given fine result is the last level, and
    every scalar gets a limit and an error; the indentation converges at second order."""
    layer = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5e-3, 5e-3))
    problem, friction = Problem(layer, Sphere(0.02), grid, Loading(0.05, load=150.0)), Friction(0.2)
    fine, _ = solve_friction(problem, friction, energy=True)
    est = estimate_grid_error(problem, friction, fine=fine)
    assert est.spacings == pytest.approx((1e-3, 0.5e-3, 0.25e-3))
    assert set(est.figures) == set(SCALARS)
    rf = est.figures["rolling_resistance_friction"]
    assert rf.values[-1] == fine.rolling_resistance_friction and rf.error_finest > 0
    d = est.figures["indentation"]
    assert d.asymptotic and 1.5 < d.order < 4 and d.error_finest < 1e-3 * fine.indentation
    assert all(math.isfinite(c.extrapolated) for c in est.figures.values())
    text = "\n".join(est.lines())
    assert "rolling_resistance_friction" in text and " N, limit " in text
    assert est.summary()["figures"]["omega"]["values"][-1] == fine.omega


def test_cli_error_estimate_reports_every_figure_with_the_fine_result_as_its_last_value(capsys):
    import json
    from pathlib import Path

    from bem.cli import main

    case = str(Path(__file__).resolve().parents[3] / "examples" / "paper-section11-friction.toml")
    code = main(["solve", case, "--json", "--quiet", "--error-estimate", "--set", "grid.spacing=5e-4",
                 "--set", "grid.truncation=400", "--set", "grid.half_width=8e-3"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    estimate = out["grid_error"]
    assert estimate["spacings"] == pytest.approx([2e-3, 1e-3, 5e-4])
    for name in ("rolling_resistance", "rolling_resistance_friction", "indentation"):
        assert estimate["figures"][name]["values"][-1] == out[name]  # the fine level is the solve itself
        assert estimate["figures"][name]["error"] >= 0


def test_cli_error_estimate_without_friction_is_a_usage_error(capsys):
    from pathlib import Path

    from bem.cli import main

    case = str(Path(__file__).resolve().parents[3] / "examples" / "paper-section11-frictionless.toml")
    assert main(["solve", case, "--quiet", "--error-estimate"]) == 2
    assert "needs a [friction] section" in capsys.readouterr().err


def test_a_level_started_from_the_case_solution_reaches_the_state_it_reaches_alone():
    """The grid error's levels start from the sets and forces of the level above on their
    nodes (``finer``). On ``examples/elastic-paraboloid-creepage.toml`` at 0.2 mm (61 x
    61; levels 31 x 31 and 15 x 15) each level ends on the state it reaches from its own
    start: the same contact and stick sets, forces within 1e-9 of the largest, in no more
    active-set or GMRES iterations (measured: 8 / 125 -> 7 / 62 and 6 -> 3, dense LU).
    The start itself is the finer solution's sets on the level's nodes and its tangential
    forces times the ratio of the node areas (4)."""
    from dataclasses import replace
    from pathlib import Path

    import numpy as np

    from bem.case import friction_from_config, problem_from_config, read_case
    from bem.frictional.starts import nodes_within, restricted_start

    case = Path(__file__).resolve().parents[3] / "examples" / "elastic-paraboloid-creepage.toml"
    config = read_case(case)
    problem, friction = problem_from_config(config)[0], friction_from_config(config)
    finer, _ = solve_friction(problem, friction, energy=False)
    for factor in (2, 4):
        p = replace(problem, grid=coarsened_grid(problem.grid, factor))
        alone, _ = solve_friction(p, friction, energy=False)
        started, _ = solve_friction(p, friction, energy=False, finer=finer)
        np.testing.assert_array_equal(started.contact, alone.contact)
        np.testing.assert_array_equal(started.stick, alone.stick)
        for f in ("force", "force_x", "force_y"):
            assert np.abs(getattr(started, f) - getattr(alone, f)).max() <= 1e-9 * np.abs(alone.force).max(), f
        assert started.record.iterations <= alone.record.iterations
        assert started.record.linear_iterations <= alone.record.linear_iterations
        rows, cols = nodes_within(finer.grid, p.grid)
        N0 = alone.force.ravel()  # normal forces with the level's contact
        state, (N, Sx, Sy, d, omega) = restricted_start(finer, p.grid, N0, 1e-3, friction.mu)
        slip_above = (finer.contact & ~finer.stick)[rows, cols].ravel()
        np.testing.assert_array_equal(state.contact, N0 > 0)
        np.testing.assert_array_equal(state.contact & ~state.stick, (N0 > 0) & slip_above)
        np.testing.assert_allclose(Sx, np.where(N0 > 0, finer.force_x[rows, cols].ravel() * 4, 0.0))  # twice the spacing
        assert omega == finer.omega and d == 1e-3 and N is N0
        finer = started
