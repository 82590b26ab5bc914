"""Start states of the active set: from the frictionless contact, from the coarse grid's
frictional solution, and the continuation in ``mu`` for free-``Omega`` modes."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Callable

import numpy as np

from ..coarse_levels import prolonged
from .model import Friction, FrictionNotConverged
from .active_set import ActiveSetResult, LinearSolves, run_active_set
from .options import SolverOptions
from .system import RollingSetup, SetState

__all__ = ["frictionless_start", "saturation_creepage", "coarse_start", "coarse_forces", "nodes_within",
           "restricted_start", "continuation"]


def frictionless_start(N0: np.ndarray, ell: np.ndarray, speed: float, friction: Friction,
                       saturation: np.ndarray | float = 0.0,
                       slip_creep: float = SolverOptions.slip_creep) -> SetState:
    """The frictionless contact (normal forces ``N0``, N), all in stick except (``Omega``
    given) the nodes whose rigid creep ``|V - Omega l|`` exceeds ``V`` times ``slip_creep``
    (-, :class:`~bem.frictional.options.SolverOptions`) and their ``saturation`` creepage
    (-, :func:`saturation_creepage`), which slip along it with the slip law's own
    linearisation ``k = |creep| / (mu N)`` (with ``k = 0`` the slip rows
    would force ``w`` along ``e`` with a free perpendicular force, which at small ``mu`` is
    orders of magnitude above ``mu N`` and sends the iteration astray).

    Below saturation the contact rolls with a stick zone (Carter): a start in slip there
    grew that zone a strip per iteration (elastic paraboloid, creepage 0.01, 16 x 16 grid:
    8 iterations from all slip, 6 from all stick)."""
    contact = N0 > 0
    stick = contact.copy()
    direction = np.zeros((N0.size, 2))
    slope = np.zeros(N0.size)
    if friction.omega is not None:
        creep = speed - friction.omega * ell
        start_slip = contact & (np.abs(creep) > np.maximum(slip_creep, saturation) * speed)
        stick &= ~start_slip
        direction[start_slip, 0] = np.sign(creep[start_slip])
        slope[start_slip] = np.abs(creep[start_slip]) / (friction.mu * N0[start_slip])
    return SetState(contact=contact, stick=stick, direction=direction, slope=slope)


def saturation_creepage(contact: np.ndarray, shape: tuple[int, int], spacing_x: float, mu: float,
                        radius: float) -> np.ndarray:
    """Carter's creepage of full sliding ``mu a / R`` (-) at each node, ``a`` (m) half the
    length of the contact along ``x`` on the node's grid row (``contact`` flat, bool, on a
    grid of ``shape`` with node spacing ``spacing_x``, m), ``R`` = ``radius`` (m): in
    Carter's solution a rolling cylinder of radius ``R`` and contact half-width ``a``
    slides over its whole contact from a creepage of about ``mu a / R`` on and keeps a
    stick zone below it (Johnson, Contact Mechanics, ch. 8; the factor depends on the
    elastic constants). A start heuristic per row of the 3-D contact, not a result."""
    Ky, Kx = shape
    half = 0.5 * spacing_x * contact.reshape(Ky, Kx).sum(1)
    return np.repeat(mu * half / radius, Kx)


def coarse_start(coarse_result, shape: tuple[int, int], N0: np.ndarray, mu: float) -> SetState:
    """Start sets on the fine grid (``shape``) from the solution on every other node: the
    contact of the fine frictionless solve (``N0``, N), in slip where any of the (one, two
    or four) coarse nodes around a fine node slips, along the mean of their forces, with
    ``k = |w| / (mu N)`` for the largest of their slip speeds ``|w|``; in stick elsewhere.

    Taking any slipping neighbour moves the start's stick/slip border by up to one fine
    node into the stick zone, where the converged border lies: the nearest coarse node
    (the upstream one between two) starts with too much stick and the fine iteration adds
    the missing slip nodes a strip at a time. Measured (fine-grid active-set iterations and
    GMRES iterations, nearest -> any, the converged state unchanged): elastic paraboloid,
    creepage 0.01, 61 x 61 6 -> 5 and 176 -> 139, 121 x 121 6 -> 5 and 227 -> 181; section
    11 at 129 x 129 7 -> 7 and 225 -> 215. Widening the slip zone by one more fine node overshot
    (61 x 61: 6 iterations, 165 and 205 GMRES).
    """
    res = coarse_result
    coarse_slip = res.contact & ~res.stick
    speed = np.hypot(res.slip_x, res.slip_y)
    # sums over the slipping neighbours: none leaves S = 0 and |w| = 0, a stick node
    Sx, Sy, wmag = np.zeros(shape), np.zeros(shape), np.zeros(shape)
    for near in _around(shape):
        s = coarse_slip[near]
        Sx += np.where(s, res.force_x[near], 0.0)
        Sy += np.where(s, res.force_y[near], 0.0)
        wmag = np.maximum(wmag, np.where(s, speed[near], 0.0))
    Sx, Sy, wmag = Sx.ravel(), Sy.ravel(), wmag.ravel()
    smag = np.hypot(Sx, Sy)
    contact = N0 > 0
    slip = contact & (smag > 0) & (wmag > 0)
    direction = np.zeros((N0.size, 2))
    slope = np.zeros(N0.size)
    direction[slip] = np.stack([Sx, Sy], 1)[slip] / smag[slip, None]
    slope[slip] = wmag[slip] / (mu * N0[slip])
    return SetState(contact=contact, stick=contact & ~slip, direction=direction, slope=slope)


def _around(shape: tuple[int, int]):
    """The four index pairs (``np.ix_``) that read, on every other node, the coarse nodes
    around each node of a grid of ``shape`` (odd sizes): below-left, below-right, above-left,
    above-right, the same node twice or four times where a fine node lies on a coarse
    row, column or node."""
    Ky, Kx = shape
    for jy in (np.arange(Ky) // 2, (np.arange(Ky) + 1) // 2):
        for ix in (np.arange(Kx) // 2, (np.arange(Kx) + 1) // 2):
            yield np.ix_(jy, ix)


def coarse_forces(coarse_result, shape: tuple[int, int], N0: np.ndarray, d0: float, below=None) -> tuple:
    """The first iterate of the fine grid (``shape``) from the frictional solution on every
    other node: ``(N, S_x, S_y, d, Omega)``, flat full-grid forces (N), ``d`` (m) and
    ``Omega`` (rad/s), for :func:`~bem.frictional.active_set.run_active_set`'s ``forces``.

    The normal forces are the fine frictionless solve's ``N0`` (N), exact for the fine grid
    but for friction's share; the tangential forces the coarse ones prolonged
    (:func:`bem.coarse_levels.prolonged`, bilinear) on the contact of ``N0``, a quarter of the coarse value (a nodal force
    is the traction times the node's area, a quarter of a coarse node's); ``d`` is the fine
    frictionless ``d0`` (m) plus what friction adds on the coarse grid (the coarse
    frictional minus the coarse frictionless ``below``'s; ``d0`` alone without ``below``),
    ``Omega`` the coarse one.

    Without it the first solve started from zero and its loose GMRES left the forces rough
    enough to flip nodes that the coarse solution had right. Measured (section 11 at 513 x
    513, fine-grid active-set / GMRES iterations, the same converged state): from zero 9 /
    159; from these forces 7 / 133 (the slip misfit after the first solve 24 -> 1.1), and
    7 / 121 with that solve asked ``start_reduction`` of ``|b|``
    (:class:`~bem.frictional.options.SolverOptions`; ``docs/frictional-solver.md``).
    """
    res = coarse_result
    contact = N0 > 0
    Sx = np.where(contact, prolonged(res.force_x, shape).ravel() / 4, 0.0)
    Sy = np.where(contact, prolonged(res.force_y, shape).ravel() / 4, 0.0)
    d = d0 + (res.indentation - below.indentation if below is not None else 0.0)
    return N0, Sx, Sy, d, res.omega


def nodes_within(fine, grid) -> tuple[np.ndarray, np.ndarray] | None:
    """The indices ``(j, i)`` of ``fine``'s nodes that sit on the nodes of ``grid``
    (``ix_``-style: rows ``(K_y, 1)``, columns ``(1, K_x)``; a line contact's one row)
    when ``grid``'s spacings are whole multiples of ``fine``'s and every node of ``grid``
    is a node of ``fine`` (to 1e-9 of its spacing), as the grid error's levels are of the
    case's grid (:func:`bem.frictional.grid_error.coarsened_grid`); else ``None``."""
    index = []
    for ax in "xy":
        K, k = getattr(fine, f"nodes_{ax}"), getattr(grid, f"nodes_{ax}")
        if K == k == 1:  # the one row of a line contact
            index.append(np.zeros(1, int))
            continue
        step = getattr(grid, f"spacing_{ax}") / getattr(fine, f"spacing_{ax}")
        # node i of a grid of K nodes sits at (i - (K - 1) / 2) spacing (bem.grid.Grid)
        at = (np.arange(k) - (k - 1) / 2) * step + (K - 1) / 2
        i = np.rint(at).astype(int)
        if abs(step - round(step)) > 1e-9 or np.abs(at - i).max() > 1e-9 or i.min() < 0 or i.max() >= K:
            return None
        index.append(i)
    ix, iy = index
    return iy[:, None], ix[None, :]


def restricted_start(finer, grid, N0: np.ndarray, d0: float, mu: float) -> tuple[SetState, tuple] | None:
    """Start sets and first iterate on ``grid`` from a solution on a grid that holds its
    nodes (``finer``, a :class:`~bem.frictional.model.FrictionalContact`; the grid error's
    levels from the case's own solution); ``None`` when ``grid``'s nodes are not among
    ``finer``'s (:func:`nodes_within`). The contact is ``grid``'s frictionless one (``N0``,
    N, flat); a node slips where the node under it slips, along its force, with ``k = |w| /
    (mu N0)`` from its slip speed; the first iterate (``forces`` of
    :func:`~bem.frictional.active_set.run_active_set`) is ``(N0, S_x, S_y, d0, Omega)``, the
    tangential forces read there times the ratio of the node areas (a nodal force is the
    traction times the node's area) and ``Omega`` the solved one.

    A grid twice as coarse has sets that differ from the finer one's by its own grid
    error, a node or two at the stick/slip border, and slip directions and speeds close
    to its own; measured in ``tests/bem/frictional/test_grid_error.py``.
    """
    at = nodes_within(finer.grid, grid)
    if at is None:
        return None
    rows, cols = at
    contact = N0 > 0

    def read(a):
        return np.asarray(a)[rows, cols].ravel()

    Sx, Sy = read(finer.force_x), read(finer.force_y)
    wmag, smag = np.hypot(read(finer.slip_x), read(finer.slip_y)), np.hypot(Sx, Sy)
    slip = contact & read(finer.contact & ~finer.stick) & (smag > 0) & (wmag > 0)
    direction = np.zeros((N0.size, 2))
    slope = np.zeros(N0.size)
    direction[slip] = np.stack([Sx, Sy], 1)[slip] / smag[slip, None]
    slope[slip] = wmag[slip] / (mu * N0[slip])
    areas = grid.cell_area / finer.grid.cell_area
    state = SetState(contact=contact, stick=contact & ~slip, direction=direction, slope=slope)
    return state, (N0, np.where(contact, Sx * areas, 0.0), np.where(contact, Sy * areas, 0.0), d0, finer.omega)


def continuation(setup: RollingSetup, friction: Friction, N0: np.ndarray, solves: LinearSolves,
                 progress: Callable[[str], None] | None, cause: Exception,
                 options: SolverOptions | None = None) -> ActiveSetResult:
    """Continuation in ``mu`` after a failed direct solve (loading modes with a free
    ``Omega``): solve at ``mu 2^K`` (``K >= 1``, the smallest with ``mu 2^K >=``
    ``options.continuation_mu``, 0.2 by default, where a stick zone carries the moment),
    then halve ``mu`` down to the requested value,
    each solve starting from the previous sets and slip directions. At small ``mu`` the
    contact slips almost everywhere and the moment balance is met by one or a few stick
    nodes near the point where the slip reverses; the direct start (all stick) reaches
    the wrong ones and cycles, the continuation moves them there one step at a time.
    Raises :class:`FrictionNotConverged` naming the ``mu`` at which it stopped.
    """
    o = SolverOptions() if options is None else options
    mu = friction.mu
    K = max(1, math.ceil(math.log2(o.continuation_mu / mu)))  # mu > 0 here
    ladder = [mu * 2.0**j for j in range(K, -1, -1)]
    if progress:
        progress(f"friction: direct solve failed ({cause}); continuation in mu from {ladder[0]:.4g}")
    state = frictionless_start(N0, setup.ell, setup.speed, friction)  # Omega free: all stick
    history: list = []
    for m in ladder:
        try:
            out = run_active_set(replace(setup, mu=m), replace(friction, mu=m), state, solves, progress, options=o)
        except FrictionNotConverged as exc:
            raise FrictionNotConverged(
                f"mode {friction.mode!r}, mu = {mu}: the direct solve failed ({cause}) and the "
                f"continuation in mu stopped at mu = {m:.4g} ({exc}); try mode 'omega' with a "
                f"prescribed Omega, or a finer grid") from exc
        history.extend(out.history)
        state = out.state
    return replace(out, history=history)
