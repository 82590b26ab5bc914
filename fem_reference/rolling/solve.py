"""Driver of a steady-rolling solve: a rigid cylinder on the plane-strain section, or a
rigid sphere on the half layer y >= 0 (``fem.model = "3d"``). One sequence of stages:

1. Sizes (:func:`~.plane_strain.discretization.resolve_plane`,
   :func:`~.three_d.discretization.resolve_box`), mesh and assembly
   (:func:`~.plane_strain.system.build_rolling_system`,
   :func:`~.three_d.system.build_box_system`).
2. One factorization of the non-symmetric system. Plane strain: SuperLU (COLAMD,
   threshold pivoting; the symmetric minimum-degree ordering fills far more here). 3D:
   MKL Pardiso (pypardiso installed) serving its partial solve for W: the right-hand
   sides and the wanted entries are the same few u_z unknowns of the zone, so each solve
   touches only their paths in the elimination tree (8 times faster measured); the same
   factors then solve for the fields (whole solution, iteratively refined); they live
   outside Python and are released when the solve ends. Without pypardiso, SuperLU, up
   to ``SUPERLU_LIMIT`` unknowns.
3. The surface compliance W = C S^-1 C^T of the candidate zone (non-symmetric while
   rolling), one solve per candidate node, right-hand sides in blocks.
4. :func:`~fem_reference.contact.solve_contact` finds pressures and indentation (the
   primal-dual active set needs no symmetry) for the meshed part's share of the load:
   all of it per unit length in plane strain, half of it on the half layer.
5. One more solve gives the fields. After Pardiso's partial solves, whose W errs by
   about 1e-5 (the factors lack weighted matching and refinement), a defect correction
   re-solves the contact with the gaps shifted by -C x - W lam of the refined solve
   until that shift stops changing (``DEFECT_TOLERANCE``), so the pressures satisfy the
   contact conditions with the exact compliance.
6. The contact edges on the line y = 0 (the section itself in plane strain), the rolling
   resistance, the dashpots' dissipation; the half layer's sums count both halves.
"""

from __future__ import annotations

import resource
import time
from typing import Callable, Optional

import numpy as np

from ..contact import solve_contact
from ..edge_fit import fit_contact_radius
from ..errors import ContactZoneError, FemReferenceError, LinearSolverError
from ..linsolve import DirectSolver, PardisoSolver, pardiso_available, sparse_lu
from ..problem import ContactProblem
from ..record import SolverRecord
from .assembly import RollingSystem
from .plane_strain.discretization import resolve_plane
from .plane_strain.result import CylinderRollingResult
from .plane_strain.system import build_rolling_system, profile
from .result import RollingMeshStats, RollingResult
from .three_d.discretization import resolve_box
from .three_d.result import SphereRollingResult
from .three_d.system import build_box_system

__all__ = ["solve_rolling", "compliance"]

#: right-hand sides per block of the compliance solves (plane strain, 3D)
BLOCK = {"plane_strain": 64, "3d": 256}
#: SuperLU settings of the non-symmetric system: COLAMD, threshold pivoting (the zero
#: pressure block needs some)
ORDERINGS = (("COLAMD", 0.1), ("COLAMD", 1.0))
#: 3D linear solver: "auto" (Pardiso if installed, else SuperLU), "pardiso" or "superlu"
LINEAR_SOLVER = "auto"
#: the most unknowns a 3D rolling solve takes without Pardiso (SuperLU: 3.2 GB at 51k, 110 s)
SUPERLU_LIMIT = 100_000
#: defect correction of the partial-solve compliance: steps at most, and the relative
#: change of the weighted deflection at which it stops (the first defect measured
#: 2e-6 .. 3e-5)
DEFECT_STEPS = 6
DEFECT_TOLERANCE = 1e-10


