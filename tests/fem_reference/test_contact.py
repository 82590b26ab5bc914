"""The dense contact problem: KKT conditions, uniqueness, cycle fallback."""

import itertools

import numpy as np
import pytest

from fem_reference.contact import _primal, solve_contact
from fem_reference.errors import ContactNotConvergedError


def _problem(n, seed):
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n))
    W = A @ A.T / n + np.eye(n) * 0.1
    x = np.linspace(0, 1, n)
    m = 0.5 + rng.random(n)
    q = m * x ** 2  # a rigid profile s = x^2
    return W, m, q


def _brute_force(W, m, q, load):
    """Enumerate active sets of a tiny problem: the one satisfying the KKT conditions."""
    n = len(q)
    for k in range(1, n + 1):
        for act in itertools.combinations(range(n), k):
            idx = list(act)
            K = np.zeros((k + 1, k + 1))
            K[:k, :k] = W[np.ix_(idx, idx)]
            K[:k, k] = -m[idx]
            K[k, :k] = m[idx]
            sol = np.linalg.solve(K, np.concatenate([-q[idx], [load]]))
            lam = np.zeros(n)
            lam[idx] = sol[:k]
            g = q - sol[k] * m + W @ lam
            if np.all(lam >= -1e-12) and np.all(g >= -1e-12):
                return lam, sol[k]
    raise AssertionError("no KKT point")


@pytest.mark.parametrize("seed", range(5))
def test_load_control_matches_enumeration(seed):
    W, m, q = _problem(7, seed)
    lam_ref, d_ref = _brute_force(W, m, q, 2.0)
    sol = solve_contact(W, m, q, load=2.0)
    assert np.allclose(sol.pressure, lam_ref, atol=1e-10)
    assert sol.indentation == pytest.approx(d_ref, rel=1e-10)
    assert sol.load == pytest.approx(2.0, rel=1e-12)
    assert sol.residual < 1e-10


def test_displacement_control_is_the_inverse_of_load_control():
    W, m, q = _problem(30, 11)
    by_load = solve_contact(W, m, q, load=5.0)
    by_disp = solve_contact(W, m, q, indentation=by_load.indentation)
    assert np.allclose(by_disp.pressure, by_load.pressure, rtol=1e-9, atol=1e-12)
    assert by_disp.load == pytest.approx(5.0, rel=1e-9)


def test_primal_method_alone_reaches_the_same_point():
    W, m, q = _problem(30, 3)
    ref = solve_contact(W, m, q, load=3.0)
    lam, d, work, it = _primal(W, m, q, 3.0, None, None, 1e-14, 1000, None)
    assert np.allclose(lam, ref.pressure, atol=1e-10)
    assert d == pytest.approx(ref.indentation, rel=1e-10)


def test_iteration_limit_falls_back_to_the_finite_method():
    W, m, q = _problem(40, 5)
    ref = solve_contact(W, m, q, load=3.0)
    sol = solve_contact(W, m, q, load=3.0, max_iterations=1,
                        initial_active=np.zeros(40, bool))
    # one primal-dual step cannot finish from an empty set; the primal method can
    assert "primal" in sol.method.split(",")[-1]
    assert np.allclose(sol.pressure, ref.pressure, atol=1e-10)


def test_exhausted_limit_raises():
    W, m, q = _problem(40, 5)
    with pytest.raises(ContactNotConvergedError):
        _primal(W, m, q, 3.0, None, None, 1e-14, 2, None)
