"""Monolithic discretization of steady rolling on a plane-strain layer.

:func:`build_rolling_system` meshes the section (:mod:`.mesh_plane`), assembles the
non-symmetric system of :mod:`.rolling_forms` on the unknowns [u (P2 vector), p
(P1), (a_i, c_i) per Maxwell branch (continuous P2 scalars, SUPG)], removes the
Dirichlet unknowns (u = 0 on the base, the inflow and the outflow; a_i = c_i = 0 on
the inflow: the material enters undeformed and relaxed) and assembles the mortar
coupling C of the P1 contact multiplier with u_z on the candidate zone, with the
multiplier moments m = int phi dx (m), q = int phi s dx (m^2), mx = int phi x dx
(m^2) and ms = int phi s'(x) dx (m). SI units, per unit length along y.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import List

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementTriP1, ElementTriP2, ElementVector, FacetBasis, asm, bmat

from . import rolling_forms as rf
from .materials import PronyMaterial, as_prony
from .mesh_plane import plane_mesh
from .plane_discretization import PlaneDiscretization
from .problem import ContactProblem

__all__ = ["RollingSystem", "assemble_blocks", "build_rolling_system", "profile", "slope",
           "element_hx", "restrict", "multiplier_coupling", "diagonal_scale"]

INTORDER = 4
#: polynomial order of the continuous viscous-strain fields (1 or 2)
STRAIN_ORDER = 1


def profile(x, R):
    """Height s(x) = R - sqrt(R^2 - x^2) (m) of the cylinder above its lowest point."""
    x = np.asarray(x, float)
    return x * x / (R + np.sqrt(R * R - x * x))


def slope(x, R):
    """s'(x) = x / sqrt(R^2 - x^2) (-)."""
    x = np.asarray(x, float)
    return x / np.sqrt(R * R - x * x)


@dataclass
class RollingSystem:
    """Assembled discrete rolling layer.

    Attributes
    ----------
    mesh, ubasis, pbasis, wbasis :
        skfem mesh and bases (P2 vector displacement, P1 pressure, P2 scalar strain).
    S : sparse matrix
        System matrix on the free unknowns (non-symmetric).
    free : ndarray
        Indices of the free unknowns in the full vector [u; p; a_1; c_1; ...].
    offsets : list of int
        Start of each block (u, p, then a_i, c_i per branch) in the full vector.
    C : sparse matrix (n_c, len(free))
        Coupling of the multiplier nodes with the free unknowns.
    m, q, mx, ms : ndarray (n_c,)
        int phi dx (m), int phi s dx (m^2), int phi x dx (m^2), int phi s' dx (m).
    nodes : ndarray (n_c,)
        x (m) of the multiplier nodes, increasing.
    branches : list of (G_i, tau_i)
        Maxwell branches (Pa, s).
    scale : ndarray
        Diagonal scale of the free unknowns for the direct solver.
    """

    mesh: object
    ubasis: object
    pbasis: object
    wbasis: object
    S: sp.spmatrix
    free: np.ndarray
    offsets: List[int]
    C: sp.spmatrix
    m: np.ndarray
    q: np.ndarray
    mx: np.ndarray
    ms: np.ndarray
    nodes: np.ndarray
    branches: list
    scale: np.ndarray
    mesh_time: float
    assembly_time: float

    @property
    def n_unknowns(self) -> int:
        return len(self.free)

    #: viscous-strain components per Maxwell branch (a and c in plane strain)
    COMPONENTS = 2

    def split(self, x_free: np.ndarray):
        """Full fields from a free-unknown vector: u (m), p (Pa) and, per branch, the
        tuple of its strain components ((a_i, c_i) in plane strain)."""
        full = np.zeros(self.offsets[-1])
        full[self.free] = x_free
        o, nc = self.offsets, self.COMPONENTS
        u, p = full[o[0]:o[1]], full[o[1]:o[2]]
        w = [tuple(full[o[2 + nc * b + k]:o[3 + nc * b + k]] for k in range(nc))
             for b in range(len(self.branches))]
        return u, p, w

    def dissipation(self, u: np.ndarray, w: list, V: float) -> float:
        """Power (W/m) dissipated by the dashpots: sum_i int s_i : D eps_v,i / Dt dA, the
        branch stress 2 G_i (eps - eps_v,i) times the dashpot strain rate -V d eps_v,i /
        dx, for the fields of :meth:`split` at the speed V (m/s); 0 without branches."""
        ub, wb = self.ubasis, self.wbasis
        total = 0.0
        uf = ub.interpolate(u)
        for (Gi, ti), (a, c) in zip(self.branches, w):
            total += rf.dashpot_power.assemble(wb, u=uf, a=wb.interpolate(a), c=wb.interpolate(c),
                                               G=Gi, tau=ti, V=V)
        return float(total)


