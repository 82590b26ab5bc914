"""The frictional solve: frictionless start, coarse-grid start, active set, result."""

from __future__ import annotations

import math
import threading
import time
from dataclasses import replace
from typing import Callable

import numpy as np

from ..contact import ContactError, NormalContact, coarse_grid, coarse_solution, solve_normal
from ..energy import layer_power
from .model import Friction, FrictionalContact, FrictionNotConverged, FrictionRecord, LoadingUnreachable
from ..kinematics import indenter_radius, rolling_geometry
from ..operator import one_worker
from ..plane import LINE_DENSE_LIMIT, LineGrid, line_dissipation
from ..problem import Problem, compute_kernels, line_tables
from ..spectral import BLOCKS
from ..threads import cores, with_one_blas_thread
from .active_set import ActiveSetResult, LinearSolves, run_active_set
from .loading import check_reachable, constraint
from .operators import RollingOperators
from .options import SolverOptions
from .starts import (coarse_forces, coarse_start, continuation, frictionless_start, nodes_within, restricted_start,
                     saturation_creepage)
from .system import RollingSetup, SetState, SetSystem

__all__ = ["solve_friction", "solve_rolling"]


@with_one_blas_thread
def solve_friction(problem: Problem, friction: Friction, progress: Callable[[str], None] | None = None,
                   options: SolverOptions | None = None, kernels: dict | None = None,
                   energy: bool = True, finer: FrictionalContact | None = None) -> tuple[FrictionalContact, dict]:
    """Steady rolling/sliding of ``problem`` with Coulomb ``friction``: the frictional
    entry point (the frictionless one is :func:`bem.problem.solve_frictionless`).

    Returns the result and the timings (s) of the nine kernels, of the solve and of the
    energy figure. ``options`` tunes the solver (:class:`~bem.frictional.options.
    SolverOptions`, default ``SolverOptions()``; it changes the path, not the converged
    state). Pass ``kernels`` (all nine blocks for this grid, layer and speed) to
    reuse them. With ``energy`` the result carries ``rolling_resistance_energy``
    ``= (P_visc + P_fric) / V`` (N), the layer's dissipation summed in Fourier space
    (:func:`bem.energy.layer_power`: by FFTs from the power tables computed with the
    kernels, milliseconds; by the mode sum of :func:`bem.energy.viscous_dissipation` when
    given ``kernels`` lack them, about 2 s at ``N_t = 2000``); otherwise it
    is ``nan``. ``finer``: a solution of the same case on a grid that holds this grid's
    nodes (the grid error's levels, :func:`bem.frictional.grid_error.estimate_grid_error`),
    which then starts the iteration (:func:`solve_rolling`). A plane-strain problem (a
    :class:`bem.plane.LineGrid`) takes the line kernels (:func:`bem.plane.line_kernels`)
    and :func:`bem.plane.line_dissipation`: every force per unit length (N/m, the energy
    figure too).

    Raises
    ------
    FrictionNotConverged, LoadingUnreachable, ContactAtEdge
        A solve that cannot end on a converged state, with what to change.
    ValueError
        Bad input, a speed that is not > 0, or at or above the layer's shear-wave speed.
    """
    p = problem
    kernel_s = 0.0
    if kernels is None:
        kernels, kernel_s = (line_tables(p, BLOCKS, progress) if p.plane_strain
                              else compute_kernels(p, BLOCKS, progress, power=energy))
    t1 = time.perf_counter()
    ops = RollingOperators(p.grid, {b: kernels[b] for b in BLOCKS})
    X, Y = p.grid.coordinates()
    R = indenter_radius(p.indenter, friction.radius)
    profile, arm, ell = rolling_geometry(p.indenter, X, Y, friction.kinematics, friction.radius)
    res = solve_rolling(ops, profile, arm, ell, R, p.loading.speed, friction,
                        load=p.loading.load, indentation=p.loading.indentation, progress=progress,
                        options=options, finer=finer)
    t2 = time.perf_counter()
    timings = {"kernel_s": kernel_s, "solve_s": t2 - t1}
    if energy:
        if p.plane_strain:
            p_visc = line_dissipation(p.grid, p.layer, p.loading.speed, res.force, res.force_x)
        else:
            p_visc = layer_power(p.grid, p.layer, p.loading.speed, kernels, -res.force, res.force_x, res.force_y)
        res = replace(res, rolling_resistance_energy=(p_visc + res.friction_power) / p.loading.speed)
        timings["energy_s"] = time.perf_counter() - t2
        if progress:
            progress(f"energy: (P_visc + P_fric) / V = {res.rolling_resistance_energy:.6g} "
                     f"{'N/m' if p.plane_strain else 'N'}, {timings['energy_s']:.2f} s")
    return res, timings


