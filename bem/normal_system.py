"""The linear problem of one trial contact set of the frictionless solver
(:func:`bem.contact.solve_normal`): the bordered system under load control, the plain
one under displacement control, applied by FFT on the set's bounding box and
preconditioned there by the inverse of the kernel's wrapped circulant (SI units)."""

from __future__ import annotations

import numpy as np

from .linear import bordered, eliminate
from .operator import ComplianceOperator

__all__ = ["NormalSystem", "BOX_STEP"]


class NormalSystem:
    """The linear problem of one trial contact set ``idx`` (flat node indices): under
    load control the bordered system ``C_AA F_A - d 1 = -s_A``, ``diag sum F_A = diag P``
    (both rows in metres), under displacement control ``C_AA F_A = d - s_A``; for
    :class:`bem.linear.LinearSolver` (dense matrix, FFT product and, on the force part,
    the inverse of the kernel's wrapped circulant as preconditioner, both on the set's
    bounding box ``box``)."""

    def __init__(self, op: ComplianceOperator, idx: np.ndarray, s_A: np.ndarray, load: float | None,
                 indentation: float | None):
        self.op, self.idx, self.load, self.indentation = op, idx, load, indentation
        self.m = idx.size
        self.bordered = load is not None
        self.n = self.m + self.bordered
        self.diag = float(op.kernel[op.grid.nodes_y - 1, op.grid.nodes_x - 1])
        self.b = np.concatenate([-s_A, [self.diag * load]]) if self.bordered else indentation - s_A
        # products and preconditioner on the set's bounding box (ComplianceOperator.block)
        shape, self._local = _box(idx, op.grid.shape)
        self.box = op.block(shape)
        self._full = np.zeros(shape[0] * shape[1])
        self._pre = None
        if not self.box.has_circulant_inverse:
            self.precondition = None

    def dense(self) -> np.ndarray:
        K = self.op.dense(self.idx)
        if not self.bordered:
            return K
        m = self.m
        M = np.zeros((m + 1, m + 1))
        M[:m, :m] = K
        M[:m, m] = -1.0
        M[m, :m] = self.diag
        return M

    def _spread(self, v):
        self._full[:] = 0.0
        self._full[self._local] = v[:self.m]
        return self._full.reshape(self.box.grid.shape)

    def matvec(self, v):
        out = self.box.apply(self._spread(v)).ravel()[self._local]
        if not self.bordered:
            return out
        return np.concatenate([out - v[self.m], [self.diag * v[:self.m].sum()]])

    def precondition(self, v):
        """The inverse of the kernel's wrapped circulant on the forces; under load
        control ``d`` eliminated by its Schur complement (:func:`bem.linear.bordered`;
        passing its row on instead cost 9-20 % more GMRES iterations: section 11 at
        257 x 257 70 / 53 / 46 -> 64 / 45 / 36 on its 257, 129 and 65 levels)."""
        if self._pre is None:
            forces = self._forces
            if self.bordered:
                diag = self.diag

                def load_row(x):
                    return diag * x.sum(0, keepdims=True)

                parts = eliminate(forces, -np.ones((self.m, 1)), load_row)
                forces = bordered(forces, load_row, parts) if parts is not None else (
                    lambda v: np.concatenate([self._forces(v[:self.m]), v[self.m:]]))
            self._pre = forces
        return self._pre(v)

    def _forces(self, v):
        return self.box.circulant_inverse(self._spread(v)).ravel()[self._local]

    def split(self, x: np.ndarray) -> tuple[np.ndarray, float]:
        """Forces on the set and the indentation from the solution vector."""
        return (x[:self.m], float(x[self.m])) if self.bordered else (x, self.indentation)


#: a contact set's bounding box is widened to a multiple of this many nodes a side (within
#: the grid), so that the boxes of successive sets share their operators (each new shape
#: costs two transforms of the kernel). The 13 sets of the viscoelastic solve of
#: ``benchmarks/bem_viscoelastic_rolling.py`` at 155 x 155 (both levels) ask 9 shapes at 1
#: node, 5 at 8, 4 at 16; the solve's CPU time is the same within the noise (0.14 s)
BOX_STEP = 8


def _box(idx: np.ndarray, shape: tuple[int, int]) -> tuple[tuple[int, int], np.ndarray]:
    """The block of the grid (``shape``) that holds the flat node indices ``idx``: its shape,
    each side the set's extent rounded up to :data:`BOX_STEP` nodes (at most the grid's),
    and ``idx`` as flat indices into it."""
    Ky, Kx = shape
    j, i = np.divmod(idx, Kx)
    by = min(Ky, -(-(int(j.max()) - int(j.min()) + 1) // BOX_STEP) * BOX_STEP)
    bx = min(Kx, -(-(int(i.max()) - int(i.min()) + 1) // BOX_STEP) * BOX_STEP)
    j0, i0 = min(int(j.min()), Ky - by), min(int(i.min()), Kx - bx)
    return (by, bx), (j - j0) * bx + (i - i0)
