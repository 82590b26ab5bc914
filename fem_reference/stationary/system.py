"""Taylor-Hood (P2-P1) discretization of the stationary layer and its contact coupling.

:func:`build_system` meshes the layer (axisymmetric section or quarter cylinder),
assembles the saddle matrix [[A, -B^T], [-B, 0]] (see :mod:`.forms`), removes the
Dirichlet unknowns (u = 0 on the base; u_r = 0 on the axis; u_x = 0 on x = 0 and
u_y = 0 on y = 0 in 3D) and assembles, on the candidate zone of the top surface,
the mortar coupling C (n_c x unknowns) between the P1 contact multiplier and
u_z, with m = int phi dS (m^2) and q = int phi s dS (m^3).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import (Basis, ElementTetP1, ElementTetP2, ElementTriP1, ElementTriP2,
                   ElementVector, FacetBasis, asm, bmat)

from ..mesh.axisymmetric_section import axisymmetric_mesh
from ..mesh.quarter_cylinder import quarter_cylinder_mesh
from ..problem import ContactProblem
from . import forms
from .discretization import Discretization

__all__ = ["LayerSystem", "build_system"]


@dataclass
class LayerSystem:
    """Assembled discrete layer.

    Attributes
    ----------
    mesh, ubasis, pbasis :
        scikit-fem mesh and bases (P2 vector displacement, P1 pressure).
    S : sparse matrix
        Condensed saddle matrix on the free unknowns.
    free : ndarray
        Indices of the free unknowns in the full vector [u; p].
    C : sparse matrix (n_c, len(free))
        Coupling of the multiplier nodes with the free unknowns.
    m, q : ndarray (n_c,)
        int phi dS (m^2) and int phi s dS (m^3).
    nodes : ndarray (n_c, dim - 1)
        Surface coordinates of the multiplier nodes (m): r, or (x, y).
    radius : ndarray (n_c,)
        Distance of each multiplier node from the axis (m).
    symmetry : float
        Number of copies of the model that make the full layer (1 or 4).
    Mp : sparse matrix
        Pressure mass matrix (m^3) on the pressure unknowns.
    near_null : ndarray
        Rigid-body modes restricted to the free displacement unknowns.
    scale : ndarray
        Diagonal scale of the free unknowns (displacement diagonal of S, lumped
        M_p / (2 G)) for the direct solver.
    """

    mesh: object
    ubasis: object
    pbasis: object
    S: sp.spmatrix
    free: np.ndarray
    n_u_free: int
    C: sp.spmatrix
    m: np.ndarray
    q: np.ndarray
    nodes: np.ndarray
    radius: np.ndarray
    symmetry: float
    Mp: sp.spmatrix
    near_null: np.ndarray
    scale: np.ndarray
    assembly_time: float
    mesh_time: float

    @property
    def n_unknowns(self) -> int:
        return len(self.free)


def _components(ubasis, dim):
    """Component index of every displacement DOF."""
    comp = np.full(ubasis.N, -1)
    for attr in ("nodal_dofs", "facet_dofs", "edge_dofs", "interior_dofs"):
        arr = getattr(ubasis, attr, None)
        if arr is None or arr.size == 0:
            continue
        if arr.shape[0] % dim:
            raise RuntimeError(f"unexpected {attr} layout {arr.shape}")
        per = arr.shape[0] // dim
        for k in range(arr.shape[0]):
            comp[arr[k]] = k // per if per > 1 else k
    return comp


def build_system(problem: ContactProblem, disc: Discretization) -> LayerSystem:
    """Mesh and assemble the discrete layer of ``problem`` (module docstring)."""
    three_d = problem.fem.model == "3d"
    H = problem.layer.thickness
    t0 = time.perf_counter()
    mesh = quarter_cylinder_mesh(H, disc) if three_d else axisymmetric_mesh(H, disc)
    if disc.refine:
        mesh = mesh.refined(disc.refine)
    t1 = time.perf_counter()
    if three_d:
        dim = 3
        ue, pe, le = ElementVector(ElementTetP2()), ElementTetP1(), ElementTetP1()
        f = dict(A=forms.stiffness_3d, B=forms.divergence_3d, C=forms.coupling_3d,
                 m=forms.area_3d, q=forms.profile_3d)
    else:
        dim = 2
        ue, pe, le = ElementVector(ElementTriP2()), ElementTriP1(), ElementTriP1()
        f = dict(A=forms.axi_stiffness, B=forms.axi_divergence, C=forms.axi_coupling,
                 m=forms.axi_area, q=forms.axi_profile)
    ub = Basis(mesh, ue, intorder=4)
    pb = Basis(mesh, pe, intorder=4)
    G = problem.material.shear_modulus
    A = asm(f["A"], ub, G=G)
    B = asm(f["B"], ub, pb)
    S_full = bmat([[A, -B.T], [-B, None]], "csr")
    comp = _components(ub, dim)
    if np.any(comp < 0):
        raise RuntimeError("could not tell the displacement components apart")
    fixed = [ub.get_dofs("base").all()]
    if three_d:
        fixed += [np.intersect1d(ub.get_dofs("sym_x").all(), np.flatnonzero(comp == 0)),
                  np.intersect1d(ub.get_dofs("sym_y").all(), np.flatnonzero(comp == 1))]
    else:
        fixed += [np.intersect1d(ub.get_dofs("axis").all(), np.flatnonzero(comp == 0))]
    fixed = np.unique(np.concatenate(fixed))
    free_u = np.setdiff1d(np.arange(ub.N), fixed)
    free = np.concatenate([free_u, ub.N + np.arange(pb.N)])
    S = S_full[free][:, free].tocsr()

    zone = mesh.boundaries["zone"]
    fbu = FacetBasis(mesh, ue, facets=zone, intorder=6)
    fbl = FacetBasis(mesh, le, facets=zone, intorder=6)
    lam_nodes = np.unique(mesh.facets[:, zone])
    Cu = asm(f["C"], fbu, fbl).tocsr()[lam_nodes]
    Cfull = sp.hstack([Cu, sp.csr_matrix((len(lam_nodes), pb.N))]).tocsr()
    C = Cfull[:, free].tocsr()
    m = asm(f["m"], fbl)[lam_nodes]
    xq = np.asarray(fbl.global_coordinates())
    s_q = problem.indenter.profile(np.sqrt(np.sum(xq[:dim - 1] ** 2, axis=0)))
    q = asm(f["q"], fbl, s=s_q)[lam_nodes]
    xy = mesh.p[:dim - 1, lam_nodes].T
    radius = np.sqrt(np.sum(xy ** 2, axis=1))
    order = np.argsort(radius, kind="stable")
    C, m, q, xy, radius = C[order], m[order], q[order], xy[order], radius[order]

    Mp = asm(forms.pressure_mass, pb)
    X = ub.doflocs
    if three_d:
        x, y, z = X
        modes = [comp == 0, comp == 1, comp == 2,
                 np.where(comp == 0, -y, np.where(comp == 1, x, 0.0)),
                 np.where(comp == 1, -z, np.where(comp == 2, y, 0.0)),
                 np.where(comp == 2, x, np.where(comp == 0, -z, 0.0))]
    else:
        modes = [comp == 0, comp == 1]
    near_null = np.column_stack([np.asarray(v, float) for v in modes])[free_u]
    scale = np.concatenate([np.abs(S.diagonal()[:len(free_u)]),
                            np.asarray(Mp.sum(axis=1)).ravel() / (2.0 * G)])
    t2 = time.perf_counter()
    return LayerSystem(mesh=mesh, ubasis=ub, pbasis=pb, S=S, free=free, n_u_free=len(free_u),
                       C=C, m=np.asarray(m), q=np.asarray(q), nodes=xy, radius=radius,
                       symmetry=4.0 if three_d else 1.0, Mp=Mp, near_null=near_null, scale=scale,
                       assembly_time=t2 - t1, mesh_time=t1 - t0)