def compliance(system: RollingSystem, solver, block: int, say) -> np.ndarray:
    """W = C S^-1 C^T (m^2/Pa per unit length in plane strain, m^6/N... per unit nodal
    multiplier in 3D), one solve per column, ``block`` columns at a time; a block whose
    relative residual exceeds 1e-10 gets iterative refinement (not with Pardiso's partial
    solve, which has no residual: corrected afterwards, step 5 of the module docstring)."""
    C = system.C
    n_c = C.shape[0]
    W = np.empty((n_c, n_c))
    partial = getattr(solver, "partial", False)
    for start in range(0, n_c, block):
        stop = min(start + block, n_c)
        rhs = C[start:stop].T.toarray()
        x = solver._apply(rhs)
        if not partial:
            rel = np.linalg.norm(rhs - system.S @ x, axis=0) / np.linalg.norm(rhs, axis=0)
            if rel.max() > 1e-10:
                x = solver.solve(rhs)
        W[:, start:stop] = C @ x
        if n_c > block:
            say(f"surface compliance: {stop}/{n_c} columns")
    return W


def _factorize(system: RollingSystem, model: str, say):
    """The factorized solver of ``system`` (step 2 of the module docstring)."""
    if model == "plane_strain":
        return DirectSolver(system.S, system.scale, orderings=ORDERINGS)
    partial = LINEAR_SOLVER != "superlu" and pardiso_available()
    if not partial and system.n_unknowns > SUPERLU_LIMIT:
        raise LinearSolverError(
            f"{system.n_unknowns} unknowns are too many for SuperLU in 3D (its fill measured 104M nonzeros, "
            f"3.2 GB, at 51k unknowns and grows faster than the unknowns): install MKL Pardiso "
            f"(pip install pypardiso; x86_64 only) or give a coarser fem.element_size, grading or far_size "
            f"(at most {SUPERLU_LIMIT} unknowns without Pardiso)")
    if partial:
        solver = PardisoSolver(system.S, system.scale, selected=np.unique(system.C.indices))
    else:
        solver = sparse_lu(system.S, system.scale, prefer=LINEAR_SOLVER, orderings=ORDERINGS)
    say(f"{solver.name}{' (partial solve)' if partial else ''}: factorized in "
        f"{solver.setup_time:.1f} s ({solver.fill} nonzeros)")
    return solver


def _defect_correction(system: RollingSystem, solver, W, sol, x, contact, times):
    """(sol, x) after the defect correction of a partial-solve W (step 5)."""
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
                "fem_reference.rolling.solve.LINEAR_SOLVER = \"superlu\"")
        e += step
        sol = contact(W, system.q + e)
        x = solver.solve(-(system.C.T @ sol.pressure))
    return sol, x


def _contact_and_fields(system: RollingSystem, solver, model: str, problem: ContactProblem,
                        times: dict, say):
    """(sol, x): steps 3 to 5 of the module docstring on the factorized ``solver``."""
    partial = getattr(solver, "partial", False)
    times["factorization"] = solver.setup_time
    t1 = time.perf_counter()
    W = compliance(system, solver, BLOCK[model], say)
    times["compliance"] = time.perf_counter() - t1
    if partial:
        solver.full_solves()
    copies = 2.0 if model == "3d" else 1.0  # the half layer carries half the load
    load = problem.loading.load

    def contact(W, q):
        if not np.all(np.isfinite(W)) or np.any(np.diag(W) <= 0):
            raise FemReferenceError("the surface compliance is not positive: the rolling layer "
                                    "model is singular (check the boundary conditions and the speed)")
        return solve_contact(W, system.m, q, load=None if load is None else load / copies,
                             indentation=problem.loading.indentation,
                             max_iterations=problem.fem.max_iterations, progress=say)

    t2 = time.perf_counter()
    sol = contact(W, system.q)
    times["contact"] = time.perf_counter() - t2
    t3 = time.perf_counter()
    x = solver.solve(-(system.C.T @ sol.pressure))
    if partial:
        sol, x = _defect_correction(system, solver, W, sol, x, contact, times)
    times["fields"] = time.perf_counter() - t3
    return sol, x


