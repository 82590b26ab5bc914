"""Driver of a stationary solve: mesh, assemble, condense to the contact zone, solve the
contact.

1. :func:`~.system.build_system` meshes and assembles the Taylor-Hood layer.
2. The saddle system is factorized (or preconditioned) once; the surface
   compliance W = C S^-1 C^T of the candidate zone takes one solve per
   candidate node (right-hand sides in blocks).
3. :func:`~fem_reference.contact.solve_contact` finds pressures and indentation.
4. One more solve gives the displacement and pressure fields.
"""

from __future__ import annotations

import time
from typing import Callable, Optional

import numpy as np

from ..contact import solve_contact
from ..edge_fit import fit_contact_radius
from ..errors import ContactZoneError, FemReferenceError
from ..linsolve import DirectSolver, MinresSolver
from ..problem import ContactProblem
from ..record import SolverRecord
from .discretization import resolve
from .result import ContactResult, MeshStats
from .system import LayerSystem, build_system

__all__ = ["solve_stationary"]

BLOCK = 64


def _linear_solver(system: LayerSystem, problem: ContactProblem):
    if problem.fem.solver == "direct":
        return DirectSolver(system.S, system.scale)
    return MinresSolver(system.S, system.n_u_free, system.Mp, problem.material.shear_modulus,
                        system.scale, near_null=system.near_null, rtol=problem.fem.rtol)


def _compliance(system: LayerSystem, solver, progress) -> np.ndarray:
    C = system.C
    n_c = C.shape[0]
    W = np.empty((n_c, n_c))
    for start in range(0, n_c, BLOCK):
        stop = min(start + BLOCK, n_c)
        rhs = C[start:stop].T.toarray()
        W[:, start:stop] = C @ solver.solve(rhs)
        if progress and n_c > BLOCK:
            progress(f"surface compliance: {stop}/{n_c} columns")
    return 0.5 * (W + W.T)


def _top_vertices(system: LayerSystem, u: np.ndarray):
    """Radius (m), u_z (m) and "on a radial line" flag of the top-surface vertices."""
    mesh, ub = system.mesh, system.ubasis
    dim = mesh.p.shape[0]
    top = np.unique(mesh.facets[:, np.concatenate([mesh.boundaries["zone"],
                                                   mesh.boundaries["free"]])])
    xy = mesh.p[:dim - 1, top]
    r = np.sqrt(np.sum(xy ** 2, axis=0))
    order = np.argsort(r, kind="stable")
    top, r = top[order], r[order]
    uz = u[ub.nodal_dofs[dim - 1, top]]
    line = np.ones(len(top), bool) if dim == 2 else \
        np.abs(mesh.p[1, top]) <= 1e-9 * system.radius.max()
    return r, uz, line


def solve_stationary(problem: ContactProblem,
                     progress: Optional[Callable[[str], None]] = None) -> ContactResult:
    """Solve the stationary frictionless contact of ``problem`` (axisymmetric or 3D
    quarter cylinder; module docstring).

    Parameters
    ----------
    problem : ContactProblem
        Layer, material, indenter, loading and ``fem`` settings (SI units).
    progress : callable, optional
        Receives one line of text per stage and per active-set iteration.

    Raises
    ------
    InputError, MeshError, LinearSolverError, ContactNotConvergedError, ContactZoneError
        See :mod:`fem_reference.errors`.
    """
    say = progress or (lambda _: None)
    times = {}
    t0 = time.perf_counter()
    disc = resolve(problem)
    say(f"{problem.fem.model}: meshing (h = {disc.element_size:.3e} m in the zone r <= "
        f"{disc.contact_zone:.3e} m, domain radius {disc.domain_radius:.3e} m)")
    system = build_system(problem, disc)
    times["mesh"] = system.mesh_time
    times["assembly"] = system.assembly_time
    say(f"{system.mesh.t.shape[1]} elements, {system.n_unknowns} unknowns, "
        f"{len(system.m)} contact candidate nodes")
    solver = _linear_solver(system, problem)
    times["factorization"] = solver.setup_time
    t1 = time.perf_counter()
    W = _compliance(system, solver, say)
    times["compliance"] = time.perf_counter() - t1
    if not np.all(np.isfinite(W)) or np.any(np.diag(W) <= 0):
        raise FemReferenceError("the surface compliance is not positive: the layer "
                                "model is singular (check the boundary conditions)")
    t2 = time.perf_counter()
    k = system.symmetry
    load = problem.loading.load
    sol = solve_contact(W, system.m, system.q,
                        load=None if load is None else load / k,
                        indentation=problem.loading.indentation,
                        max_iterations=problem.fem.max_iterations, progress=say)
    times["contact"] = time.perf_counter() - t2
    h = disc.element_size
    r_active = system.radius[sol.active]
    margin = (problem.fem.fit_nodes + 0.5) * h  # room for the gap fit of the radius
    if r_active.size and r_active.max() > disc.contact_zone - margin:
        raise ContactZoneError(
            f"the contact reaches the edge of the candidate zone r = {disc.contact_zone:.4e} m "
            f"(contact node at r = {r_active.max():.4e} m, less than {margin:.3e} m inside): "
            "raise fem.contact_zone or lower the load")
    t3 = time.perf_counter()
    x = solver.solve(-(system.C.T @ sol.pressure))
    times["fields"] = time.perf_counter() - t3
    ub, pb = system.ubasis, system.pbasis
    full = np.zeros(ub.N + pb.N)
    full[system.free] = x
    u, p = full[:ub.N], full[ub.N:]
    r_s, uz_s, line = _top_vertices(system, u)
    gap = problem.indenter.profile(np.minimum(r_s, disc.contact_zone)) - sol.indentation - uz_s
    radius = fit_contact_radius(float(r_active.max()) if r_active.size else 0.0, r_s, gap, h,
                                problem.fem.fit_nodes)
    if radius > disc.contact_zone - 0.5 * h:
        raise ContactZoneError(f"the fitted contact radius {radius:.4e} m reaches the candidate "
                               f"zone r = {disc.contact_zone:.4e} m: raise fem.contact_zone")
    r_s, uz_s = r_s[line], uz_s[line]
    times["total"] = time.perf_counter() - t0
    mesh = system.mesh
    stats = MeshStats(model=problem.fem.model, elements=int(mesh.t.shape[1]),
                      vertices=int(mesh.p.shape[1]), displacement_dofs=int(ub.N),
                      pressure_dofs=int(pb.N), unknowns=int(system.n_unknowns),
                      contact_nodes=int(len(system.m)), element_size=h,
                      contact_zone=disc.contact_zone, domain_radius=disc.domain_radius,
                      far_size=disc.far_size)
    record = SolverRecord(iterations=sol.iterations, residual=sol.residual, history=sol.history,
                          method=sol.method, linear_solver=solver.name,
                          linear_iterations=solver.iterations, linear_residual=solver.max_residual,
                          factor_nonzeros=int(solver.fill), times=times)
    say(f"done: contact radius {radius:.5e} m, indentation {sol.indentation:.5e} m, "
        f"peak pressure {sol.pressure.max():.5e} Pa ({times['total']:.1f} s)")
    return ContactResult(load=k * sol.load, indentation=sol.indentation, contact_radius=radius,
                         peak_pressure=float(sol.pressure.max()), radius=system.radius,
                         nodes=system.nodes, pressure=sol.pressure, surface_radius=r_s,
                         surface_uz=uz_s, mesh=stats, solver=record,
                         fields={"mesh": mesh, "u": u, "p": p, "ubasis": ub, "pbasis": pb})
