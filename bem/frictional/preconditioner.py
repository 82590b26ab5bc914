"""The preconditioner of the matrix-free frictional solve: exact solves on lines of
contact nodes along ``x`` (block Jacobi by grid rows).

Why lines. A stick row is the upwind difference ``u_{i+1} - u_i`` along ``x``; its
inverse is a running sum over the run of contact nodes from its leading end, plus the
displacement just ahead of the run, which the forces of the whole line set. A
preconditioner that drops that displacement (a running sum from zero, then the inverse
circulant embedding of the 3 x 3 compliance, the former one) leaves one slow mode per
run and component: 212 GMRES iterations on the converged 61 x 61 state of the
benchmark case (``benchmarks/bem_friction_rolling.py``) and none converged in 4000 at
121 x 121. The exact inverse of the system restricted to one grid row holds the running
sum, the displacement ahead of each run and the slip rows of that row exactly; what it
leaves out is the coupling between rows: 66 and 73 iterations on the same states. Blocks
of two rows gave 42 and 62 iterations for four times the factorisation cost; applying
the circulant step before or after the line solves made things worse (147-542).

Why a filter after them. A line sees its own row's compliance only, the symbol averaged
over ``k_y``, and so gets forces smooth in ``y`` too large and forces alternating from
row to row too small; multiplying its forces in Fourier space by ``(C_row / C) ** p``
(:data:`FILTER_POWER`, ``docs/derivations.md`` section 5) corrects that in the interior
at the cost of two FFTs of the contact's box: GMRES iterations on converged states
84 -> 38 at 257 x 257 and 105 -> 52 at 513 x 513 (section 11).

Cost: per line of ``m`` contact nodes the inverses of an ``m x m`` and a ``2 m x 2 m``
block (``O(K m^3)`` flops, ``O(K m^2)`` memory for ``K`` lines), and products with them
per GMRES iteration (``O(K m^2)``). On a grid row the layer's ``uv`` blocks vanish (its
kernels are odd in ``y``), so lines of :data:`SPLIT_FROM` nodes or more invert the
tangential block by :func:`tangential_inverse`: two ``s x s`` inverses (``s`` stick nodes)
and a Schur complement on the slip nodes instead of one ``2 m x 2 m`` inverse (section 11
at 257 x 257: the fine grid's inversions 4.9 -> 3.2 s CPU). A line whose nodes and stick
pattern did not change since the previous active-set iteration keeps its inverses unless
one of its slip directions turned by more than :data:`TURN` since they were built (the
kept blocks' slip law lags; it is only a preconditioner, but a stale one cost 15 % more
GMRES iterations).
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from scipy.linalg import lapack

from .system import SetSystem, force_rows

__all__ = ["LinePreconditioner", "FILTER_POWER", "LU_FROM", "SPLIT_FROM", "THREAD_FROM", "BUILD_FROM", "tangential_inverse"]

#: the lines' forces are multiplied, in Fourier space on the contact's box, by
#: ``(C_row / C) ** FILTER_POWER`` per component (``ww``, ``uu``, ``vv``;
#: :meth:`~bem.frictional.operators.RollingOperators.row_filter`; 0: off). A
#: line solve sees only its own row's compliance ``C_row``, the symbol ``C`` averaged over
#: ``k_y``: it overshoots forces smooth in ``y`` (whose displacement the neighbouring rows
#: add to) and undershoots forces alternating from row to row, and the preconditioned
#: operator's spectrum spreads from 0.12 to about 20 (section 11 at 129 x 129, 200 Arnoldi
#: steps on the converged state), besides the run ends' outliers. The filter is the
#: interior's exact correction at power 1; the run ends prefer less. Measured (GMRES
#: iterations from zero to 1e-10 |b| on the converged fine state, lines alone -> power 0.3 /
#: 0.5 / 0.6 / 0.75 / 1): section 11 at 129 x 129 67 -> 42 / 32 / 29 / 37 / 56, at 257 x 257
#: 84 -> 38 (0.5) / 39 (0.6) / 44 (0.7), at 513 x 513 105 -> 52 (0.5); the issue-11 case
#: at 121 x 121 63 -> 35 / 33 / 37 (0.5 / 0.6 / 0.7). Before the lines instead of after,
#: or on both sides: no better (129 x 129: 35 at 0.5; 0.3 on each side 39); the normal or
#: the tangential components alone: 67 and 56
FILTER_POWER = 0.5
#: lines of this many contact nodes or more keep LU factors (``getrf``: a quarter of the
#: flops of an inverse) applied by ``getrs`` line by line, without the padded batch
#: copies; shorter lines keep inverses applied by batched products (one BLAS call per
#: group). Measured: 257 x 257 (lines of up to 215 nodes), LU from 128 nodes CPU
#: 35.5-36.4 s against 31-34 s with inverses; 513 x 513 (lines up to 420 nodes), the two
#: runs side by side: the same CPU (342 / 335 s) but peak RSS 5.7 against 8.5 GB and wall
#: 554 against 1215 s
LU_FROM = 256
#: lines of this many contact nodes or more invert their tangential block by
#: :func:`tangential_inverse` (the ``x`` and ``y`` rows apart, coupled through the slip
#: nodes); shorter ones by one ``2 m x 2 m`` inverse. Measured on section 11's kernels,
#: 80 % stick, one thread: 0.59x as fast at 64 nodes (numpy's call overhead), 1.25x at
#: 96, 1.5x at 128-160, 1.9x at 215, 2.2x at 256
SPLIT_FROM = 96
#: a line whose nodes and stick pattern repeat keeps its blocks unless one of its slip
#: directions turned by more than this (rad) since they were built. Measured (GMRES
#: iterations in all, never refreshed -> 0.2 rad): issue-11 case 61 x 61 190 -> 176,
#: section 11 129 x 129 265 -> 225, 257 x 257 379 -> 328 (CPU 22.1 -> 18.9 s, loaded
#: machine), 513 x 513 988 -> 823; 0.5 rad 334 at 257, 0.1 rad as 0.2; also refreshing
#: on a slope changed 4x: no change
TURN = 0.2
#: an application splits its line groups over two threads when the blocks it reads take
#: this many bytes or more (numpy's batched products release the GIL). Measured, one
#: application on the converged state, one thread -> two: section 11 at 257 x 257 (blocks
#: of 190 MB) 17.3 -> 10.7 ms, at 129 x 129 (17 MB) 1.83 -> 0.97 ms, issue-11 case at
#: 121 x 121 (15 MB) 1.31 -> 1.19 ms; at 61 x 61 (2 MB) 0.18 -> 0.40 ms: the thread's
#: hand-over costs more than it saves
THREAD_FROM = 4_000_000
#: :meth:`LinePreconditioner.attach` inverts the lines it must (re)build on two threads
#: when their inversions take about this many flops or more (``8 m^3`` a line of ``m``
#: nodes: the ``2 m x 2 m`` tangential block)
BUILD_FROM = 1e8


class LinePreconditioner:
    """Block-Jacobi preconditioner by grid rows for :class:`SetSystem`.

    Each line's block is taken without the layer's normal-tangential coupling (the
    ``C_wu, C_wv`` blocks in the gap rows and ``C_uw, C_vw`` in the slip-velocity rows)
    and solved block-triangularly: the normal forces from the gap rows, then the
    tangential forces from their rows less the slip nodes' ``mu N``. Against the full
    ``3 m x 3 m`` block this costs a third of the inversion (``m^3 + (2 m)^3``) and a
    half of the memory, for about 15 % more GMRES iterations (section 11 at 129 x 129:
    577 against 504 in all).

    Use :meth:`attach` for each new system: it builds (or reuses) the inverses and sets
    ``system.precondition``. The inverses are applied as batched matrix products, lines
    grouped by size (padded to a multiple of ``pad`` nodes), so a GMRES iteration costs a
    few BLAS calls, not one call per line. ``factorised`` counts the lines inverted; a
    line's blocks are kept while its nodes and stick pattern repeat and no slip direction
    turned by more than ``turn`` (rad, default :data:`TURN`) since they were built.

    The inverses are computed in double precision and kept in ``dtype`` (single by
    default): the products are memory-bound on large grids (257 x 257: 36 -> 18 ms an
    application) and the memory halves; the flexible GMRES of :func:`bem.linear.fgmres`
    keeps every preconditioned vector, so the rounding of the products costs no accuracy
    (the same iteration counts were measured in double and single precision). With
    ``threads`` an application whose blocks take :data:`THREAD_FROM` bytes or more runs
    its line groups on two threads, and :meth:`attach` inverts the lines it rebuilds on two
    threads when they take :data:`BUILD_FROM` flops or more (the same results: each line
    is built and applied by one thread). ``filter_power`` (default :data:`FILTER_POWER`, read
    at construction; 0: the lines alone) sets the row filter applied after the lines.
    """

    def __init__(self, pad: int = 8, dtype=np.float32, lu_from: int | None = None, turn: float = TURN,
                 threads: bool = True, filter_power: float | None = None):
        self.threads = threads
        self.filter_power = FILTER_POWER if filter_power is None else filter_power
        self._cache: dict = {}
        self._built: dict = {}
        self._normal: dict = {}
        self.turn = turn
        self._batches: tuple = (None, None)
        self.factorised = 0
        self.pad = pad
        self.dtype = dtype
        self.lu_from = LU_FROM if lu_from is None else lu_from

    def attach(self, system: SetSystem) -> None:
        Kx = system.ops.grid.nodes_x
        nC, n = system.nC, system.n
        rows = system.C // Kx
        cuts = np.flatnonzero(np.diff(rows)) + 1
        lines = np.split(np.arange(nC), cuts)
        slip_pos = np.full(nC, -1)
        slip_pos[system.B] = np.arange(system.B.size)
        cache, groups, keys, long_lines, built, normal = {}, {}, [], [], {}, {}
        refreshed = False
        plan = []  # per line: J, stick pattern, nodes, key, LU or not, slip law, blocks (None: to build)
        for J in lines:
            st = system.stick[J]
            nodes = system.C[J].tobytes()
            key = nodes + st.tobytes()
            keys.append(key)
            pair = self._cache.get(key)
            p = slip_pos[J[~st]]
            law = (system.dir_x[p], system.dir_y[p])
            if pair is not None and _turned(self._built[key], law, self.turn):
                pair, refreshed = None, True
            plan.append([J, st, nodes, key, J.size >= self.lu_from, law, pair])
        todo = [line for line in plan if line[6] is None]

        def build(part):
            for line in part:
                J, st, nodes, _, lu = line[:5]
                line[6] = self._inverses(system, J, st, slip_pos, self.dtype if lu else None, self._normal.get(nodes))

        # the lines' inversions on two threads when they are large (see BUILD_FROM)
        flops = sum(8.0 * line[0].size ** 3 for line in todo)
        if self.threads and (os.cpu_count() or 1) > 1 and flops >= BUILD_FROM:
            halves = _balanced(todo, lambda line: line[0].size ** 3)
            job = _second_thread().submit(build, halves[1])
            build(halves[0])
            job.result()
        else:
            build(todo)
        self.factorised += len(todo)
        fresh = {id(line) for line in todo}
        for line in plan:
            J, st, nodes, key, lu, law, pair = line
            built[key] = law if id(line) in fresh else self._built[key]
            cache[key] = pair
            # the normal block depends on the line's nodes alone: kept (own copy) for a
            # line whose stick pattern or slip directions change
            normal[nodes] = self._normal.get(nodes)
            if normal[nodes] is None:
                normal[nodes] = pair[0] if lu else np.array(pair[0], self.dtype)
            if lu:
                long_lines.append((J, np.concatenate([nC + J, 2 * nC + J]), pair))
                continue
            size = -(-J.size // self.pad) * self.pad
            groups.setdefault(size, []).append((J, key, pair))
        whole = b"|".join(keys)
        batches = self._batches[1] if self._batches[0] == whole and not refreshed else []
        for size, members in (groups.items() if not batches else ()):
            L = len(members)
            idx_n, idx_t = np.full((L, size), n), np.full((L, 2 * size), n)  # padding: slot n
            inv_n, inv_t = np.zeros((L, size, size), self.dtype), np.zeros((L, 2 * size, 2 * size), self.dtype)
            coup = np.zeros((L, 2 * size), self.dtype)  # -mu diag on the slip nodes' e . S rows
            for b, (J, key, (a_n, a_t, c)) in enumerate(members):
                m = J.size
                idx_n[b, :m] = J
                idx_t[b, :2 * m] = np.concatenate([nC + J, 2 * nC + J])
                inv_n[b, :m, :m], inv_t[b, :2 * m, :2 * m], coup[b, :m] = a_n, a_t, c
                cache[key] = (inv_n[b, :m, :m], inv_t[b, :2 * m, :2 * m], coup[b, :m])  # views: one copy
            batches.append((idx_n, idx_t, inv_n, inv_t, coup))
        self._cache, self._built, self._normal = cache, built, normal
        self._batches = (whole, batches)
        om_step = 1.0 / system.ax  # the inverse of the scaled Omega's stick-row coefficient
        ext = np.zeros(n + 1, self.dtype)
        getrs = lapack.sgetrs if self.dtype == np.float32 else lapack.dgetrs

        def apply(part, out):
            for idx_n, idx_t, inv_n, inv_t, coup in part[0]:
                N = np.matmul(inv_n, ext[idx_n][:, :, None])[:, :, 0]
                rt = ext[idx_t]
                rt[:, :N.shape[1]] -= coup[:, :N.shape[1]] * N
                out[idx_n] = N
                out[idx_t] = np.matmul(inv_t, rt[:, :, None])[:, :, 0]
            for J, idx_t, ((lu_n, piv_n), (lu_t, piv_t), coup) in part[1]:
                N = getrs(lu_n, piv_n, ext[J])[0]
                rt = ext[idx_t]
                rt[:J.size] -= coup * N
                out[J] = N
                out[idx_t] = getrs(lu_t, piv_t, rt)[0]

        # on two threads when the blocks are large: the products are memory-bound and one
        # core does not draw the machine's bandwidth (see THREAD_FROM)
        two = self.threads and (os.cpu_count() or 1) > 1 and _nbytes(batches, long_lines) >= THREAD_FROM
        parts = _halves(batches, long_lines) if two else None

        # the lines' forces through the row filter (see FILTER_POWER), on the contact's box
        box, spectra = system.box, None
        if self.filter_power:
            spectra = box.row_filter(self.filter_power, np.complex64 if self.dtype == np.float32 else np.complex128)

        def precondition(r):
            ext[:n] = r
            out = np.empty(n + 1)
            if parts is None:
                apply((batches, long_lines), out)
            else:
                job = _second_thread().submit(apply, parts[1], out)
                apply(parts[0], out)
                job.result()
            if spectra is not None:
                out[:3 * nC] = box.filter_on(system.in_box, out[:3 * nC].reshape(3, nC), spectra).ravel()
            if system.free_d:
                out[system.iD] = r[system.iD]
            if system.free_om:
                out[system.iO] = r[system.iO] * om_step
            return out[:n]

        system.precondition = precondition

    @staticmethod
    def _inverses(system: SetSystem, J, stick, slip_pos, lu_dtype=None, normal=None):
        """The inverses of the line's normal block (``C_ww``) and tangential block (the
        ``x, y`` rows in ``S_x, S_y``, without ``C_uw, C_vw``) and the slip nodes'
        coupling ``-mu diag`` (0 on stick nodes), for contact positions ``J``; with
        ``lu_dtype`` the blocks' LU factors ``(lu, piv)`` in that precision instead; ``normal``
        is the normal block's inverse (or factors) when already known."""
        ops, ax = system.ops, system.ax
        c = system.C[J]
        m = J.size
        p = slip_pos[J[~stick]]
        dir_x, dir_y, slope = system.dir_x[p], system.dir_y[p], system.slope[p]
        coup = np.where(stick, 0.0, -system.setup.mu * system.diag)
        W = ops.dense("ww", c, c) if normal is None else None
        if lu_dtype is None and m >= SPLIT_FROM and not _row_coupled(ops):
            return normal if W is None else np.linalg.inv(W), tangential_inverse(ax * ops.dense("duu", c, c), ax * ops.dense("dvv", c, c),
                                                        stick, dir_x, dir_y, slope, system.diag), coup
        Dx = ax * np.hstack([ops.dense("duu", c, c), ops.dense("duv", c, c)])
        Dy = ax * np.hstack([ops.dense("dvu", c, c), ops.dense("dvv", c, c)])
        eye, zero = np.eye(2 * m), np.zeros((m, 2 * m))
        T = force_rows(stick, dir_x, dir_y, slope, system.setup.mu, system.diag, zero, Dx, Dy, zero,
                       eye[:m], eye[m:])[m:]
        if lu_dtype is None:
            return normal if W is None else np.linalg.inv(W), np.linalg.inv(T), coup
        getrf = lapack.sgetrf if lu_dtype == np.float32 else lapack.dgetrf
        factors = []
        for block in (W, T):
            if block is None:
                factors.append(normal)
                continue
            lu, piv, info = getrf(block.astype(lu_dtype), overwrite_a=True)
            if info != 0:
                raise np.linalg.LinAlgError(f"singular line block of {m} contact nodes (getrf info {info})")
            factors.append((lu, piv))
        return factors[0], factors[1], coup.astype(lu_dtype)


