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
        if precondition is not None:
            self.precondition = precondition

    def dense(self):
        return self.A

    def matvec(self, x):
        return self.A @ x


def _near_identity(n=120, eps=1e-4, seed=3):
    """``I + eps R`` (``R`` Gaussian, scaled by ``1/sqrt(n)``) and a Gaussian ``b``."""
    rng = np.random.default_rng(seed)
    return np.eye(n) + eps * rng.normal(size=(n, n)) / np.sqrt(n), rng.normal(size=n)


def test_a_zero_right_hand_side_is_solved_by_zero_in_no_iteration():
    x, ok, its = fgmres(lambda v: 2.0 * v, np.zeros(4), tol=0.0)
    assert ok and its == 0 and not x.any()


def test_a_wide_spectrum_needs_the_second_gram_schmidt_pass():
    """A symmetric operator with eigenvalues spread over six decades (n = 300): one
    classical Gram-Schmidt pass loses the basis' orthogonality over the long Krylov
    sequence. With the second pass fgmres converges to 1e-10 |b| in 269 iterations,
    within one cycle of 300; measured without it: 501 (so not within one cycle)."""
    rng = np.random.default_rng(4)
    n = 300
    Q, _ = np.linalg.qr(rng.normal(size=(n, n)))
    A = Q @ np.diag(np.logspace(0, 6, n)) @ Q.T + 0.1 * np.diag(rng.uniform(size=n))
    b = rng.normal(size=n)
    x, ok, its = fgmres(lambda v: A @ v, b, tol=1e-10 * np.linalg.norm(b), restart=300, maxiter=1)
    assert ok and its < 300
    assert np.linalg.norm(b - A @ x) <= 1e-10 * np.linalg.norm(b)


def test_restarted_cycles_continue_until_the_tolerance():
    """Restarted every 5 iterations, a system that needs about 20 converges over several
    cycles, each starting from the true residual of the last."""
    A, b = _near_identity(n=60, eps=0.6, seed=8)
    x, ok, its = fgmres(lambda v: A @ v, b, tol=1e-10 * np.linalg.norm(b), restart=5, maxiter=50)
    assert ok and its > 10
    assert np.linalg.norm(b - A @ x) <= 1e-10 * np.linalg.norm(b)


def test_a_non_finite_product_ends_the_solve_as_failed():
    """A product that returns NaN ends the cycle: the last finite iterate (here the
    start, 0) and a failure, which the dispatcher turns into the caller's error."""
    x, ok, its = fgmres(lambda v: np.full_like(v, np.nan), np.ones(5), tol=1e-12, restart=3, maxiter=4)
    assert not ok and 1 <= its <= 3
    np.testing.assert_array_equal(x, np.zeros(5))

    class Failed(RuntimeError):
        pass

    system = Dense(np.eye(5), np.ones(5))
    system.matvec = lambda v: np.full_like(v, np.nan)
    with pytest.raises(Failed, match="^GMRES did not reduce the residual by 1.0e-12 on 5 unknowns in "):
        LinearSolver(0, 1e-12, restart=3, maxiter=4, error=Failed)(system)


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
    """A = 1000 diag(1, 2, 3, 4), b = (1, 1, 0, 0): the first two Krylov vectors span an
    invariant space (the third product, orthogonalised, is rounding: ~1e-13 of it); the
    cycle stops there, after two iterations, with the exact solution, even when the
    tolerance asked is beyond rounding."""
    A = 1000.0 * np.diag([1.0, 2.0, 3.0, 4.0])
    x, ok, its = fgmres(lambda v: A @ v, np.array([1.0, 1.0, 0.0, 0.0]), tol=1e-300, restart=4, maxiter=1)
    assert its == 2
    np.testing.assert_allclose(x, [1e-3, 5e-4, 0.0, 0.0], rtol=0, atol=1e-18)


def test_a_product_that_vanishes_exactly_leaves_the_iterate_at_zero():
    """A = diag(1, 0), b = (0, 1): the first product is exactly 0 (a zero Hessenberg
    column, the rotation left as the identity); no step reduces the residual, so every
    cycle returns x = 0 and the solve reports failure after its three cycles."""
    x, ok, its = fgmres(lambda v: np.array([v[0], 0.0]), np.array([0.0, 1.0]), tol=1e-12, restart=2,
                        maxiter=3)
    assert not ok and its == 3
    np.testing.assert_array_equal(x, [0.0, 0.0])


