"""Surface compliance of the 3D rolling half layer, normal and tangential, condensed from
the moving-frame FEM (:mod:`fem_reference.rolling.three_d`).

The layer is the steady-rolling half box of :func:`~fem_reference.rolling.three_d.system.
build_box_system`: the frame of the sphere, the material flowing at -V along x, bonded at
z = 0, its top z = H, meshed on y >= 0 with the symmetry plane y = 0 (u_y = 0 there, and
the viscous strains odd in y vanish). On the candidate half disk of the top surface the
tractions are P1 fields t_a = sum_j lam_a,j phi_j (Pa, on the layer along +a, a = x, y,
z) and the displacements are read as hat averages u_a,i = int phi_i u_a dS / m_i (m), m_i
= int phi_i dS (m^2, over y >= 0). With the mortar rows C_a (int phi_i u_a dS) of the free
FEM unknowns and the factorized system S (one factorization, 3n right-hand sides)

    K = [C_x; C_y; C_z] S^-1 [C_x; C_y; C_z]^T,   C = M^-1 K M^-1,   M = diag(m, m, m)

and [u_x; u_y; u_z] = C [F_x; F_y; F_z] (m per N) with the nodal forces F_a,j = m_j
lam_a,j (N, on the half layer).

**The symmetry plane.** The half layer is the restriction to y >= 0 of a layer whose
loads are mirror pairs: a force (F_x, F_y, F_z) at a node (x, y > 0) stands for itself
and (F_x, -F_y, F_z) at (x, -y), so the normal load and S_x are even in y and S_y odd,
as in the sphere's symmetric problem. A node on y = 0 has the half hat of y >= 0 (m_i is
half the full hat's area): its force is half the whole layer's force there, and its S_y
is 0 (a P1 traction odd in y vanishes on y = 0; the solver fixes it and drops that node's
w_y, which is 0 by symmetry: the matrix keeps the hat averages of u_y there, which are
not values of the odd field). Sums over the half count both halves twice, the nodes on
y = 0 once (their forces are halves already): totals = 2 x sums.

Two identities (docs/derivations.md section 12, in 3D):

- reciprocity: on an elastic layer S is symmetric at any speed (the inertia term rho V^2
  du/dx . dv/dx is symmetric), so C = C^T;
- reversal: C(V) = P C(V)^T P, P the mirror x -> -x of the zone's nodes (the mesh is its
  own mirror image) with the sign of the x components reversed; the viscous layer obeys it
  to the discretization error of the transport (:meth:`SurfaceCompliance3D.reversal_defect`).

SI units: m, N, Pa, m/s.
"""

from __future__ import annotations

import resource
import time
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm, ElementTetP1, asm

from ..errors import InputError
from ..linsolve import PardisoSolver, pardiso_available
from ..problem import ContactProblem
from ..rolling import solve as rolling_solve
from ..rolling.assembly import multiplier_coupling
from ..rolling.forms import weighted
from ..rolling.three_d.discretization import resolve_box
from ..rolling.three_d.system import BoxSystem, build_box_system
from .compliance import CompliancePairs

__all__ = ["SurfaceCompliance3D", "surface_compliance_3d", "check_sphere"]

#: right-hand sides per block of the compliance solves
BLOCK = 256


@BilinearForm
def _coupling_x(u, mu, w):
    """mu u_x on the top surface."""
    return mu * u[0]


@BilinearForm
def _coupling_y(u, mu, w):
    """mu u_y on the top surface."""
    return mu * u[1]


def check_sphere(problem: ContactProblem) -> None:
    """Raise :class:`~fem_reference.errors.InputError` unless ``problem`` is a rolling
    sphere in the 3D model (``fem.model = "3d"``, ``indenter.shape = "sphere"``, speed >
    0): the 3D frictional reference solves the sphere only."""
    if problem.fem.model != "3d" or problem.indenter.shape != "sphere" or not problem.loading.speed > 0:
        raise InputError(
            f"fem.model = {problem.fem.model!r} with indenter.shape = {problem.indenter.shape!r} and "
            f"loading.speed = {problem.loading.speed!r} m/s: the 3D frictional FEM reference "
            "(fem_reference.frictional.three_d) solves a rolling sphere only (fem.model = \"3d\", "
            "indenter.shape = \"sphere\", loading.speed > 0)")


