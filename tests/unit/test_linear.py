"""bem.linear: the flexible GMRES and the linear-solver dispatcher that both contact
solvers share, on small systems whose answers are known exactly or by a dense solve.

Each test names the behaviour it pins; tolerances are stated against the measured error
(rounding of a well-conditioned system of a few hundred unknowns: ~1e-15 relative).
"""

import numpy as np
import pytest

from bem.linear import LinearSolver, fgmres


class Dense:
    """A system for :class:`LinearSolver`: ``A x = b`` with an optional preconditioner."""

    def __init__(self, A, b, precondition=None):
        self.A, self.b, self.n = A, b, b.size
        self.products = 0
        if precondition is not None:
            self.precondition = precondition

    def dense(self):
        return self.A

    def matvec(self, x):
        self.products += 1
        return self.A @ x


def _near_identity(n=120, eps=1e-4, scale=1.0, seed=3):
    rng = np.random.default_rng(seed)
    return scale * (np.eye(n) + eps * rng.normal(size=(n, n)) / np.sqrt(n)), rng.normal(size=n)


def test_a_zero_right_hand_side_is_solved_by_zero_in_no_iteration():
    x, ok, its = fgmres(lambda v: 2.0 * v, np.zeros(4), tol=0.0)
    assert ok and its == 0 and not x.any()


@pytest.mark.parametrize("scale", [1.0, 1e6])
def test_a_near_identity_operator_needs_the_second_gram_schmidt_pass(scale):
    """A = s (I + 1e-4 R): each new Krylov vector is the previous one to 1e-4, so one
    classical Gram-Schmidt pass leaves ~1e-4 of the vector and loses orthogonality; the
    second pass restores it. The true residual meets the asked 1e-13 |b|, and the solution
    equals the dense one to 1e-12 of its largest entry."""
    A, b = _near_identity(scale=scale)
    tol = 1e-13 * np.linalg.norm(b)
    x, ok, its = fgmres(lambda v: A @ v, b, tol=tol, restart=50, maxiter=1)
    assert ok and 1 < its < 20
    assert np.linalg.norm(b - A @ x) <= tol
    np.testing.assert_allclose(x, np.linalg.solve(A, b), rtol=0, atol=1e-12 * np.abs(x).max())


def test_the_callback_sees_the_residual_of_each_iteration():
    """The estimates passed to the callback are the least-squares residuals of the
    iterations, |b - A x_j| for the iterate x_j of iteration j; checked at every j by
    solving again with j iterations (restart = j, one cycle), away from rounding
    (tol 1e-9 |b|): they agree to 1e-8 relative, and they decrease."""
    A, b = _near_identity(n=80, eps=0.5, seed=7)
    seen = []
    _, ok, its = fgmres(lambda v: A @ v, b, tol=1e-9 * np.linalg.norm(b), restart=80, maxiter=1,
                        callback=seen.append)
    assert ok and its == len(seen) > 3
    for j, estimate in enumerate(seen, 1):
        xj, _, _ = fgmres(lambda v: A @ v, b, tol=0.0, restart=j, maxiter=1)
        assert estimate == pytest.approx(np.linalg.norm(b - A @ xj), rel=1e-8)
    assert all(later < earlier for earlier, later in zip(seen, seen[1:]))


def test_an_invariant_krylov_space_stops_the_cycle_at_once():
    """A = 1000 I: the first Krylov vector spans an invariant space (the orthogonalised
    product is rounding, 1e-13 of it); the cycle stops there, one iteration, with the
    exact solution, even when the tolerance asked is beyond rounding."""
    b = np.array([1.0, -2.0, 3.0, 0.5])
    x, ok, its = fgmres(lambda v: 1000.0 * v, b, tol=1e-300, restart=10, maxiter=1)
    assert its == 1
    np.testing.assert_allclose(x, b / 1000.0, rtol=1e-15)


