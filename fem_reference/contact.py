"""Frictionless unilateral contact on the candidate zone: a small dense problem.

With the multiplier (contact pressure) lam_j >= 0 (Pa) at the candidate nodes and
the weighted gaps

    g_j = int phi_j (s - d - u_z) dS = q_j - d m_j + (W lam)_j     (m^3),

(q_j = int phi_j s dS, m_j = int phi_j dS, W = C S^-1 C^T the symmetric positive
definite surface compliance, m^3/Pa), the discrete contact conditions are

    lam >= 0,  g >= 0,  lam_j g_j = 0,  and  m^T lam = P  (load control),

the optimality conditions of the strictly convex quadratic program
min 1/2 lam^T W lam + q^T lam subject to lam >= 0, m^T lam = P, with the
indentation d (m) the multiplier of the load equation. Under displacement control
d is given and the equation is dropped. The solution is unique.

:func:`solve_contact` runs the primal-dual active-set iteration (a semismooth
Newton method: a few iterations from a good start). It keeps every active set it
has visited; meeting one again is a cycle, and then it switches to the primal
active-set method, whose objective decreases strictly from one working set to
the next, so that no working set repeats and it ends after finitely many steps.
Both are capped by ``max_iterations``; reaching the cap raises
:class:`~fem_reference.errors.ContactNotConvergedError`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np

from .errors import ContactNotConvergedError, InputError

__all__ = ["ContactSolution", "solve_contact"]


@dataclass(frozen=True)
class ContactSolution:
    """Solution of the contact problem on the candidate nodes.

    Attributes
    ----------
    pressure : ndarray
        Nodal contact pressure lam (Pa), >= 0.
    gap : ndarray
        Weighted gaps g (m^3), >= 0 up to round-off.
    indentation : float
        Rigid downward displacement d of the indenter (m).
    load : float
        m^T lam (N).
    active : ndarray of bool
        Nodes in contact.
    iterations : int
        Active-set iterations (both methods together).
    history : tuple of int
        Nodes in the active set at each primal-dual iteration.
    method : str
        "primal-dual" or "primal-dual, then primal (cycle)".
    residual : float
        max(|min(lam, c g)|) / max(lam) with c = 1 / diag(W): the complementarity residual (-).
    """

    pressure: np.ndarray
    gap: np.ndarray
    indentation: float
    load: float
    active: np.ndarray
    iterations: int
    method: str
    residual: float
    history: tuple = ()


def _solve_on(W, m, q, work, load, indentation):
    """Pressures on the working set (zero elsewhere) and d: equality-constrained step."""
    lam = np.zeros(len(q))
    idx = np.flatnonzero(work)
    if load is None:
        d = indentation
        if len(idx):
            lam[idx] = np.linalg.solve(W[np.ix_(idx, idx)], -(q[idx] - d * m[idx]))
        return lam, d
    n = len(idx)
    K = np.zeros((n + 1, n + 1))
    K[:n, :n] = W[np.ix_(idx, idx)]
    K[:n, n] = -m[idx]
    K[n, :n] = m[idx]
    rhs = np.concatenate([-q[idx], [load]])
    sol = np.linalg.solve(K, rhs)
    lam[idx] = sol[:n]
    return lam, sol[n]


def _gap(W, m, q, lam, d):
    return q - d * m + W @ lam


def _primal(W, m, q, load, indentation, work, tol_g, max_iterations, progress):
    """Primal active-set method from a feasible point; finite (objective decreases)."""
    n = len(q)
    lam = np.zeros(n)
    if load is not None:  # feasible start: the whole load on one working node
        work = np.zeros(n, bool)
        j = int(np.argmin(q / m))
        work[j] = True
        lam[j] = load / m[j]
    else:
        work = np.zeros(n, bool)
    for it in range(1, max_iterations + 1):
        z, d = _solve_on(W, m, q, work, load, indentation)
        if np.all(z[work] > 0):
            lam = z
            g = _gap(W, m, q, lam, d)
            g[work] = 0.0
            j = int(np.argmin(g))
            if g[j] >= -tol_g:
                return lam, d, work, it
            work[j] = True
        else:
            block = work & (z <= 0)
            steps = lam[block] / (lam[block] - z[block])
            alpha = float(np.min(steps))
            lam = lam + alpha * (z - lam)
            drop = np.flatnonzero(block)[np.argmin(steps)]
            lam[drop] = 0.0
            work[drop] = False
            work &= lam > 0
        if progress:
            progress(f"contact primal iteration {it}: {int(work.sum())} nodes in the working set")
    raise ContactNotConvergedError(f"primal active-set method did not converge in "
                                   f"{max_iterations} iterations (fem.max_iterations)")


def _check_reaches_a_node(m, q, indentation):
    """Raise if the rigid indentation d (m) closes no node's weighted gap q_j / m_j (m).

    With g_j(lam = 0) = q_j - d m_j >= 0 for every j, lam = 0 satisfies all the contact
    conditions, and the solution is unique: the indenter carries no load."""
    gaps = q / m
    j = int(np.argmin(gaps))
    if indentation <= gaps[j]:
        raise InputError(
            f"loading.indentation = {indentation:.6g} m reaches no node of the candidate zone: "
            f"to touch the nearest one the indenter would need to close {gaps[j]:.5e} m (the gap "
            f"between the undeformed surface and the indenter, averaged over that node's hat "
            f"function), so the load would be 0; raise loading.indentation above {gaps[j]:.5e} m, "
            "or refine fem.element_size (that gap shrinks as h^2)")


def solve_contact(W: np.ndarray, m: np.ndarray, q: np.ndarray, *,
                  load: Optional[float] = None, indentation: Optional[float] = None,
                  initial_active: Optional[np.ndarray] = None, max_iterations: int = 100,
                  progress: Optional[Callable[[str], None]] = None) -> ContactSolution:
    """Solve the discrete frictionless contact problem (module docstring).

    Parameters
    ----------
    W : ndarray (n, n)
        Symmetric positive definite surface compliance (m^3/Pa... per unit multiplier).
    m, q : ndarray (n,)
        int phi_j dS (m^2) and int phi_j s dS (m^3).
    load : float, optional
        Total load P (N) carried by the nodes (load control).
    indentation : float, optional
        Indentation d (m) (displacement control). Exactly one of load, indentation.
    initial_active : ndarray of bool, optional
        First active set; default: nodes where the rigid gap q - d0 m is < 0 with
        d0 chosen so that about a third of the nodes start in contact.
    max_iterations : int
        Limit of each of the two active-set methods.
    progress : callable, optional
        Called with one line of text per iteration.

    Raises
    ------
    InputError
        Under displacement control, if the indentation closes the gap of no node:
        d <= min_j q_j / m_j makes lam = 0 the (unique) solution, a contact of no load.
    ContactNotConvergedError
        If an iteration limit is reached.
    """
    if (load is None) == (indentation is None):
        raise ValueError("solve_contact needs exactly one of load and indentation")
    if indentation is not None:
        _check_reaches_a_node(m, q, indentation)
    n = len(q)
    c = 1.0 / np.diag(W)
    tol_g = 1e-12 * np.max(np.abs(q)) + 1e-300
    if initial_active is None:
        rigid = q / m
        d0 = indentation if indentation is not None else np.quantile(rigid, 1.0 / 3.0)
        active = rigid < d0
    else:
        active = np.asarray(initial_active, bool).copy()
    if load is not None and not active.any():
        active[int(np.argmin(q / m))] = True
    seen = set()
    method = "primal-dual"
    it = 0
    history = []
    while True:
        it += 1
        history.append(int(active.sum()))
        lam, d = _solve_on(W, m, q, active, load, indentation)
        g = _gap(W, m, q, lam, d)
        new = (lam - c * g) > 0
        if load is not None and not new.any():
            new[int(np.argmin(g / m))] = True
        if progress:
            progress(f"contact iteration {it}: {int(active.sum())} active nodes, "
                     f"indentation {d:.6e} m")
        if np.array_equal(new, active):
            break
        key = new.tobytes()
        if key in seen or it >= max_iterations:
            method = "primal-dual, then primal (cycle)" if key in seen else \
                     "primal-dual, then primal (iteration limit)"
            lam, d, active, it2 = _primal(W, m, q, load, indentation, active, tol_g,
                                          max_iterations * max(n, 1), progress)
            it += it2
            g = _gap(W, m, q, lam, d)
            break
        seen.add(active.tobytes())
        active = new
    lam = np.maximum(lam, 0.0) if method == "primal-dual" and np.all(lam >= -1e-12 * lam.max()) else lam
    if np.any(lam < 0) or np.any(g < -1e3 * tol_g):
        raise ContactNotConvergedError(
            f"active-set iteration ended on an infeasible state: min pressure {lam.min():.3e} Pa, "
            f"min weighted gap {g.min():.3e} m^3")
    scale = max(lam.max(), 1e-300)
    residual = float(np.max(np.abs(np.minimum(lam, c * g))) / scale)
    return ContactSolution(pressure=lam, gap=g, indentation=float(d), load=float(m @ lam),
                           active=lam > 0, iterations=it, method=method, residual=residual,
                           history=tuple(history))
