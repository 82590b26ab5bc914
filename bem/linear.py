"""The linear-solver dispatcher of the contact solvers: dense LU on small systems,
preconditioned restarted GMRES (matrix-free) on large ones.

A system is any object with ``n`` (unknowns), ``b`` (right-hand side), ``dense()`` (its
``n x n`` matrix), ``matvec(x)`` and, optionally, ``precondition(r)`` (an approximate
inverse; ``None`` when it has none). :class:`LinearSolver` picks the method by ``n``,
counts GMRES iterations over its calls, and raises the caller's error class, with a
message that says what to change, when a solve fails. The frictionless solver
(:mod:`bem.contact`) and the frictional one (:mod:`bem.frictional`) both use it.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from scipy.sparse.linalg import LinearOperator, gmres

__all__ = ["LinearSystem", "LinearSolver"]


class LinearSystem(Protocol):
    """What :class:`LinearSolver` needs of a system (see the module docstring)."""

    n: int
    b: np.ndarray

    def dense(self) -> np.ndarray: ...

    def matvec(self, x: np.ndarray) -> np.ndarray: ...


class LinearSolver:
    """Dense LU up to ``dense_limit`` unknowns, preconditioned GMRES above.

    Parameters
    ----------
    dense_limit : int
        Largest system (unknowns) solved by dense LU.
    rtol : float
        GMRES: reduction of the residual asked for (-), relative to ``|b|``, or with
        ``correction`` to the residual of the starting guess.
    correction : bool
        Solve for the correction to the guess (its residual reduced by ``rtol``): a solve
        that starts from the previous iterate of an outer iteration then gains accuracy
        as the iteration settles, instead of stalling at ``rtol |b|``.
    restart, maxiter : int
        GMRES restart length and number of restarts.
    error : type
        Exception class raised when a solve fails.
    what : str
        Names the system in error messages (``"3 x 1977 unknowns of the stick/slip set"``).

    Attributes
    ----------
    iterations : int
        GMRES iterations summed over the calls.
    used_gmres : bool
        Whether any call went to GMRES.
    """

    def __init__(self, dense_limit: int, rtol: float, *, restart: int = 100, maxiter: int = 100,
                 correction: bool = False, error: type = RuntimeError):
        self.dense_limit, self.rtol, self.correction = dense_limit, rtol, correction
        self.restart, self.maxiter, self.error = restart, maxiter, error
        self.iterations, self.used_gmres = 0, False

    def __call__(self, system, guess: np.ndarray | None = None, *, rtol: float | None = None, what: str = "",
                 hint: str = "") -> np.ndarray:
        """Solve ``system`` (``guess`` starts GMRES; ``rtol`` overrides the solver's for
        this call); returns the solution vector. ``what`` names the system and ``hint``
        says what to change, in error messages."""
        rtol = self.rtol if rtol is None else rtol
        n = system.n
        if n <= self.dense_limit:
            try:
                return np.linalg.solve(system.dense(), system.b)
            except np.linalg.LinAlgError as exc:
                raise self.error(f"singular system ({what or f'{n} unknowns'}): {exc}") from exc
        self.used_gmres = True
        prec = getattr(system, "precondition", None)
        M = None if prec is None else LinearOperator((n, n), matvec=prec, dtype=float)
        A = LinearOperator((n, n), matvec=system.matvec, dtype=float)
        count = [0]
        x0 = np.zeros(n) if guess is None else np.asarray(guess, float)
        if self.correction:
            b, start = (system.b - system.matvec(x0) if guess is not None else system.b), None
        else:
            b, start = system.b, x0
        x, info = gmres(A, b, x0=start, rtol=rtol, atol=0.0, restart=self.restart, maxiter=self.maxiter, M=M,
                         callback=lambda _: count.__setitem__(0, count[0] + 1), callback_type="pr_norm")
        self.iterations += count[0]
        if info != 0 or not np.isfinite(x).all():
            raise self.error(f"GMRES did not reduce the residual by {rtol:.1e} on {what or f'{n} unknowns'} "
                             f"in {count[0]} iterations" + (f"; {hint}" if hint else ""))
        return x0 + x if self.correction else x
