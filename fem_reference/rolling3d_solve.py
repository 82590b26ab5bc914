"""Driver of a 3D steady-rolling solve: a rigid sphere on the half layer y >= 0.

1. :func:`~.rolling3d_discretization.resolve_box` sizes the half box;
   :func:`~.rolling3d_system.build_box_system` meshes and assembles.
2. The surface compliance W = C S^-1 C^T of the candidate half disk takes one solve
   per candidate node, all right-hand sides in blocks. With MKL Pardiso (pypardiso
   installed) the factorization serves Pardiso's partial solve: the right-hand sides and
   the wanted entries are the same few u_z unknowns of the zone, so each solve touches
   only their paths in the elimination tree (8 times faster measured); the same factors
   then solve for the fields (whole solution, iteratively refined). The partial solves'
   W errs by about 1e-5 (the factors lack weighted matching and refinement): a defect
   correction re-solves the contact with the gaps shifted by -C x - W lam of the refined
   solve until that shift stops changing (``DEFECT_TOLERANCE``), so the pressures satisfy
   the contact conditions with the exact compliance. Without pypardiso, SuperLU does both.
3. :func:`~.contact.solve_contact` finds pressures and indentation for half the load.
4. One more solve gives the fields; edges on y = 0, rolling resistance, the dashpots'
   dissipation (both halves) follow.
"""

from __future__ import annotations

import resource
import time
from typing import Callable, Optional

import numpy as np

from . import rolling3d_forms as rf
from .contact import solve_contact
from .errors import ContactZoneError, FemReferenceError, LinearSolverError
from .linsolve import PardisoSolver, pardiso_available, sparse_lu
from .postprocess import fit_contact_radius
from .problem import ContactProblem
from .result import SolverRecord
from .rolling3d_discretization import resolve_box
from .rolling3d_result import BoxMeshStats, SphereRollingResult
from .rolling3d_system import BoxSystem, build_box_system, sphere_profile

__all__ = ["solve_rolling_3d", "dissipation"]

#: right-hand sides per block of the compliance solves
BLOCK = 256
#: linear solver: "auto" (Pardiso if installed, else SuperLU), "pardiso" or "superlu"
LINEAR_SOLVER = "auto"
#: the most unknowns a 3D rolling solve takes without Pardiso (SuperLU: 3.2 GB at 51k, 110 s)
SUPERLU_LIMIT = 100_000
#: defect correction of the partial-solve compliance: steps at most, and the relative
#: change of the weighted deflection at which it stops (the first defect measured
#: 2e-6 .. 3e-5)
DEFECT_STEPS = 6
DEFECT_TOLERANCE = 1e-10


def _compliance(system: BoxSystem, solver, say) -> np.ndarray:
    """W = C S^-1 C^T (m^6/N: weighted gap per unit nodal multiplier), one solve per
    column; a block whose relative residual exceeds 1e-10 gets iterative refinement
    (not with Pardiso's partial solve, checked afterwards in :func:`solve_rolling_3d`)."""
    C = system.C
    n_c = C.shape[0]
    W = np.empty((n_c, n_c))
    for start in range(0, n_c, BLOCK):
        stop = min(start + BLOCK, n_c)
        rhs = C[start:stop].T.toarray()
        x = solver._apply(rhs)
        if not getattr(solver, "partial", False):  # a partial solution has no residual
            rel = np.linalg.norm(rhs - system.S @ x, axis=0) / np.linalg.norm(rhs, axis=0)
            if rel.max() > 1e-10:  # iterative refinement only where needed
                x = solver.solve(rhs)
        W[:, start:stop] = C @ x
        if n_c > BLOCK:
            say(f"surface compliance: {stop}/{n_c} columns")
    return W


def dissipation(system: BoxSystem, u: np.ndarray, w: list, V: float) -> float:
    """Power (W) dissipated by the dashpots in the half layer: sum_i int 2 G_i (dev eps -
    eps_v,i) : (-V d eps_v,i / dx) dV."""
    ub, wb = system.ubasis, system.wbasis
    total = 0.0
    uf = ub.interpolate(u)
    for (Gi, _), comps in zip(system.branches, w):
        fields = {f"w{k}": wb.interpolate(c) for k, c in enumerate(comps)}
        total += rf.dashpot_power.assemble(wb, u=uf, G=Gi, V=V, **fields)
    return float(total)


