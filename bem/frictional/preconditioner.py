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

Cost: one LU of ``3 m x 3 m`` per line of ``m`` contact nodes (``O(K m^3)``), and its
solve per GMRES iteration (``O(K m^2)``). A line whose nodes and stick pattern did not
change since the previous active-set iteration keeps its factors (the slip directions
it was built with lag by one iteration; it is only a preconditioner).
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from .system import SetSystem, force_rows

__all__ = ["LinePreconditioner"]


class LinePreconditioner:
    """Block-Jacobi preconditioner by grid rows for :class:`SetSystem`.

    Use :meth:`attach` for each new system: it builds (or reuses) the line factors and
    sets ``system.precondition``. ``factorised`` counts the LU factorisations done.
    """

    def __init__(self):
        self._cache: dict = {}
        self.factorised = 0

    def attach(self, system: SetSystem) -> None:
        Kx = system.ops.grid.nodes_x
        rows = system.C // Kx
        cuts = np.flatnonzero(np.diff(rows)) + 1
        lines = np.split(np.arange(system.nC), cuts)
        slip_pos = np.full(system.nC, -1)
        slip_pos[system.B] = np.arange(system.B.size)
        nC = system.nC
        cache, blocks = {}, []
        for J in lines:
            st = system.stick[J]
            key = system.C[J].tobytes() + st.tobytes()
            lu = self._cache.get(key)
            if lu is None:
                lu = lu_factor(self._local(system, J, st, slip_pos), check_finite=False)
                self.factorised += 1
            cache[key] = lu
            blocks.append((np.concatenate([J, nC + J, 2 * nC + J]), lu))
        self._cache = cache
        om_step = 1.0 / system.ax  # the inverse of the scaled Omega's stick-row coefficient

        def precondition(r):
            out = np.empty_like(r)
            for idx, lu in blocks:
                out[idx] = lu_solve(lu, r[idx], check_finite=False)
            if system.free_d:
                out[system.iD] = r[system.iD]
            if system.free_om:
                out[system.iO] = r[system.iO] * om_step
            return out

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
