"""The layer's Fourier-space compliance: closed form against the matrix exponential,
exact limits, and the identities of linear viscoelasticity."""

import numpy as np
import pytest

from bem.layer import normal_compliance, normal_compliance_outer, surface_compliance, surface_compliance_expm

H = 5e-3
KH = [0.0, 1e-8, 1e-4, 1e-2, 0.3, 0.99, 1.0, 1.01, 2.0, 2.01, 5.0, 10.0, 30.0, 49.0, 51.0, 1e2, 1e3, 1e4, 1e5]
# (G*, rho V^2): static elastic, viscoelastic, viscoelastic with inertia, transonic and
# supersonic speeds relative to the shear wave (rho V^2 / G = 0.7, 0.999, 1.5)
MATERIALS = [(3e6, 0.0), (3e6 + 1e6j, 0.0), (3e6 + 1e6j, 2.5), (3e6, 2.1e6), (3e6, 2.997e6), (3e6 + 5e5j, 4.5e6)]
ANGLES = [0.0, 0.7, np.pi / 2, 2.5]


@pytest.mark.parametrize("G, rho_V2", MATERIALS)
def test_closed_form_matches_matrix_exponential(G, rho_V2):
    """All nine entries, kH from 0 to 1e5: 1e-11 relative to the largest entry (measured
    1.3e-12; the issue asks 1e-10; the reference itself carries ~1e-13; entries that vanish like (kH)^2 next to H/G cannot
    be resolved relative to themselves by the exponential route)."""
    errors = []
    for kh in KH:
        for ang in ANGLES:
            k = kh / H
            nx, ny = k * np.cos(ang), k * np.sin(ang)
            C = surface_compliance(nx, ny, G, rho_V2, H)
            R = surface_compliance_expm(nx, ny, G, rho_V2, H)
            errors.append(np.abs(C - R).max() / np.abs(R).max())
    # np.max, not a running max(): a NaN (a broken entry of either route) must fail
    assert np.max(errors) < 1e-11


def test_k_zero_is_exact():
    """Uniform traction: no vertical motion (bonded incompressible), simple shear H/G;
    computed without a floating-point warning (no 0/0 on the way), alone or among other
    modes."""
    import warnings

    G = 3e6 + 2e5j
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        C = surface_compliance(0.0, 0.0, G, 7.0, H)
        np.testing.assert_array_equal(C, np.diag([0, H / G, H / G]))
        Cs = surface_compliance(np.array([0.0, 300.0, 0.0]), np.array([0.0, 0.0, -50.0]), G, 7.0, H)
    np.testing.assert_array_equal(Cs[0], C)
    np.testing.assert_array_equal(Cs[1], surface_compliance(300.0, 0.0, G, 7.0, H))


def _compliance_mp(nx, ny, G, rho_V2, H, digits=30):
    """T12 T22^-1 of eq. 45 (beta_y corrected; its own transcription here) with a
    30-digit matrix exponential (mpmath): a reference for every entry on its own scale."""
    import mpmath as mp

    with mp.workdps(digits):
        G, nx, ny, rv2 = mp.mpc(G), mp.mpf(nx), mp.mpf(ny), mp.mpf(rho_V2)
        ix, iy = mp.mpc(0, 1) * nx, mp.mpc(0, 1) * ny
        inertia = rv2 * nx**2
        bx, by, bxy = (4 * nx**2 + ny**2) * G - inertia, (nx**2 + 4 * ny**2) * G - inertia, 3 * nx * ny * G
        A = mp.matrix([[0, -ix, -iy, 0, 0, 0], [-ix, 0, 0, 0, 1 / G, 0], [-iy, 0, 0, 0, 0, 1 / G],
                       [-inertia, 0, 0, 0, -ix, -iy], [0, bx, bxy, -ix, 0, 0], [0, bxy, by, -iy, 0, 0]])
        T = mp.expm(A * mp.mpf(H))
        C = T[0:3, 3:6] * mp.inverse(T[3:6, 3:6])
        return np.array([[complex(C[i, j]) for j in range(3)] for i in range(3)])


@pytest.mark.parametrize("G, rho_V2, ang", [(3e6, 0.0, 0.7), (3e6 + 1e6j, 2.5, 0.7), (3e6, 2.1e6, 0.7), (3e6, 4.5e6, 0.3),
                                            (3e6 + 5e5j, 4.5e6, 0.7), (1e5 + 3e6j, 1e6, 0.7)])
