"""Linear solvers of the (condensed) displacement-pressure saddle system.

:class:`DirectSolver` factorizes once with SuperLU (fill-reducing ordering of
A^T + A, partial pivoting: the zero pressure block needs it). :class:`MinresSolver`
runs MINRES preconditioned by blockdiag(AMG(A_uu), M_p / (2 G)): smoothed
aggregation (pyamg, rigid-body near-null space) on the displacement block, and the
pressure mass matrix, spectrally equivalent to the Schur complement
B A_uu^-1 B^T of an incompressible solid, on the pressure block. pyamg is optional
(``pip install 'viscolayer[minres]'``); without it :class:`MinresSolver` raises
:class:`~fem_reference.errors.MissingDependencyError`.
"""

from __future__ import annotations

import time
from typing import Optional

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ._deps import import_pyamg
from .errors import LinearSolverError

__all__ = ["DirectSolver", "MinresSolver", "PardisoSolver", "pardiso_available", "sparse_lu"]


class DirectSolver:
    """Sparse LU of the saddle matrix ``S``, symmetrically scaled by ``scale``.

    The unknowns (m and Pa) differ by many orders of magnitude, so the matrix is
    factorized as D S D with D = diag(scale)^-1/2 (``scale``: the displacement
    diagonal of S and the lumped M_p / (2 G)). The first attempt keeps the
    symmetric minimum-degree ordering (no pivoting: least fill); if it breaks
    down or is inaccurate, SuperLU runs again with COLAMD and partial pivoting.
    Each solve does one step of iterative refinement and checks its residual.
    ``orderings``: the (permc_spec, diag_pivot_thresh) pairs tried in turn; the
    non-symmetric rolling system goes straight to COLAMD with threshold pivoting.
    """

    name = "direct"

    ORDERINGS = (("MMD_AT_PLUS_A", 0.0), ("COLAMD", 1.0))

    def __init__(self, S: sp.spmatrix, scale: np.ndarray, orderings=ORDERINGS):
        t0 = time.perf_counter()
        self.S = S.tocsr()
        self.D = 1.0 / np.sqrt(scale)
        Dm = sp.diags(self.D)
        Ss = (Dm @ self.S @ Dm).tocsc()
        probe = np.random.default_rng(0).standard_normal(Ss.shape[0])
        self.lu = None
        for perm, thresh in orderings:
            try:
                lu = spla.splu(Ss, permc_spec=perm, diag_pivot_thresh=thresh,
                               options=dict(SymmetricMode=thresh == 0.0))
            except RuntimeError:
                continue
            x = lu.solve(probe)
            if np.all(np.isfinite(x)) and \
                    np.linalg.norm(Ss @ x - probe) <= 1e-8 * np.linalg.norm(probe):
                self.lu = lu
                break
        if self.lu is None:
            raise LinearSolverError("SuperLU failed to factorize the saddle system "
                                    "(singular or too ill-conditioned)")
        self.setup_time = time.perf_counter() - t0
        self.iterations = 0
        self.max_residual = 0.0
        self.fill = self.lu.L.nnz + self.lu.U.nnz

    def _apply(self, b):
        if b.ndim == 1:
            return self.D * self.lu.solve(self.D * b)
        # column by column: SuperLU's multi-right-hand-side solve is far slower
        return np.column_stack([self._apply(b[:, k]) for k in range(b.shape[1])])

    def solve(self, b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=float)
        x = self._apply(b)
        x += self._apply(b - self.S @ x)
        r = b - self.S @ x
        rel = np.linalg.norm(r, axis=0) / np.maximum(np.linalg.norm(b, axis=0), 1e-300)
        rel = float(np.max(rel))
        self.max_residual = max(self.max_residual, rel)
        if not np.all(np.isfinite(x)) or rel > 1e-8:
            raise LinearSolverError(f"SuperLU solve has relative residual {rel:.2e} (> 1e-8)")
        return x


