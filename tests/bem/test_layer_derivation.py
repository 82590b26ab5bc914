"""Re-derivation of the paper's first-order system dq/dz = A q (eqs. 44-45) with sympy.

Starts from the governing equations, not from the paper's intermediate eqs. 34-42:
equilibrium in the moving frame (eq. 8), incompressibility, deviatoric stress
s = 2 G* eps (eq. 26) with eps the symmetric gradient of u (eqs. 28-33 are then computed,
not copied), one Fourier mode exp(i (nu_x x + nu_y y)), state q = (w, u, v, sigma_z,
tau_xz, tau_yz) (eq. 43). Finding: eq. 27's beta_y carries a transcription typo (its
inertia term must be -rho V^2 nu_x^2, not -rho V^2 nu_y^2). See docs/derivations.md.
"""

from __future__ import annotations

import functools

import numpy as np
import sympy as sp

from bem.materials import Prony

x, y, z, t = sp.symbols("x y z t", real=True)
nx, ny = sp.symbols("nu_x nu_y", real=True)
G = sp.Symbol("G", nonzero=True)  # complex modulus G*(omega_m)
rV2 = sp.Symbol("rhoV2", nonnegative=True)  # rho V^2
lam = sp.Symbol("lambda")
I = sp.I


def paper_matrix(printed_beta_y: bool) -> sp.Matrix:
    """Eq. 45 with eq. 27's betas, as printed (``printed_beta_y``) or corrected."""
    bx = (4 * nx**2 + ny**2) * G - rV2 * nx**2
    by = (nx**2 + 4 * ny**2) * G - rV2 * (ny**2 if printed_beta_y else nx**2)
    bxy = 3 * nx * ny * G
    return sp.Matrix(
        [
            [0, -I * nx, -I * ny, 0, 0, 0],
            [-I * nx, 0, 0, 0, 1 / G, 0],
            [-I * ny, 0, 0, 0, 0, 1 / G],
            [-rV2 * nx**2, 0, 0, 0, -I * nx, -I * ny],
            [0, bx, bxy, -I * nx, 0, 0],
            [0, bxy, by, -I * ny, 0, 0],
        ]
    )


@functools.lru_cache(maxsize=None)
def derived_matrix() -> sp.Matrix:
    """A such that dq/dz = A q, derived from eqs. 8 and 26 for one Fourier mode."""
    E = sp.exp(I * (nx * x + ny * y))
    w, u, v, p = (sp.Function(name)(z) for name in "wuvp")
    X = (x, y, z)
    disp = (u * E, v * E, w * E)  # displacement components along x, y, z
    eps = sp.Matrix(3, 3, lambda i, j: (sp.diff(disp[i], X[j]) + sp.diff(disp[j], X[i])) / 2)
    s = 2 * G * eps  # deviatoric stress (incompressible, eq. 26)
    pressure = p * E
    # eq. 8: rho V^2 d2u/dx2 = div(s) - grad(p), divided by the mode's exponential
    div_s = [sum(sp.diff(s[i, j], X[j]) for j in range(3)) for i in range(3)]
    equilibrium = [sp.expand((rV2 * sp.diff(disp[i], x, 2) - div_s[i] + sp.diff(pressure, X[i])) / E) for i in range(3)]
    incompressible = sp.expand(sum(sp.diff(disp[i], X[i]) for i in range(3)) / E)
    state = [w, u, v, sp.expand((s[2, 2] - pressure) / E), sp.expand(s[0, 2] / E), sp.expand(s[1, 2] / E)]
    dstate = [sp.diff(e, z) for e in state]

    # Replace the functions and their derivatives by plain symbols, highest order first.
    W, U, V, S, TX, TY = Q = sp.symbols("W U V S T_x T_y")
    w1, u1, v1, w2, u2, v2, p0, p1 = unknowns = sp.symbols("w1 u1 v1 w2 u2 v2 p0 p1")
    to_symbols = [
        (sp.diff(w, z, 2), w2), (sp.diff(u, z, 2), u2), (sp.diff(v, z, 2), v2),
        (sp.diff(w, z), w1), (sp.diff(u, z), u1), (sp.diff(v, z), v1), (sp.diff(p, z), p1),
        (w, W), (u, U), (v, V), (p, p0),
    ]  # fmt: skip
    sym = lambda e: e.subs(to_symbols)  # noqa: E731
    equations = [sym(e) for e in equilibrium]
    equations += [sym(incompressible), sym(sp.diff(incompressible, z))]
    equations += [sym(state[k]) - Q[k] for k in (3, 4, 5)]  # definitions of sigma_z, tau_xz, tau_yz
    (solution,) = sp.solve(equations, unknowns, dict=True)
    dq = sp.Matrix([sp.expand(sym(e).subs(solution)) for e in dstate])
    A = dq.jacobian(Q)
    assert sp.expand(dq - A * sp.Matrix(Q)) == sp.zeros(6, 1)  # linear and homogeneous in q
    return A.applyfunc(sp.simplify)


