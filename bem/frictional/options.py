"""The frictional solver's tuning: one frozen :class:`SolverOptions`, passed down the call
chain (:func:`~bem.frictional.solve.solve_friction` and
:func:`~bem.frictional.solve.solve_rolling` take ``options``).

These knobs change how fast the solver gets to the converged state, not which state that
is (the convergence criteria of the result are :class:`~bem.frictional.model.Friction`'s
``max_iter``, ``direction_tol``, ``set_tol`` and ``dense_limit``). Each field says what it
trades; ``docs/frictional-solver.md`` gives the measurements behind each default.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["SolverOptions"]


@dataclass(frozen=True)
class SolverOptions:
    """Tuning of the frictional solver (all dimensionless unless said; defaults measured on
    the benchmark grids, ``docs/frictional-solver.md``).

    Attributes
    ----------
    loose_reduction : float
        GMRES reduction of the inexact solves while the slip law is unsettled: looser
        saves GMRES iterations per solve, too loose leaves slip directions too rough and
        costs active-set iterations.
    loose_until : float
        Slip misfit above which solves stay inexact: lower delays the tight solves.
    settled : float
        Slip misfit at or below which a solve right after a set change is tight, and a
        tight solve that took no GMRES iteration ends the iteration.
    start_reduction : float
        Residual, as a fraction of ``|b|``, the first solve from the coarse grid's forces
        stops at: the coarse guess is already near this.
    settle_changes : float
        A coarse level ends once its sets change by at most this fraction of its contact
        nodes (and its misfit is at most ``coarse_settle``): saves the solve that would
        confirm the last changes, which the fine grid redoes anyway.
    few_changes : int
        Stick/slip changes after a solve at most this many count as few: their rows are
        solved locally on large contacts.
    local_from : int
        Contact nodes from which few changes are solved locally (their cost does not grow
        with the grid, a global solve's does; below it they cost more than they save).
    slope_floor : float
        Floor of the slip-law slope ``k``, in units of ``V / (mu N)`` while the misfit is 1
        or more, faded in proportion below: keeps barely slipping nodes' forces near their
        direction while the slip law is far from settled.
    slip_creep : float
        With ``Omega`` given, nodes whose rigid creep ``|V - Omega l|`` exceeds this
        fraction of ``V`` start (and join the contact) in slip rather than in stick.
    cone_tol : float
        Relative excess over the cone ``mu N`` a stick node may carry before it slips
        (rounding, not physics).
    penetration_tol : float
        Penetration, as a fraction of ``|d|``, a node outside the contact may show before
        it joins (rounding).
    tight_reduction : float
        GMRES reduction of the tight solves, the ones that can end the iteration.
    residual_floor : float
        Every solve stops once its residual is below this fraction of ``|b|``: below it the
        iterations chase rounding.
    single_from : float
        Solves asking a reduction of this or less (the loose ones) take their products in
        single precision inside the GMRES cycles; half the memory traffic.
    single_start : float
        Tight solves are iterative refinement: phases that each reduce the residual by this
        in single precision, the residual recomputed in double between them.
    restart : int
        GMRES cycle length: longer keeps more Krylov vectors (memory, orthogonalisation).
    max_cycles : int
        GMRES cycles before a solve gives up and raises.
    local_window : int
        Contact nodes on either side of a changed node, along its grid row, that its local
        solve frees: wider costs ``(2 m)^3`` more for a window of ``m`` nodes.
    local_rounds : int
        Local solves at most after one global solve.
    filter_power : float
        Power ``p`` of the row filter ``(C_row / C)^p`` applied after the line solves (0:
        off); 1 is the interior's exact correction, the run ends prefer less.
    filter_long : float or None
        The row filter's power on the longest waves across the contact, blended into
        ``filter_power`` on the short ones (``None``: one power).
    filter_waves : float
        Waves across the contact's box at which the blend is ``1/e`` of the way from
        ``filter_long`` to ``filter_power``.
    thread_from : int
        Bytes of the run operands from which one preconditioner application runs on two
        threads: below it the threads' overhead exceeds their gain.
    chunk : int
        Slip nodes whose Toeplitz-inverse columns are computed at a time (working memory
        against the number of batches).
    compose_upto : int
        Runs with at most this many slip nodes (padded to 8) apply ``K^{-1}`` composed (one
        product); longer ones apply its factors (no ``2 p x 2 p`` product to build).
    dense_upto : int
        Longest run (rounded up to 16 nodes) up to which runs are solved by their explicit
        Toeplitz inverses; above it by transforms (memory traffic against FFT work).
    batched_upto : int
        Longest run up to which the explicit inverses are padded to one batched product;
        above it they are grouped by run length.
    coarse_settle : float or None
        A coarse level ends once its misfit is at most this (and few sets change), without
        its tight solve; ``None``: coarse levels converge fully.
    start_rtol : float
        GMRES tolerance (of ``|b|``) of the frictionless solve that starts a frictional one:
        only its contact set and forces are read.
    frictionless_rtol : float
        GMRES tolerance of the frictionless solve when it is the result (``mu = 0``).
    overlap_from : int
        Grid nodes from which the fine frictionless start solves on a second thread while
        the coarse levels solve (below it the threads mostly wait for the GIL).
    continuation_mu : float
        After a failed direct solve with a free ``Omega``, the continuation starts at the
        smallest ``mu 2^K >= continuation_mu`` (``K >= 1``), where a stick zone carries the
        moment, and halves ``mu`` back.
    """

    loose_reduction: float = 3e-3
    loose_until: float = 1e-2
    settled: float = 1e-5
    start_reduction: float = 1e-5
    settle_changes: float = 0.01
    few_changes: int = 20
    local_from: int = 20_000
    slope_floor: float = 1e-3
    slip_creep: float = 1e-2
    cone_tol: float = 1e-10
    penetration_tol: float = 1e-12
    tight_reduction: float = 1e-10
    residual_floor: float = 1e-15
    single_from: float = 1e-4
    single_start: float = 1e-4
    restart: int = 200
    max_cycles: int = 10
    local_window: int = 8
    local_rounds: int = 8
    filter_power: float = 0.5
    filter_long: float | None = 0.7
    filter_waves: float = 5.0
    thread_from: int = 4_000_000
    chunk: int = 2048
    compose_upto: int = 16
    dense_upto: int = 128
    batched_upto: int = 64
    coarse_settle: float | None = 0.3
    start_rtol: float = 1e-8
    frictionless_rtol: float = 1e-11
    overlap_from: int = 4000
    continuation_mu: float = 0.2

    def __post_init__(self):
        for name in ("loose_reduction", "start_reduction", "tight_reduction", "single_from", "single_start",
                     "start_rtol", "frictionless_rtol"):
            _check(self, name, lambda v: 0 < v < 1, "in (0, 1)")
        for name in ("loose_until", "settled", "slope_floor", "slip_creep", "cone_tol", "penetration_tol",
                     "residual_floor", "filter_power"):
            _check(self, name, lambda v: v >= 0, ">= 0")
        _check(self, "settle_changes", lambda v: 0 <= v <= 1, "in [0, 1]")
        _check(self, "filter_waves", lambda v: v > 0, "> 0")
        _check(self, "continuation_mu", lambda v: v > 0, "> 0")
        for name in ("filter_long", "coarse_settle"):
            if getattr(self, name) is not None:
                _check(self, name, lambda v: v >= 0, ">= 0 or None")
        for name in ("restart", "max_cycles", "local_window", "local_rounds", "chunk"):
            _check_int(self, name, 1)
        for name in ("few_changes", "local_from", "thread_from", "compose_upto", "dense_upto", "batched_upto",
                     "overlap_from"):
            _check_int(self, name, 0)


def _check(options: SolverOptions, name: str, rule, text: str) -> None:
    value = getattr(options, name)
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and rule(value)
    if not ok:
        raise ValueError(f"SolverOptions.{name} must be a finite number {text}, got {value!r}")


def _check_int(options: SolverOptions, name: str, least: int) -> None:
    value = getattr(options, name)
    if not (isinstance(value, int) and not isinstance(value, bool) and value >= least):
        raise ValueError(f"SolverOptions.{name} must be an integer >= {least}, got {value!r}")