def solve_rolling(ops: RollingOperators, profile, arm, ell, radius: float, speed: float,
                  friction: Friction, *, load=None, indentation=None,
                  progress: Callable[[str], None] | None = None, settle: float | None = None,
                  normal: NormalContact | None = None, options: SolverOptions | None = None,
                  finer: FrictionalContact | None = None) -> FrictionalContact:
    """Frictional steady rolling/sliding on prepared operators.

    Parameters
    ----------
    ops : RollingOperators
    profile : ndarray ``(K_y, K_x)``
        Indenter profile (m), ``inf`` where it cannot touch.
    arm : ndarray
        Horizontal projection of a unit (vertical) normal force (-), ``dg/dx`` for a
        consistent energy balance (:func:`bem.kinematics.rolling_geometry`).
    ell : ndarray
        Rolling radius (m): the indenter's horizontal surface speed is ``Omega ell``.
    radius : float
        ``R`` (m), the height of the top point above the centre.
    speed : float
        ``V`` (m/s), > 0.
    friction : Friction
    load, indentation : float
        ``P`` (N) or ``d`` (m), exactly one.
    settle : float, optional
        End once the sets repeat with a slip misfit of at most this (-), without the tight
        solve (a coarse level of the start, ``options.coarse_settle``); ``None``: converge.
    normal : NormalContact, optional
        The frictionless solution of the same problem on this grid when already known (a
        coarse level's: the fine frictionless solve's ``coarse``); solved otherwise.
    options : SolverOptions, optional
        The solver's tuning (default ``SolverOptions()``), passed to the coarse levels.
    finer : FrictionalContact, optional
        The same problem solved on a grid that holds this grid's nodes
        (:func:`~bem.frictional.starts.nodes_within`): its sets and forces there start the
        iteration (:func:`~bem.frictional.starts.restricted_start`) instead of a coarse
        level's solution, which is then not solved; ignored on other grids.

    Raises
    ------
    FrictionNotConverged, LoadingUnreachable, ContactAtEdge, ValueError
    """
    if not (math.isfinite(speed) and speed > 0):
        raise ValueError(f"speed must be > 0 m/s for rolling or sliding with friction, got {speed!r}")
    o = SolverOptions() if options is None else options
    g = ops.grid
    size = g.nodes_x * g.nodes_y
    if isinstance(g, LineGrid):
        # plane strain: a line's systems are short, dense LU up to LINE_DENSE_LIMIT contact
        # nodes whatever friction.dense_limit says; above, GMRES with the row preconditioner
        # (the whole contact is one run of its row)
        friction = replace(friction, dense_limit=max(friction.dense_limit, 3 * LINE_DENSE_LIMIT + 2))
    arm, ell = np.asarray(arm, float).ravel(), np.asarray(ell, float).ravel()
    profile = np.asarray(profile, float)
    cons = constraint(friction.mode, arm, ell, radius)
    setup = RollingSetup(ops=ops, profile=profile.ravel(), arm=arm, ell=ell, radius=radius,
                         speed=speed, mu=friction.mu, load=load, indentation=indentation, omega=friction.omega,
                         constraint=cons)
    solves = LinearSolves(friction.dense_limit, o)
    known = normal if normal is not None and normal.grid.shape == g.shape else None
    if finer is not None and nodes_within(finer.grid, g) is None:
        finer = None
    normal, coarse = _first_solves(setup, friction, known, progress, solves, o, levels=finer is None)
    N0 = normal.force.ravel()
    check_reachable(friction.mode, friction.mu, cons, N0)
    if friction.mu == 0:
        zero = np.zeros(size)
        return _result(setup, friction, N0, zero, zero, normal.indentation,
                       friction.omega if friction.omega is not None else math.nan,
                       np.zeros(size, bool), (), "dense", 0)

    saturation = saturation_creepage(N0 > 0, g.shape, g.spacing_x, friction.mu, radius)
    starts = [("all stick", frictionless_start(N0, ell, speed, friction, saturation, o.slip_creep), None)]
    if coarse is not None:
        # the coarse solution's sets start the fine grid's, its forces (prolonged) the first solve
        starts.insert(0, ("the coarse grid's", coarse_start(coarse, g.shape, N0, friction.mu),
                          coarse_forces(coarse, g.shape, N0, normal.indentation, normal.coarse)))
    if finer is not None:
        fg = finer.grid
        starts.insert(0, (f"the {fg.nodes_x} x {fg.nodes_y} solution's",
                          *restricted_start(finer, g, N0, normal.indentation, friction.mu)))
    try:
        for i, (label, start, forces) in enumerate(starts):
            try:
                out = run_active_set(setup, friction, start, solves, progress, settle, forces, o)
                break
            except FrictionNotConverged as exc:
                if i == len(starts) - 1:
                    raise
                if progress:
                    progress(f"friction: {label} start failed ({exc}); starting from {starts[i + 1][0]}")
    except LoadingUnreachable:
        raise
    except FrictionNotConverged as exc:
        if friction.mode == "omega":
            raise
        out = continuation(setup, friction, N0, solves, progress, exc, o)
    return _finish(setup, friction, out, solves)


