"""Driver of a plane-strain steady-rolling solve.

1. :func:`~.plane_discretization.resolve_plane` sizes the mesh and checks the lengths;
   :func:`~.rolling_system.build_rolling_system` meshes and assembles.
2. The non-symmetric system is factorized once (SuperLU); the surface compliance
   W = C S^-1 C^T of the candidate zone (non-symmetric while rolling) takes one solve
   per candidate node.
3. :func:`~.contact.solve_contact` finds pressures and indentation (the primal-dual
   active set needs no symmetry).
4. One more solve gives the fields; edges, rolling resistance and the dashpots'
   dissipation follow.
"""

from __future__ import annotations

import time
from typing import Callable, Optional

import numpy as np

from . import rolling_forms as rf
from .contact import solve_contact
from .errors import ContactZoneError, FemReferenceError
from .linsolve import DirectSolver
from .plane_discretization import resolve_plane
from .postprocess import fit_contact_radius
from .problem import ContactProblem
from .result import SolverRecord
from .rolling_result import PlaneMeshStats, RollingResult
from .rolling_system import RollingSystem, build_rolling_system, profile

__all__ = ["solve_rolling"]

BLOCK = 64
#: SuperLU settings of the non-symmetric system: COLAMD, threshold pivoting (the zero
#: pressure block needs some); the symmetric minimum-degree ordering fills far more here
ORDERINGS = (("COLAMD", 0.1), ("COLAMD", 1.0))


def _compliance(system: RollingSystem, solver) -> np.ndarray:
    """W = C S^-1 C^T (m^2/Pa per unit length), one LU solve per column; a block whose
    relative residual exceeds 1e-10 gets a step of iterative refinement."""
    C = system.C
    n_c = C.shape[0]
    W = np.empty((n_c, n_c))
    for start in range(0, n_c, BLOCK):
        stop = min(start + BLOCK, n_c)
        rhs = C[start:stop].T.toarray()
        x = solver._apply(rhs)
        rel = np.linalg.norm(rhs - system.S @ x, axis=0) / np.linalg.norm(rhs, axis=0)
        if rel.max() > 1e-10:
            x = solver.solve(rhs)
        W[:, start:stop] = C @ x
    return W


def _surface(system: RollingSystem, u: np.ndarray):
    mesh, ub = system.mesh, system.ubasis
    top = np.unique(mesh.facets[:, np.concatenate([mesh.boundaries["zone"],
                                                   mesh.boundaries["free"]])])
    x = mesh.p[0, top]
    order = np.argsort(x, kind="stable")
    top, x = top[order], x[order]
    return x, u[ub.nodal_dofs[1, top]]


def dissipation(system: RollingSystem, u: np.ndarray, w: list, V: float, form=None) -> float:
    """Power (W/m) dissipated by the dashpots: sum_i int s_i : D eps_v,i / Dt dA, the
    branch stress 2 G_i (eps - eps_v,i) times the dashpot strain rate -V d eps_v,i / dx
    (``form``: another of :mod:`.rolling_forms`' dissipation densities)."""
    ub, wb = system.ubasis, system.wbasis
    form = form or rf.dashpot_power
    total = 0.0
    uf = ub.interpolate(u)
    for (Gi, ti), (a, c) in zip(system.branches, w):
        total += form.assemble(wb, u=uf, a=wb.interpolate(a), c=wb.interpolate(c),
                               G=Gi, tau=ti, V=V)
    return float(total)