def _surface_line(system: RollingSystem, u: np.ndarray):
    """x (m, increasing) and u_z (m) of the top-surface vertices on y = 0 (all of them
    in plane strain)."""
    mesh, ub = system.mesh, system.ubasis
    dim = mesh.p.shape[0]
    top = np.unique(mesh.facets[:, np.concatenate([mesh.boundaries["zone"],
                                                   mesh.boundaries["free"]])])
    if dim == 3:
        tol = 1e-9 * (np.ptp(mesh.p[0]) + np.ptp(mesh.p[1]))
        top = top[np.abs(mesh.p[1, top]) <= tol]
    top = top[np.argsort(mesh.p[0, top], kind="stable")]
    return mesh.p[0, top], u[ub.nodal_dofs[dim - 1, top]]


def solve_rolling(problem: ContactProblem,
                  progress: Optional[Callable[[str], None]] = None) -> RollingResult:
    """Solve the steady frictionless rolling of ``problem`` (module docstring): a line
    indenter in plane strain, or a sphere when ``fem.model = "3d"``.

    Returns
    -------
    RollingResult
        A :class:`~.plane_strain.result.CylinderRollingResult` in plane strain, a
        :class:`~.three_d.result.SphereRollingResult` in 3D.

    Raises
    ------
    InputError, LinearSolverError, ContactNotConvergedError, ContactZoneError
        See :mod:`fem_reference.errors`.
    """
    say = progress or (lambda _: None)
    times = {}
    t0 = time.perf_counter()
    model = problem.fem.model
    three_d = model == "3d"
    V = problem.loading.speed
    if three_d:
        disc = resolve_box(problem)
        shown = (f"the half disk r <= {disc.contact_zone:.3e} m" if disc.zone_y is None else
                 f"the rectangle |x| <= {disc.contact_zone:.3e} m, y <= {disc.zone_y:.3e} m")
        say(f"3d rolling: meshing the half box (h = {disc.element_size:.3e} m on {shown}, x in "
            f"[-{disc.downstream:.3e}, {disc.upstream:.3e}] m, y <= {disc.lateral:.3e} m, V = {V:g} m/s)")
        system = build_box_system(problem, disc)
    else:
        disc = resolve_plane(problem)
        say(f"plane_strain: meshing (h = {disc.element_size:.3e} m on |x| <= {disc.contact_zone:.3e} m, "
            f"upstream {disc.upstream:.3e} m, downstream {disc.downstream:.3e} m, V = {V:g} m/s)")
        system = build_rolling_system(problem, disc)
    times["mesh"] = system.mesh_time
    times["assembly"] = system.assembly_time
    say(f"{system.mesh.t.shape[1]} elements, {system.n_unknowns} unknowns, "
        f"{len(system.m)} contact candidate nodes")
    solver = _factorize(system, model, say)
    try:
        sol, x = _contact_and_fields(system, solver, model, problem, times, say)
    finally:
        if hasattr(solver, "free"):  # Pardiso's factors live outside Python: release them
            solver.free()
    copies = 2.0 if three_d else 1.0  # the half layer carries half the load
    h, zone = disc.element_size, disc.contact_zone
    nodes = system.nodes
    x_nodes = nodes[:, 0] if three_d else nodes
    dist = system.zone_distance() if three_d else np.abs(nodes)
    where = ("|x|" if system.rectangular else "the half disk r") if three_d else "|x|"
    margin = (problem.fem.fit_nodes + 0.5) * h
    if sol.active.any() and dist[sol.active].max() > zone - margin:
        raise ContactZoneError(
            f"the contact reaches the edge of the candidate zone ({where} <= {zone:.4e} m): a contact "
            f"node at {dist[sol.active].max():.4e} m, less than {margin:.3e} m inside; raise "
            "fem.contact_zone or lower the load")
    u, p, w = system.split(x)
    R = problem.indenter.radius
    xs, uz = _surface_line(system, u)
    inside = np.abs(xs) < R
    gap = np.full(xs.shape, np.inf)
    gap[inside] = profile(xs[inside], R) - sol.indentation - uz[inside]
    on_line = np.abs(nodes[:, 1]) <= 1e-9 * zone if three_d else np.ones(len(nodes), bool)
    x_act = x_nodes[sol.active & on_line]
    if x_act.size == 0:
        raise FemReferenceError("no contact node on the symmetry line y = 0: refine fem.element_size")
    fit = problem.fem.fit_nodes
    lead = fit_contact_radius(float(x_act.max()), xs, gap, h, fit)
    trail = -fit_contact_radius(float(-x_act.min()), -xs, gap, h, fit)
    if lead > zone - 0.5 * h or trail < -zone + 0.5 * h:
        raise ContactZoneError(f"the fitted contact edges [{trail:.4e}, {lead:.4e}] m reach the "
                               f"candidate zone ({where} <= {zone:.4e} m): raise fem.contact_zone")
    lam = sol.pressure
    total_load = copies * float(system.m @ lam)
    moment = copies * float(system.mx @ lam)
    t4 = time.perf_counter()
    diss = copies * system.dissipation(u, w, V) if system.branches else 0.0
    times["dissipation"] = time.perf_counter() - t4
    times["total"] = time.perf_counter() - t0
    line = np.flatnonzero(on_line)
    line = line[np.argsort(x_nodes[line], kind="stable")]
    mesh = system.mesh
    stats = RollingMeshStats(
        model=model, elements=int(mesh.t.shape[1]), vertices=int(mesh.p.shape[1]),
        displacement_dofs=int(system.ubasis.N), pressure_dofs=int(system.pbasis.N),
        internal_dofs=int(system.COMPONENTS * len(system.branches) * system.wbasis.N),
        unknowns=int(system.n_unknowns), contact_nodes=int(len(system.m)), element_size=h,
        contact_zone=zone, upstream=disc.upstream, downstream=disc.downstream,
        lateral=disc.lateral if three_d else None, far_size=disc.far_size, grading=disc.grading)
    record = SolverRecord(iterations=sol.iterations, residual=sol.residual, history=sol.history,
                          method=sol.method, linear_solver=solver.name,
                          linear_iterations=solver.iterations, linear_residual=solver.max_residual,
                          factor_nonzeros=int(solver.fill), times=times)
    result = dict(speed=V, load=total_load, indentation=sol.indentation,
                  rolling_resistance=moment / R, pressure_centroid=moment / total_load,
                  leading_edge=lead, trailing_edge=trail, peak_pressure=float(lam.max()),
                  dissipation=diss, pressure_power=copies * float(V * (system.ms @ lam)),
                  pressure_x=x_nodes[line], pressure=lam[line], surface_x=xs, surface_uz=uz,
                  mesh=stats, solver=record,
                  fields={"mesh": mesh, "u": u, "p": p, "w": w, "ubasis": system.ubasis,
                          "pbasis": system.pbasis, "wbasis": system.wbasis, "system": system})
    if three_d:
        result = SphereRollingResult(
            **result, zone_xy=nodes, zone_pressure=lam,
            lateral_edge=float(nodes[sol.active, 1].max()),
            peak_memory=1024.0 * resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
            factor_memory=float(getattr(solver, "memory", np.nan)))
    else:
        result = CylinderRollingResult(**result)
    per, on = ("", " on y = 0") if three_d else ("/m", "")
    say(f"done: R_r {result.rolling_resistance:.6e} N{per} (D/V {result.rolling_resistance_energy:.6e} "
        f"N{per}), edges{on} [{trail:.5e}, {lead:.5e}] m, indentation {sol.indentation:.5e} m "
        f"({times['total']:.1f} s)")
    return result
