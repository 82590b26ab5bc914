"""One point of a sweep, solved with its group's kernels (a Dask task).

The point's case is turned into a problem by :func:`bem.case.problem_from_config`; the
group's kernel set is cut to the point's grid (:func:`sweeps.kernels.fit_kernels`) and
handed to :func:`bem.solve`, so no kernel is formed again. The result carries its energy
figure (``P_visc / V``, frictionless or frictional). Any error becomes a ``failed`` row
with its message: one bad point never stops the others.
"""

from __future__ import annotations

import time

import bem
from bem.case import friction_from_config, problem_from_config

from .kernels import fit_kernels
from .table import RESULTS

__all__ = ["solve_point", "scalars"]


def scalars(summary: dict) -> dict:
    """The result columns of a ``summary()`` (nested entries are left out)."""
    return {k: summary[k] for k in RESULTS if k in summary and not isinstance(summary[k], (dict, list))}


def solve_point(index: int, config: dict, kernels: dict | None) -> dict:
    """Solve one point; returns its table row (without the axis values).

    Parameters
    ----------
    index : int
        The point's position in the sweep.
    config : dict
        Its checked case (``casefile.validate(..., "bem")``).
    kernels : dict or None
        The group's kernel tables (a region at least as wide as the point's); ``None``
        forms them here.
    """
    t0 = time.perf_counter()
    row = {"index": index}
    try:
        problem, auto = problem_from_config(config)
        friction = friction_from_config(config)
        own = None if kernels is None or getattr(problem, "plane_strain", False) else fit_kernels(kernels, problem.grid)
        result = bem.solve(problem, friction, grow=auto and friction is None, kernels=own)
        values = scalars(result.summary())
        if friction is not None:
            values["friction_share"] = result.rolling_resistance_friction / result.rolling_resistance_energy
        row.update(values)
        row.update(status="ok", error="", nodes_x=getattr(result.grid, "nodes_x", ""),
                   nodes_y=getattr(result.grid, "nodes_y", ""),
                   iterations=result.record.iterations, **result.record.times)
    except Exception as exc:  # recorded, never raised: the sweep goes on
        row.update(status="failed", error=f"{type(exc).__name__}: {exc}".replace("\n", " "))
    row["seconds"] = time.perf_counter() - t0
    return row
