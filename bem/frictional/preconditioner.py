"""The preconditioner of the matrix-free frictional solve: exact solves on runs of contact
nodes along ``x`` (block Jacobi by grid rows), by FFT.

Why lines. A stick row is the upwind difference ``u_{i+1} - u_i`` along ``x``; its
inverse is a running sum over the run of contact nodes from its leading end, plus the
displacement just ahead of the run, which the forces of the whole line set. A
preconditioner that drops that displacement (a running sum from zero, then the inverse
circulant embedding of the 3 x 3 compliance) leaves one slow mode per
run and component: 212 GMRES iterations on the converged 61 x 61 state of the elastic
paraboloid (``benchmarks/bem_friction_rolling.py``) and none converged in 4000 at
121 x 121. The exact inverse of the system restricted to one run of a grid row holds the
running sum, the displacement ahead of the run and the slip rows exactly; what it leaves
out is the coupling between rows: 66 and 73 iterations on the same states.

Why Toeplitz. On a grid row the compliance between two nodes depends on their distance
alone, so a run of ``m`` contact nodes sees Toeplitz blocks (the ``uv`` blocks vanish on a
grid row: the layer's kernels are odd in ``y``), whose inverses for every run length come
from Levinson's recursion and Gohberg-Semencul's formula (:mod:`bem.frictional.toeplitz`).
The slip rows (the slip law) replace ``2 p`` of the run's ``2 m`` tangential rows:
Woodbury's identity with the Toeplitz inverses' columns at the slip
nodes (``2 p m`` numbers) and a ``2 p x 2 p`` matrix ``K`` a run makes the solve exact;
``K^{-1}`` comes from the ``p x p`` inverses of the slip-slip blocks of the Toeplitz
inverses (kept while a run's length and slip places repeat: they hold no direction or
slope) and of one ``p x p`` matrix that holds the slip directions and slopes, not by
inverting ``K`` (``docs/derivations.md`` section 5). Against the dense inverse of each
line (``5 m^2`` numbers a line, ``O(m^3)`` to build) the results agree to rounding and the
build is cheap (``O(p m log m + p^3)``); ``docs/frictional-solver.md`` has the figures.

Why a filter after them. A line sees its own row's compliance only, the symbol averaged
over ``k_y``, and so gets forces smooth in ``y`` too large and forces alternating from
row to row too small; multiplying its forces in Fourier space by ``(C_row / C) ** p``
(``filter_power``, ``docs/derivations.md`` section 5) corrects that in the interior
at the cost of two FFTs of the contact's box. The symbols are those of the kernels
wrapped onto a period of about 1.5 times the box (:meth:`~bem.frictional.operators.
RollingOperators.row_filter`), not of the products' zero-padded embedding (twice the
box): 2.25 times fewer transform points for the same GMRES iterations. GMRES from zero
to 1e-10 ``|b|`` on converged states, lines alone -> lines and filter: paraboloid
61 x 61 57 -> 24 (25 on the embedding), 121 x 121 74 -> 28; sphere 129 x 129 72 -> 26,
257 x 257 94 -> 34 (the same on the embedding).
"""

from __future__ import annotations

import numpy as np

from .model import FrictionNotConverged
from ..linear import bordered, eliminate
from ..threads import cores
from . import toeplitz
from .options import SolverOptions
from .system import SetSystem
from .toeplitz import RowInverses

__all__ = ["LinePreconditioner"]


def _runs(system: SetSystem) -> tuple[np.ndarray, np.ndarray]:
    """The runs of ``system``'s contact nodes along grid rows: their first nodes (indices
    into the contact) and lengths."""
    row, col = system.Cj, system.Ci
    starts = np.flatnonzero(np.r_[True, (np.diff(row) != 0) | (np.diff(col) != 1)])
    return starts, np.diff(np.r_[starts, system.nC])


