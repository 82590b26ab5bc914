"""What both steady-rolling models assemble alike: the monolithic non-symmetric system
on [u (P2 vector), p (P1), the viscous-strain components per Maxwell branch (continuous
scalars, SUPG)] before any boundary condition (:func:`assemble_blocks`), its restriction
to the free unknowns, the mortar coupling of the P1 contact multiplier with u_z on the
candidate zone, the diagonal scale of the direct solver, and the assembled system's
common shape (:class:`RollingSystem`). The models: :mod:`.plane_strain.system` and
:mod:`.three_d.system`. SI units.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import ClassVar, List

import numpy as np
import scipy.sparse as sp
from skfem import FacetBasis, asm, bmat

from ..materials import PronyMaterial, as_prony
from ..problem import ContactProblem
from .forms import pressure_mass

__all__ = ["RollingSystem", "assemble_blocks", "diagonal_scale", "element_hx",
           "multiplier_coupling", "restrict", "supg_weight"]

#: the SUPG weight is off where an element spans less than this many memory lengths
#: V tau_i along x (docs/derivations.md section 7, "SUPG weight")
SUPG_CELL_NUMBER = 2.0


@dataclass
class RollingSystem(ABC):
    """Assembled discrete rolling layer, what the plane-strain section and the 3D half
    layer have in common; each model sets :attr:`COMPONENTS` and :meth:`dissipation`.

    Attributes
    ----------
    mesh, ubasis, pbasis, wbasis :
        skfem mesh and bases (P2 vector displacement, P1 pressure, scalar strain).
    S : sparse matrix
        System matrix on the free unknowns (non-symmetric).
    free : ndarray
        Indices of the free unknowns in the full vector [u; p; (w_k per component)
        per branch].
    offsets : list of int
        Start of each block (u, p, then the strain components per branch) in the full
        vector.
    C : sparse matrix (n_c, len(free))
        Coupling of the multiplier nodes with the free unknowns.
    m, q, mx, ms : ndarray (n_c,)
        The multiplier's moments int phi, int phi s, int phi x, int phi ds/dx over the
        candidate zone (m, m^2, m^2, m per unit length in plane strain; m^2, m^3, m^3,
        m^2 in 3D).
    nodes : ndarray
        The multiplier nodes: x (m, increasing) in plane strain, (x, y) (m) in 3D.
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

    #: viscous-strain components per Maxwell branch (set by each model)
    COMPONENTS: ClassVar[int]

    def split(self, x_free: np.ndarray):
        """Full fields from a free-unknown vector: u (m), p (Pa) and, per branch, the
        tuple of its strain components (-)."""
        full = np.zeros(self.offsets[-1])
        full[self.free] = x_free
        o, nc = self.offsets, self.COMPONENTS
        u, p = full[o[0]:o[1]], full[o[1]:o[2]]
        w = [tuple(full[o[2 + nc * b + k]:o[3 + nc * b + k]] for k in range(nc))
             for b in range(len(self.branches))]
        return u, p, w

    @abstractmethod
    def dissipation(self, u: np.ndarray, w: list, V: float) -> float:
        """Power dissipated by the dashpots (W/m in plane strain, W in the 3D half layer)
        for the fields of :meth:`split` at the speed V (m/s); 0 without branches."""


def element_hx(mesh) -> np.ndarray:
    """Extent (m) of each element along x (the SUPG length scale)."""
    xs = mesh.p[0, mesh.t]
    return xs.max(axis=0) - xs.min(axis=0)


def supg_weight(spacing: np.ndarray, ell: float) -> np.ndarray:
    """SUPG weight delta (-) of a branch with memory length ``ell`` = V tau_i (m) on elements
    of node spacing ``spacing`` along x (m): max(0, (h - 2 l) / (h + 2 l)).

    Galerkin (delta = 0) where h < 2 l: there the P1 Galerkin transport carries the
    exponential memory exp(x / l) (fading downstream, -x) from node to node exact to
    (h / l)^4 / 180 per element, without sign changes, while a streamline weight biases the
    solution linearly in its size (on the section 11 sphere, R_r by -0.6% to -2.9%). Coarser, the weight
    grows to 1 (the L2 projection w = E(u) as V -> 0), the regime where Galerkin's
    discrete memory oscillates (its growth factor turns negative beyond h = 3 l)."""
    h = np.asarray(spacing, float)
    return np.maximum(0.0, (h - SUPG_CELL_NUMBER * ell) / (h + SUPG_CELL_NUMBER * ell))


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
    Mp = asm(pressure_mass, pbasis)
    diag = np.abs(S.diagonal())
    n_u_free = int(np.sum(free < offsets[1]))
    p_free = free[(free >= offsets[1]) & (free < offsets[2])] - offsets[1]
    diag[n_u_free:n_u_free + len(p_free)] = np.asarray(Mp.sum(axis=1)).ravel()[p_free] / (2.0 * G)
    return diag


def assemble_blocks(problem: ContactProblem, forms, ub, pb, wb, n_components: int,
                    spacing: np.ndarray):
    """(S_full, offsets, branches, G_g): the monolithic rolling system on [u, p, (w_k,
    k < ``n_components``) per Maxwell branch] before any boundary condition, with the
    weak forms of ``forms`` (:mod:`.plane_strain.forms` or :mod:`.three_d.forms`, the
    same equations with 2 or 5 strain components), the block offsets in the full vector, the
    branches (G_i Pa, tau_i s) and the glassy modulus (Pa). ``spacing``: the node spacing
    along x per element (m), the SUPG length (:func:`supg_weight`)."""
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
        delta = np.repeat(supg_weight(spacing, ell)[:, None], nq, axis=1)
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