def test_every_entry_on_its_own_scale_against_a_30_digit_exponential(G, rho_V2, ang):
    """At small kH the w-entries vanish like kH or (kH)^2 next to H/G, so a comparison
    relative to the largest entry cannot see them; against a 30-digit matrix exponential
    each entry is compared with itself: ww, uu, vv 5e-14 (measured <= 8e-16, and 1.0e-14
    in ww at kH = 6 above the shear-wave speed); the w-u
    couplings 1e-12 (measured <= 8e-16 for kH <= 2, 2.5e-13 at kH = 6 in the large-kH
    basis); uv = vu =
    cos sin (c_LL - c_TT) is a difference of two O(H/G) numbers that agree to (kH)^2: its
    round-off is eps / (kH)^2 relative to itself (measured 2e-8 at kH = 1e-4), allowed
    1e-15 / (kH)^2 + 1e-14; its absolute error stays at round-off of H/G. A real modulus
    above the shear-wave speed (rho V^2 = 1.5 G) makes q^2 < 0 for the modes within 35
    degrees of x (here 17 degrees: q = i |q|, taken in complex arithmetic). The last
    material (loss factor 30, rho V^2 = |G| / 3) has Re q > k, where the
    scaled bases take exp((k - kappa) H) != 1."""
    for kh in (1e-4, 1e-3, 0.02, 0.3, 1.5, 6.0):
        k = kh / H
        nx, ny = k * np.cos(ang), k * np.sin(ang)
        R = _compliance_mp(nx, ny, G, rho_V2, H)
        err = np.abs(surface_compliance(nx, ny, G, rho_V2, H) - R) / np.abs(R)
        tol = np.full((3, 3), 1e-12)
        tol[[0, 1, 2], [0, 1, 2]] = 5e-14
        tol[1, 2] = tol[2, 1] = 1e-15 / kh**2 + 1e-14
        assert np.all(err <= tol), (kh, err)


@pytest.mark.parametrize("G", [3e6, 3e6 + 1.5e6j])
def test_deep_couplings_with_a_little_inertia_on_their_own_scale(G):
    """Beyond k H = 50 with eps = rho V^2 nu_x^2 / (G k^2) of 6e-7 and 6e-10 the normal-
    tangential entries are of order eps: i (k - q) / (G R) with k - q = eps k / 2 to first
    order, so k - q is taken as (k^2 - q^2) / (k + q) (the difference of k and q keeps
    1e-16 k: 1e-10 to 3e-7 of the entry, measured). Against a 40-digit matrix exponential,
    each entry on its own scale: 1e-13 (measured 1.3-6.2e-16)."""
    for kh, rho_V2 in ((60.0, 3.0), (300.0, 3.0), (300.0, 3e-3)):
        k = kh / H
        nx, ny = k * np.cos(0.7), k * np.sin(0.7)
        R = _compliance_mp(nx, ny, G, rho_V2, H, digits=40)
        C = surface_compliance(nx, ny, G, rho_V2, H)
        for i, j in ((0, 1), (0, 2), (1, 0), (2, 0)):
            assert abs(C[i, j] - R[i, j]) <= 1e-13 * abs(R[i, j]), (kh, rho_V2, i, j)


def test_static_normal_compliance_independent_formula():
    """V = 0: w/sigma_z = (sinh 2kH - 2kH) / (2 G k (cosh 2kH + 2 (kH)^2 + 1)), the bonded
    incompressible layer of Jaffar's L(omega) (paper eq. 68, kappa = 1), to 1e-13."""
    G = 3e6
    kh = np.logspace(-1, np.log10(300), 60)
    k = kh / H
    ref = (np.sinh(2 * kh) - 2 * kh) / (2 * G * k * (np.cosh(2 * kh) + 2 * kh**2 + 1))
    got = normal_compliance(k, 0.0, G, 0.0, H)
    np.testing.assert_allclose(got.real, ref, rtol=1e-13)
    assert np.all(got.imag == 0)