def _top_line(system: BoxSystem, u: np.ndarray):
    """x (m, increasing) and u_z (m) of the top-surface vertices on y = 0."""
    mesh, ub = system.mesh, system.ubasis
    top = np.unique(mesh.facets[:, np.concatenate([mesh.boundaries["zone"],
                                                   mesh.boundaries["free"]])])
    tol = 1e-9 * (np.ptp(mesh.p[0]) + np.ptp(mesh.p[1]))
    top = top[np.abs(mesh.p[1, top]) <= tol]
    order = np.argsort(mesh.p[0, top], kind="stable")
    top = top[order]
    return mesh.p[0, top], u[ub.nodal_dofs[2, top]]


def solve_rolling_3d(problem: ContactProblem,
                     progress: Optional[Callable[[str], None]] = None) -> SphereRollingResult:
    """Solve the steady frictionless rolling of a sphere (module docstring).

    Raises
    ------
    InputError, LinearSolverError, ContactNotConvergedError, ContactZoneError
        See :mod:`fem_reference.errors`.
    """
    say = progress or (lambda _: None)
    times = {}
    t0 = time.perf_counter()
    disc = resolve_box(problem)
    V = problem.loading.speed
    say(f"3d rolling: meshing the half box (h = {disc.element_size:.3e} m on the half disk r <= "
        f"{disc.contact_zone:.3e} m, x in [-{disc.downstream:.3e}, {disc.upstream:.3e}] m, "
        f"y <= {disc.lateral:.3e} m, V = {V:g} m/s)")
    system = build_box_system(problem, disc)
    times["mesh"] = system.mesh_time
    times["assembly"] = system.assembly_time
    say(f"{system.mesh.t.shape[1]} tetrahedra, {system.n_unknowns} unknowns, "
        f"{len(system.m)} contact candidate nodes")
    partial = LINEAR_SOLVER != "superlu" and pardiso_available()
    if not partial and system.n_unknowns > SUPERLU_LIMIT:
        raise LinearSolverError(
            f"{system.n_unknowns} unknowns are too many for SuperLU in 3D (its fill measured 104M nonzeros, "
            f"3.2 GB, at 51k unknowns and grows faster than the unknowns): install MKL Pardiso "
            f"(pip install pypardiso; x86_64 only) or give a coarser fem.element_size, grading or far_size "
            f"(at most {SUPERLU_LIMIT} unknowns without Pardiso)")
    if partial:  # Pardiso's partial solve for W, then full solves on the same factors
        solver = PardisoSolver(system.S, system.scale, selected=np.unique(system.C.indices))
    else:
        solver = sparse_lu(system.S, system.scale, prefer=LINEAR_SOLVER)
    times["factorization"] = solver.setup_time
    say(f"{solver.name}{' (partial solve)' if partial else ''}: factorized in "
        f"{solver.setup_time:.1f} s ({solver.fill} nonzeros)")
    t1 = time.perf_counter()
    W = _compliance(system, solver, say)
    times["compliance"] = time.perf_counter() - t1
    if partial:
        solver.full_solves()
    load = problem.loading.load

    def contact(W, q):
        if not np.all(np.isfinite(W)) or np.any(np.diag(W) <= 0):
            raise FemReferenceError("the surface compliance is not positive: the rolling layer "
                                    "model is singular (check the boundary conditions and the speed)")
        return solve_contact(W, system.m, q, load=None if load is None else 0.5 * load,
                             indentation=problem.loading.indentation,
                             max_iterations=problem.fem.max_iterations, progress=say)

    t2 = time.perf_counter()
    sol = contact(W, system.q)
    times["contact"] = time.perf_counter() - t2
    t3 = time.perf_counter()
    x = solver.solve(-(system.C.T @ sol.pressure))
    if partial:
        # defect correction: the partial solves' W (no weighted matching, no refinement)
        # errs by about 1e-5; the refined full solve gives the true weighted deflection
        # -C x of the current pressures, and the contact is solved again with the gaps
        # shifted by the difference e = -C x - W lam until it stops changing
        e = np.zeros_like(system.q)
        for k in range(1, DEFECT_STEPS + 1):
            Wl = W @ sol.pressure
            step = -(system.C @ x) - Wl - e
            times["compliance_defect"] = float(np.linalg.norm(step) / np.linalg.norm(Wl))
            if times["compliance_defect"] <= DEFECT_TOLERANCE:
                break
            if k == DEFECT_STEPS:
                raise LinearSolverError(
                    f"the partial-solve compliance does not converge under defect correction "
                    f"(relative defect {times['compliance_defect']:.2e} after {k} steps): set "
                    "fem_reference.rolling3d_solve.LINEAR_SOLVER = \"superlu\"")
            e += step
            sol = contact(W, system.q + e)
            x = solver.solve(-(system.C.T @ sol.pressure))
    times["fields"] = time.perf_counter() - t3
    h = disc.element_size
    zone = disc.contact_zone
    xy = system.nodes
    r_act = np.hypot(xy[sol.active, 0], xy[sol.active, 1])
    margin = (problem.fem.fit_nodes + 0.5) * h
    if r_act.size and r_act.max() > zone - margin:
        raise ContactZoneError(
            f"the contact reaches the edge of the candidate half disk r <= {zone:.4e} m (a contact "
            f"node at r = {r_act.max():.4e} m, less than {margin:.3e} m inside): raise "
            "fem.contact_zone or lower the load")
    u, p, w = system.split(x)
    R = problem.indenter.radius
    xs, uz = _top_line(system, u)
    inside = np.abs(xs) < R
    gap = np.full(xs.shape, np.inf)
    gap[inside] = sphere_profile(xs[inside], 0.0, R) - sol.indentation - uz[inside]
    tol = 1e-9 * zone
    on_line = np.abs(xy[:, 1]) <= tol
    x_line_act = xy[sol.active & on_line, 0]
    if x_line_act.size == 0:
        raise FemReferenceError("no contact node on the symmetry line y = 0: refine fem.element_size")
    fit = problem.fem.fit_nodes
    lead = fit_contact_radius(float(x_line_act.max()), xs, gap, h, fit)
    trail = -fit_contact_radius(float(-x_line_act.min()), -xs, gap, h, fit)
    if lead > zone - 0.5 * h or trail < -zone + 0.5 * h:
        raise ContactZoneError(f"the fitted contact edges [{trail:.4e}, {lead:.4e}] m reach the "
                               f"candidate zone r <= {zone:.4e} m: raise fem.contact_zone")
    lam = sol.pressure
    total_load = 2.0 * float(system.m @ lam)
    moment = 2.0 * float(system.mx @ lam)
    t4 = time.perf_counter()
    diss = 2.0 * dissipation(system, u, w, V) if system.branches else 0.0
    times["dissipation"] = time.perf_counter() - t4
    times["total"] = time.perf_counter() - t0
    line_idx = np.flatnonzero(on_line)
    line_idx = line_idx[np.argsort(xy[line_idx, 0], kind="stable")]
    mesh = system.mesh
    stats = BoxMeshStats(model="3d", elements=int(mesh.t.shape[1]), vertices=int(mesh.p.shape[1]),
                         displacement_dofs=int(system.ubasis.N), pressure_dofs=int(system.pbasis.N),
                         internal_dofs=int(rf.N_COMPONENTS * len(system.branches) * system.wbasis.N),
                         unknowns=int(system.n_unknowns), contact_nodes=int(len(system.m)),
                         element_size=h, contact_zone=zone, upstream=disc.upstream,
                         downstream=disc.downstream, lateral=disc.lateral, far_size=disc.far_size,
                         grading=disc.grading)
    record = SolverRecord(iterations=sol.iterations, residual=sol.residual, history=sol.history,
                          method=sol.method, linear_solver=solver.name,
                          linear_iterations=solver.iterations, linear_residual=solver.max_residual,
                          factor_nonzeros=int(solver.fill), times=times)
    peak = 1024.0 * resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    result = SphereRollingResult(
        speed=V, load=total_load, indentation=sol.indentation, rolling_resistance=moment / R,
        pressure_centroid=moment / total_load, leading_edge=lead, trailing_edge=trail,
        peak_pressure=float(lam.max()), dissipation=diss,
        pressure_power=2.0 * float(V * (system.ms @ lam)), pressure_x=xy[line_idx, 0],
        pressure=lam[line_idx], surface_x=xs, surface_uz=uz, mesh=stats, solver=record,
        fields={"mesh": mesh, "u": u, "p": p, "w": w, "ubasis": system.ubasis,
                "pbasis": system.pbasis, "wbasis": system.wbasis, "system": system},
        zone_xy=xy, zone_pressure=lam,
        lateral_edge=float(xy[sol.active, 1].max()) if sol.active.any() else 0.0,
        peak_memory=peak, factor_memory=float(getattr(solver, "memory", np.nan)))
    say(f"done: R_r {result.rolling_resistance:.6e} N (D/V {result.rolling_resistance_energy:.6e} N), "
        f"edges on y = 0 [{trail:.5e}, {lead:.5e}] m, indentation {sol.indentation:.5e} m "
        f"({times['total']:.1f} s)")
    return result
