"""The linear-solver dispatcher of the contact solvers: dense LU on small systems,
flexible right-preconditioned restarted GMRES (matrix-free, :func:`fgmres`) on large ones.

A system is any object with ``n`` (unknowns), ``b`` (right-hand side), ``dense()`` (its
``n x n`` matrix), ``matvec(x)`` and, optionally, ``precondition(r)`` (an approximate
inverse; ``None`` when it has none) and ``residual(x)`` (``b - A x`` of a starting guess,
when the system can give it without a product). :class:`LinearSolver` picks the method
by ``n``, counts GMRES iterations over its calls, and raises the caller's error class,
with a message that says what to change, when a solve fails. The frictionless solver
(:mod:`bem.contact`) and the frictional one (:mod:`bem.frictional`) both use it.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

__all__ = ["LinearSystem", "LinearSolver", "fgmres", "bordered", "eliminate", "RANK_TOL", "SCHUR_COND"]

#: :func:`fgmres` takes a least-squares step instead of the triangular solve when a
#: diagonal entry of its Hessenberg factor falls below this fraction of the largest (a
#: product ``A z_j`` in the span of the earlier ones, to rounding): on ``diag(1, 2, 0)``
#: the triangular solve gave a step of 3e14 (a diagonal entry of 1e-16, not exactly 0)
RANK_TOL = 1e-13
#: :func:`eliminate` declines a Schur complement whose condition number exceeds this
SCHUR_COND = 1e12


class LinearSystem(Protocol):
    """What :class:`LinearSolver` needs of a system (see the module docstring)."""

    n: int
    b: np.ndarray

    def dense(self) -> np.ndarray: ...

    def matvec(self, x: np.ndarray) -> np.ndarray: ...


def fgmres(matvec, b: np.ndarray, precondition=None, *, tol: float, restart: int = 100, maxiter: int = 100,
           callback=None, inner=None, basis=np.float64) -> tuple[np.ndarray, bool, int]:
    """Flexible right-preconditioned restarted GMRES from ``x = 0``.

    Minimises the true residual ``|b - A x|`` over ``x in span(z_1 .. z_j)``,
    ``z_j = M v_j`` kept (so ``M`` may change from one application to the next, e.g. be
    applied in single precision), with classical Gram-Schmidt by matrix products and a
    second pass when the first lost more than half of the vector (Kahan's "twice is
    enough"). Stops when the residual is at most ``tol`` (in the units of ``b``): the
    recurrence's estimate inside a cycle, the recomputed residual at its end.

    Parameters
    ----------
    matvec, precondition : callable
        ``A x`` and ``M r`` (``None``: ``M = I``).
    b : ndarray
        Right-hand side.
    tol : float
        Absolute residual asked for (units of ``b``).
    restart, maxiter : int
        Cycle length and number of cycles.
    callback : callable, optional
        Called with the residual estimate after each iteration.
    inner : callable, optional
        ``A x`` inside the cycles when a cheaper, less accurate product exists (e.g. in
        single precision); ``matvec`` still gives the residual at each cycle's end, so the
        convergence test reads the true residual and a cycle that fell short of ``tol``
        by the inner product's error restarts from it.
    basis : dtype
        Storage and Gram-Schmidt of the Krylov vectors ``v_j`` and ``z_j``. ``float32``
        halves the memory traffic of the orthogonalisation (the Hessenberg matrix and the
        step stay in double); a cycle then reduces the residual by about 1e-7 at most, as
        with a single-precision ``inner`` product, and restarts from the residual
        recomputed by ``matvec``: for solves whose products are single precision anyway.

    Returns
    -------
    x : ndarray
    converged : bool
    iterations : int
    """
    n = b.size
    restart = max(1, min(restart, n))
    x = np.zeros(n)
    r = np.array(b, float)
    beta = float(np.linalg.norm(r))
    its = 0
    if beta <= tol:
        return x, True, 0
    V = np.empty((restart + 1, n), basis)
    Z = np.empty((restart, n), basis)
    H = np.zeros((restart + 1, restart))
    cs, sn = np.zeros(restart), np.zeros(restart)
    product = matvec if inner is None else inner
    for _ in range(maxiter):
        V[0] = r / beta
        g = np.zeros(restart + 1)
        g[0] = beta
        j = 0
        for j in range(restart):
            Z[j] = V[j] if precondition is None else precondition(V[j])
            w = product(Z[j]).astype(basis, copy=False)
            norm0 = float(np.linalg.norm(w))
            h = V[:j + 1] @ w
            w -= h @ V[:j + 1]
            norm1 = float(np.linalg.norm(w))
            if norm1 < 0.5 * norm0:  # reorthogonalise once
                h2 = V[:j + 1] @ w
                w -= h2 @ V[:j + 1]
                h += h2
                norm1 = float(np.linalg.norm(w))
            H[:j + 1, j] = h
            H[j + 1, j] = norm1
            for i in range(j):  # the previous rotations on the new column
                a, c = H[i, j], H[i + 1, j]
                H[i, j], H[i + 1, j] = cs[i] * a + sn[i] * c, -sn[i] * a + cs[i] * c
            a, c = H[j, j], H[j + 1, j]
            rho = float(np.hypot(a, c))
            cs[j], sn[j] = (1.0, 0.0) if rho == 0 else (a / rho, c / rho)
            H[j, j], H[j + 1, j] = rho, 0.0
            g[j + 1] = -sn[j] * g[j]
            g[j] *= cs[j]
            its += 1
            if callback is not None:
                callback(abs(g[j + 1]))
            breakdown = norm1 <= 1e-14 * norm0
            if not breakdown:
                V[j + 1] = w / norm1
            if abs(g[j + 1]) <= tol or breakdown:
                break
        k = j + 1
        R = np.triu(H[:k, :k])
        if not (np.isfinite(R).all() and np.isfinite(g[:k]).all()):
            break  # a product was not finite: the last iterate, and a failure
        d = np.abs(np.diag(R))
        if d.min() > RANK_TOL * d.max():
            y = np.linalg.solve(R, g[:k])
        else:  # A z_j in the span of the others, to rounding: the least-squares step on the
            # well-determined directions, and a failure if it does not suffice
            y = np.linalg.lstsq(R, g[:k], rcond=RANK_TOL)[0]
        x += y.astype(basis, copy=False) @ Z[:k]
        r = b - matvec(x)
        beta = float(np.linalg.norm(r))
        if beta <= tol:
            return x, True, its
        if not np.isfinite(beta):
            break
    return x, False, its


def eliminate(forces, F: np.ndarray, rows):
    """What :func:`bordered` needs of the global unknowns: ``(M F, S^{-1})`` with ``S = -G M
    F`` (``k`` applications of ``forces``), or ``None`` when ``S`` is singular (condition
    number above :data:`SCHUR_COND`, or not finite): the caller keeps its own treatment
    then. ``F`` ``(m, k)`` holds the global unknowns' columns in the force rows, ``rows(x)``
    the global rows ``G x`` on force vectors ``x`` ``(m, j)`` as ``(k, j)``."""
    MF = np.stack([forces(F[:, j]) for j in range(F.shape[1])], 1)
    S = -rows(MF)
    if not np.isfinite(S).all() or np.linalg.cond(S) > SCHUR_COND:
        return None
    return MF, np.linalg.inv(S)


def bordered(forces, rows, parts):
    """A preconditioner of the bordered system ``[[A, F], [G, 0]]`` (``m`` force unknowns,
    ``k`` global ones such as the indentation under load control) from ``forces``, an
    approximate inverse ``M`` of ``A`` (``r_f`` of size ``m`` to ``m``), by block
    elimination with the Schur complement of the global unknowns (``parts`` from
    :func:`eliminate`):

        ``y = M r_f``, ``x_g = S^{-1} (r_g - G y)``, ``x_f = y - (M F) x_g``,
        ``S = -G M F``

    exact for the bordered matrix when ``M = A^{-1}``; ``parts`` of an earlier ``M`` give an
    inexact but fixed elimination (a flexible GMRES takes either). Passing the global rows
    on unchanged instead leaves outliers in
    the preconditioned spectrum whose vectors lie on the global unknowns
    (``docs/frictional-solver.md``)."""
    MF, S_inv = parts
    m, k = MF.shape

    def precondition(r):
        y = forces(r[:m])
        xg = S_inv @ (r[m:] - rows(y[:, None])[:, 0])
        out = np.empty(m + k)
        out[:m] = y - MF @ xg
        out[m:] = xg
        return out

    return precondition


class LinearSolver:
    """Dense LU up to ``dense_limit`` unknowns, :func:`fgmres` above (right preconditioning,
    the true residual; on the frictionless solver 1.2-1.7x faster than SciPy's
    left-preconditioned GMRES, measured in BENCHMARKS.md).

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
    floor : float
        A residual below ``floor |b|`` is good enough whatever ``rtol`` asks (-): a
        correction whose residual is already near rounding is not reduced ten more orders.
    single_from : float
        A call whose ``rtol`` is at least this (-) runs its GMRES cycles on the system's
        ``matvec_single`` when it has one (a product in single precision), on Krylov
        vectors kept in single precision (:func:`fgmres`'s ``basis``), the residual at each
        cycle's end on ``matvec``; ``inf``: never.
    single_start : float
        A call whose ``rtol`` is below ``single_from`` is iterative refinement: phases as a
        call at ``single_from`` runs them (single-precision products and basis), each
        reducing the residual left, recomputed by ``matvec``, by at most this (-); it goes
        on in double precision only when a phase fails; 0: in double precision throughout.
    dense_fallback : int
        A GMRES solve that fails on a system of at most this many unknowns is solved by
        dense LU instead (0: never), and so are the later calls up to that size: where the
        preconditioner misses the system's spectrum, a bounded dense solve (``8 n^2``
        bytes) instead of an error, and one failed GMRES run instead of one a call.
    what : str
        Names the system in error messages (``"3 x 1977 unknowns of the stick/slip set"``).

    Attributes
    ----------
    iterations : int
        GMRES iterations summed over the calls.
    used_gmres : bool
        Whether any call went to GMRES.
    fallbacks : int
        GMRES solves that failed and were solved by dense LU (``dense_fallback``).
    """

    def __init__(self, dense_limit: int, rtol: float, *, restart: int = 100, maxiter: int = 100,
                 correction: bool = False, error: type = RuntimeError, floor: float = 0.0,
                 single_from: float = np.inf, single_start: float = 0.0, dense_fallback: int = 0):
        self.dense_limit, self.rtol, self.correction = dense_limit, rtol, correction
        self.dense_fallback, self.fallbacks = dense_fallback, 0
        self.single_from, self.single_start = single_from, single_start
        self.restart, self.maxiter, self.error = restart, maxiter, error
        self.floor = floor
        self.iterations, self.used_gmres = 0, False

    def dense_for(self, n: int) -> bool:
        """Whether a system of ``n`` unknowns goes to dense LU (exact whatever ``rtol``)."""
        return n <= self.dense_limit or bool(self.fallbacks and n <= self.dense_fallback)

    def __call__(self, system, guess: np.ndarray | None = None, *, rtol: float | None = None, what: str = "",
                 hint: str = "", of_b: bool = False, maxiter: int | None = None) -> np.ndarray:
        """Solve ``system`` (``guess`` starts GMRES; ``rtol`` overrides the solver's for
        this call; with ``of_b`` it is relative to ``|b|`` even with ``correction``: a
        guess from elsewhere, whose residual says little of the accuracy needed;
        ``maxiter`` overrides the number of restarts); returns the solution vector.
        ``what`` names the system and ``hint`` says what to change, in error messages."""
        rtol = self.rtol if rtol is None else rtol
        n = system.n
        if self.dense_for(n):
            return self._dense(system, what)
        self.used_gmres = True
        try:
            return self._fgmres(system, getattr(system, "precondition", None), guess, rtol, what, hint, of_b,
                                self.maxiter if maxiter is None else maxiter)
        except self.error:
            if n > self.dense_fallback:
                raise
        self.fallbacks += 1
        return self._dense(system, what)

    def _dense(self, system, what):
        """Dense LU on ``system``; the caller's error when it is singular."""
        try:
            return np.linalg.solve(system.dense(), system.b)
        except np.linalg.LinAlgError as exc:
            raise self.error(f"singular system ({what or f'{system.n} unknowns'}): {exc}") from exc

    def _fgmres(self, system, prec, guess, rtol, what, hint, of_b=False, maxiter=None):
        """:func:`fgmres` on the correction to ``guess`` (or from zero), the residual
        reduced by ``rtol`` (``of_b``: to ``rtol |b|``), in ``maxiter`` restarts (default
        the solver's)."""
        maxiter = self.maxiter if maxiter is None else maxiter
        n = system.n
        x0 = np.zeros(n) if guess is None else np.asarray(guess, float)
        residual = getattr(system, "residual", None)  # b - A x, when the system has it
        b = system.b if guess is None else residual(x0) if residual else system.b - system.matvec(x0)
        ref = b if self.correction and not of_b else system.b
        tol = max(rtol * float(np.linalg.norm(ref)), self.floor * float(np.linalg.norm(system.b)))
        if of_b:  # the reduction this asks of the guess's residual decides the precision
            rtol = min(1.0, tol / max(float(np.linalg.norm(b)), 1e-300))
        single = getattr(system, "matvec_single", None)
        inner = single if rtol >= self.single_from else None
        x = np.zeros(n)
        done = False
        if inner is None and single is not None and self.single_start:
            # iterative refinement: phases in single precision, each reducing the residual
            # left (recomputed in double) by at most single_start (a phase ends on its true
            # residual); in double from the residual left only if a phase fails
            while not done:
                goal = max(tol, self.single_start * float(np.linalg.norm(b)))
                dx, ok, its = fgmres(system.matvec, b, prec, tol=goal, restart=self.restart, maxiter=maxiter,
                                     inner=single, basis=np.float32)
                self.iterations += its
                if not ok:
                    break
                x += dx
                done = goal == tol
                if not done:
                    b = b - system.matvec(dx)
        if not done:
            dx, ok, its = fgmres(system.matvec, b, prec, tol=tol, restart=self.restart, maxiter=maxiter,
                                 inner=inner, basis=np.float64 if inner is None else np.float32)
            x += dx
            self.iterations += its
        if not ok or not np.isfinite(x).all():
            raise self.error(f"GMRES did not reduce the residual by {rtol:.1e} on {what or f'{n} unknowns'} "
                             f"in {its} iterations" + (f"; {hint}" if hint else ""))
        return x0 + x