def test_thin_and_half_space_limits():
    G = 3e6
    for kh in (1e-3, 1e-4):  # thin: k^2 H^3 / (3 G) (1 - 9/5 (kH)^2 + ...), by series
        k = kh / H
        got = normal_compliance(k, 0.0, G, 0.0, H).real
        np.testing.assert_allclose(got, k**2 * H**3 / (3 * G) * (1 - 1.8 * kh**2), rtol=1e-4 * kh**2)
    k = 1e3 / H  # half-space: normal 1/(2Gk), in-plane 1/(2Gk) along and 1/(Gk) across k
    C = surface_compliance(k, 0.0, G, 0.0, H)
    np.testing.assert_allclose(np.diag(C).real, [1 / (2 * G * k), 1 / (2 * G * k), 1 / (G * k)], rtol=1e-14)


@pytest.mark.parametrize("G", [3e6, 3e6 + 1.2e6j])
def test_reciprocity_at_rest(G):
    """V = 0 (elastic or at one frequency): C(nu)^T = C(-nu) (Betti's theorem)."""
    rng = np.random.default_rng(0)
    for _ in range(20):
        nx, ny = rng.normal(size=2) * 10 ** rng.uniform(0, 5) / H
        C = surface_compliance(nx, ny, G, 0.0, H)
        Cm = surface_compliance(-nx, -ny, G, 0.0, H)
        np.testing.assert_allclose(C.T, Cm, rtol=1e-12, atol=1e-12 * np.abs(C).max())


def test_reality_in_the_moving_frame():
    """Mode -m sees the conjugate modulus: C(-nu, conj G) = conj C(nu, G), any speed."""
    rng = np.random.default_rng(1)
    for _ in range(20):
        nx, ny = rng.normal(size=2) * 10 ** rng.uniform(0, 4) / H
        G = 3e6 + 1e6j * rng.uniform()
        rv2 = rng.uniform(0, 4e6)
        np.testing.assert_allclose(
            surface_compliance(-nx, -ny, np.conj(G), rv2, H),
            np.conj(surface_compliance(nx, ny, G, rv2, H)),
            rtol=1e-12, atol=1e-14 * H / 3e6,
        )


def test_viscous_layer_dissipates():
    """At rest and one frequency omega > 0 (G'' > 0) the layer absorbs power for every
    traction: the Hermitian form -Im(t^H C t) is >= 0."""
    rng = np.random.default_rng(2)
    for _ in range(20):
        nx, ny = rng.normal(size=2) * 10 ** rng.uniform(0, 4) / H
        C = surface_compliance(nx, ny, 3e6 + 1e6j, 0.0, H)
        anti = (C - C.conj().T) / 2j
        assert np.linalg.eigvalsh(anti).max() <= 1e-12 * np.abs(C).max()


