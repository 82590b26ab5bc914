"""The entry point :func:`solve`: a :class:`bem.problem.Problem` to its result.

Without friction:

1. the influence kernel of the grid (:func:`bem.spectral.influence_kernels`, or
   :func:`bem.plane.line_kernel` in plane strain), unless given;
2. the contact on the compliance operator (:func:`bem.contact.solve_normal`); with
   ``grow=True`` a contact that reaches the edge of the region widens the region by
   half and solves again;
3. the figures of the rolling contact, computed here once because they need the problem
   (the layer, the speed, the indenter's exact profile): the power the layer dissipates,
   the power of the pressure and the contact's edges on ``y = 0``.

With a :class:`bem.frictional.Friction` the frictional solver
(:func:`bem.frictional.solve_friction`) does the whole, in 3D or, on a line grid, in plane
strain with the nine line kernels (:func:`bem.plane.line_kernels`).
"""

from __future__ import annotations

import math
import time
from dataclasses import fields, replace
from typing import TYPE_CHECKING, Callable

import numpy as np

from .contact import DENSE_LIMIT, ContactAtEdge, solve_normal
from .energy import layer_power
from .grid import Grid
from .operator import ComplianceOperator
from .plane import LINE_DENSE_LIMIT, LineContact, LineGrid, edges_along, line_dissipation
from .problem import Problem, compute_kernels, line_tables
from .result import NormalContact
from .threads import with_one_blas_thread

if TYPE_CHECKING:
    from .frictional import Friction, FrictionalContact
    from .frictional.options import SolverOptions

__all__ = ["solve", "LINE_DENSE_LIMIT", "SLOPE_STEP"]

#: half-step of the central difference that gives the indenter's slope ``ds/dx`` for
#: :attr:`NormalContact.pressure_power`, in node spacings (-): small against the
#: profile's curvature, large against rounding
SLOPE_STEP = 1e-3


@with_one_blas_thread
def solve(problem: Problem, friction: Friction | None = None, *,
          progress: Callable[[str], None] | None = None, grow: bool = False, kernels: dict | None = None,
          energy: bool = True, options: SolverOptions | None = None) -> NormalContact | LineContact | FrictionalContact:
    """Solve the contact of ``problem``: frictionless (at rest or in steady rolling, in 3D
    or, for a :class:`bem.indenters.LineCylinder` on a :class:`bem.plane.LineGrid`, in
    plane strain per unit length), or with Coulomb ``friction`` (steady rolling or
    sliding, in 3D or in plane strain per unit length).

    Parameters
    ----------
    problem : Problem
        Layer, indenter, grid and loading (SI units).
    friction : Friction, optional
        Coulomb friction and the rolling mode; ``None`` for a frictionless contact.
    progress : callable, optional
        Receives one line of text per stage and per active-set iteration.
    grow : bool
        Frictionless only: a contact that reaches the edge of the region widens the region
        by half and solves again (up to 0.95 of the indenter's radius); otherwise that
        raises :class:`bem.contact.ContactAtEdge`. For a region sized automatically.
    kernels : dict, optional
        Kernel tables of this grid, layer and speed to reuse
        (:func:`bem.problem.compute_kernels`): the ``"ww"`` table without friction (for a
        line contact the :func:`bem.plane.line_kernel` table), all nine blocks with it
        (:func:`bem.plane.line_kernels` for a line contact). A widened region computes its own.
    energy : bool
        Compute the layer's dissipation (:attr:`NormalContact.dissipation`; with friction
        ``rolling_resistance_energy``), a sum over every Fourier mode; ``nan`` without it.
    options : SolverOptions, optional
        With friction only: the frictional solver's tuning
        (:class:`bem.frictional.options.SolverOptions`; its defaults without).

    Returns
    -------
    NormalContact, LineContact or FrictionalContact
        A :class:`bem.result.NormalContact` (3D) or :class:`bem.plane.LineContact` (plane
        strain) without friction, a :class:`bem.frictional.FrictionalContact` with it (its
        forces per unit length in plane strain, :attr:`~bem.frictional.FrictionalContact.
        plane_strain`). The
        times of the stages (s) are in ``result.record.times``.

    Raises
    ------
    ContactNotConverged, ContactAtEdge, FrictionNotConverged, LoadingUnreachable
        A solve that cannot end on a converged state, with what to change.
    ValueError
        Bad input (``grow`` with friction, ``options`` without, kernels of another grid),
        or a speed at or above the layer's shear-wave speed.
    """
    _check_inputs(problem, friction, kernels)
    if friction is not None:
        if grow:
            raise ValueError("grow widens the region of a frictionless solve only: give grid.half_width "
                             "for a frictional one")
        from .frictional import solve_friction

        result, times = solve_friction(problem, friction, progress=progress, options=options, kernels=kernels,
                                       energy=energy)
        return replace(result, record=replace(result.record, times=times))
    if options is not None:
        raise ValueError("options tune the frictional solver: give them with friction")
    p = problem
    given = kernels  # with "ww": _check_inputs
    need = (2 * p.grid.nodes_y - 1, 2 * p.grid.nodes_x - 1)
    if given is not None and np.shape(given["ww"]) != need:
        raise ValueError(f"kernels['ww'] has shape {np.shape(given['ww'])}, a grid of {p.grid.nodes_x} x "
                         f"{p.grid.nodes_y} nodes needs {need}")
    while True:
        tables, kernel_s = _kernel(p, progress, energy) if given is None else (given, 0.0)
        given, table = None, tables["ww"]
        X, Y = p.grid.coordinates()
        t1 = time.perf_counter()
        try:
            res = solve_normal(ComplianceOperator(p.grid, table), p.indenter.profile(X, Y), load=p.loading.load,
                               indentation=p.loading.indentation, arm=p.indenter.rolling_arm(X, Y),
                               progress=progress, dense_limit=LINE_DENSE_LIMIT if p.plane_strain else DENSE_LIMIT)
        except ContactAtEdge:
            bigger = _wider(p) if grow else None
            if bigger is None:
                raise
            if progress:
                progress(f"contact reached the region's edge: widening to |x| <= {bigger.x[-1]:.4g} m")
            p = replace(p, grid=bigger)
            continue
        t2 = time.perf_counter()
        figures = _rolling_figures(p, res, energy, tables)
        t3 = time.perf_counter()
        if progress and math.isfinite(figures["dissipation"]) and p.loading.speed > 0:
            unit = "N/m" if p.plane_strain else "N"
            progress(f"energy: P_visc / V = {figures['dissipation'] / p.loading.speed:.6g} {unit}, {t3 - t2:.2f} s")
        times = {"kernel_s": kernel_s, "solve_s": t2 - t1, "energy_s": t3 - t2}
        values = {f.name: getattr(res, f.name) for f in fields(res)}
        values.update(figures, record=replace(res.record, times=times))
        return (LineContact if p.plane_strain else NormalContact)(**values)