class MinresSolver:
    """Block-preconditioned MINRES for [[A, -B^T], [-B, 0]] (first ``n_u`` unknowns
    displacements, then pressures).

    Parameters
    ----------
    S : sparse matrix
        Condensed saddle matrix.
    n_u : int
        Number of displacement unknowns (they come first).
    Mp : sparse matrix
        Pressure mass matrix (m^3) of the pressure unknowns.
    G : float
        Shear modulus (Pa).
    scale : ndarray
        Diagonal scale of the unknowns (see :class:`DirectSolver`); MINRES runs on
        the scaled system.
    near_null : ndarray (n_u, k), optional
        Near-null space (rigid-body modes) for the aggregation AMG.
    rtol : float
        Relative residual tolerance (-).

    Raises
    ------
    MissingDependencyError
        If pyamg is not installed.
    """

    name = "minres"

    def __init__(self, S, n_u: int, Mp, G: float, scale: np.ndarray,
                 near_null: Optional[np.ndarray] = None, rtol: float = 1e-10,
                 maxiter: int = 5000):
        pyamg = import_pyamg()
        t0 = time.perf_counter()
        self.D = 1.0 / np.sqrt(scale)  # same symmetric scaling as DirectSolver
        Dm = sp.diags(self.D)
        self.S0 = S.tocsr()
        self.S = (Dm @ self.S0 @ Dm).tocsr()
        self.n_u = n_u
        Auu = self.S[:n_u, :n_u].tocsr()
        if near_null is not None:
            near_null = near_null / self.D[:n_u, None]
        self.amg = pyamg.smoothed_aggregation_solver(Auu, B=near_null, symmetry="symmetric",
                                                     max_coarse=500)
        self.amg_op = self.amg.aspreconditioner(cycle="V")
        Dp = sp.diags(self.D[n_u:])
        self.mp = spla.splu((Dp @ sp.csc_matrix(Mp) @ Dp / (2.0 * G)).tocsc())
        n = S.shape[0]

        def apply(x):
            y = np.empty_like(x)
            y[:n_u] = self.amg_op @ x[:n_u]
            y[n_u:] = self.mp.solve(x[n_u:])
            return y

        self.prec = spla.LinearOperator((n, n), matvec=apply, dtype=float)
        self.rtol = rtol
        self.maxiter = maxiter
        self.setup_time = time.perf_counter() - t0
        self.iterations = 0
        self.max_residual = 0.0
        self.fill = 0

    ROUNDS = 6  # refinement rounds on the true residual

    def _solve1(self, b):
        """MINRES stops on the preconditioned residual, which can sit far below the true
        one (measured 1.9e-5 true at rtol 1e-8 on an axisymmetric case); so solve again
        for the true residual's correction until it meets ``rtol`` (iterative
        refinement, a few rounds). A true residual still above ``10 rtol`` raises
        :class:`LinearSolverError`: the contact would follow the error (measured on a
        sphere on a layer: a residual of 1e-2 moved the peak pressure by 2 %)."""
        count = [0]

        def cb(_):
            count[0] += 1

        norm_b = max(np.linalg.norm(b), 1e-300)
        x = np.zeros_like(b)
        r = b
        for _ in range(self.ROUNDS):
            xs, info = spla.minres(self.S, self.D * r, M=self.prec, rtol=self.rtol,
                                   maxiter=self.maxiter, callback=cb)
            x = x + self.D * xs
            r = b - self.S0 @ x
            rel = float(np.linalg.norm(r) / norm_b)
            if info != 0 or not np.isfinite(rel) or rel <= self.rtol:
                break
        self.iterations += count[0]
        self.max_residual = max(self.max_residual, rel)
        if info != 0 or not np.isfinite(rel) or rel > 10 * self.rtol:
            raise LinearSolverError(f"MINRES stopped with info={info} after {count[0]} iterations, "
                                    f"relative residual {rel:.2e} (rtol {self.rtol:.1e})")
        return x

    def solve(self, b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=float)
        if b.ndim == 1:
            return self._solve1(b)
        return np.column_stack([self._solve1(b[:, k]) for k in range(b.shape[1])])