def test_a_singular_operator_gives_the_least_squares_step_and_says_it_failed():
    """A = diag(1, 2, 0), b = (1, 1, 1): no x reaches ``A x = b``; the Krylov space
    holds ``A z = 0`` for a vector z, so the Hessenberg factor is singular and the step is
    the least-squares one: ``A x = (1, 1, 0)``, residual exactly 1, reported as not
    converged."""
    A = np.diag([1.0, 2.0, 0.0])
    b = np.ones(3)
    x, ok, its = fgmres(lambda v: A @ v, b, tol=1e-12, restart=3, maxiter=2)
    assert not ok and its >= 3
    np.testing.assert_allclose(A @ x, [1.0, 1.0, 0.0], rtol=0, atol=1e-12)
    assert np.linalg.norm(b - A @ x) == pytest.approx(1.0, abs=1e-12)


def test_the_solver_counts_iterations_over_calls_and_solves_small_systems_densely():
    A, b = _near_identity(n=30)
    dense = LinearSolver(30, 1e-12)
    x = dense(Dense(A, b))
    np.testing.assert_allclose(x, np.linalg.solve(A, b), rtol=1e-14)
    assert dense.iterations == 0 and not dense.used_gmres
    krylov = LinearSolver(29, 1e-12)
    for _ in range(2):
        x = krylov(Dense(A, b))
        assert np.linalg.norm(b - A @ x) <= 1e-12 * np.linalg.norm(b)
    assert krylov.used_gmres and krylov.iterations > 2


def test_a_singular_dense_system_raises_the_callers_error_naming_it():
    class Failed(RuntimeError):
        pass

    with pytest.raises(Failed, match=r"^singular system \(3 test nodes\): "):
        LinearSolver(10, 1e-12, error=Failed)(Dense(np.zeros((3, 3)), np.ones(3)), what="3 test nodes")


def test_the_tolerance_is_relative_to_b_or_with_correction_to_the_guess_residual():
    """From a guess whose residual is 1e-6 |b|: asked 1e-3, a plain solve is already done
    (0 iterations, the guess returned); a correction solve reduces the guess's residual
    1000 times more (its residual at most 1e-9 |b|)."""
    A, b = _near_identity(n=60, eps=0.3)
    exact = np.linalg.solve(A, b)
    rng = np.random.default_rng(5)
    guess = exact + 1e-6 * np.linalg.norm(exact) * rng.normal(size=b.size) / np.sqrt(b.size)
    r0 = np.linalg.norm(b - A @ guess)
    assert 1e-7 * np.linalg.norm(b) < r0 < 1e-3 * np.linalg.norm(b)
    plain = LinearSolver(0, 1e-3)
    np.testing.assert_array_equal(plain(Dense(A, b), guess), guess)
    assert plain.iterations == 0
    corr = LinearSolver(0, 1e-3, correction=True)
    x = corr(Dense(A, b), guess)
    assert corr.iterations > 0 and np.linalg.norm(b - A @ x) <= 1e-3 * r0


def test_the_floor_ends_a_correction_solve_near_rounding():
    """A correction whose residual is already below ``floor |b|`` is not reduced further."""
    A, b = _near_identity(n=60, eps=0.3)
    exact = np.linalg.solve(A, b)
    solver = LinearSolver(0, 1e-10, correction=True, floor=1e-12)
    x = solver(Dense(A, b), exact)
    assert solver.iterations == 0 and np.array_equal(x, exact)


@pytest.mark.parametrize("hint, tail", [("", " iterations"), ("refine less", " iterations; refine less")])
def test_a_failed_solve_says_what_failed_and_what_to_change(hint, tail):
    """One cycle of one iteration cannot solve a 60-unknown system to 1e-12: the error
    names the reduction, the system and the iterations, then the hint if one is given."""
    A, b = _near_identity(n=60, eps=0.3)

    class Failed(RuntimeError):
        pass

    solver = LinearSolver(0, 1e-12, restart=1, maxiter=1, error=Failed)
    with pytest.raises(Failed) as info:
        solver(Dense(A, b), what="60 test nodes", hint=hint)
    assert str(info.value) == "GMRES did not reduce the residual by 1.0e-12 on 60 test nodes in 1" + tail