def _check_inputs(problem, friction, kernels) -> None:
    """Raise ``TypeError``/``ValueError`` naming the argument when ``problem`` is not a
    :class:`Problem` or ``kernels`` lacks a block the solve reads."""
    if not isinstance(problem, Problem):
        raise TypeError(f"problem must be a bem.problem.Problem, got {problem!r}")
    if kernels is None:
        return
    if not isinstance(kernels, dict):
        raise TypeError(f"kernels must be a dict of kernel tables (bem.problem.compute_kernels), got {kernels!r}")
    from .spectral import BLOCKS

    need = ("ww",) if friction is None else tuple(BLOCKS)
    missing = [b for b in need if b not in kernels]
    if missing:
        raise ValueError(f"kernels lacks the block(s) {', '.join(map(repr, missing))}: a "
                         f"{'frictionless' if friction is None else 'frictional'} solve reads "
                         f"{', '.join(map(repr, need))} (bem.problem.compute_kernels)")


def _kernel(p: Problem, progress, energy: bool) -> tuple[dict, float]:
    """The ``"ww"`` kernel table of the problem's grid, layer and speed (with its power
    table when ``energy`` asks for the dissipation, :func:`bem.problem.compute_kernels`),
    and the seconds they took."""
    if not p.plane_strain:
        return compute_kernels(p, ("ww",), progress, power=energy)
    return line_tables(p, ("ww",), progress)


def _wider(p: Problem) -> Grid | LineGrid | None:
    """The problem's region widened by half (up to 0.95 of the indenter's radius: the
    region stays under the indenter), or ``None`` once it spans 0.9 of that."""
    g = p.grid
    cap = 0.95 * getattr(p.indenter, "radius", math.inf)
    if max(g.x[-1], g.y[-1]) >= 0.9 * cap:
        return None
    if isinstance(g, LineGrid):
        return LineGrid.centred(g.spacing, g.period, g.truncation, min(1.5 * g.x[-1], cap))
    return Grid.centred((g.spacing_x, g.spacing_y), (g.period_x, g.period_y), (g.truncation_x, g.truncation_y),
                        (min(1.5 * g.x[-1], cap), min(1.5 * g.y[-1], cap)))


def _rolling_figures(p: Problem, res: NormalContact, energy: bool, kernels: dict) -> dict:
    """``speed``, ``dissipation``, ``pressure_power``, ``trailing_edge`` and
    ``leading_edge`` of the solution ``res`` of ``p`` (the fields of
    :class:`NormalContact`, in its units); the dissipation by the power table of
    ``kernels`` when they carry it (:func:`bem.energy.layer_power`)."""
    g, V, F = p.grid, p.loading.speed, res.force
    X, Y = g.coordinates()
    on = F > 0
    step = SLOPE_STEP * g.spacing_x
    slope = (p.indenter.profile(X[on] + step, Y[on]) - p.indenter.profile(X[on] - step, Y[on])) / (2 * step)
    figures = {"speed": V, "pressure_power": V * float(np.sum(F[on] * slope)),
               "trailing_edge": math.nan, "leading_edge": math.nan}
    row = np.flatnonzero(g.y == 0.0)  # the line y = 0 (a centred grid of an odd row count has one)
    if row.size and on[row[0]].any():
        figures["trailing_edge"], figures["leading_edge"] = edges_along(g.x, g.spacing_x, F[row[0]], res.gap[row[0]])
    if not energy:
        figures["dissipation"] = math.nan
    elif V == 0:
        figures["dissipation"] = 0.0
    elif p.plane_strain:
        figures["dissipation"] = line_dissipation(g, p.layer, V, F)
    else:
        zero = np.zeros_like(F)
        figures["dissipation"] = layer_power(g, p.layer, V, kernels, -F, zero, zero)
    return figures
