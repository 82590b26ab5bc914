"""The grid error of the frictional figures, by Richardson extrapolation.

The frictional solve converges slowly with the node spacing ``a``: the stick/slip border
and the upwind derivative of the kinematics are first-order in ``a`` at best, and the
slipping-friction part ``R_r^F`` (eq. 2), a small difference of slip velocities over a
thin slip band, converges at an observed order between 0.5 and 1 on the paper's section
11 example (docs/derivations.md, "Grid error of the frictional figures"). Its value
on one grid is then no better than its grid error, which this module estimates: solve the
case on its grid and on the grid coarsened by 2 and by 4 (same region and periods, the
truncations divided by the same factor), and extrapolate each scalar from the three
levels (:func:`bem.convergence.richardson`: the observed order ``p``, the limit
``q* = q3 + (q3 - q2) / (2^p - 1)`` and ``|q* - q3|`` as the error of the given grid;
where ``p`` is outside ``[0.5, 5]`` the error is three times the last change).

Why the truncation follows the spacing. The discretisation has two parameters, the node
spacing ``a`` and the truncation ``N_t`` (the shortest wave ``L / N_t``), and its error
vanishes as both refine together; the three levels keep ``N_t a`` (the modes per node),
so they are one family of discretisations, each the case as the user would write it on
that grid, and the estimate covers what the truncation contributes as well as the
spacing. With the fine truncation kept, the coarse levels resolved more modes per node
than the case: on ``examples/elastic-paraboloid-creepage.toml`` (``N_t = L / 2a``) the
driving force at 0.2 mm is 7.0418 N with ``N_t = 1500`` and 7.0598 N with 3000, and the
estimate at 0.05 mm gave +/- 0.008 N where the three cases solved on their own (7.0418,
7.0005, 6.9813 N) give order 1.1 and +/- 0.017 N; the stick fraction +/- 2e-5 where the
cases change by 0.0040 and 0.0023.

Cost: the two coarse levels (a quarter and a sixteenth of the nodes, a half and a
quarter of the modes each way) add their kernels and solves. Their nodes are the case's
(every second and every fourth), so each level starts from the solution of the level
above on its nodes (:func:`bem.frictional.starts.restricted_start`), which leaves it the
few border nodes and slip directions its own grid error changes: on
``examples/elastic-paraboloid-creepage.toml`` at 0.2 mm the levels' solves take 48 and
17 ms against 78 and 29 ms from their frictionless contacts (medians of five in one
process), and the whole ``bem solve`` 0.31 s against 0.25 s without the estimate (one
thread; BENCHMARKS.md, "External references"). ``bem solve`` makes the estimate for
every frictional case unless told not to (``--no-error-estimate``): no frictional figure
is printed without its error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable

from ..convergence import Convergence, richardson
from ..grid import Grid
from ..plane import LineGrid
from ..threads import with_one_blas_thread

__all__ = ["SCALARS", "GridErrorEstimate", "coarsened_grid", "estimate_grid_error"]

#: the frictional scalars estimated, with their units
SCALARS = {
    "rolling_resistance": "N",
    "rolling_resistance_energy": "N",
    "rolling_resistance_friction": "N",
    "rolling_resistance_viscous": "N",
    "driving_force": "N",
    "omega": "rad/s",
    "indentation": "m",
    "stick_fraction": "-",
}


@dataclass(frozen=True)
class GridErrorEstimate:
    """Richardson estimates of the frictional scalars.

    Attributes
    ----------
    spacings : tuple of float
        Node spacings ``a_x`` (m) of the three levels, coarse to fine (the last is the
        case's own grid).
    figures : dict
        Scalar name (:data:`SCALARS`) to :class:`bem.convergence.Convergence`:
        values coarse to fine, observed order, extrapolated limit, error of the finest.
    per_length : bool
        A line contact (plane strain): the forces are per unit length (N/m).
    """

    spacings: tuple
    figures: dict
    per_length: bool = False

    def lines(self) -> list[str]:
        """One human-readable line per scalar, with its unit."""
        out = [f"grid error (Richardson from a = {', '.join(f'{a * 1e3:g}' for a in self.spacings)} mm):"]
        for name, c in self.figures.items():
            unit = SCALARS[name] + ("/m" if self.per_length and SCALARS[name] == "N" else "")
            order = f"order {c.order:.2f}" if c.asymptotic else "not asymptotic: 3 x last change"
            out.append(f"  {name:28s} {c.values[-1]:.6g} {unit}, limit {c.extrapolated:.6g} {unit} "
                       f"+/- {c.error_finest:.2g} {unit} ({order})")
        return out

    def summary(self) -> dict:
        """JSON-ready: per scalar its three values, order, limit and error (SI units)."""
        return {"spacings": list(self.spacings),
                "figures": {n: {"values": list(c.values), "order": c.order, "limit": c.extrapolated,
                                "error": c.error_finest, "asymptotic": c.asymptotic}
                            for n, c in self.figures.items()}}


def coarsened_grid(grid: Grid, factor: int) -> Grid:
    """``grid`` with its spacings times ``factor`` (an integer >= 1) over the same region
    (the half widths of the fine grid) and periods, its truncations divided by ``factor``
    (rounded up; never below the ``L / 2a`` a grid needs): the modes per node kept (module
    docstring)."""
    if not (isinstance(factor, int) and factor >= 1):
        raise ValueError(f"factor must be an integer >= 1, got {factor!r}")

    def modes(truncation, period, spacing):
        return max(math.ceil(truncation / factor - 1e-9), math.ceil(period / (2 * spacing * factor) - 1e-9))

    if isinstance(grid, LineGrid):
        return LineGrid.centred(grid.spacing * factor, grid.period, modes(grid.truncation, grid.period, grid.spacing),
                                (grid.nodes - 1) / 2 * grid.spacing)
    hw = ((grid.nodes_x - 1) / 2 * grid.spacing_x, (grid.nodes_y - 1) / 2 * grid.spacing_y)
    return Grid.centred((grid.spacing_x * factor, grid.spacing_y * factor), (grid.period_x, grid.period_y),
                        (modes(grid.truncation_x, grid.period_x, grid.spacing_x),
                         modes(grid.truncation_y, grid.period_y, grid.spacing_y)), hw)


@with_one_blas_thread
def estimate_grid_error(problem, friction, fine=None, progress: Callable[[str], None] | None = None,
                        options=None) -> GridErrorEstimate:
    """Solve ``problem`` with ``friction`` (:func:`bem.frictional.solve_friction`) on its
    grid coarsened by 2 and by 4, and extrapolate every scalar of :data:`SCALARS` with the
    result ``fine`` on its own grid (solved here when not given). Each level starts from
    the sets and forces of the level above on its nodes (``finer``): they are the case's
    nodes, every second and every fourth one.

    Raises what :func:`bem.frictional.solve_friction` raises, on any level.
    """

    from .solve import solve_friction

    results = [fine if fine is not None else solve_friction(problem, friction, options=options)[0]]
    for factor in (2, 4):
        p = replace(problem, grid=coarsened_grid(problem.grid, factor))
        if progress:
            progress(f"grid error: solving at a = {p.grid.spacing_x * 1e3:g} mm ({p.grid.nodes_x} x {p.grid.nodes_y})")
        results.insert(0, solve_friction(p, friction, options=options, finer=results[0])[0])
    figures = {name: richardson([getattr(r, name) for r in results]) for name in SCALARS}
    return GridErrorEstimate(tuple(r.grid.spacing_x for r in results), figures, problem.plane_strain)
