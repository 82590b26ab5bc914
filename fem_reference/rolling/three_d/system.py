"""Monolithic discretization of 3D steady rolling of a sphere or a roller on the half
layer y >= 0.

:func:`build_box_system` meshes the half box (:mod:`fem_reference.mesh.half_box`),
assembles the non-symmetric system of :mod:`.forms` on the unknowns [u (P2 vector), p
(P1), (w_0 .. w_4) per Maxwell branch (continuous P1 scalars, SUPG)], removes the
Dirichlet unknowns and assembles the mortar coupling C of the P1 contact multiplier with
u_z on the candidate half disk, with the multiplier moments m = int phi dS (m^2), q =
int phi s dS (m^3), mx = int phi x dS (m^3) and ms = int phi ds/dx dS (m^2).

Dirichlet conditions: u = 0 on the base, the inflow and the outflow; w = 0 on the
inflow (the material enters undeformed and relaxed); on the symmetry plane y = 0,
u_y = 0 and the components odd in y, w_2 = eps_xy and w_4 = eps_yz, vanish (the
restriction to y >= 0 of the mirror-symmetric solution; the branch equations transport
along x only and need no other condition there). The lateral side y = lateral and the
top outside the contact are traction free. SI units; the half layer carries half the
load.
"""

from __future__ import annotations

import time

import numpy as np
from skfem import Basis, ElementTetP1, ElementTetP2, ElementVector, asm

from ...mesh.half_box import half_box_mesh
from ...problem import ContactProblem
from ..assembly import (RollingSystem, assemble_blocks, diagonal_scale, element_hx,
                        multiplier_coupling, restrict)
from . import forms as rf
from .discretization import BoxDiscretization

__all__ = ["BoxSystem", "build_box_system", "sphere_profile", "sphere_slope"]

#: quadrature order of the volume forms: every integrand is a polynomial of degree <= 2 on
#: an affine tetrahedron (grad P2 and the P1 strains are linear), which the 4-point rule
#: integrates exactly; higher orders give the same matrices at 2.75 times the points
INTORDER = 2
NC = rf.N_COMPONENTS
#: components odd in y (eps_xy, eps_yz): zero on the symmetry plane
ODD = (2, 4)


def sphere_profile(x, y, R):
    """Height s = R - sqrt(R^2 - x^2 - y^2) (m) of the sphere above its lowest point."""
    r2 = np.asarray(x, float) ** 2 + np.asarray(y, float) ** 2
    return r2 / (R + np.sqrt(R * R - r2))


def sphere_slope(x, y, R):
    """ds/dx = x / sqrt(R^2 - x^2 - y^2) (-)."""
    x = np.asarray(x, float)
    return x / np.sqrt(R * R - x * x - np.asarray(y, float) ** 2)


class BoxSystem(RollingSystem):
    """Assembled discrete half layer (see
    :class:`~fem_reference.rolling.assembly.RollingSystem`).

    Attributes
    ----------
    mesh, ubasis, pbasis, wbasis :
        skfem mesh and bases (P2 vector, P1 pressure, P1 scalar strain).
    S : sparse matrix
        System matrix on the free unknowns (non-symmetric).
    free : ndarray
        Indices of the free unknowns in [u; p; w_0,1 .. w_4,1; w_0,2 ...].
    offsets : list of int
        Start of each block in the full vector.
    C : sparse matrix (n_c, len(free))
        Coupling of the multiplier nodes with the free unknowns.
    m, q, mx, ms : ndarray (n_c,)
        int phi dS (m^2), int phi s dS (m^3), int phi x dS (m^3), int phi ds/dx dS (m^2).
    nodes : ndarray (n_c, 2)
        (x, y) (m) of the multiplier nodes.
    branches : list of (G_i, tau_i)
        Maxwell branches (Pa, s).
    scale : ndarray
        Diagonal scale of the free unknowns for the direct solver.
    """

    COMPONENTS = NC
    #: the candidate zone is a roller's rectangle |x| <= Z, y <= L/2 (else a half disk)
    rectangular: bool = False

    def zone_distance(self) -> np.ndarray:
        """How far (m) each multiplier node lies towards the zone's edge: |x| in a roller's
        rectangle (its ends y = L/2 are the roller's own), the radius in a half disk."""
        x, y = self.nodes[:, 0], self.nodes[:, 1]
        return np.abs(x) if self.rectangular else np.hypot(x, y)

    def dissipation(self, u: np.ndarray, w: list, V: float) -> float:
        """Power (W) dissipated by the dashpots in the half layer: sum_i int 2 G_i (dev eps -
        eps_v,i) : (-V d eps_v,i / dx) dV; 0 without branches."""
        ub, wb = self.ubasis, self.wbasis
        total = 0.0
        uf = ub.interpolate(u)
        for (Gi, _), comps in zip(self.branches, w):
            fields = {f"w{k}": wb.interpolate(c) for k, c in enumerate(comps)}
            total += rf.dashpot_power.assemble(wb, u=uf, G=Gi, V=V, **fields)
        return float(total)