def element_hx(mesh) -> np.ndarray:
    """Extent (m) of each element along x (the SUPG length scale)."""
    xs = mesh.p[0, mesh.t]
    return xs.max(axis=0) - xs.min(axis=0)


def restrict(S_full: sp.spmatrix, fixed: np.ndarray, n_total: int):
    """(S, free): the system on the unknowns not in ``fixed``, and their indices."""
    keep = np.ones(n_total, bool)
    keep[fixed] = False
    free = np.flatnonzero(keep)
    return S_full[free][:, free].tocsr(), free


def multiplier_coupling(mesh, ue, lam_element, coupling, free: np.ndarray, n_total: int, n_u: int):
    """(C, fbl, lam_nodes): the mortar coupling ``coupling`` of the P1 multiplier (element
    ``lam_element``) on the ``zone`` boundary with the free unknowns, its facet basis and
    its nodes (mesh vertices)."""
    zone = mesh.boundaries["zone"]
    fbu = FacetBasis(mesh, ue, facets=zone, intorder=6)
    fbl = FacetBasis(mesh, lam_element, facets=zone, intorder=6)
    lam_nodes = np.unique(mesh.facets[:, zone])
    Cu = asm(coupling, fbu, fbl).tocsr()[lam_nodes]
    Cfull = sp.hstack([Cu, sp.csr_matrix((len(lam_nodes), n_total - n_u))]).tocsr()
    return Cfull[:, free].tocsr(), fbl, lam_nodes


def diagonal_scale(S: sp.spmatrix, free: np.ndarray, offsets, pbasis, G: float) -> np.ndarray:
    """Diagonal scale of the free unknowns for the direct solver: |S_ii|, with the
    pressure rows' lumped mass / (2 G) in place of their zero diagonal."""
    Mp = asm(rf.pressure_mass, pbasis)
    diag = np.abs(S.diagonal())
    n_u_free = int(np.sum(free < offsets[1]))
    p_free = free[(free >= offsets[1]) & (free < offsets[2])] - offsets[1]
    diag[n_u_free:n_u_free + len(p_free)] = np.asarray(Mp.sum(axis=1)).ravel()[p_free] / (2.0 * G)
    return diag


