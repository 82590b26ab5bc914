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
leaves out is the coupling between rows, smooth and well handled by GMRES: 66 and 73
iterations on the same states. Blocks of two rows gave 42 and 62 iterations for four
times the factorisation cost; applying the circulant step before or after the line
solves made things worse (147-542).

Cost: the inverse of one ``3 m x 3 m`` block per line of ``m`` contact nodes
(``O(K m^3)`` flops, ``O(K m^2)`` memory), and a product with it per GMRES iteration
(``O(K m^2)``). A line whose nodes and stick pattern did not
change since the previous active-set iteration keeps its factors (the slip directions
it was built with lag by one iteration; it is only a preconditioner).
"""

from __future__ import annotations

import numpy as np

from .system import SetSystem, force_rows

__all__ = ["LinePreconditioner"]


class LinePreconditioner:
    """Block-Jacobi preconditioner by grid rows for :class:`SetSystem`.

    Use :meth:`attach` for each new system: it builds (or reuses) the inverse of each
    line's block and sets ``system.precondition``. The inverses are applied as batched
    matrix products, lines grouped by size (padded to a multiple of ``pad`` nodes), so a
    GMRES iteration costs a few BLAS calls, not one call per line. ``factorised`` counts
    the blocks inverted.
    """

    def __init__(self, pad: int = 8):
        self._cache: dict = {}
        self._batches: tuple = (None, None)
        self.factorised = 0
        self.pad = pad

    def attach(self, system: SetSystem) -> None:
        Kx = system.ops.grid.nodes_x
        nC, n = system.nC, system.n
        rows = system.C // Kx
        cuts = np.flatnonzero(np.diff(rows)) + 1
        lines = np.split(np.arange(nC), cuts)
        slip_pos = np.full(nC, -1)
        slip_pos[system.B] = np.arange(system.B.size)
        cache, groups, keys, keys_of = {}, {}, [], {}
        for J in lines:
            st = system.stick[J]
            key = system.C[J].tobytes() + st.tobytes()
            keys.append(key)
            inv = self._cache.get(key)
            if inv is None:
                inv = np.linalg.inv(self._local(system, J, st, slip_pos))
                self.factorised += 1
            cache[key] = inv
            keys_of[id(inv)] = key
            size = -(-J.size // self.pad) * self.pad
            groups.setdefault(size, []).append((J, inv))
        self._cache = cache
        whole = b"|".join(keys)
        batches = self._batches[1] if self._batches[0] == whole else []
        for size, members in (groups.items() if not batches else ()):
            idx = np.full((len(members), 3 * size), n)  # padding reads and writes slot n
            stack = np.zeros((len(members), 3 * size, 3 * size))
            for b, (J, inv) in enumerate(members):
                m3 = 3 * J.size
                idx[b, :m3] = np.concatenate([J, nC + J, 2 * nC + J])
                stack[b, :m3, :m3] = inv
                cache[keys_of[id(inv)]] = stack[b, :m3, :m3]  # a view: one copy in memory
            batches.append((idx, stack))
        self._batches = (whole, batches)
        om_step = 1.0 / system.ax  # the inverse of the scaled Omega's stick-row coefficient
        ext = np.zeros(n + 1)

        def precondition(r):
            ext[:n] = r
            ext[n] = 0.0
            out = np.empty(n + 1)
            for idx, stack in batches:
                out[idx] = np.matmul(stack, ext[idx][:, :, None])[:, :, 0]
            if system.free_d:
                out[system.iD] = r[system.iD]
            if system.free_om:
                out[system.iO] = r[system.iO] * om_step
            return out[:n]

        system.precondition = precondition

    @staticmethod
    def _local(system: SetSystem, J, stick, slip_pos):
        """The system's rows and columns of the forces of contact positions ``J``."""
        gap, Dx, Dy = system.blocks(J, J)
        p = slip_pos[J[~stick]]
        m = J.size
        eye = np.eye(3 * m)
        return force_rows(stick, system.dir_x[p], system.dir_y[p], system.slope[p], system.setup.mu, system.diag,
                          gap, Dx, Dy, eye[:m], eye[m:2 * m], eye[2 * m:])