def solve_rolling(problem: ContactProblem,
                  progress: Optional[Callable[[str], None]] = None) -> RollingResult:
    """Solve the steady frictionless rolling of a line ``problem`` (module docstring).

    Raises
    ------
    InputError, LinearSolverError, ContactNotConvergedError, ContactZoneError
        See :mod:`fem_reference.errors`.
    """
    say = progress or (lambda _: None)
    times = {}
    t0 = time.perf_counter()
    disc = resolve_plane(problem)
    V = problem.loading.speed
    say(f"plane_strain: meshing (h = {disc.element_size:.3e} m on |x| <= {disc.contact_zone:.3e} m, "
        f"upstream {disc.upstream:.3e} m, downstream {disc.downstream:.3e} m, V = {V:g} m/s)")
    system = build_rolling_system(problem, disc)
    times["mesh"] = system.mesh_time
    times["assembly"] = system.assembly_time
    say(f"{system.mesh.t.shape[1]} elements, {system.n_unknowns} unknowns, "
        f"{len(system.m)} contact candidate nodes")
    solver = DirectSolver(system.S, system.scale, orderings=ORDERINGS)
    times["factorization"] = solver.setup_time
    t1 = time.perf_counter()
    W = _compliance(system, solver)
    times["compliance"] = time.perf_counter() - t1
    if not np.all(np.isfinite(W)) or np.any(np.diag(W) <= 0):
        raise FemReferenceError("the surface compliance is not positive: the rolling layer model "
                                "is singular (check the boundary conditions and the speed)")
    t2 = time.perf_counter()
    sol = solve_contact(W, system.m, system.q, load=problem.loading.load,
                        indentation=problem.loading.indentation,
                        max_iterations=problem.fem.max_iterations, progress=say)
    times["contact"] = time.perf_counter() - t2
    h = disc.element_size
    x_act = system.nodes[sol.active]
    margin = (problem.fem.fit_nodes + 0.5) * h
    zone = disc.contact_zone
    if x_act.size and (x_act.max() > zone - margin or x_act.min() < -zone + margin):
        raise ContactZoneError(
            f"the contact reaches the edge of the candidate zone |x| <= {zone:.4e} m (contact nodes "
            f"from x = {x_act.min():.4e} to {x_act.max():.4e} m, less than {margin:.3e} m inside): "
            "raise fem.contact_zone or lower the load")
    t3 = time.perf_counter()
    u, p, w = system.split(solver.solve(-(system.C.T @ sol.pressure)))
    times["fields"] = time.perf_counter() - t3
    R = problem.indenter.radius
    xs, uz = _surface(system, u)
    inside = np.abs(xs) < R
    gap = np.full(xs.shape, np.inf)
    gap[inside] = profile(xs[inside], R) - sol.indentation - uz[inside]
    fit = problem.fem.fit_nodes
    lead = fit_contact_radius(float(x_act.max()), xs, gap, h, fit)
    trail = -fit_contact_radius(float(-x_act.min()), -xs, gap, h, fit)
    if lead > zone - 0.5 * h or trail < -zone + 0.5 * h:
        raise ContactZoneError(f"the fitted contact edges [{trail:.4e}, {lead:.4e}] m reach the "
                               f"candidate zone |x| <= {zone:.4e} m: raise fem.contact_zone")
    lam = sol.pressure
    load = float(system.m @ lam)
    moment = float(system.mx @ lam)
    t4 = time.perf_counter()
    diss = dissipation(system, u, w, V) if system.branches else 0.0
    times["dissipation"] = time.perf_counter() - t4
    times["total"] = time.perf_counter() - t0
    mesh = system.mesh
    stats = PlaneMeshStats(model="plane_strain", elements=int(mesh.t.shape[1]),
                           vertices=int(mesh.p.shape[1]), displacement_dofs=int(system.ubasis.N),
                           pressure_dofs=int(system.pbasis.N),
                           internal_dofs=int(2 * len(system.branches) * system.wbasis.N),
                           unknowns=int(system.n_unknowns), contact_nodes=int(len(system.m)),
                           element_size=h, contact_zone=zone, upstream=disc.upstream,
                           downstream=disc.downstream, far_size=disc.far_z)
    record = SolverRecord(iterations=sol.iterations, residual=sol.residual, history=sol.history,
                          method=sol.method, linear_solver=solver.name,
                          linear_iterations=solver.iterations, linear_residual=solver.max_residual,
                          factor_nonzeros=int(solver.fill), times=times)
    result = RollingResult(speed=V, load=load, indentation=sol.indentation,
                           rolling_resistance=moment / R, pressure_centroid=moment / load,
                           leading_edge=lead, trailing_edge=trail, peak_pressure=float(lam.max()),
                           dissipation=diss, pressure_power=float(V * (system.ms @ lam)),
                           pressure_x=system.nodes, pressure=lam, surface_x=xs, surface_uz=uz,
                           mesh=stats, solver=record,
                           fields={"mesh": mesh, "u": u, "p": p, "w": w, "ubasis": system.ubasis,
                                   "pbasis": system.pbasis, "wbasis": system.wbasis,
                                   "system": system})
    say(f"done: R_r {result.rolling_resistance:.6e} N/m, edges [{trail:.5e}, {lead:.5e}] m, "
        f"indentation {sol.indentation:.5e} m ({times['total']:.1f} s)")
    return result