@dataclass
class SurfaceCompliance3D(CompliancePairs):
    """Condensed surface compliance of the half layer (module docstring).

    Attributes
    ----------
    xy : ndarray (n, 2)
        Candidate nodes (x, y) (m), y >= 0.
    weights : ndarray (n,)
        m_i = int phi_i dS over y >= 0 (m^2).
    on_plane : ndarray (n,) of bool
        Nodes on the symmetry plane y = 0 (S_y = 0 there, module docstring).
    triangles : ndarray (3, n_t)
        The zone's surface triangles as node indices (into ``xy``).
    matrix : ndarray (3n, 3n)
        C (m per N): [u_x; u_y; u_z] = C [F_x; F_y; F_z], forces on the half layer along
        +x, +y, +z.
    speed : float
        V (m/s).
    system, solver :
        The assembled half box and its factorization (full solves).
    coupling : sparse matrix (3n, free unknowns)
        [C_x; C_y; C_z] (m^2).
    times : dict
        Seconds: mesh, assembly, factorization, compliance.
    peak_memory : float
        Peak resident memory of the process (bytes) after the compliance.
    facet_basis, vertices :
        The multiplier's facet basis on the zone and the candidate nodes' mesh vertices
        (for :meth:`hat_average`).
    """

    xy: np.ndarray
    weights: np.ndarray
    on_plane: np.ndarray
    triangles: np.ndarray
    matrix: np.ndarray
    speed: float
    system: BoxSystem
    solver: object
    coupling: sp.spmatrix
    times: dict
    peak_memory: float
    facet_basis: object = None
    vertices: np.ndarray = None

    @property
    def n(self) -> int:
        return len(self.weights)

    def block(self, a: str, b: str) -> np.ndarray:
        """C_ab (m per N): displacement ``a`` under force ``b`` ("x", "y" or "z")."""
        n, i, j = self.n, "xyz".index(a), "xyz".index(b)
        return self.matrix[i * n:(i + 1) * n, j * n:(j + 1) * n]

    def hat_average(self, f: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> np.ndarray:
        """int phi_i f dS / m_i at the candidate nodes of a function f(x, y) (x, y in m;
        the zone's quadrature, exact for the polynomials of the small-slope geometry)."""
        xq = np.asarray(self.facet_basis.global_coordinates())
        return np.asarray(asm(weighted, self.facet_basis, f=f(xq[0], xq[1])))[self.vertices] / self.weights

    def mirror(self) -> np.ndarray:
        """P (3n, 3n): the node permutation x -> -x with the x components' sign reversed."""
        x, y = self.xy[:, 0], self.xy[:, 1]
        scale = np.ptp(x)
        key = np.round(np.column_stack([x, y]) / (1e-7 * scale)).astype(np.int64)
        index = {tuple(k): i for i, k in enumerate(key)}
        try:
            perm = np.array([index[(-k[0], k[1])] for k in key])
        except KeyError:
            raise ValueError("the candidate nodes are not symmetric about x = 0: no mirror image") from None
        n = self.n
        Pn = np.zeros((n, n))
        Pn[np.arange(n), perm] = 1.0
        Z = np.zeros((n, n))
        return np.block([[-Pn, Z, Z], [Z, Pn, Z], [Z, Z, Pn]])

    def fields(self, F: np.ndarray):
        """(u, p, w) of :meth:`BoxSystem.split` under the nodal forces ``F`` = [F_x; F_y;
        F_z] (N, on the half layer): one more solve."""
        m3 = np.tile(self.weights, 3)
        return self.system.split(self.solver.solve(self.coupling.T @ (F / m3)))

    def release(self) -> None:
        """Free the factorization (Pardiso's factors live outside Python); the matrix stays,
        :meth:`fields` and :meth:`dissipation` no longer work."""
        if hasattr(self.solver, "free"):
            self.solver.free()
        self.solver = None

    def dissipation(self, F: np.ndarray) -> float:
        """Power dissipated by the dashpots of the whole layer (W, twice the half's) under
        the nodal forces ``F`` (N); 0 for an elastic layer."""
        if not self.system.branches:
            return 0.0
        u, _, w = self.fields(F)
        return 2.0 * self.system.dissipation(u, w, self.speed)


def surface_compliance_3d(problem: ContactProblem,
                          progress: Optional[Callable[[str], None]] = None) -> SurfaceCompliance3D:
    """Mesh, assemble and factorize the half layer of ``problem`` once and condense its
    surface compliance on the candidate half disk (module docstring); the mesh and the
    zone are those of the frictionless 3D solve (``[fem]`` settings).

    The compliance columns are full solves, iteratively refined to a relative residual of
    1e-10 (MKL Pardiso with weighted matching; SuperLU without pypardiso): Pardiso's
    partial solve, without matching or refinement, errs by ~3e-4 in these columns
    (measured), more than the identities tested here.

    Raises
    ------
    InputError
        Not a rolling sphere in the 3D model, or the sizes of ``[fem]``.
    LinearSolverError
        The factorization failed.
    """
    say = progress or (lambda _: None)
    check_sphere(problem)
    t0 = time.perf_counter()
    disc = resolve_box(problem)
    system = build_box_system(problem, disc)
    ue, mesh = system.ubasis.elem, system.mesh
    n_total, n_u = system.offsets[-1], system.ubasis.N
    Cx, fbl, nx = multiplier_coupling(mesh, ue, ElementTetP1(), _coupling_x, system.free, n_total, n_u)
    Cy, _, ny = multiplier_coupling(mesh, ue, ElementTetP1(), _coupling_y, system.free, n_total, n_u)
    nodes = np.unique(mesh.facets[:, mesh.boundaries["zone"]])
    if not (np.array_equal(nx, nodes) and np.array_equal(ny, nodes)):
        raise AssertionError("the x, y and z couplings disagree on the candidate nodes")
    Cb = sp.vstack([Cx, Cy, system.C]).tocsr()
    local = np.full(mesh.p.shape[1], -1)
    local[nodes] = np.arange(len(nodes))
    tri = local[mesh.facets[:, mesh.boundaries["zone"]]]
    xy = np.asarray(system.nodes, float)
    on_plane = np.abs(xy[:, 1]) <= 1e-9 * disc.contact_zone
    t1 = time.perf_counter()
    if rolling_solve.LINEAR_SOLVER != "superlu" and pardiso_available():
        solver = PardisoSolver(system.S, system.scale)  # full solves, refined to 1e-10
    else:
        solver = rolling_solve._factorize(system, "3d", say)
    n3 = Cb.shape[0]
    say(f"3d frictional compliance: {system.n_unknowns} unknowns factorized in {solver.setup_time:.1f} s, "
        f"{n3} columns")
    t2 = time.perf_counter()
    K = np.empty((n3, n3))
    for start in range(0, n3, BLOCK):
        stop = min(start + BLOCK, n3)
        rhs = Cb[start:stop].T.toarray()
        x = solver._apply(rhs)  # refined only where the residual asks for it
        rel = np.linalg.norm(rhs - system.S @ x, axis=0) / np.linalg.norm(rhs, axis=0)
        if rel.max() > 1e-10:
            x = solver.solve(rhs)
        K[:, start:stop] = Cb @ x
        say(f"3d frictional compliance: {stop}/{n3} columns")
    m = np.asarray(system.m, float)
    m3 = np.tile(m, 3)
    C = K / m3[:, None] / m3[None, :]
    t3 = time.perf_counter()
    times = {"mesh": system.mesh_time, "assembly": t1 - t0 - system.mesh_time, "factorization": t2 - t1,
             "compliance": t3 - t2}
    return SurfaceCompliance3D(xy=xy, weights=m, on_plane=on_plane, triangles=tri, matrix=C,
                               speed=problem.loading.speed, system=system, solver=solver, coupling=Cb,
                               times=times, facet_basis=fbl, vertices=nodes,
                               peak_memory=1024.0 * resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