def _first_solves(setup: RollingSetup, friction: Friction, normal: NormalContact | None, progress,
                  solves: LinearSolves, options: SolverOptions, levels: bool = True):
    """The frictionless solution of the grid (``normal`` when known; GMRES to
    ``options.start_rtol``, or dense LU up to the frictional solve's own limit, 3 unknowns a
    node: at 61 x 61, 1977 contact nodes, dense LU took 0.9 s of a 1.5 s solve, GMRES
    0.05 s) and, with friction, the frictional solution on every other node
    (:func:`_coarse_solution`; ``None`` without). Both start from the frictionless solution
    on every other node; when the first is still to solve it runs on a second thread
    while the coarse levels solve (the transforms and products release the GIL), and
    that thread then builds what ``solves`` will need on its contact set
    (:meth:`LinearSolves.prepare`); the grid's field spectra are built by the thread free
    first (this one at 513 x 513, the second below: the coarse levels end last there). Both
    threads meanwhile transform on one worker each (:func:`bem.operator.one_worker`):
    with every core each, four transform threads shared two cores, and at 513 x 513 the
    coarse levels ended 2.4 s later and the fine frictionless solve took 5.2 s instead of
    3.9 s (one run each). From ``options.overlap_from`` grid nodes on. Without ``levels``
    no frictional coarse level (its start comes from elsewhere) and ``None`` for it."""
    ops, mu = setup.ops, friction.mu
    g = ops.grid
    ww, profile = ops.op("ww"), setup.profile
    kw = dict(load=setup.load, indentation=setup.indentation, dense_limit=friction.dense_limit // 3,
              rtol=options.start_rtol if mu > 0 else options.frictionless_rtol)
    levels = levels and mu > 0
    if normal is None and levels and g.nodes_x * g.nodes_y >= options.overlap_from and cores() > 1:
        below = coarse_solution(ww, profile, **kw)
        if below is not None:
            # the grid's field spectra, which the first fine measure reads, built by the
            # thread that is free first (the other one skips them)
            once = threading.Lock()

            def fields():
                if once.acquire(blocking=False):
                    ops.fields(*(np.zeros(g.shape),) * 3)

            from concurrent.futures import ThreadPoolExecutor  # only where two threads run

            with one_worker(), ThreadPoolExecutor(1, thread_name_prefix="frictionless-start") as pool:
                job = pool.submit(_frictionless_prepared, setup, solves, ww, profile, below, kw, fields)
                try:
                    coarse = _coarse_solution(setup, friction, progress, options, below)
                    fields()
                finally:
                    normal = job.result()
            return normal, coarse
    if normal is None:
        normal = solve_normal(ww, profile, **kw)
    return normal, (_coarse_solution(setup, friction, progress, options, normal.coarse) if levels else None)


def _frictionless_prepared(setup: RollingSetup, solves: LinearSolves, ww, profile, below, kw,
                           then: Callable[[], None]) -> NormalContact:
    """:func:`solve_normal` from the coarse solution ``below``, then ``solves`` prepared
    for the system of its contact set (all in stick), then ``then()``."""
    normal = solve_normal(ww, profile, coarse=below, **kw)
    contact = normal.force.ravel() > 0
    if contact.any():
        zero = np.zeros(contact.size)
        solves.prepare(SetSystem(setup, SetState(contact=contact, stick=contact, direction=np.zeros((zero.size, 2)),
                                                 slope=zero)))
    then()
    return normal