def build_box_system(problem: ContactProblem, disc: BoxDiscretization) -> BoxSystem:
    """Mesh and assemble the half layer of ``problem`` (module docstring)."""
    t0 = time.perf_counter()
    H = problem.layer.thickness
    mesh = half_box_mesh(H, disc.contact_zone, max(disc.upstream, disc.downstream), disc.lateral,
                         disc, disc.zone_y)
    if disc.refine:
        mesh = mesh.refined(disc.refine)
    t1 = time.perf_counter()
    ue = ElementVector(ElementTetP2())
    ub = Basis(mesh, ue, intorder=INTORDER)
    pb = Basis(mesh, ElementTetP1(), intorder=INTORDER)
    wb = pb
    S_full, offsets, branches, Gg = assemble_blocks(problem, rf, ub, pb, wb, NC, element_hx(mesh))
    nb = len(branches)
    dofs_y = ub.get_dofs("sym_y")
    fixed = [np.unique(np.concatenate([ub.get_dofs(name).all()
                                       for name in ("base", "inflow", "outflow")])),
             dofs_y.all("u^2")]
    inflow_w = wb.get_dofs("inflow").all()
    sym_w = wb.get_dofs("sym_y").all()
    for b in range(nb):
        for k in range(NC):
            o = offsets[2 + NC * b + k]
            fixed.append(o + inflow_w)
            if k in ODD:
                fixed.append(o + sym_w)
    fixed = np.unique(np.concatenate(fixed))
    S, free = restrict(S_full, fixed, offsets[-1])
    C, fbl, lam_nodes = multiplier_coupling(mesh, ue, ElementTetP1(), rf.coupling, free, offsets[-1], ub.N)
    xq = np.asarray(fbl.global_coordinates())
    ind = problem.indenter
    m = asm(rf.area, fbl)[lam_nodes]
    q = asm(rf.weighted, fbl, f=ind.surface(xq[0], xq[1]))[lam_nodes]
    mx = asm(rf.weighted, fbl, f=xq[0])[lam_nodes]
    ms = asm(rf.weighted, fbl, f=ind.slope(xq[0], xq[1]))[lam_nodes]
    nodes = mesh.p[:2, lam_nodes].T

    diag = diagonal_scale(S, free, offsets, pb, Gg)
    t2 = time.perf_counter()
    system = BoxSystem(mesh=mesh, ubasis=ub, pbasis=pb, wbasis=wb, S=S, free=free, offsets=offsets,
                       C=C, m=np.asarray(m), q=np.asarray(q), mx=np.asarray(mx), ms=np.asarray(ms),
                       nodes=nodes, branches=branches, scale=diag, mesh_time=t1 - t0,
                       assembly_time=t2 - t1)
    system.rectangular = disc.zone_y is not None
    return system