def _nbytes(batches, long_lines) -> int:
    """Bytes of the inverses and factors that one application reads."""
    return (sum(inv_n.nbytes + inv_t.nbytes for _, _, inv_n, inv_t, _ in batches)
            + sum(lu_n.nbytes + lu_t.nbytes for _, _, ((lu_n, _), (lu_t, _), _) in long_lines))


def _balanced(items, weight) -> tuple[list, list]:
    """``items`` dealt to two lists of about equal total ``weight(item)``: the heaviest
    first, each to the lighter list (ties to the first)."""
    parts, load = ([], []), [0.0, 0.0]
    for item in sorted(items, key=lambda it: -weight(it)):
        k = int(load[1] < load[0])
        parts[k].append(item)
        load[k] += weight(item)
    return parts


def _halves(batches, long_lines):
    """The groups and long lines in two parts ``(groups, long lines)`` of about equal bytes."""
    items = [([b], []) for b in batches] + [([], [ln]) for ln in long_lines]
    return tuple(([b for g, _ in part for b in g], [ln for _, lines in part for ln in lines])
                 for part in _balanced(items, lambda it: _nbytes(*it)))


def _second_thread() -> ThreadPoolExecutor:
    """One worker thread, started on first use and kept (a forked child starts its own:
    the parent's thread does not exist there, and work handed to it would never run)."""
    global _POOL
    if _POOL is None:
        _POOL = ThreadPoolExecutor(1, thread_name_prefix="line-preconditioner")
    return _POOL