def _bordered(system: SetSystem, forces, kept=None):
    """The preconditioner of the whole system from ``forces``, that of its force rows:
    ``d`` (load control) and ``Omega`` (when free) eliminated by their Schur complement
    (:func:`bem.linear.bordered`; their columns ``F`` in the force rows from
    :meth:`SetSystem.rows` with no forces, their rows from :meth:`SetSystem.global_rows`);
    when that complement is singular, the global rows passed on,
    ``Omega``'s scaled by the inverse of its stick-row coefficient ``1 / a_x``. ``kept``:
    the complement's parts from an earlier state with the same contact set, reused
    (returns the preconditioner and the parts it used).

    With the rows passed on the preconditioned operator keeps a real pair of outliers at
    about -113 and 116 whose vectors lie 88 % on ``d`` and ``Omega`` and a complex pair at
    ``1.6 +- 28.6 i`` (normal forces on the contact's edge), both gone with the
    elimination (section 11 at 129 x 129, the converged state); fine-grid GMRES
    iterations 155 -> 126 at 257 x 257."""
    nC, n, k = system.nC, system.n, system.n - 3 * system.nC
    parts = kept
    if parts is None:
        unit = np.zeros((n, k))
        unit[3 * nC:] = np.eye(k)
        zero = np.zeros((nC, k))
        F = system.rows(zero, zero, zero, unit)[:3 * nC]
        parts = eliminate(forces, F, system.global_rows)
    if parts is not None:
        return bordered(forces, system.global_rows, parts), parts
    scale = np.where(np.arange(3 * nC, n) == system.iO, 1.0 / system.ax, 1.0) if system.free_om else 1.0
    return (lambda r: np.concatenate([forces(r), r[3 * nC:] * scale])), None


