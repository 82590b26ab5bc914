"""Frictionless normal contact of a rigid indenter on the layer (paper sec. 9, eq. 53).

Unknowns: compressive nodal forces ``F >= 0`` (N) and the indentation ``d`` (m). With
``u = C F`` the downward surface deflection (m) and ``s`` the indenter profile (m), the
gap ``h = s - d + u`` satisfies ``h >= 0``, ``F >= 0``, ``F h = 0`` node by node, and
``sum F = P`` under load control (``d`` given under displacement control).

Solver: the primal-dual active-set method (Hintermueller, Ito and Kunisch 2002), i.e.
Kalker's active-set contact algorithm: on a trial contact set ``A`` solve the linear
problem ``C_AA F_A - d 1 = -s_A`` (with ``1^T F_A = P``), then drop nodes in tension and
add penetrating ones, until the set repeats. The first set is the contact of the same
problem on the coarse level (recursively, :func:`~bem.coarse_levels.coarse_level`: every
other node along an odd-sized axis, the middle of each pair of nodes along an even-sized
one), whose forces, interpolated, start the first solve; on small grids every reachable
node under load control and the geometric overlap ``{s < d}`` under displacement control (with
``d`` prescribed, all reachable nodes would ask for upward displacements of up to the
profile's height, i.e. tension, on most of them). It needs no symmetry of ``C`` (steady
rolling makes it non-symmetric) and ends with the exact complementarity solution of the
discrete problem. Steps on GMRES are solved loosely while the set still changes much
(:data:`LOOSE_RTOL`), the converged set always to ``rtol``. Linear solves are dense LU
on small sets (and on sets of up to
:data:`DENSE_FALLBACK` nodes where GMRES fails) and restarted GMRES with the FFT operator
otherwise (the flexible, right-preconditioned :func:`bem.linear.fgmres`,
which minimises the true residual and orthogonalises by matrix products: 1.2-1.7x
faster than SciPy's GMRES here, 55 -> 47 iterations at 61 x 61, 87 -> 70 at 257 x 257),
preconditioned by the inverse of the kernel's wrapped circulant (two FFTs,
:meth:`bem.operator.ComplianceOperator.circulant_inverse`), so memory stays ``O(N)``.
Products and preconditioner act on the set's bounding box (:mod:`bem.normal_system`,
:meth:`~bem.operator.ComplianceOperator.block`), not the whole grid: the transforms shrink
with the contact (the benchmark's viscoelastic contact below: a 120 x 104 box of the
155 x 155 grid, products on a 240 x 216 embedding instead of 320 x 320).

Why the wrapped circulant. The inverse of the zero-padded embedding that applies ``C``
has eigenvalues near zero and below it (the kernel cut off at the table's border; see
:mod:`bem.operator`), worst for a viscoelastic kernel, whose long tail along the rolling
direction makes the cut larger: on the standard linear solid's half-space
(``benchmarks/bem_viscoelastic_rolling.py``, 155 x 155 nodes, every step solved to 1e-11)
the fine grid took 223 GMRES iterations against 79 for the elastic layer on the same
grid. The wrapped circulant (the kernel at its true values on a period of about ``2 K``;
the compliance of the layer made periodic) takes 67 against 48, the preconditioned
spectra of the converged sets alike (real parts 0.96-2.85 viscoelastic, 1.00-2.56
elastic, 77 x 77). What remains is the contact's Schur complement: the whole grid's
inverse restricted to the set does no better (14 against 11 from zero on the converged
77 x 77 sets, the wrapped circulant 15 and 11); exact solves on the runs of each grid row
with the row filter ``(C_row / C)`` after them (``bem.frictional.preconditioner``'s form)
gave 12 and 11, but the runs' dense inverses cost 26 ms CPU a set at 155 x 155 (113 runs
of up to 100 nodes), the price of 28 GMRES iterations (0.95 ms each, product and
preconditioner), to save about three. With every step solved to ``rtol``, the
viscoelastic solve spends its extra iterations on digits of intermediate sets that the
next step discards; :data:`LOOSE_RTOL` does not ask for them. GMRES iterations, fine grid
/ all levels, viscoelastic against elastic (one BLAS thread, ``benchmarks/
bem_viscoelastic_rolling.py``): 22 / 60 against 20 / 54 at 155 x 155 (1.10 / 1.11; the
elastic ones include a 20 x 20 level that the solve drops, its contact reaching that
grid's edge), 18 / 37 against 14 / 29 at 77 x 77 (1.29 / 1.28). With every step to
``rtol``, no guess from the coarse forces, no coarse level of even-sized grids and the
coarse contact widened by a node as the first set they were 67 / 151 against 48 / 91 and
53 / 105 against 39 / 73, and a solve took 1.4-1.8 times as long (CPU, median of 7
pairs). Each measure on the fine grid at 155 x 155 (elastic / viscoelastic, iterations
without it and with it, measured with the widened first set): the loose steps 46 / 64
and 21 / 25; the coarse forces as the first guess 22 / 28 and 21 / 25; on the even-sized
78 x 78 level, a coarse level of its own (instead of every reachable node as the first
set) 22 / 37 and 12 / 17. The first set from the coarse deflection
(:func:`_coarse_start`) then took 25 / 65 -> 22 / 60 and 21 / 55 -> 20 / 54.

A penetrating node joins the next set only if it penetrates under the compressive forces
alone (:func:`_lifted`, one product on the grid when a step both drops and adds): a tensile
node lifts the surface around it, and on a lagging layer chiefly behind it, where the
layer recovers slowly. A converged set is one for either rule (it has no tension, so
nothing is removed), and there is only one: every Fourier mode of the kernel has a
compliance of positive real part (:func:`bem.spectral.mode_symbols`; the uniform mode,
zero on an incompressible layer, aside), so ``x^T C x > 0`` on any set, and two
solutions ``F1``, ``F2`` of the same load would give ``(F1 - F2)^T C (F1 - F2) =
-F1^T h2 - F2^T h1 <= 0``. The rule changes the path only: on the conveyor idler of
``examples/conveyor-idler-dma.toml`` at -30 degC (65 x 377 nodes) the plain update takes
49-55 sets at the four speeds of its sweep, a node creeping one step a set along a
rounded roll end (see :func:`_lifted`), and this one 7-9 (the same sets; forces within
5e-8 of the largest, the GMRES accuracy: each 2e-8 from dense LU on the set); at -20
degC, 6 m/s and ``a_x`` = 0.125 mm (129 x 377 nodes) 100 sets or more against 9-10.

A set that recurs (a cycle) switches to one-node updates; a cycle there raises
:class:`ContactNotConverged`.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from .coarse_levels import coarse_grid, coarse_kernel, coarse_level, prolonged, restricted, upsampled
from .linear import LinearSolver
from .normal_system import NormalSystem
from .operator import ComplianceOperator
from .result import SHARED_SCALARS, ContactFigures, NormalContact, SolveRecord, grid_summary, pressure_centroid_x

# the result types live in bem.result; importing them from here keeps working
__all__ = [
    "ContactError", "ContactNotConverged", "ContactAtEdge", "SolveRecord", "ContactFigures", "NormalContact",
    "solve_normal", "grid_summary", "pressure_centroid_x", "SHARED_SCALARS", "NormalSystem", "coarse_grid",
    "edge_nodes", "coarse_solution", "coarse_level", "prolonged", "DENSE_LIMIT", "DENSE_FALLBACK",
    "LOOSE_RTOL",
]


class ContactError(RuntimeError):
    """A contact solve that cannot return a valid answer."""


class ContactNotConverged(ContactError):
    """The active set or a linear solve did not converge."""


class ContactAtEdge(ContactError):
    """The contact reaches the border of the candidate region: the region is too small."""


def edge_nodes(shape: tuple[int, int]) -> np.ndarray:
    """Flat mask of the nodes on the border of a grid of ``shape`` (where a contact that
    reaches them raises :class:`ContactAtEdge`)."""
    edge = np.zeros(shape, dtype=bool)
    edge[:, 0] = edge[:, -1] = True
    if shape[0] > 1:  # a single row is a line contact (plane strain): its two ends only
        edge[0, :] = edge[-1, :] = True
    return edge.ravel()


#: contact sets up to this many nodes are solved by dense LU, larger ones by GMRES (FFT
#: products, circulant-inverse preconditioner): dense LU costs ``O(n^3)``. Measured (CPU,
#: one thread, the whole solve with its coarse-grid starts; 3000 -> 300 or 0): section 11
#: at 41 x 41 0.20 -> 0.06 s, at 129 x 129 2.54 -> 0.47 s, at 257 x 257 3.05 -> 1.33 s;
#: the CONTACT comparison case (benchmarks/bem_friction_rolling.py) at 61 x 61 (1977 contact
#: nodes) 1.00 -> 0.13 s
DENSE_LIMIT = 300


#: a set of up to this many nodes on which GMRES fails is solved by dense LU instead
#: (:class:`bem.linear.LinearSolver`'s ``dense_fallback``; 128 MB, about 1 s of one core
#: at 4000). GMRES fails where the wrapped circulant misses the set's spectrum: a 10 mm
#: layer of a three-parameter solid (G0 = 0.65 MPa, f = 65, tau = 0.35 ms) under a sphere
#: (R = 20 mm, 100 N, 2.8 m/s) on 49 x 49 nodes, where the preconditioned matrix of a
#: 1455-node set has half its eigenvalues below 0.05 in real part, some down to -10
DENSE_FALLBACK = 4000


#: an active-set step on GMRES is solved to ``min(LOOSE_RTOL, c^2)`` of ``|b|`` (``rtol``
#: when that is not looser), ``c`` the share of the set's nodes that the step before
#: dropped or added (1 for the first): early sets change by hundreds of nodes and need the
#: forces' signs, not eleven digits. A set that such a solve leaves unchanged is solved
#: again to ``rtol`` (from there) before it is accepted, and every later step to ``rtol``,
#: so the converged set is the one of tight solves throughout (it is unique, see the module
#: docstring). A loose solve gets one restart cycle (100 iterations; 3-5 on the benchmark
#: below): one that needs more has a set whose spectrum the preconditioner misses, and
#: goes to dense LU at once (``DENSE_FALLBACK``; above it, GMRES to ``rtol``) instead of
#: after a failed tight run of 10 000 iterations. Measured
#: (``benchmarks/bem_viscoelastic_rolling.py``, GMRES on the fine grid, viscoelastic /
#: elastic, 155 x 155): every step to 1e-11 64 / 46; a constant loose tolerance
#: (without the ``c^2``) of 1e-3 made the sets cycle (the viscoelastic solve at 155 x 155
#: failed in one-node updates; a cycle among loose steps now switches to tight solves),
#: 1e-4 32 / 25 (a loose cycle at 155 x 155), 1e-5 37 / 28, 1e-6 35 / 26; ``min(1e-4,
#: c^2)`` 25 / 21
LOOSE_RTOL = 1e-4


def coarse_solution(operator: ComplianceOperator, profile: np.ndarray, *, load: float | None = None,
                    indentation: float | None = None, dense_limit: int = DENSE_LIMIT,
                    rtol: float = 1e-11) -> NormalContact | None:
    """:func:`solve_normal` of the same problem on :func:`coarse_level`'s nodes (the kernel
    table read at even offsets, the exact compliance between those nodes; the profile
    there, or the mean of a pair's along an even-sized axis), or ``None`` when the grid
    has no coarse level, the indentation reaches no coarse node or the coarse solve fails."""
    grid = operator.grid
    coarse = coarse_level(grid)
    if coarse is None:
        return None
    prof = restricted(np.asarray(profile, dtype=float).reshape(grid.shape))
    if indentation is not None and not (prof < indentation).any():
        return None
    try:
        return solve_normal(ComplianceOperator(coarse, coarse_kernel(operator.kernel)), prof, load=load,
                            indentation=indentation, dense_limit=dense_limit, rtol=rtol)
    except ContactError:
        return None


def _coarse_start(operator, s, reachable, load, indentation, dense_limit, rtol, known=None):
    """Trial contact set from the same problem on :func:`coarse_level`'s nodes
    (recursively, :func:`coarse_solution`; ``known``: that solution when already solved).

    Its contact set, upsampled (:func:`~bem.coarse_levels.upsampled`), with the fine nodes
    whose gap it predicts at most 0, starts the active set on the full grid, which then
    needs a few iterations instead of tens. The predicted gap is the fine profile (exact)
    less the coarse indentation plus the coarse deflection prolonged
    (:func:`~bem.coarse_levels.prolonged`): the deflection is smooth across the contact's
    edge, where the pressure is not. Returns the start set and the coarse solution, or
    ``(None, None)`` when the grid is small (< 625 nodes) or the coarse solve fails.

    Against the upsampled set widened by one node along the odd-sized axes (every node
    next to the coarse contact), active-set iterations of the elastic paraboloid of
    ``examples/elastic-paraboloid-creepage.toml``, frictionless: 61 x 61 5 -> 4 (19.5 ->
    17 ms), 121 x 121 6 -> 4 (55 -> 43 ms); the thick layer of section 10 5 -> 4 (11.0 ->
    9.6 ms); the predicted gap alone, without the upsampled set, missed contact nodes
    between the coarse ones (61 x 61: 1702 of 1977) and took 5.
    """
    grid = operator.grid
    coarse = coarse_level(grid)
    if coarse is None:
        return None, None
    res = known if known is not None and known.grid.shape == coarse.shape else coarse_solution(
        operator, np.where(reachable, s, np.inf), load=load, indentation=indentation, dense_limit=dense_limit,
        rtol=rtol)
    if res is None:
        return None, None
    gap = s - res.indentation + prolonged(res.deflection, grid.shape).ravel()  # inf where unreachable
    return (upsampled(res.contact, grid.shape).ravel() | (gap <= 0)) & reachable, res


def _lifted(operator: ComplianceOperator, F: np.ndarray, drop: np.ndarray, base: np.ndarray,
            tol: float) -> np.ndarray:
    """Flat mask of the nodes whose gap ``base + C F`` (m; ``base = s - d``) is at least
    ``-tol`` once the forces on ``drop`` (the tensile ones, N) are removed: a penetration
    there is made by the tension that the next set drops, so the node does not join it.

    Without this test, a lagging layer makes the primal-dual active set creep: a node
    that joins far from the contact (on the rounded end of a roll, where the profile is
    hundreds of micrometres above the indentation) needs a tension of 9-120 N to close its
    gap (the largest compressive nodal force 0.1-16 N), which lifts its trailing neighbour
    (the layer recovers slowly behind a load) into a penetration of 0.15 to 1 times the
    indentation; the next set swaps the node for that neighbour, and so on one node a step
    to the region's edge, no set repeating (the conveyor idler at -20 degC, 6 m/s, 129 x
    377 nodes: 100 sets or more; at -30 degC on 65 x 377 nodes, 49-55 sets)."""
    return base + operator.apply(np.where(drop, 0.0, F).reshape(operator.grid.shape)).ravel() >= -tol


def _next_set(active, drop, add, F, h, careful: bool) -> np.ndarray:
    """The next trial set (flat masks): the tensile nodes ``drop`` out and the penetrating
    ``add`` in, or with ``careful`` (after a cycle) one node, the most tensile (forces
    ``F``, N) or else the deepest (gaps ``h``, m)."""
    if not careful:
        return (active & ~drop) | add
    new = active.copy()
    if drop.any():
        new[np.argmin(np.where(drop, F, np.inf))] = False
    else:
        new[np.argmin(np.where(add, h, np.inf))] = True
    return new


def _solve_step(solve: LinearSolver, system: NormalSystem, guess: np.ndarray, rtol: float,
                loose: float | None) -> tuple[np.ndarray, bool, bool]:
    """One active-set step's linear solve (:data:`LOOSE_RTOL`): to ``loose`` (of ``|b|``)
    in one restart cycle when ``loose`` is given, above ``rtol``, and the system goes to
    GMRES; otherwise to ``rtol``. A loose solve that fails (more than one cycle: the
    preconditioner misses the set) is redone to ``rtol`` (dense LU up to
    :data:`DENSE_FALLBACK` nodes). Returns the solution, whether it is exact (to ``rtol``
    or by dense LU) and whether a loose solve failed."""
    what, hint = f"{system.m} contact nodes", "refine less, or raise dense_limit if memory allows"
    exact = loose is None or loose <= rtol or solve.dense_for(system.n)
    try:
        x = solve(system, guess[:system.n], rtol=rtol if exact else loose, maxiter=None if exact else 1,
                  what=what, hint=hint)
    except ContactNotConverged:
        if exact:
            raise
        return solve(system, guess[:system.n], what=what, hint=hint), True, True
    return x, exact or solve.dense_for(system.n), False


def solve_normal(
    operator: ComplianceOperator,
    profile: np.ndarray,
    *,
    load: float | None = None,
    indentation: float | None = None,
    arm: np.ndarray | None = None,
    max_iter: int = 100,
    dense_limit: int = DENSE_LIMIT,
    rtol: float = 1e-11,
    progress: Callable[[str], None] | None = None,
    coarse: NormalContact | None = None,
) -> NormalContact:
    """Frictionless contact under load control (``load``, N) or displacement control
    (``indentation``, m); give exactly one.

    Parameters
    ----------
    operator : ComplianceOperator
        The ``C_WW`` block (m/N).
    profile : ndarray, shape ``(K_y, K_x)``
        Indenter profile ``s`` (m) above its lowest point, ``inf`` where it cannot touch.
    arm : ndarray, optional
        Rolling arm (-) so that ``R_r = sum F arm`` (see :mod:`bem.indenters`).
    max_iter : int
        Active-set iterations allowed.
    dense_limit : int
        Largest contact set solved by dense LU; larger ones use GMRES (default
        :data:`DENSE_LIMIT`), and by dense LU after GMRES fails on them up to
        :data:`DENSE_FALLBACK` nodes; 0: GMRES on every set, never dense LU.
    rtol : float
        GMRES relative tolerance (-, of ``|b|``) of the converged set's solve; the steps
        before it ask at most :data:`LOOSE_RTOL`.
    progress : callable, optional
        Called with one line per active-set iteration.
    coarse : NormalContact, optional
        The same problem already solved on the coarse level
        (:func:`~bem.coarse_levels.coarse_level`): its contact and forces start the active
        set instead of a new coarse solve (ignored when its grid is not that one).

    Raises
    ------
    ContactNotConverged, ContactAtEdge
    ValueError
        Bad arguments, or (displacement control) an indentation that reaches no node.
    """
    if (load is None) == (indentation is None):
        raise ValueError("give exactly one of load (N) and indentation (m)")
    if load is not None and not (math.isfinite(load) and load > 0):
        raise ValueError(f"load must be > 0 N, got {load!r}")
    if indentation is not None and not (math.isfinite(indentation) and indentation > 0):
        raise ValueError(f"indentation must be > 0 m, got {indentation!r}")
    grid = operator.grid
    s = np.asarray(profile, dtype=float).reshape(-1)
    if s.size != grid.nodes_x * grid.nodes_y:
        raise ValueError(f"profile must have the grid's shape {grid.shape}, got {np.shape(profile)}")
    reachable = np.isfinite(s)
    if not reachable.any():
        raise ValueError("the indenter reaches no node of the grid")

    if load is None:
        first = reachable & (s < indentation)  # the geometric overlap of the undeformed surface
        if not first.any():
            raise ValueError(
                f"indentation = {indentation:g} m reaches no node: the indenter's lowest node is "
                f"{s[reachable].min():g} m above its lowest point; increase loading.indentation "
                "or refine the grid"
            )
    else:
        first = reachable
    solve = LinearSolver(dense_limit, rtol, restart=100, maxiter=100, error=ContactNotConverged,
                         dense_fallback=max(dense_limit, DENSE_FALLBACK) if dense_limit else 0)
    start, coarse = _coarse_start(operator, s, reachable, load, indentation, dense_limit, rtol, coarse)
    active = first.copy() if start is None or not start.any() else start
    seen: set[bytes] = set()
    careful = False
    history = []
    guess = np.zeros(active.sum() + 1)
    if coarse is not None and active is start:
        # the coarse forces, prolonged (a nodal force is the pressure times the node's area, a
        # quarter of a coarse node's), and the coarse indentation start the first solve
        guess = np.concatenate([prolonged(coarse.force, grid.shape).ravel()[active] / 4, [coarse.indentation]])
    tight = False  # every solve to rtol from here on (see LOOSE_RTOL)
    changed = 1.0  # share of the set's nodes that the last step dropped or added
    for it in range(1, max_iter + 1):
        idx = np.flatnonzero(active)
        system = NormalSystem(operator, idx, s[idx], load, indentation)
        x, exact, failed = _solve_step(solve, system, guess, rtol, None if tight else min(LOOSE_RTOL, changed ** 2))
        tight = tight or failed  # a loose solve that failed: every solve to rtol from here on
        fA, d = system.split(x)
        F = np.zeros_like(s)
        F[idx] = fA
        u = operator.apply(F.reshape(grid.shape)).ravel()
        h = np.where(reachable, s - d + u, np.inf)
        scale = max(abs(d), 1e-300)
        drop = active & (F <= 0)
        add = ~active & (h < -1e-12 * scale)
        if drop.any() and add.any():
            # a node joins only if it penetrates under the compressive forces alone (see
            # _lifted): the tension about to be dropped lifts the surface next to it
            add &= ~_lifted(operator, F, drop, s - d, 1e-12 * scale)
        history.append(int(active.sum()))
        if progress:
            progress(f"active set {it}: {idx.size} nodes, d = {d:.6e} m, -{int(drop.sum())} +{int(add.sum())}")
        if not drop.any() and not add.any():
            if exact:
                break
            tight = True  # a set that a loose solve leaves unchanged is confirmed by a tight one
            guess = np.concatenate([fA, [d]])
            continue
        new = _next_set(active, drop, add, F, h, careful)
        changed = (int(drop.sum()) + int(add.sum())) / idx.size
        if not new.any() and load is None:
            # every force came out tensile (only possible with d prescribed): restart from the
            # deepest node, which alone carries (d - s) / C_ii > 0 (s < d there, checked above)
            new[np.argmin(np.where(reachable, s, np.inf))] = True
        key = np.packbits(new).tobytes()
        if key in seen and not exact:  # a loose solve's misjudged node: tight solves from here on
            tight = True
            seen.clear()
        elif key in seen:
            if careful:
                raise ContactNotConverged(f"the active set cycles after {it} iterations even with one-node updates")
            careful = True
        seen.add(key)
        active = new
        if not active.any():
            raise ContactNotConverged("the active set emptied: check the load sign and the indenter profile")
        guess = np.concatenate([F[active], [d]])
    else:
        raise ContactNotConverged(f"no converged contact set in {max_iter} active-set iterations")

    contact = F > 0
    if (contact & edge_nodes(grid.shape)).any():
        raise ContactAtEdge(
            "the contact reaches the edge of the candidate region "
            f"(|x| <= {grid.x[-1]:.4g} m, |y| <= {grid.y[-1]:.4g} m): increase grid.half_width"
        )
    # |h| on the contact set and penetration elsewhere, relative to the indentation
    resid = max(np.abs(h[active]).max(initial=0.0), (-h[reachable & ~active]).max(initial=0.0)) / scale
    rr = float((F * np.asarray(arm).ravel()).sum()) if arm is not None else math.nan
    record = SolveRecord(it, tuple(history), "gmres" if solve.used_gmres else "dense", solve.iterations, resid)
    shape = grid.shape
    return NormalContact(grid, F.reshape(shape), u.reshape(shape), h.reshape(shape), float(d), float(F.sum()), rr,
                         record, coarse)