def _forget_pool() -> None:
    global _POOL
    _POOL = None


_POOL: ThreadPoolExecutor | None = None
os.register_at_fork(after_in_child=_forget_pool)


def _turned(old, new, turn: float) -> bool:
    """Whether a slip direction of a line turned by more than ``turn`` (rad) since its
    blocks were built (``old``, ``new``: the slip nodes' ``dir_x, dir_y``)."""
    if not np.isfinite(turn) or old[0].size == 0:
        return False
    cross = old[0] * new[1] - old[1] * new[0]
    dot = old[0] * new[0] + old[1] * new[1]
    return bool(np.abs(np.arctan2(cross, dot)).max() > turn)


def _row_coupled(ops) -> bool:
    """Whether the ``uv`` blocks couple ``x`` and ``y`` along a grid row (they vanish
    there for a layer: its kernels are odd in ``y``)."""
    row = ops.grid.nodes_y - 1
    return bool(ops.tables["duv"][row].any() or ops.tables["dvu"][row].any())


def tangential_inverse(Dx, Dy, stick, dir_x, dir_y, slope, diag):
    """The inverse of a line's tangential block (``2 m x 2 m``, unknowns ``S_x, S_y``, rows
    ``x`` then ``y`` as in :func:`~bem.frictional.system.force_rows` without ``N``), for
    ``Dx, Dy`` the line's ``a_x C_uu`` and ``a_x C_vv`` upwind differences (``m x m``; the
    ``uv`` blocks vanish on a grid row: the kernels are odd in ``y``), ``stick`` (bool,
    ``m``), ``dir_x, dir_y, slope`` on the slip nodes in their order, ``diag`` (m/N).

    In the slip nodes' own axes (``S = a e + b e_perp``) the magnitude rows give ``a`` alone
    and the rest splits into the stick ``x`` rows in ``S_x``, the stick ``y`` rows in
    ``S_y`` and the slip rows in ``b``, coupled only through ``b``: two ``s x s`` inverses
    and a ``p x p`` Schur complement (``s`` stick, ``p`` slip nodes) instead of one
    ``2 m x 2 m`` inverse, 3-4 times fewer flops at ``p = m / 5``. Equals ``inv(T)`` to
    rounding.
    """
    m = stick.size
    s, p = np.flatnonzero(stick), np.flatnonzero(~stick)
    ex, ey, ns = dir_x, dir_y, s.size
    Axi = np.linalg.inv(Dx[np.ix_(s, s)])
    Ayi = np.linalg.inv(Dy[np.ix_(s, s)])
    Dx_sp, Dy_sp, Dx_pp, Dy_pp = Dx[np.ix_(s, p)], Dy[np.ix_(s, p)], Dx[np.ix_(p, p)], Dy[np.ix_(p, p)]
    # the unknowns (S_x on stick, S_y on stick, b on slip): [[Ax, 0, Bx], [0, Ay, By], [Cx, Cy, Dpp]]
    Xb = Axi @ (-Dx_sp * ey)
    Yb = Ayi @ (Dy_sp * ex)
    CAx = (-ey[:, None] * Dx[np.ix_(p, s)]) @ Axi
    CAy = (ex[:, None] * Dy[np.ix_(p, s)]) @ Ayi
    Dpp = ey[:, None] * Dx_pp * ey + ex[:, None] * Dy_pp * ex - np.diag(slope)
    Sci = np.linalg.inv(Dpp - CAx @ (-Dx_sp * ey) - CAy @ (Dy_sp * ex))
    Lx, Ly = Sci @ CAx, Sci @ CAy
    k = 2 * ns + p.size
    Z = np.empty((k + p.size, 2 * m))  # rows S_x stick, S_y stick, b, a; columns the rows of T
    cols = np.concatenate([s, m + s, m + p])
    XY = np.vstack([Xb, Yb])
    M3 = np.empty((k, k))
    M3[:2 * ns, :2 * ns] = XY @ np.hstack([Lx, Ly])
    M3[:ns, :ns] += Axi
    M3[ns:2 * ns, ns:2 * ns] += Ayi
    M3[:2 * ns, 2 * ns:] = -XY @ Sci
    M3[2 * ns:, :ns], M3[2 * ns:, ns:2 * ns], M3[2 * ns:, 2 * ns:] = -Lx, -Ly, Sci
    Z[:k, cols] = M3
    # the magnitude rows: a = r / diag, moved over in the other rows
    Ga = np.vstack([Dx_sp * ex, Dy_sp * ey, -ey[:, None] * Dx_pp * ex + ex[:, None] * Dy_pp * ey])
    Z[:k, p] = -(M3 @ Ga) / diag
    Z[k:] = 0.0
    Z[k + np.arange(p.size), p] = 1.0 / diag
    out = np.empty((2 * m, 2 * m))
    out[s], out[m + s] = Z[:ns], Z[ns:2 * ns]
    a, b = Z[k:], Z[2 * ns:k]
    out[p] = ex[:, None] * a - ey[:, None] * b
    out[m + p] = ey[:, None] * a + ex[:, None] * b
    return out
