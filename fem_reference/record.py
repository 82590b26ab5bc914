"""How a solve went: the record every model's result carries."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict

__all__ = ["SolverRecord"]


@dataclass(frozen=True)
class SolverRecord:
    """How the solve went, in the vocabulary of every solver of the project.

    ``iterations`` of the contact active set (both methods together), ``residual`` its
    complementarity residual (-), ``history`` the active nodes at each primal-dual
    iteration, ``method`` the contact method that ended the solve; ``linear_solver``,
    ``linear_iterations`` (Krylov, summed; 0 for the direct solver) and
    ``linear_residual`` (the largest relative residual of the saddle solves, -) for the
    linear systems; ``factor_nonzeros`` of the LU factors; ``times`` the wall-clock
    seconds of each stage.
    """

    iterations: int
    residual: float
    history: tuple
    method: str
    linear_solver: str
    linear_iterations: int
    linear_residual: float
    factor_nonzeros: int
    times: Dict[str, float]