def test_a_singular_operator_gives_the_least_squares_step_and_says_it_failed():
    """A = 1000 diag(1, 2, 0), b = (1, 1, 1): no x reaches ``A x = b``; the Krylov space
    holds ``A z = 0`` for a vector z, so the Hessenberg factor is singular and the step is
    the least-squares one: ``A x = (1, 1, 0)``, residual exactly 1, reported as not
    converged (the triangular solve gave a step of 3e14 from a 1e-16 diagonal entry)."""
    A = 1000.0 * np.diag([1.0, 2.0, 0.0])  # scaled: the rank test is relative
    b = np.ones(3)
    x, ok, its = fgmres(lambda v: A @ v, b, tol=1e-12, restart=3, maxiter=2)
    assert not ok and its >= 3
    np.testing.assert_allclose(A @ x, [1.0, 1.0, 0.0], rtol=0, atol=1e-12)
    assert np.linalg.norm(b - A @ x) == pytest.approx(1.0, abs=1e-12)


def test_a_direction_below_the_rank_tolerance_counts_as_singular():
    """A = 1000 diag(1, 2, 1e-14): the third direction is 1e-14 of the largest, below
    RANK_TOL = 1e-13, so the step is the least-squares one on the first two (``A x =
    (1, 1, 0)``, residual 1) and the solve fails, rather than a step of 1e14 that no
    double-precision product can check."""
    A = 1000.0 * np.diag([1.0, 2.0, 1e-14])
    b = np.ones(3)
    x, ok, _ = fgmres(lambda v: A @ v, b, tol=1e-12, restart=3, maxiter=1)
    assert not ok and np.abs(x).max() < 1e-2
    np.testing.assert_allclose(A @ x, [1.0, 1.0, 0.0], rtol=0, atol=1e-9)


def test_a_non_finite_residual_at_the_end_of_a_cycle_ends_the_solve_as_failed():
    """Finite Krylov products, then a NaN when the cycle's iterate is checked: the solve
    stops with that iterate and a failure."""
    calls = []

    def matvec(v):
        calls.append(1)
        return np.full_like(v, np.nan) if len(calls) == 3 else 2.0 * v + np.roll(v, 1)

    x, ok, its = fgmres(matvec, np.arange(1.0, 6.0), tol=1e-300, restart=2, maxiter=5)
    assert not ok and its == 2 and len(calls) == 3 and np.isfinite(x).all()


def test_the_solver_counts_iterations_over_calls_and_solves_small_systems_densely():
    A, b = _near_identity(n=30)
    dense = LinearSolver(30, 1e-12)
    x = dense(Dense(A, b))
    np.testing.assert_allclose(x, np.linalg.solve(A, b), rtol=1e-14)
    assert dense.iterations == 0 and not dense.used_gmres
    krylov = LinearSolver(29, 1e-12)
    counts = []
    for _ in range(2):
        x = krylov(Dense(A, b))
        assert np.linalg.norm(b - A @ x) <= 1e-12 * np.linalg.norm(b)
        counts.append(krylov.iterations)
    assert krylov.used_gmres and counts[0] > 1 and counts[1] == 2 * counts[0]


def test_the_systems_preconditioner_is_used():
    """With its exact inverse as preconditioner a system is solved in one iteration; the
    same system without one takes more."""
    A, b = _near_identity(n=60, eps=0.6, seed=2)
    inverse = np.linalg.inv(A)
    with_inverse = LinearSolver(0, 1e-10)
    with_inverse(Dense(A, b, precondition=lambda r: inverse @ r))
    plain = LinearSolver(0, 1e-10)
    plain(Dense(A, b))
    assert with_inverse.iterations == 1 < plain.iterations


def test_a_call_may_ask_its_own_tolerance():
    """The solver's 1e-12 overridden by the call's 1e-2: fewer iterations, a residual
    between the two."""
    A, b = _near_identity(n=60, eps=0.6, seed=2)
    tight, loose = LinearSolver(0, 1e-12), LinearSolver(0, 1e-12)
    tight(Dense(A, b))
    x = loose(Dense(A, b), rtol=1e-2)
    assert loose.iterations < tight.iterations
    assert 1e-12 * np.linalg.norm(b) < np.linalg.norm(b - A @ x) <= 1e-2 * np.linalg.norm(b)