def _coarse_solution(setup: RollingSetup, friction: Friction, progress, options: SolverOptions,
                     normal=None) -> FrictionalContact | None:
    """The same problem on every other node (recursively, as the frictionless solver's
    start; :func:`bem.frictional.starts.coarse_start` turns it into the fine grid's start
    sets): most of the stick/slip border is then in place and the fine grid needs a few
    iterations for the rest and for the slip directions. ``None`` below 625 nodes, on
    even-sized grids, when the coarse solve fails, and when the coarse level would be
    solved by dense LU under a level solved by GMRES (its frictionless contact ``normal``
    known: at most ``friction.dense_limit`` unknowns there, more than that with four times
    its contact nodes): building and factorising a dense system at every iteration there
    cost more than the iterations it saved the level above. Measured
    (whole solves alternated with and without that level, median ratios): the elastic
    paraboloid at 121 x 121 0.937-0.943 (its 16 x 16 level, about 370 unknowns, 58 ms of the calling
    thread's coarse phase; the 31 x 31 level then takes one iteration more), 61 x 61
    0.998, section 11 at 129 x 129 1.03 (its 17 x 17 level; the coarse phase there ends
    with the fine frictionless solve on the other thread), with the same fine-grid paths.
    ``normal``: the coarse grid's frictionless solution when known (the fine frictionless
    solve's ``coarse``, the same solve)."""
    ops = setup.ops
    Ky, Kx = ops.grid.shape
    coarse = coarse_grid(ops.grid)
    if coarse is None:
        return None
    if normal is not None and normal.grid.shape == coarse.shape:
        nodes, glob = int((normal.force > 0).sum()), (setup.load is not None) + (setup.omega is None)
        if 3 * nodes + glob <= friction.dense_limit < 12 * nodes + glob:
            return None

    def fine(a):
        return a.reshape(Ky, Kx)[::2, ::2]

    label = f"coarse {coarse.nodes_x} x {coarse.nodes_y}: "
    try:
        return solve_rolling(ops.coarse(coarse), fine(setup.profile), fine(setup.arm), fine(setup.ell), setup.radius,
                             setup.speed, friction, load=setup.load, indentation=setup.indentation,
                             progress=(lambda m: progress(label + m)) if progress else None,
                             settle=options.coarse_settle, normal=normal, options=options)
    except ContactError:
        return None


def _finish(setup: RollingSetup, friction: Friction, out: ActiveSetResult, solves: LinearSolves):
    h, st = out.gap, out.state
    contact, reach = st.contact, setup.reach
    gap_resid = max(np.abs(h[contact]).max(initial=0.0), (-h[reach & ~contact]).max(initial=0.0)) / out.scale
    return _result(setup, friction, out.N, out.Sx, out.Sy, out.indentation, out.omega, st.stick & contact,
                   tuple(out.history), "gmres" if solves.used_gmres else "dense", solves.iterations, gap_resid,
                   out.fields)


def _result(setup: RollingSetup, friction: Friction, N, Sx, Sy, d, om, stick, history, solver, lin_it,
            gap_resid=0.0, fields=None) -> FrictionalContact:
    """The result dataclass with its fields, figures and residuals (``fields``: the
    deflection and strains of the forces when already computed, flat)."""
    ops, s, arm, ell, V = setup.ops, setup.profile, setup.arm, setup.ell, setup.speed
    g = ops.grid
    shape = g.shape
    N2, X2, Y2 = N.reshape(shape), Sx.reshape(shape), Sy.reshape(shape)
    delta, sx, sy = ops.fields(N2, X2, Y2) if fields is None else (f.reshape(shape) for f in fields)
    u, v = ops.displacements(N2, X2, Y2)
    contact = N2 > 0
    omega_eff = 0.0 if math.isnan(om) else om
    wx = np.where(contact, V * (1 + sx) - omega_eff * ell.reshape(shape), 0.0)
    wy = np.where(contact, V * sy, 0.0)
    st = stick.reshape(shape)
    wx[st] = wy[st] = 0.0  # exactly zero by the stick equations; clear round-off
    stick_res = float(np.hypot(V * (1 + sx) - omega_eff * ell.reshape(shape), V * sy)[st].max(initial=0.0) / V)
    mu = friction.mu
    with np.errstate(invalid="ignore", divide="ignore"):
        cone = np.hypot(X2, Y2)[st] / (mu * N2[st]) - 1 if mu > 0 else np.zeros(0)
    coul = float(np.maximum(cone, 0).max(initial=0.0))
    sl = contact & ~st
    if mu > 0 and sl.any():
        with np.errstate(invalid="ignore", divide="ignore"):
            sm = np.hypot(X2, Y2)[sl]
            mag = np.abs(sm / (mu * N2[sl]) - 1)
            ang = 1 - (X2 * wx + Y2 * wy)[sl] / (sm * np.hypot(wx, wy)[sl])  # 0 when S || w
        coul = max(coul, float(np.nan_to_num(mag, nan=1.0).max()), float(np.nan_to_num(ang, nan=1.0).max()))
    Q = float((N * arm).sum() + Sx.sum())
    T = float(-(ell * Sx).sum())
    if friction.mode == "torque":
        Q = 0.0 if mu > 0 else Q
    rr = Q + (T * om / V if T != 0.0 else 0.0)
    p_fric = float((X2 * wx + Y2 * wy).sum())
    record = FrictionRecord(len(history), history, solver, lin_it, gap_resid, stick_res, coul)
    return FrictionalContact(
        g, N2, X2, Y2, delta, u, v, s.reshape(shape) - d + delta, wx, wy, st, float(d), float(N.sum()),
        float(om), Q, T, rr, p_fric / V, rr - p_fric / V, V, mu, friction.mode, record,
        kinematics=friction.kinematics)