class LinePreconditioner:
    """Block-Jacobi preconditioner by runs of contact nodes along grid rows for
    :class:`SetSystem` (see the module docstring).

    Each run's block is taken without the layer's normal-tangential coupling (the
    ``C_wu, C_wv`` blocks in the gap rows and ``C_uw, C_vw`` in the slip-velocity rows)
    and solved block-triangularly: the normal forces from the gap rows, then the
    tangential forces from their rows less the slip nodes' ``mu N``. Against the full
    ``3 m x 3 m`` block this costs about 15 % more GMRES iterations (section 11 at
    129 x 129: 577 against 504 in all) and keeps the Toeplitz structure. A contact node
    whose right-hand neighbour on its grid row is not in contact ends its run; runs on one
    row are solved apart.

    Use :meth:`attach` for each new system: it builds what it must and sets
    ``system.precondition``. The columns of the runs' Toeplitz inverses at their slip
    nodes are kept per run length and place while some run asks for them (``factorised``
    counts the columns computed, ``x`` and ``y`` blocks together), and so are the inverses
    of their slip-slip blocks, per run length and slip places (those of the last attach);
    the ``p x p`` matrices that hold the slip directions and slopes are built every time,
    so the solve is exact for every state. The
    applications run in ``dtype`` (single by default: the flexible GMRES of
    :func:`bem.linear.fgmres` keeps every preconditioned vector, so rounding there costs
    no accuracy), the columns too, the Woodbury terms are inverted in double. With
    ``threads`` an application whose operands take ``options.thread_from`` bytes or more
    runs on two threads; the build runs on one (on two threads, solves on two cores took
    1.00-1.05 times as long: ``docs/frictional-solver.md``, "Threads"). ``options``
    (:class:`~bem.frictional.options.SolverOptions`, default ``SolverOptions()``) also sets
    the row filter applied after the lines (``filter_power``, 0: the lines alone;
    ``filter_long``, ``filter_waves``) and the thresholds ``chunk``, ``compose_upto``,
    ``dense_upto``, ``batched_upto``. The global unknowns (``d``, a free ``Omega``) are
    eliminated by their Schur complement (:func:`_bordered`), whose parts are kept while
    the contact set, ``mu`` and the operators repeat.
    """

    def __init__(self, dtype=np.float32, threads: bool = True, options: SolverOptions | None = None):
        self.dtype = np.dtype(dtype)
        self.threads = threads
        self.options = SolverOptions() if options is None else options
        self.inverses: RowInverses | None = None
        self._ops = None
        self._columns: tuple = (np.zeros(0, int), None)  # (length, place) keys, their columns
        self._schur: tuple = (None, None)
        self._blocks: dict = {}
        self.factorised = 0

    def _row_inverses(self, ops, longest: int) -> RowInverses:
        """The :class:`RowInverses` of ``ops`` for runs of up to ``longest`` nodes (kept;
        rebuilt for new operators or a longer run, to a multiple of 16 nodes). Raises
        :class:`~bem.frictional.FrictionNotConverged` when a row block's leading block is
        singular (Levinson's recursion needs every one regular)."""
        if self._ops is not ops or self.inverses.M < longest:
            try:
                o = self.options
                self.inverses = RowInverses(ops, -(-longest // 16) * 16, dense_upto=o.dense_upto,
                                            batched_upto=o.batched_upto)
            except np.linalg.LinAlgError as exc:
                raise FrictionNotConverged(
                    f"the line preconditioner cannot be built on this grid: {exc}; solve by dense LU "
                    "(raise friction.dense_limit above the system's unknowns) or change the grid spacing") from exc
            self._ops, self._columns, self._schur, self._blocks = ops, (np.zeros(0, int), None), (None, None), {}
        return self.inverses

    def prepare(self, system: SetSystem) -> None:
        """Build ahead what :meth:`attach` reads for ``system``'s contact set alone (the
        row inverses for its longest run, the row filter of its box), e.g. on an idle
        thread."""
        lens = _runs(system)[1]
        inv = self._row_inverses(system.ops, int(lens.max()))
        if inv.dense:  # the inverses of the run lengths present
            inv.operand(0, lens, self.dtype)
            inv.operand((1, 2), lens, self.dtype)
        self._row_filter(system)

    def _row_filter(self, system: SetSystem):
        """The row filter's spectra on ``system``'s box (``None`` when off)."""
        o = self.options
        if not o.filter_power:
            return None
        cplx = np.complex64 if self.dtype == np.float32 else np.complex128
        return system.box.row_filter(o.filter_power, cplx, long=o.filter_long, waves=o.filter_waves)

    def attach(self, system: SetSystem) -> None:
        ops, nC, n = system.ops, system.nC, system.n
        starts, lens = _runs(system)
        inv = self._row_inverses(ops, int(lens.max()))
        M, R = inv.M, starts.size
        run = np.repeat(np.arange(R), lens)
        at = run * M + np.arange(nC) - starts[run]  # the contact nodes' places in the runs (R, M)
        place = np.zeros(R * M, bool)
        place[at] = True
        spread = (np.arange(3)[:, None] * (R * M) + at).ravel()  # N, S_x, S_y into (3, R, M)
        spec_n = inv.operand(0, lens, self.dtype)
        spec_t = inv.operand((1, 2), lens, self.dtype)
        groups = self._woodbury(system, inv, starts, lens, run)
        slip = at[system.B]
        coup = np.zeros(R * M, self.dtype)
        coup[slip] = -system.setup.mu * system.diag
        coup = coup.reshape(R, M)
        dt, diag = self.dtype, system.diag
        ex, ey, kk = (a.astype(dt) for a in (system.dir_x, system.dir_y, system.slope))
        size = spec_n.nbytes + spec_t.nbytes
        two = self.threads and cores() > 1 and size >= self.options.thread_from
        box, spectra = system.box, self._row_filter(system)

        def correct(Z, c, qs):
            for (members, *_, Y), q in zip(groups, qs):
                Z[c, members] -= np.matmul(q[:, c, None], Y[c])[:, 0]

        def forces(r):
            """The lines (and the row filter) on the force rows ``r[:3 nC]``."""
            v = np.zeros(3 * R * M, dt)
            v[spread] = r[:3 * nC]  # one flat index: 2.5x faster than a boolean mask a row
            v = v.reshape(3, R, M)
            N = inv.solve(spec_n, v[0], threads=two)
            rt = v[1:]
            rt[0] -= coup * N
            Z = inv.solve(spec_t, rt.reshape(2 * R, M), threads=two).reshape(2, R, M)
            if groups:
                # Woodbury: the slip rows' residuals of the all-stick solution, through the
                # inverse of the runs' 2p x 2p matrices K, back through the Toeplitz inverses'
                # slip columns (x and y on two threads)
                z, rs = Z.reshape(2, -1)[:, slip], rt.reshape(2, -1)[:, slip]
                w = np.concatenate([diag * (ex * z[0] + ey * z[1]) - rs[0],
                                    -ey * rs[0] + ex * rs[1] + kk * (ey * z[0] - ex * z[1]) - rs[1]])
                qs = []
                for members, at, where, Gi, Hi, e1, e2, _ in groups:
                    L, P = e1.shape
                    W = np.zeros((L, 2 * P), dt)
                    W.reshape(-1)[at] = w[where]
                    if Hi.shape[1] == 2 * P:  # K^-1 itself
                        qs.append(np.matmul(Hi, W[:, :, None]).reshape(L, 2, P))
                        continue
                    # K^-1 W by its factors (see _woodbury): alpha, beta the slip-frame parts
                    al = W[:, :P] / dt.type(diag)
                    c = np.matmul(Gi, np.stack([e1 * al, e2 * al], 1)[..., None])[..., 0]
                    be = np.matmul(Hi, (W[:, P:] + e2 * c[:, 0] - e1 * c[:, 1])[..., None])[..., 0]
                    uv = np.stack([e1 * al + e2 * be, e2 * al - e1 * be], 1)
                    qs.append(np.matmul(Gi, uv[..., None])[..., 0])
                job = toeplitz.second_thread().submit(correct, Z, 1, qs) if two else None
                correct(Z, 0, qs)
                if job is None:
                    correct(Z, 1, qs)
                else:
                    job.result()
            out = np.empty((3, nC))
            out[0] = N.reshape(-1)[place]
            out[1] = Z[0].reshape(-1)[place]
            out[2] = Z[1].reshape(-1)[place]
            if spectra is not None:
                out = box.filter_on(system.in_box, out, spectra)
            return out.reshape(-1)

        if system.n == 3 * nC:
            system.precondition = forces
        else:
            # the Schur complement's parts are kept while the contact set repeats (the stick
            # set, directions and slopes then move little): measured, the same GMRES
            # iterations on the elastic paraboloid and section 11 up to 257 x 257 as with a new
            # complement every time, or one for each stick set too; two applications
            # saved an attach
            key = (system.C.tobytes(), system.free_d, system.free_om, system.setup.mu)
            kept = self._schur[1] if self._schur[0] == key else None
            system.precondition, parts = _bordered(system, forces, kept)
            self._schur = (key, parts)

    def _woodbury(self, system: SetSystem, inv: RowInverses, starts, lens, run) -> list:
        """The runs' Woodbury terms, grouped by slip count ``p`` (padded to a multiple of 8,
        ``P``): ``[(members, at, where, G^{-1}, H^{-1} or K^{-1}, e_x, e_y, Y)]`` for the runs
        ``members`` (``L``), with ``G^{-1}`` ``(L, 2, P, P)`` the inverses of ``G_x, G_y``,
        ``H^{-1}`` ``(L, P, P)`` (or, for ``P <= compose_upto``, ``K^{-1}`` ``(L, 2 P,
        2 P)`` itself, composed from them), the slip directions ``(L, P)``, ``Y`` ``(2, L, P,
        M)`` the runs' Toeplitz inverses' columns at their slip nodes (``x`` then ``y``, as
        rows), all in ``dtype``, 0 (identity blocks) on padding; ``where`` the slip rows (``x``
        rows, then the ``y`` rows) and ``at`` their flat places in ``(L, 2 P)``.

        For a run with slip nodes ``P`` (``p``) and ``G_x, G_y`` the ``P x P`` blocks of its
        Toeplitz inverses, the rows of the slip law on ``z = B^{-1} e`` (``e`` a unit vector
        of a slip row) are ``K = [[d E_x G_x, d E_y G_y], [-E_y + S E_y G_x, E_x - S E_x
        G_y]]``, ``E_x, E_y, S`` the diagonal matrices of the slip nodes' ``e_x, e_y`` and
        slopes and ``d`` = ``system.diag``; the solve is ``z - B^{-1} E_P K^{-1} (R_P z -
        r_P)``, ``z = B^{-1} r`` (``docs/derivations.md`` section 5). ``K [a; b] = [w_1;
        w_2]`` is solved in the slip frame: ``alpha = w_1 / d`` (``alpha = e . (G_x a, G_y
        b)``), ``H beta = w_2 + D alpha`` with ``H = S - E_y G_x^{-1} E_y - E_x G_y^{-1}
        E_x``, ``D = E_y G_x^{-1} E_x - E_x G_y^{-1} E_y``, then ``a = G_x^{-1} (E_x alpha +
        E_y beta)``, ``b = G_y^{-1} (E_y alpha - E_x beta)``: ``p x p`` inverses only, and
        those of ``G_x, G_y`` depend on the run's length and slip places alone."""
        B = system.B
        if B.size == 0:
            self._columns = (np.zeros(0, int), None)
            return []
        diag, M = system.diag, inv.M
        sr = run[B]  # the slip nodes' runs, in order
        first = np.searchsorted(sr, np.arange(starts.size))
        count = np.bincount(sr, minlength=starts.size)
        local = B - starts[sr]
        # a column of a run's Toeplitz inverse depends on the run's length and the column
        # alone: one per (length, place), shared by runs of one length (the rows y and -y
        # of a symmetric contact) and kept while it is asked for
        key = lens[sr] * M + local
        uniq, which = np.unique(key, return_inverse=True)
        old_keys, old_cols = self._columns
        found = np.searchsorted(old_keys, uniq)
        have = found < old_keys.size
        have[have] = old_keys[found[have]] == uniq[have]
        columns = np.empty((2, uniq.size, M), self.dtype)  # x then y blocks
        if have.any():
            columns[:, have] = old_cols[:, found[have]]
        todo = np.flatnonzero(~have)
        if todo.size:
            # the missing columns, one row of positions per run length (padded), lengths with
            # about as many missing columns together
            n_of, pos_of = np.divmod(uniq[todo], M)
            lengths, per = np.unique(n_of, return_counts=True)
            order = np.argsort(per, kind="stable")[::-1]
            start = np.r_[0, np.cumsum(per)[:-1]]
            i = 0
            while i < order.size:
                P = per[order[i]]
                part = order[i:i + max(1, self.options.chunk // P)]
                i += part.size
                pos = np.zeros((part.size, P), int)
                dest = np.full((part.size, P), -1)
                for r, g in enumerate(part):
                    pos[r, :per[g]] = pos_of[start[g]:start[g] + per[g]]
                    dest[r, :per[g]] = todo[start[g]:start[g] + per[g]]
                cols = [inv.columns(1 + b, lengths[part], pos, self.dtype) for b in (0, 1)]
                filled = dest >= 0
                for b in (0, 1):
                    columns[b, dest[filled]] = cols[b][filled]
            self.factorised += todo.size
        self._columns = (uniq, columns)
        ex, ey, kk = system.dir_x, system.dir_y, system.slope
        by_size: dict = {}
        for q in np.flatnonzero(count):
            by_size.setdefault(-(-count[q] // 8) * 8, []).append(q)
        kept = self._blocks
        groups = []
        for P, members in by_size.items():
            L = len(members)
            p = count[members]
            valid = np.arange(P) < p[:, None]  # (L, P): the slip nodes of each run, then padding
            s = np.where(valid, first[members][:, None] + np.arange(P), 0)  # their slip indices
            # the columns as rows, gathered in one pass per block, 0 on padding
            Y = np.empty((2, L, P, M), self.dtype)
            for b in (0, 1):
                np.take(columns[b], which[s], axis=0, out=Y[b], mode="clip")
            Y[:, ~valid] = 0
            loc = np.where(valid, local[s], 0)
            # the inverses of G_x, G_y depend on the run's length and slip places alone: kept
            # (the length as 8 bytes: bytes(n) would be n zero bytes, and a run of length n with
            # its first slip node at place 0 then shares its key with one of length n + 8)
            keys = [np.int64(lens[q]).tobytes() + loc[i, :p[i]].astype(np.int64).tobytes()
                    for i, q in enumerate(members)]
            Gi = np.empty((L, 2, P, P))
            fresh = np.array([k not in kept for k in keys])
            for i in np.flatnonzero(~fresh):
                Gi[i] = kept[keys[i]]
            G = None
            if fresh.any():
                # G[i, j]: row P_i of column P_j of the runs' Toeplitz inverses; the identity
                # on padding
                vf = valid[fresh]
                lf = np.broadcast_to(loc[fresh][None, :, None, :], (2, vf.shape[0], P, P))
                G = (np.take_along_axis(Y[:, fresh], lf, 3).transpose(1, 0, 3, 2)
                     * vf[:, None, None, :] * vf[:, None, :, None])
                G[:, :, np.arange(P), np.arange(P)] += ~vf[:, None, :]
            e1, e2, k1 = (np.where(valid, a[s], 0.0) for a in (ex, ey, kk))
            both = np.concatenate([valid, valid], 1)
            d = np.arange(P)
            at = (np.arange(L)[:, None] * 2 * P + np.concatenate([d, P + d])[None, :])[both]
            where = np.concatenate([s, B.size + s], 1)[both]
            groups.append({"members": np.array(members), "at": at, "where": where, "Y": Y, "keys": keys,
                           "Gi": Gi, "fresh": fresh, "G": G, "e1": e1, "e2": e2, "k": np.where(valid, k1, 1.0)})

        def invert(part):
            for g in part:
                Gi, e1, e2 = g["Gi"], g["e1"], g["e2"]
                if g["G"] is not None:
                    Gi[g["fresh"]] = np.linalg.inv(g["G"])
                # H = diag(k) - E_y G_x^-1 E_y - E_x G_y^-1 E_x (the identity on padding)
                H = -(e2[:, :, None] * Gi[:, 0] * e2[:, None, :] + e1[:, :, None] * Gi[:, 1] * e1[:, None, :])
                P = H.shape[1]
                H[:, np.arange(P), np.arange(P)] += g["k"]
                Hi = np.linalg.inv(H)
                if P > self.options.compose_upto:
                    g["H"] = Hi
                    continue
                # small runs: K^-1 itself, [[G_x^-1 (E_x + E_y H^-1 D) / d, G_x^-1 E_y H^-1],
                # [G_y^-1 (E_y - E_x H^-1 D) / d, -G_y^-1 E_x H^-1]], D = E_y G_x^-1 E_x -
                # E_x G_y^-1 E_y: one product an application
                D = e2[:, :, None] * Gi[:, 0] * e1[:, None, :] - e1[:, :, None] * Gi[:, 1] * e2[:, None, :]
                HD, eye = Hi @ D, np.eye(P)
                top = np.concatenate([(e1[:, :, None] * eye + e2[:, :, None] * HD) / diag, e2[:, :, None] * Hi], 2)
                bot = np.concatenate([(e2[:, :, None] * eye - e1[:, :, None] * HD) / diag, -e1[:, :, None] * Hi], 2)
                g["H"] = np.concatenate([Gi[:, 0] @ top, Gi[:, 1] @ bot], 1)

        invert(groups)
        self._blocks = {key: Gi for g in groups for key, Gi in zip(g["keys"], g["Gi"])}
        dt = self.dtype
        return [(g["members"], g["at"], g["where"], g["Gi"].astype(dt), g["H"].astype(dt), g["e1"].astype(dt),
                 g["e2"].astype(dt), g["Y"]) for g in groups]