def test_derived_matrix_is_eq45_with_corrected_beta_y():
    A = derived_matrix()
    corrected, printed = paper_matrix(printed_beta_y=False), paper_matrix(printed_beta_y=True)
    for i in range(6):
        for j in range(6):
            assert sp.simplify(A[i, j] - corrected[i, j]) == 0, (i, j, A[i, j])
            if (i, j) != (5, 2):
                assert sp.simplify(A[i, j] - printed[i, j]) == 0, (i, j)
    # The printed beta_y (row tau_yz, column v) differs whenever nu_x^2 != nu_y^2 and rho V^2 != 0:
    difference = sp.factor(A[5, 2] - printed[5, 2])
    assert sp.simplify(difference - rV2 * (ny**2 - nx**2)) == 0
    assert difference.subs({nx: 2, ny: 1, rV2: 3}) != 0
    # Physical reading: a mode constant along x is static in the material (omega_m = 0),
    # so inertia must drop out of it. It does in the derived matrix, not in the printed one.
    assert rV2 not in A.subs(nx, 0).free_symbols
    assert rV2 in printed.subs(nx, 0).free_symbols


def test_characteristic_polynomial_roots_k_single_and_q_double():
    # Roots +-k once (the pressure, harmonic: div of eq. 8 gives lap p = 0) and +-q twice
    # (the in-plane and the antiplane shear parts, slowed by inertia).
    k2 = nx**2 + ny**2
    q2 = k2 - rV2 * nx**2 / G
    expected = (lam**2 - k2) * (lam**2 - q2) ** 2
    charpoly = derived_matrix().charpoly(lam).as_expr()
    assert sp.expand(G**2 * (charpoly - expected)) == 0
    # Not +-k double and +-q single: that differs as soon as rho V^2 nu_x^2 != 0.
    swapped = (lam**2 - k2) ** 2 * (lam**2 - q2)
    assert sp.expand(G**2 * (charpoly - swapped)) != 0
    # With the printed beta_y the roots are not +-k, +-q at all.
    printed = paper_matrix(printed_beta_y=True).charpoly(lam).as_expr()
    assert sp.expand(G**2 * (printed - expected)) != 0
    assert sp.expand(G**2 * (printed - swapped)) != 0


def test_moving_frame_frequency_and_complex_modulus_convention():
    # x = x' - V t (eq. 5): the mode exp(i nu_x x) is exp(i nu_x x') exp(i omega t) in the
    # material, with omega = -nu_x V (eq. 25).
    Vs, xp = sp.symbols("V x_p", real=True)
    omega = -nx * Vs
    assert sp.simplify(sp.exp(I * nx * (xp - Vs * t)) - sp.exp(I * nx * xp) * sp.exp(I * omega * t)) == 0
    # Boltzmann integral (eq. 9) for eps = eps0 exp(i w t) and one Maxwell branch
    # G(t) = G1 exp(-t/tau): s = 2 G*(w) eps with G*(w) = i w int_0^oo G(t) exp(-i w t) dt,
    # which is Prony's G1 i w tau / (1 + i w tau); G(t) real gives G*(-w) = conj G*(w).
    w_, G1, tau = sp.Symbol("omega", real=True), sp.Symbol("G1", positive=True), sp.Symbol("tau", positive=True)
    Gstar = I * w_ * sp.integrate(G1 * sp.exp(-t / tau) * sp.exp(-I * w_ * t), (t, 0, sp.oo), conds="none")
    assert sp.simplify(Gstar - G1 * I * w_ * tau / (1 + I * w_ * tau)) == 0
    values = {G1: 2.0e6, tau: 0.1}
    for wv in (-30.0, 0.5, 7.0):
        exact = complex(Gstar.subs(values).subs(w_, wv))
        assert np.isclose(Prony(1.0, (2.0e6,), (0.1,)).modulus(wv) - 1.0, exact, rtol=1e-14, atol=0)
        assert np.isclose(complex(Gstar.subs(values).subs(w_, -wv)), np.conj(exact), rtol=1e-14, atol=0)


def test_bem_layer_system_matrix_matches_the_derivation():
    from bem.layer import system_matrix  # imported here: the module may land after this test

    A = sp.lambdify((nx, ny, G, rV2), derived_matrix(), "numpy")
    rng = np.random.default_rng(45)
    for _ in range(8):
        nu_x, nu_y = rng.uniform(-1e3, 1e3, 2)
        modulus = complex(rng.uniform(1e5, 1e7), rng.uniform(-1e6, 1e6))
        rho_V2 = rng.uniform(0, 1e4)
        expected = np.array(A(nu_x, nu_y, modulus, rho_V2), dtype=complex)
        np.testing.assert_allclose(system_matrix(nu_x, nu_y, modulus, rho_V2), expected, rtol=1e-13, atol=0)
    at_rest = np.array(A(0.0, 0.0, 3e6, 0.0), dtype=complex)  # the k = 0 mode
    np.testing.assert_allclose(system_matrix(0.0, 0.0, 3e6, 0.0), at_rest, rtol=0, atol=0)