class PardisoSolver:
    """Sparse LU of the non-symmetric matrix ``S`` by MKL Pardiso (``pypardiso``),
    scaled as in :class:`DirectSolver`; many right-hand sides go in one call.

    Pardiso's nested-dissection ordering and supernodal, multithreaded factorization
    fill far less than SuperLU's COLAMD on 3D Taylor-Hood systems (BENCHMARKS.md,
    "fem_reference steady rolling, 3D"). pypardiso is a dependency on x86_64 (MKL
    exists only there); :func:`sparse_lu` falls back to SuperLU without it.
    ``memory`` is Pardiso's own peak memory report (bytes).

    ``selected``: indices of the only unknowns where the right-hand sides are nonzero
    and the solution is wanted (Pardiso's partial solve, iparm[30] = 2): the forward and
    backward substitutions then touch only their paths in the elimination tree (a
    condensed compliance C S^-1 C^T at a fraction of the cost). It needs Pardiso's own
    parameters (scaling on, weighted matching and iterative refinement off, which would
    disable it); such a solver's :meth:`solve` returns only the ``selected`` entries
    (the others are zero) and does no refinement, until :meth:`full_solves` turns it
    into a full solver on the same factors.
    """

    name = "pardiso"

    def __init__(self, S: sp.spmatrix, scale: np.ndarray, selected: Optional[np.ndarray] = None):
        import ctypes

        import pypardiso

        t0 = time.perf_counter()
        self.S = S.tocsr()
        self.D = 1.0 / np.sqrt(scale)
        Dm = sp.diags(self.D)
        self.Ss = (Dm @ self.S @ Dm).tocsr()
        self.Ss.sort_indices()
        self.ps = pypardiso.PyPardisoSolver(mtype=11)
        self.partial = selected is not None
        if self.partial:
            ps = self.ps
            ps.libmkl.pardisoinit(ps.pt.ctypes.data_as(ctypes.POINTER(ps._pt_type[0])),
                                  ctypes.byref(ctypes.c_int32(11)),
                                  ps.iparm.ctypes.data_as(ctypes.POINTER(ctypes.c_int32)))
            ps.iparm[0] = 1    # the parameters below, not the defaults
            ps.iparm[7] = 0    # no iterative refinement (it needs the full solution)
            ps.iparm[10] = 1   # scaling
            ps.iparm[12] = 0   # no weighted matching (it disables the partial solve)
            ps.iparm[30] = 2   # sparse right-hand sides, selected solution entries
            ps.iparm[34] = 0   # one-based indices, as pypardiso passes them
            perm = np.zeros(self.S.shape[0], np.int32)
            perm[np.asarray(selected)] = 1
            ps.perm = perm
        try:
            self.ps.factorize(self.Ss)
        except Exception as exc:  # PyPardisoError
            raise LinearSolverError(f"Pardiso failed to factorize the system: {exc}") from exc
        ip = self.ps.iparm  # 0-based: 14 peak symbolic, 15 permanent, 16 numerical (KB)
        self.memory = 1024.0 * max(float(ip[14]), float(ip[15]) + float(ip[16]))
        self.fill = int(ip[17])
        self.setup_time = time.perf_counter() - t0
        self.iterations = 0
        self.max_residual = 0.0

    def _apply(self, b):
        x = self.ps.solve(self.Ss, np.asfortranarray((self.D * b.T).T if b.ndim == 2 else self.D * b))
        return (self.D * x.T).T if b.ndim == 2 else self.D * x

    #: steps of iterative refinement at most (the partial-solve factors, without weighted
    #: matching, leave 1e-3 relative residuals that three steps bring to 1e-14)
    REFINE = 4

    def solve(self, b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=float)
        x = self._apply(b)
        if self.partial:
            return x
        norm_b = np.maximum(np.linalg.norm(b, axis=0), 1e-300)
        for _ in range(self.REFINE):
            x += self._apply(b - self.S @ x)
            rel = float(np.max(np.linalg.norm(b - self.S @ x, axis=0) / norm_b))
            if not np.isfinite(rel) or rel <= 1e-10:
                break
        self.max_residual = max(self.max_residual, rel)
        if not np.all(np.isfinite(x)) or rel > 1e-8:
            raise LinearSolverError(f"Pardiso solve has relative residual {rel:.2e} (> 1e-8)")
        return x

    def full_solves(self) -> None:
        """Turn a partial-solve solver into a full one on the same factors: the whole
        solution, iteratively refined in :meth:`solve`."""
        self.ps.iparm[30] = 0
        self.partial = False

    def free(self) -> None:
        """Release Pardiso's factors."""
        self.ps.free_memory(everything=True)


def pardiso_available() -> bool:
    """True when pypardiso (MKL Pardiso) imports."""
    try:
        import pypardiso  # noqa: F401
    except ImportError:
        return False
    return True


def sparse_lu(S: sp.spmatrix, scale: np.ndarray, prefer: str = "auto",
              orderings=(("COLAMD", 0.1), ("COLAMD", 1.0))):
    """A factorized non-symmetric solver of ``S``: :class:`PardisoSolver` when ``prefer``
    is "auto" and pypardiso imports, else SuperLU (:class:`DirectSolver` with
    ``orderings``). ``prefer``: "auto", "pardiso" (raises
    :class:`~fem_reference.errors.MissingDependencyError` without it) or "superlu"."""
    if prefer in ("auto", "pardiso"):
        try:
            import pypardiso  # noqa: F401
        except ImportError:
            if prefer == "pardiso":
                from .errors import MissingDependencyError
                raise MissingDependencyError(
                    "the Pardiso solver needs pypardiso (a dependency on x86_64; pip install pypardiso), "
                    "or use the SuperLU fallback") from None
        else:
            return PardisoSolver(S, scale)
    return DirectSolver(S, scale, orderings=orderings)