def assemble_blocks(problem: ContactProblem, forms, ub, pb, wb, n_components: int,
                    spacing: np.ndarray):
    """(S_full, offsets, branches, G_g): the monolithic rolling system on [u, p, (w_k,
    k < ``n_components``) per Maxwell branch] before any boundary condition, with the
    weak forms of ``forms`` (:mod:`.rolling_forms` or :mod:`.rolling3d_forms`, the same
    equations with 2 or 5 strain components), the block offsets in the full vector, the
    branches (G_i Pa, tau_i s) and the glassy modulus (Pa). ``spacing``: the node spacing
    along x per element (m), the SUPG length: delta = spacing / (2 V tau_i + spacing)."""
    mat = as_prony(problem.material)
    branches = list(zip(mat.G, mat.tau)) if isinstance(mat, PronyMaterial) else []
    V, rho = problem.loading.speed, problem.layer.density
    Gg = mat.glassy_modulus
    A = asm(forms.glassy_stiffness, ub, G=Gg, rho_v2=rho * V * V)
    B = asm(forms.divergence, ub, pb)
    nb = len(branches)
    nblk = 2 + n_components * nb
    blocks = [[None] * nblk for _ in range(nblk)]
    blocks[0][0], blocks[0][1], blocks[1][0] = A, -B.T, -B
    nq = wb.X.shape[1]
    for b, (Gi, ti) in enumerate(branches):
        ell = V * ti
        delta = np.repeat((spacing / (2.0 * ell + spacing))[:, None], nq, axis=1)
        Aw = asm(forms.branch_advection, wb, G=Gi, ell=ell, delta=delta)
        for k in range(n_components):
            j = 2 + n_components * b + k
            blocks[0][j] = asm(forms.branch_stress, wb, ub, G=Gi, comp=k)
            blocks[j][0] = asm(forms.branch_source, ub, wb, G=Gi, ell=ell, delta=delta, comp=k)
            blocks[j][j] = Aw
    sizes = [ub.N, pb.N] + [wb.N] * (n_components * nb)
    offsets = list(np.concatenate([[0], np.cumsum(sizes)]).astype(int))
    blocks[1][1] = sp.csr_matrix((pb.N, pb.N))
    return bmat(blocks, "csr"), offsets, branches, Gg


def build_rolling_system(problem: ContactProblem, disc: PlaneDiscretization) -> RollingSystem:
    """Mesh and assemble the plane-strain rolling layer of ``problem`` (module docstring)."""
    t0 = time.perf_counter()
    H = problem.layer.thickness
    mesh, _, _ = plane_mesh(H, disc.contact_zone, disc.upstream, disc.downstream, disc.mesh_size,
                            disc.band, disc.grading, disc.far_x_up, disc.far_x_down, disc.far_z)
    if disc.refine:
        mesh = mesh.refined(disc.refine)
    t1 = time.perf_counter()
    ue = ElementVector(ElementTriP2())
    ub = Basis(mesh, ue, intorder=INTORDER)
    pb = Basis(mesh, ElementTriP1(), intorder=INTORDER)
    wb = Basis(mesh, ElementTriP2() if STRAIN_ORDER == 2 else ElementTriP1(), intorder=INTORDER)
    S_full, offsets, branches, Gg = assemble_blocks(problem, rf, ub, pb, wb, 2,
                                                    element_hx(mesh) / STRAIN_ORDER)
    nb = len(branches)
    fixed_u = np.unique(np.concatenate([ub.get_dofs(name).all()
                                        for name in ("base", "inflow", "outflow")]))
    fixed = [fixed_u]
    inflow_w = wb.get_dofs("inflow").all()
    for j in range(2 * nb):
        fixed.append(offsets[2 + j] + inflow_w)
    fixed = np.concatenate(fixed)
    S, free = restrict(S_full, fixed, offsets[-1])
    C, fbl, lam_nodes = multiplier_coupling(mesh, ue, ElementTriP1(), rf.coupling, free, offsets[-1], ub.N)
    xq = np.asarray(fbl.global_coordinates())[0]
    R = problem.indenter.radius
    m = asm(rf.area, fbl)[lam_nodes]
    q = asm(rf.weighted, fbl, f=profile(xq, R))[lam_nodes]
    mx = asm(rf.weighted, fbl, f=xq)[lam_nodes]
    ms = asm(rf.weighted, fbl, f=slope(xq, R))[lam_nodes]
    x_nodes = mesh.p[0, lam_nodes]
    order = np.argsort(x_nodes, kind="stable")
    C, m, q, mx, ms, x_nodes = C[order], m[order], q[order], mx[order], ms[order], x_nodes[order]

    diag = diagonal_scale(S, free, offsets, pb, Gg)
    t2 = time.perf_counter()
    return RollingSystem(mesh=mesh, ubasis=ub, pbasis=pb, wbasis=wb, S=S, free=free, offsets=offsets,
                         C=C, m=np.asarray(m), q=np.asarray(q), mx=np.asarray(mx), ms=np.asarray(ms),
                         nodes=x_nodes, branches=branches, scale=diag, mesh_time=t1 - t0,
                         assembly_time=t2 - t1)