def test_a_call_may_ask_its_own_number_of_restarts():
    """A system that needs about 20 iterations, restarted every 5: one cycle is not
    enough (the caller's error; with a dense fallback, dense LU instead), the solver's 50
    are."""
    A, b = _near_identity(n=60, eps=0.6, seed=8)

    class Failed(Exception):
        pass

    solver = LinearSolver(0, 1e-10, restart=5, maxiter=50, error=Failed)
    with pytest.raises(Failed):
        solver(Dense(A, b), maxiter=1)
    assert solver.iterations == 5
    x = solver(Dense(A, b))
    assert solver.iterations > 15 and np.linalg.norm(b - A @ x) <= 1e-10 * np.linalg.norm(b)
    fallback = LinearSolver(0, 1e-10, restart=5, maxiter=50, error=Failed, dense_fallback=60)
    x = fallback(Dense(A, b), maxiter=1)
    assert fallback.fallbacks == 1 and fallback.iterations == 5
    np.testing.assert_allclose(x, np.linalg.solve(A, b), rtol=0, atol=1e-12 * np.abs(x).max())


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


def test_a_correction_call_may_ask_its_tolerance_of_b():
    """``of_b``: a correction solver's call from a guess stops at ``rtol |b|``, as a call
    from zero would, not at ``rtol`` times the guess's residual: from a guess with residual
    1e-4 |b|, asked 1e-6 it ends between 1e-7 and 1e-6 |b| in fewer iterations than the
    correction (at most 1e-10 |b|; measured 6.1e-7 |b| in 8 iterations against 1.2e-10 |b|
    in 21); asked 1e-3, more than the guess's residual, it returns
    the guess in no iteration. The reduction this asks of the guess's residual decides the
    precision: 2e-2 (at least ``single_from``, 1e-2 here) takes the single-precision
    product, 5e-3 does not."""
    A, b = _near_identity(n=60, eps=0.6, seed=6)
    exact = np.linalg.solve(A, b)
    rng = np.random.default_rng(8)
    guess = exact + 1e-4 * np.linalg.norm(exact) * rng.normal(size=b.size) / np.sqrt(b.size)
    nb, r0 = np.linalg.norm(b), np.linalg.norm(b - A @ guess)
    assert 3e-5 * nb < r0 < 3e-4 * nb
    corr = LinearSolver(0, 1e-6, correction=True)
    x = corr(Dense(A, b), guess)
    assert np.linalg.norm(b - A @ x) <= 1e-6 * r0
    of_b = LinearSolver(0, 1e-6, correction=True)
    x = of_b(Dense(A, b), guess, of_b=True)
    assert 1e-7 * nb < np.linalg.norm(b - A @ x) <= 1e-6 * nb and 0 < of_b.iterations < corr.iterations
    done = LinearSolver(0, 1e-3, correction=True)
    np.testing.assert_array_equal(done(Dense(A, b), guess, of_b=True), guess)
    assert done.iterations == 0
    calls = []
    Single = _with_single(calls)
    for reduction, single in ((2e-2, True), (5e-3, False)):  # of the guess's residual
        calls.clear()
        solver = LinearSolver(0, 1e-10, correction=True, single_from=1e-2)
        x = solver(Single(A, b), guess, rtol=reduction * r0 / nb, of_b=True)
        assert solver.iterations > 0 and np.linalg.norm(b - A @ x) <= reduction * r0
        assert bool(calls) == single and set(calls) <= {np.dtype(np.float32)}


def test_the_floor_ends_a_correction_solve_near_rounding():
    """A correction whose residual is already below ``floor |b|`` is not reduced further."""
    A, b = _near_identity(n=60, eps=0.3)
    b = 1e7 * b  # the floor is relative to |b|
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
    with pytest.raises(Failed) as info:  # unnamed: the size names it, and no hint
        solver(Dense(A, b))
    assert str(info.value) == "GMRES did not reduce the residual by 1.0e-12 on 60 unknowns in 1 iterations"


def test_an_inexact_inner_product_still_ends_on_the_true_residual():
    """The cycles run on a product perturbed by 1e-7 of its size (a single-precision
    one); the residual at each cycle's end is the exact product's, so the solve reaches
    1e-12 of |b| by restarting from it, which the inexact product alone cannot (its own
    Arnoldi residual stalls near 1e-7)."""
    A, b = _near_identity(n=80, eps=0.6, seed=5)
    rng = np.random.default_rng(6)
    exact, inexact = [], []

    def matvec(v):
        exact.append(1)
        return A @ v

    def inner(v):
        inexact.append(1)
        w = A @ v
        return w + 1e-7 * np.linalg.norm(w) * rng.normal(size=w.size) / np.sqrt(w.size)

    tol = 1e-12 * np.linalg.norm(b)
    x, ok, its = fgmres(matvec, b, tol=tol, restart=60, maxiter=10, inner=inner)
    assert ok and np.linalg.norm(b - A @ x) <= tol
    assert len(inexact) == its and len(exact) >= 2  # restarted at least once
    _, alone, _ = fgmres(inner, b, tol=tol, restart=60, maxiter=1)
    assert not alone


