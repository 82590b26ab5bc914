"""Surface compliance of the plane-strain rolling layer, normal and tangential, condensed
from the moving-frame FEM (:mod:`fem_reference.rolling.plane_strain`).

The layer is the steady-rolling section of :func:`~fem_reference.rolling.plane_strain.
system.build_rolling_system`: the frame of the cylinder, the material flowing at -V
along x, a Prony (or elastic) layer bonded at z = 0, its top z = H. On the candidate
zone |x| <= Z of the top surface the surface tractions are P1 fields t_x = sum_j
lam_x,j phi_j and t_z = sum_j lam_z,j phi_j (Pa, on the layer, along +x and +z), and the
displacements are read as hat-weighted averages u_a,i = int phi_i u_a dx / m_i (m),
m_i = int phi_i dx (m). With the mortar couplings C_x, C_z (rows int phi_i u_a dx) of
the free FEM unknowns and the factorized system S (one factorization, one solve per
column)

    K = [C_x; C_z] S^-1 [C_x; C_z]^T          (m^2 per Pa: weighted displacement per
                                               traction coefficient)

and with the lumped nodal line loads F_a,j = m_j lam_a,j (N/m, per unit length along y)

    [u_x; u_z] = C [F_x; F_z],   C = M^-1 K M^-1,   M = diag(m, m)    (m per N/m).

Unit line loads at node j are the tractions 1 / m_j on its hat. Nodes are ordered by
increasing x; the unknowns [F_x (n), F_z (n)], the displacements [u_x (n), u_z (n)].
The normal block C_zz is the FEM's own frictionless compliance W = C_z S^-1 C_z^T
(:func:`fem_reference.rolling.solve.compliance`) as M^-1 W M^-1.

Two identities (docs/derivations.md, "Frictional steady rolling on the FEM layer"):

- reciprocity: at V = 0 the elastic layer's S is symmetric, so C = C^T;
- reversal: at fixed frequency the viscoelastic layer is reciprocal, C_ab(k, omega) =
  C_ba(-k, omega); the moving frame evaluates mode k at omega = -k V, so C_ab(k; V) =
  C_ba(-k; -V), i.e. C(V) = C(-V)^T. The layer is its own mirror image x -> -x, which
  maps C(-V) to P C(V) P (P reverses the node order and the sign of the x components):
  C(V) = P C(V)^T P, testable at one speed. The truncated section is not its own mirror
  image (its inflow and outflow lengths differ) and the viscous strains are transported
  by a stabilized scheme, so the discrete identity holds to the truncation and
  discretization error (:meth:`SurfaceCompliance.reversal_defect`).

SI units: m, N/m, Pa, m/s.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm, ElementTriP1

from ..errors import InputError
from ..linsolve import DirectSolver
from ..problem import ContactProblem
from ..rolling.assembly import multiplier_coupling
from ..rolling.plane_strain.discretization import resolve_plane
from ..rolling.plane_strain.system import StripSystem, build_rolling_system
from ..rolling.solve import ORDERINGS

__all__ = ["SurfaceCompliance", "surface_compliance", "check_plane_strain"]

#: right-hand sides per block of the compliance solves
BLOCK = 64


@BilinearForm
def _coupling_x(u, mu, w):
    """mu u_x on the top surface."""
    return mu * u[0]


def check_plane_strain(problem: ContactProblem) -> None:
    """Raise :class:`~fem_reference.errors.InputError` unless ``problem`` is a line
    contact in the plane-strain model: the frictional FEM model is plane strain only."""
    if problem.fem.model != "plane_strain" or problem.indenter.shape != "line":
        raise InputError(
            f"fem.model = {problem.fem.model!r} with indenter.shape = {problem.indenter.shape!r}: the "
            "frictional FEM reference (fem_reference.frictional) solves a line contact in plane strain "
            "only (fem.model = \"plane_strain\", indenter.shape = \"line\"); 3D frictional rolling is "
            "solved by bem")


class CompliancePairs:
    """The two identities a condensed compliance ``matrix`` is checked by, given its
    :meth:`mirror` (the image x -> -x of its nodes and components)."""

    def reversal_defect(self) -> float:
        """||C - P C^T P|| / ||C|| (Frobenius, -): 0 for the exact layer in the moving frame
        (module docstring)."""
        P = self.mirror()
        C = self.matrix
        return float(np.linalg.norm(C - P @ C.T @ P) / np.linalg.norm(C))

    def asymmetry(self) -> float:
        """||C - C^T|| / ||C|| (Frobenius, -): 0 for an elastic layer at V = 0."""
        C = self.matrix
        return float(np.linalg.norm(C - C.T) / np.linalg.norm(C))


@dataclass
class SurfaceCompliance(CompliancePairs):
    """Condensed surface compliance of the rolling layer (module docstring).

    Attributes
    ----------
    x : ndarray (n,)
        Candidate nodes (m, increasing).
    weights : ndarray (n,)
        m_i = int phi_i dx (m).
    matrix : ndarray (2n, 2n)
        C (m per N/m): [u_x; u_z] = C [F_x; F_z], loads on the layer along +x and +z.
    speed : float
        V (m/s).
    system, solver :
        The assembled FEM section (:class:`~fem_reference.rolling.plane_strain.system.
        StripSystem`) and its factorization (:class:`~fem_reference.linsolve.DirectSolver`).
    Cx, Cz : sparse matrix (n, free unknowns)
        The mortar couplings int phi_i u_x dx, int phi_i u_z dx (m).
    times : dict
        Seconds spent: mesh, assembly, factorization, compliance.
    """

    x: np.ndarray
    weights: np.ndarray
    matrix: np.ndarray
    speed: float
    system: StripSystem
    solver: DirectSolver
    Cx: sp.spmatrix
    Cz: sp.spmatrix
    times: dict

    @property
    def n(self) -> int:
        return len(self.x)

    def block(self, a: str, b: str) -> np.ndarray:
        """C_ab (m per N/m): displacement component ``a`` under load component ``b``
        ("x" or "z")."""
        n, i, j = self.n, "xz".index(a), "xz".index(b)
        return self.matrix[i * n:(i + 1) * n, j * n:(j + 1) * n]

    def mirror(self) -> np.ndarray:
        """P (2n, 2n): reverses the node order and the sign of the x components (the
        mirror image x -> -x of the zone's nodes, which are symmetric about x = 0)."""
        n = self.n
        if not np.allclose(self.x, -self.x[::-1], rtol=0, atol=1e-9 * np.ptp(self.x)):
            raise ValueError("the candidate nodes are not symmetric about x = 0: no mirror image")
        rev = np.eye(n)[::-1]
        return np.block([[-rev, np.zeros((n, n))], [np.zeros((n, n)), rev]])

    def fields(self, Fx: np.ndarray, Fz: np.ndarray):
        """(u, p, w) of :meth:`StripSystem.split` under the nodal line loads ``Fx``,
        ``Fz`` (N/m, on the layer along +x, +z): one more solve."""
        rhs = self.Cx.T @ (Fx / self.weights) + self.Cz.T @ (Fz / self.weights)
        return self.system.split(self.solver.solve(rhs))

    def dissipation(self, Fx: np.ndarray, Fz: np.ndarray) -> float:
        """Power dissipated by the dashpots (W/m) under the loads ``Fx``, ``Fz`` (N/m),
        from the FEM fields (:meth:`StripSystem.dissipation`); 0 for an elastic layer."""
        if not self.system.branches:
            return 0.0
        u, _, w = self.fields(Fx, Fz)
        return self.system.dissipation(u, w, self.speed)


def surface_compliance(problem: ContactProblem,
                       progress: Optional[Callable[[str], None]] = None) -> SurfaceCompliance:
    """Mesh, assemble and factorize the plane-strain rolling layer of ``problem`` once and
    condense its surface compliance on the candidate zone (module docstring); the mesh
    and the zone are those of the frictionless FEM solve (``[fem]`` settings).

    Raises
    ------
    InputError
        Not a plane-strain line contact (``fem.model``), or the sizes of ``[fem]``.
    LinearSolverError
        The factorization failed.
    """
    say = progress or (lambda _: None)
    check_plane_strain(problem)
    t0 = time.perf_counter()
    disc = resolve_plane(problem)
    system = build_rolling_system(problem, disc)
    ue = system.ubasis.elem
    Cx, _, nodes = multiplier_coupling(system.mesh, ue, ElementTriP1(), _coupling_x, system.free,
                                       system.offsets[-1], system.ubasis.N)
    order = np.argsort(system.mesh.p[0, nodes], kind="stable")
    Cx = Cx[order]
    if not np.allclose(system.mesh.p[0, nodes[order]], system.nodes, rtol=0, atol=1e-12 * disc.contact_zone):
        raise AssertionError("the x and z couplings disagree on the candidate nodes")
    Cz = system.C
    t1 = time.perf_counter()
    solver = DirectSolver(system.S, system.scale, orderings=ORDERINGS)
    say(f"frictional compliance: {system.n_unknowns} unknowns factorized in {solver.setup_time:.1f} s, "
        f"{2 * len(system.nodes)} columns")
    t2 = time.perf_counter()
    Cb = sp.vstack([Cx, Cz]).tocsr()
    n2 = Cb.shape[0]
    K = np.empty((n2, n2))
    for start in range(0, n2, BLOCK):
        stop = min(start + BLOCK, n2)
        rhs = Cb[start:stop].T.toarray()
        x = solver._apply(rhs)  # one solve per column; refined only where the residual asks for it
        rel = np.linalg.norm(rhs - system.S @ x, axis=0) / np.linalg.norm(rhs, axis=0)
        if rel.max() > 1e-10:
            x = solver.solve(rhs)
        K[:, start:stop] = Cb @ x
    m = np.asarray(system.m, float)
    mm = np.concatenate([m, m])
    C = K / mm[:, None] / mm[None, :]
    t3 = time.perf_counter()
    times = {"mesh": system.mesh_time, "assembly": t1 - t0 - system.mesh_time, "factorization": t2 - t1,
             "compliance": t3 - t2}
    return SurfaceCompliance(x=np.asarray(system.nodes, float), weights=m, matrix=C,
                             speed=problem.loading.speed, system=system, solver=solver, Cx=Cx, Cz=Cz,
                             times=times)
