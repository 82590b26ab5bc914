"""Monolithic discretization of steady rolling on a plane-strain layer.

:func:`build_rolling_system` meshes the section
(:mod:`fem_reference.mesh.plane_strain_strip`), assembles the non-symmetric system of
:mod:`.forms` on the unknowns [u (P2 vector), p (P1), (a_i, c_i) per Maxwell branch
(continuous scalars of order ``STRAIN_ORDER``, SUPG)]
(:func:`~fem_reference.rolling.assembly.assemble_blocks`), removes the Dirichlet
unknowns (u = 0 on the base, the inflow and the outflow; a_i = c_i = 0 on the inflow:
the material enters undeformed and relaxed) and assembles the mortar coupling C of the
P1 contact multiplier with u_z on the candidate zone, with the multiplier moments m =
int phi dx (m), q = int phi s dx (m^2), mx = int phi x dx (m^2) and ms = int phi s'(x)
dx (m). SI units, per unit length along y.
"""

from __future__ import annotations

import time

import numpy as np
from skfem import Basis, ElementTriP1, ElementTriP2, ElementVector, asm

from ...mesh.plane_strain_strip import plane_mesh
from ...problem import ContactProblem
from ..assembly import (RollingSystem, assemble_blocks, diagonal_scale, element_hx,
                        multiplier_coupling, restrict)
from . import forms as rf
from .discretization import PlaneDiscretization

__all__ = ["StripSystem", "build_rolling_system", "profile", "slope"]

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


class StripSystem(RollingSystem):
    """Assembled discrete plane-strain section (see
    :class:`~fem_reference.rolling.assembly.RollingSystem`): per branch the strain
    components (a_i, c_i) of eps_v,i = [[a_i, c_i], [c_i, -a_i]]; ``nodes`` the x (m,
    increasing) of the multiplier nodes; m, q, mx, ms per unit length (m, m^2, m^2, m)."""

    #: viscous-strain components per Maxwell branch (a and c)
    COMPONENTS = 2

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


def build_rolling_system(problem: ContactProblem, disc: PlaneDiscretization) -> StripSystem:
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
    return StripSystem(mesh=mesh, ubasis=ub, pbasis=pb, wbasis=wb, S=S, free=free, offsets=offsets,
                       C=C, m=np.asarray(m), q=np.asarray(q), mx=np.asarray(mx), ms=np.asarray(ms),
                       nodes=x_nodes, branches=branches, scale=diag, mesh_time=t1 - t0,
                       assembly_time=t2 - t1)