def test_a_single_precision_basis_still_ends_on_the_true_residual():
    """Krylov vectors kept and orthogonalised in single precision (``basis``): the
    preconditioner and the product see ``float32`` vectors, a cycle's Arnoldi residual is
    good to about 1e-7, and the residual recomputed in double at each cycle's end carries
    the solve to 1e-12 of |b| by restarts, as with a double basis."""
    A, b = _near_identity(n=80, eps=0.6, seed=7)
    seen = set()

    def precondition(v):
        seen.add(v.dtype)
        return v * 1.0

    tol = 1e-12 * np.linalg.norm(b)
    x64, ok64, its64 = fgmres(lambda v: A @ v, b, precondition, tol=tol, restart=60, maxiter=10)
    assert ok64 and seen == {np.dtype(np.float64)}
    seen.clear()
    x32, ok32, its32 = fgmres(lambda v: A @ v, b, precondition, tol=tol, restart=60, maxiter=10,
                              basis=np.float32)
    assert ok32 and seen == {np.dtype(np.float32)}
    assert np.linalg.norm(b - A @ x32) <= tol and x32.dtype == np.float64
    assert its64 <= its32 <= its64 + 25  # a restart or two more, from about 1e-7 (measured 42 and 63)


def _with_single(calls):
    """A :class:`Dense` system class with a ``matvec_single`` (the product in single
    precision) that records the dtype it sees in ``calls``."""

    class Single(Dense):
        def matvec_single(self, x):
            calls.append(x.dtype)
            return (self.A.astype(np.float32) @ x.astype(np.float32)).astype(float)

    return Single


def test_loose_calls_take_the_systems_single_precision_product():
    """A call reducing by ``single_from`` or less runs its cycles on ``matvec_single``
    when the system has one, on Krylov vectors kept in single precision; a tighter call
    and a system without one do not."""
    A, b = _near_identity(n=60, eps=0.6, seed=2)
    calls = []
    Single = _with_single(calls)

    solver = LinearSolver(0, 1e-12, single_from=1e-5)
    x = solver(Single(A, b), rtol=1e-5)
    assert calls and np.linalg.norm(b - A @ x) <= 1e-5 * np.linalg.norm(b)
    assert set(calls) == {np.dtype(np.float32)}
    used = len(calls)
    x = solver(Single(A, b))
    assert len(calls) == used and np.linalg.norm(b - A @ x) <= 1e-12 * np.linalg.norm(b)
    x = solver(Dense(A, b), rtol=1e-3)
    assert np.linalg.norm(b - A @ x) <= 1e-3 * np.linalg.norm(b)
    LinearSolver(0, 1e-12)(Single(A, b), rtol=1e-3)  # by default never
    assert len(calls) == used


def test_a_tight_call_refines_in_single_precision_phases():
    """With ``single_start`` a call tighter than ``single_from`` is iterative refinement:
    phases on the single-precision product and basis, with the system's preconditioner,
    each reducing the residual left by at most ``single_start`` and recomputing it in
    double; it ends on the tolerance asked (1e-12, three phases from 1e-4 a phase) with
    every GMRES product in single precision, and the iterations of all phases count, over
    calls too. A phase that fails (a single-precision product half the true one) hands the rest
    to double precision, which still ends on the tolerance. A call whose tolerance
    ``single_start`` already meets is one phase; a system without a single-precision
    product is solved in double throughout. (``b`` of norm 1e4: the reductions are
    relative to it.)"""
    A, b = _near_identity(n=60, eps=0.6, seed=4)
    b = 1e4 * b / np.linalg.norm(b)
    calls = []
    Single = _with_single(calls)
    inverse = np.linalg.inv(A + 0.01 * np.eye(60))  # a good but inexact preconditioner
    doubles = []

    class Counted(Single):
        def matvec(self, x):
            doubles.append(1)
            return super().matvec(x)

    def system(cls=Counted):
        return cls(A, b, lambda r: (inverse @ r).astype(r.dtype))

    plain = LinearSolver(0, 1e-12, single_from=1e-5)
    plain(system())
    assert not calls
    solver = LinearSolver(0, 1e-12, single_from=1e-5, single_start=1e-4)
    doubles.clear()
    x = solver(system())
    assert np.linalg.norm(b - A @ x) <= 1e-12 * np.linalg.norm(b)
    assert set(calls) == {np.dtype(np.float32)} and len(calls) == solver.iterations
    # three phases: each ends on one product in double (its cycle's residual) and the two
    # first on one more (the residual the next one starts from)
    assert len(doubles) == 5
    assert solver.iterations <= plain.iterations + 3
    first = solver.iterations
    solver(system())
    assert solver.iterations == 2 * first and len(calls) == 2 * first
    doubles.clear()
    x = LinearSolver(0, 1e-12, single_from=1e-5, single_start=1e-6)(system(), rtol=3e-6)  # one phase
    assert len(calls) > 2 * first and len(doubles) == 1 and np.linalg.norm(b - A @ x) <= 3e-6 * np.linalg.norm(b)
    used = len(calls)
    x = solver(system(Dense))
    assert len(calls) == used and np.linalg.norm(b - A @ x) <= 1e-12 * np.linalg.norm(b)

    class Rough(Counted):  # a "single-precision" product half the true one: the phase never settles
        def matvec_single(self, x):
            calls.append(x.dtype)
            return 0.5 * (self.A @ x)

    calls.clear()
    rough = LinearSolver(0, 1e-12, single_from=1e-5, single_start=1e-4)
    x = rough(system(Rough))
    assert np.linalg.norm(b - A @ x) <= 1e-12 * np.linalg.norm(b)
    assert 0 < len(calls) < rough.iterations  # single, then double