@pytest.mark.parametrize("G0, rho_V2", [(3e6, 0.0), (3e6, 2.5), (3e6, 3e3), (3e6, 3e6 * 0.7), (0.5, 1e-8)])
def test_outer_grid_fast_path_matches_exact(G0, rho_V2):
    """The half-space series used for the many high modes (eps <= 1e-6) against the exact
    closed form, through the switch to the exact path: 1e-11 relative. The soft case
    (G ~ 0.5 Pa, rho V^2 = 1e-8 Pa, eps ~ 1e-8) keeps the series in use where its
    inertia term still shows (~1e-8), so a wrong eps is seen. k = 0 is among the modes:
    no floating-point warning escapes."""
    import warnings

    nu_x = 2 * np.pi * np.arange(0, 3001, 7) / 0.2
    nu_y = 2 * np.pi * np.arange(0, 3001, 5) / 0.2
    G = G0 + G0 / 3 * 1j / (1 + (nu_x * 0.01) ** 2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fast = normal_compliance_outer(nu_x, nu_y, G, rho_V2, H)
    exact = normal_compliance(nu_x[:, None], nu_y[None, :], G[:, None], rho_V2, H)
    assert np.abs(fast - exact).max() <= 1e-11 * np.abs(exact).max()
    nz = np.abs(exact) > 0
    assert (np.abs(fast - exact)[nz] / np.abs(exact[nz])).max() < 1e-11


def test_closed_form_matches_matrix_exponential_at_unit_scale():
    """G ~ 1 Pa, H = 1 m, k ~ 0.1-5 1/m: every entry of the system matrix (eq. 45) is O(1)
    here, so an error in any of them, even one invisible next to G k^2 ~ 1e12 in SI
    units of the other test, changes the compliance; 1e-11 relative (measured ~1e-14)."""
    errors = []
    for G, rho_V2 in ((1.0, 0.0), (1.0 + 0.4j, 0.3), (0.7 + 0.2j, 0.9)):
        for k in (0.1, 0.8, 2.0, 5.0):
            for ang in ANGLES:
                nx, ny = k * np.cos(ang), k * np.sin(ang)
                C = surface_compliance(nx, ny, G, rho_V2, 1.0)
                R = surface_compliance_expm(nx, ny, G, rho_V2, 1.0)
                errors.append(np.abs(C - R).max() / np.abs(R).max())
    assert np.max(errors) < 1e-11


def test_layer_inertia_and_validation():
    """rho V^2 (Pa) at any density, exactly 0 without density even at an infinite speed;
    every invalid field named with its value."""
    from bem.layer import Layer
    from bem.materials import Elastic

    m = Elastic(3e6)
    assert Layer(H, m, 1000.0).inertia(2.0) == 4000.0
    assert Layer(H, m, 0.5).inertia(3.0) == 4.5
    assert Layer(H, m).inertia(np.inf) == 0.0 and Layer(H, m, 0.0).inertia(7.0) == 0.0
    assert Layer(1, m, 2).thickness == 1
    for bad in (0.0, -1e-3, np.inf, np.nan, "5e-3", None):
        with pytest.raises(ValueError, match=r"^thickness must be > 0 m, got "):
            Layer(bad, m)
    for bad in (-1.0, np.inf, np.nan, "1000", None):
        with pytest.raises(ValueError, match=r"^density must be >= 0 kg/m\^3, got "):
            Layer(H, m, bad)
    for bad in (object(), 3e6, type("NoCall", (), {"modulus": 3e6})()):
        with pytest.raises(TypeError, match=r"^material must have a modulus\(omega\) method, got "):
            Layer(H, bad)


@pytest.mark.parametrize("H", [1e-4, 5e-3, 0.2])
def test_without_inertia_the_closed_form_is_the_general_route(H):
    """Without inertia (q = k) the wave frame's compliances are real functions of k H over
    G (bem.layer._static_parts): against the general route (divided differences and
    decaying exponentials, taken with rho V^2 = 1e-300) from k H = 1e-6 to 1e4, to 4e-15
    relative for c_zz, c_LL, c_TT (measured 1.7-1.9e-15, 0.9-1.3e-15, 0.6e-15), the coupling
    within 1e-14 of c_LL / k (measured 0.6-1.9e-15; exponentially small past k H = 20,
    where the general route keeps only its rounding); at k = 0 the limits c_zz = 0, c_LL =
    c_TT = H / G, c_zL / k = -c_Lz / k = -i H^2 / (2 G)."""
    from bem.layer import _mode_parts

    k = np.concatenate([[0.0], np.geomspace(1e-6, 1e4, 3001) / H])
    G = np.full(k.size, 3e6 + 1e5j)
    got = _mode_parts(k, 0 * k, G, 0.0, H)
    ref = _mode_parts(k, 0 * k, G, 1e-300, H)
    for name, i in (("c_zz", 1), ("c_LL", 4), ("c_TT", 5)):
        assert np.all(np.abs(got[i] - ref[i]) <= 4e-15 * np.abs(ref[i])), name
    for i in (2, 3):
        assert np.all(np.abs(got[i] - ref[i]) * k <= 1e-14 * np.abs(ref[4])), i
    assert got[1][0] == 0 and got[4][0] == got[5][0] == H / G[0]
    assert got[2][0] == -got[3][0] == pytest.approx(-0.5j * H * H / G[0], rel=1e-15)


def _general_parts(k, d, H):
    """The general route's wave-frame compliances times G at q = sqrt(k^2 - d)
    (bem.layer._wave_frame_small / _large and the antiplane tanh(qH) / q), for modes that
    see the base (kH <= 50)."""
    from bem.layer import _antiplane, _wave_frame_large, _wave_frame_small

    q = np.sqrt(k * k - d)
    small = k * H <= 2.0
    out = [np.empty(k.shape, complex) for _ in range(5)]
    for mask, fn in ((small, _wave_frame_small), (~small, _wave_frame_large)):
        for o, v in zip(out, (*fn(k[mask], q[mask], H), _antiplane(q[mask], H))):
            o[mask] = v
    return out


@pytest.mark.parametrize("H", [1e-3, 0.05])
def test_a_little_inertia_to_second_order_is_the_general_route(H):
    """Modes that see the base (kH <= 50) with eps = d / k^2 = rho V^2 nu_x^2 / (G k^2) up
    to SERIES_EPS (1e-6) take the static parts plus d P1 + d^2 P2 (bem.layer._expanded_parts,
    _INERTIA_TERMS): from kH = 1e-6 to 50 (both sides of the series' switch at y = 2 kH =
    2.5), against the general route at eps = 1e-6, 1e-6 (1 + 0.3 i) and 6e-7 i: c_zz, c_LL,
    c_TT within 1e-14 of themselves (measured up to 3.0e-15, the general route's own
    rounding), the couplings within 1e-14 of c_LL / k (measured 2.9e-15; past kH = 3 they
    are of order eps themselves, where the general route keeps a difference of near-equal
    terms: test below). At |eps| = 1e-3 the residual is the third-order term, below 0.8
    |eps|^3 of c_zz, c_LL, c_TT and 0.4 |eps|^3 of c_LL / k for the couplings (measured
    0.688, 0.188, 0.313 and 0.344: the half-space's 11/16, 3/16, 5/16, 11/32): a wrong P2
    would leave eps^2, a wrong P1 eps."""
    from bem.layer import _expanded_parts

    k = np.geomspace(1e-6, 50.0, 1201) / H
    for eps, bound in ((1e-6, None), (1e-6 * (1 + 0.3j), None), (6e-7j, None), (1e-3, 0.8), (-1e-3 * (1 - 0.5j), 0.8)):
        d = complex(eps) * k * k
        got, ref = _expanded_parts(k, d, H), _general_parts(k, d, H)
        tol = 1e-14 if bound is None else bound * abs(eps) ** 3
        for i, name in ((0, "c_zz"), (3, "c_LL"), (4, "c_TT")):
            assert np.all(np.abs(got[i] - ref[i]) <= tol * np.abs(ref[i])), (eps, name)
        cpl = 1e-14 if bound is None else 0.4 * abs(eps) ** 3
        for i in (1, 2):
            assert np.all(np.abs(got[i] - ref[i]) * k <= cpl * np.abs(ref[3])), (eps, i)
        np.testing.assert_array_equal(got[1], -got[2])  # reciprocity, at every order


def test_a_little_inertia_terms_limits():
    """P1 and P2 of c_zz, c_zL/k (as zl: G c_zL/k = -i (zl + d zl1 + d^2 zl2)), c_LL, c_TT: at
    k = 0 sympy's 0, 5 H^4/24, H^3/3, H^3/3 and 0, 61 H^6/720, 2 H^5/15, 2 H^5/15 (1e-15);
    past kH = 60 those of the half-space's k (k + q) / R, i (k - q) / R, q (q + k) / R, 1 /
    q (R = q^3 + k q^2 + 3 k^2 q - k^3): 3/(8 k^3), -1/(8 k^4), 1/(8 k^3), 1/(2 k^3) and
    11/(32 k^5), -5/(32 k^6), 3/(32 k^5), 3/(8 k^5), to 1e-14 (the base's e^{-2kH} is far
    below); finite to k H = 1e300."""
    from bem.layer import _inertia_parts

    H = 2e-3
    (zz1, zl1, ll1, tt1), (zz2, zl2, ll2, tt2) = _inertia_parts(np.array([0.0]), H)
    np.testing.assert_allclose([zz1[0], zl1[0] / H**4, ll1[0] / H**3, tt1[0] / H**3], [0, 5 / 24, 1 / 3, 1 / 3],
                               rtol=1e-15, atol=0)
    np.testing.assert_allclose([zz2[0], zl2[0] / H**6, ll2[0] / H**5, tt2[0] / H**5], [0, 61 / 720, 2 / 15, 2 / 15],
                               rtol=1e-15, atol=0)
    k = np.geomspace(60.0, 1e4, 50) / H
    first, second = _inertia_parts(k, H)
    for got, want in zip((*first, *second), (3 / 8 / k**3, -1 / 8 / k**4, 1 / 8 / k**3, 1 / 2 / k**3,
                                             11 / 32 / k**5, -5 / 32 / k**6, 3 / 32 / k**5, 3 / 8 / k**5)):
        np.testing.assert_allclose(got, want, rtol=1e-14, atol=0)
    huge = np.array([1e3, 1e10, 1e300]) / H
    assert all(np.isfinite(a).all() for a in (*_inertia_parts(huge, H)[0], *_inertia_parts(huge, H)[1]))


@pytest.mark.parametrize("kh", [3.0, 10.0, 12.6, 30.0, 49.0])
def test_couplings_with_a_little_inertia_near_the_base_on_their_own_scale(kh):
    """Past kH = 3 a slow roll's couplings are themselves of order eps (the static
    coupling falls as e^{-2kH}, the inertia's i eps / (8 k^2) does not): the expansion
    carries them to 1e-11 of themselves against a 40-digit matrix exponential (measured
    up to 3.1e-13, their third-order term), where the general route's difference of
    near-equal terms was up to 1.7e-9 off (eps = 4.6e-7, kH = 30)."""
    G, rho_V2 = 3e6 + 1e6j, 2.5
    k = kh / H
    nx, ny = k * np.cos(0.7), k * np.sin(0.7)
    R = _compliance_mp(nx, ny, G, rho_V2, H, digits=40)
    C = surface_compliance(nx, ny, G, rho_V2, H)
    for i, j in ((0, 1), (0, 2), (1, 0), (2, 0)):
        assert abs(C[i, j] - R[i, j]) <= 1e-11 * abs(R[i, j]), (i, j)


@pytest.mark.parametrize("H", [1e-3, 0.05])
def test_a_little_inertia_terms_are_the_general_routes_derivatives(H):
    """P1 and P2 (bem.layer._inertia_parts) against central differences of the general
    route in d (d = +-h, h = 3e-3 k^2) from kH = 0.05 to 50: P1 within 3e-5 (measured up to
    1.2e-5, the difference's h^2 term), P2 within 1.5e-4 (measured up to 6.1e-5), each of
    its own size, the couplings' of the size of the c_LL term over k. The test above
    bounds the expansion's residual by eps^3; this one holds each term on its own (all of
    P2 1 % off moves c_zz by at most 6.9e-15 at eps = 1e-6, below that test's 1e-14)."""
    from bem.layer import _inertia_parts, _static_parts

    k = np.geomspace(0.05, 50.0, 300) / H
    h = 3e-3 * k * k
    plus, minus = _general_parts(k, h + 0j, H), _general_parts(k, -h + 0j, H)
    p0, (first, second) = _static_parts(k, H), _inertia_parts(k, H)
    for general, static, unit in ((0, 0, 1.0), (1, 1, -1j), (3, 2, 1.0), (4, 3, 1.0)):
        d1 = (plus[general] - minus[general]) / (2 * h)
        d2 = (plus[general] + minus[general] - 2 * unit * p0[static]) / (2 * h * h)
        size = (lambda P: np.abs(P[2]) / k) if static == 1 else (lambda P: np.abs(P[static]))
        assert np.all(np.abs(d1 - unit * first[static]) <= 3e-5 * size(first)), general
        assert np.all(np.abs(d2 - unit * second[static]) <= 1.5e-4 * size(second)), general


def test_a_little_inertia_on_the_thickest_layer_stays_finite():
    """The expansion's terms hold H^6 (the second-order coupling): they are taken over H^2
    and H^4 and multiplied by d H^2, so a layer of MAX_THICKNESS (1e100 m) with inertia
    keeps finite compliances on its only modes near the base (k H <= 50: k = 0 and k =
    1e-101 rad/m here), and at k = 0 (d = 0) the static ones, c_LL = c_TT = H / G."""
    from bem.layer import MAX_THICKNESS, _mode_parts

    G = np.full(3, 3e6 + 1e6j)
    parts = _mode_parts(np.array([0.0, 1e-101, 0.0]), np.array([0.0, 0.0, 1e-101]), G, 2.5, MAX_THICKNESS)
    assert all(np.isfinite(p).all() for p in parts)
    assert parts[4][0] == parts[5][0] == MAX_THICKNESS / G[0]
