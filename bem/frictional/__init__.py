"""Frictional steady rolling and sliding (Coulomb friction): the model (its equations,
inputs and results) and its solver, Kalker's active set on contact, stick and slip sets.

Modules, one concept each:

* :mod:`~bem.frictional.model`: the equations, :class:`Friction` (the input),
  :class:`FrictionalContact` (the result) and the errors;
* :mod:`~bem.frictional.options`: :class:`SolverOptions`, the solver's tuning in one place
  (``docs/frictional-solver.md`` says what each field trades);
* :mod:`~bem.frictional.operators`: the nine compliance blocks, FFT products and dense blocks;
* :mod:`~bem.frictional.system`: the sets (:class:`SetState`), what stays fixed
  (:class:`RollingSetup`) and the linear system of one state (:class:`SetSystem`);
* :mod:`~bem.frictional.toeplitz`: the inverses of a grid row's Toeplitz blocks for every
  run length (Levinson, Gohberg-Semencul), by FFT or as matrices;
* :mod:`~bem.frictional.preconditioner`: exact solves on runs of contact nodes along ``x``
  (those inverses, the slip rows by Woodbury, the row filter);
* :mod:`~bem.frictional.violations`: what a solution violates, and the next sets, slip
  directions and slopes;
* :mod:`~bem.frictional.active_set`: the iteration on the sets (its linear solves, their
  tolerances);
* :mod:`~bem.frictional.local`: a few changed stick/slip nodes' rows solved locally;
* :mod:`~bem.frictional.loading`: the loading modes' equilibrium rows;
* :mod:`~bem.frictional.starts`: frictionless and coarse-grid starts, continuation in ``mu``;
* :mod:`~bem.frictional.solve`: the entry points :func:`solve_friction` (a
  :class:`bem.problem.Problem`) and :func:`solve_rolling` (prepared operators).

In plane strain (a :class:`bem.plane.LineGrid`, one row of nodes) the same solver runs on
the nine line kernels (:func:`bem.plane.line_kernels`), every force per unit length
(docs/derivations.md, section 8).

Linear solves go through :class:`bem.linear.LinearSolver` (shared with the frictionless
solver): dense LU up to ``Friction.dense_limit`` unknowns, above it flexible
right-preconditioned GMRES (:func:`bem.linear.fgmres`) with FFT products and the line
preconditioner.
"""

from .model import MODES, Friction, FrictionalContact, FrictionNotConverged, FrictionRecord, LoadingUnreachable
from .active_set import ActiveSetResult, run_active_set
from .operators import RollingOperators
from .options import SolverOptions
from .solve import solve_friction, solve_rolling
from .system import RollingSetup, SetState, SetSystem

__all__ = ["MODES", "Friction", "FrictionalContact", "FrictionNotConverged", "FrictionRecord", "LoadingUnreachable",
           "ActiveSetResult", "RollingOperators", "RollingSetup", "SetState", "SetSystem", "run_active_set",
           "SolverOptions", "solve_friction", "solve_rolling"]