def test_bordered_preconditioner_is_the_block_inverse_and_declines_a_singular_complement():
    """With the exact inverse of ``A`` for the forces, :func:`bordered` on
    :func:`eliminate`'s parts is the exact inverse of ``[[A, F], [G, 0]]`` (two global
    unknowns); global rows that cannot see the forces' answer (``G M F`` singular) give
    ``None``; parts of another ``M`` still give a fixed linear map, not the inverse."""
    from bem.linear import bordered, eliminate

    rng = np.random.default_rng(3)
    m, k = 9, 2
    A = rng.normal(size=(m, m)) + 4 * np.eye(m)
    F, G = rng.normal(size=(m, k)), rng.normal(size=(k, m))
    inv = np.linalg.inv(A)
    parts = eliminate(lambda r: inv @ r, F, lambda x: G @ x)
    pre = bordered(lambda r: inv @ r, lambda x: G @ x, parts)
    K = np.block([[A, F], [G, np.zeros((k, k))]])
    r = rng.normal(size=m + k)
    np.testing.assert_allclose(K @ pre(r), r, rtol=0, atol=1e-12 * np.abs(r).max())
    np.testing.assert_allclose(pre(r), np.linalg.solve(K, r), rtol=1e-10)
    assert eliminate(lambda r: inv @ r, F, lambda x: np.zeros((k, x.shape[1]))) is None
    G_rank1 = np.vstack([G[0], 2 * G[0]])
    assert eliminate(lambda r: inv @ r, F, lambda x: G_rank1 @ x) is None
    other = eliminate(lambda r: 0.9 * inv @ r, F, lambda x: G @ x)
    stale = bordered(lambda r: inv @ r, lambda x: G @ x, other)
    assert not np.allclose(K @ stale(r), r)
    np.testing.assert_allclose(stale(2 * r + r[::-1]), 2 * stale(r) + stale(r[::-1]), rtol=1e-12)


def test_flexible_gmres_solves_to_the_asked_residual():
    """bem.linear.fgmres against a dense solve: a nonsymmetric system (n = 300) with a
    preconditioner applied in single precision (a slightly different operator at every
    call, which the flexible variant allows), restarted every 7 iterations: the true
    residual is below the asked 1e-11 |b| and x equals the dense solution to 1e-9 (the
    system's condition is ~10); without enough iterations it says so."""
    from bem.linear import fgmres

    rng = np.random.default_rng(11)
    n = 300
    A = np.diag(rng.uniform(1, 10, n)) + rng.normal(size=(n, n)) / np.sqrt(n)
    b = rng.normal(size=n)
    approx = np.linalg.inv(A + 0.3 * rng.normal(size=(n, n)) / np.sqrt(n)).astype(np.float32)

    def precondition(r):
        return (approx @ r.astype(np.float32)).astype(float)

    tol = 1e-11 * np.linalg.norm(b)
    x, ok, its = fgmres(lambda v: A @ v, b, precondition, tol=tol, restart=7, maxiter=50)
    assert ok and 0 < its <= 350
    assert np.linalg.norm(b - A @ x) <= tol
    np.testing.assert_allclose(x, np.linalg.solve(A, b), rtol=0, atol=1e-9 * np.abs(x).max())
    x, ok, its = fgmres(lambda v: A @ v, b, None, tol=tol, restart=2, maxiter=1)
    assert not ok and its == 2
