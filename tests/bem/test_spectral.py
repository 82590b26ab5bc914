"""Influence kernels: fast transforms against the paper's direct summation, symmetry of
the stationary elastic operator, and the compliance operator's products."""

import numpy as np
import pytest

from bem.grid import Grid
from bem.layer import Layer
from bem.materials import Elastic, ThreeParameterSolid
from bem.operator import ComplianceOperator
from bem.mode_sums import chirp_sum as _chirp_sum
from bem.spectral import BLOCKS, end_weights, influence_kernels, influence_kernels_direct

VISCO = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), density=1000.0)
ELASTIC = Layer(5e-3, Elastic(3.0e6))
# spacings that do not divide the periods, different in x and y, odd and even node counts
GRID = Grid(0.7e-3, 0.9e-3, 0.02, 0.025, 40, 30, 7, 6)
# 2 N_t a / L = 3 along x, 1 along y: the end modes alias onto the Nyquist frequencies, half weight
ALIASED = Grid(0.5e-3, 0.8e-3, 0.02, 0.024, 60, 15, 7, 6)


def test_chirp_sum_matches_direct_sum():
    rng = np.random.default_rng(0)
    c = rng.normal(size=(3, 57)) + 1j * rng.normal(size=(3, 57))
    ratio, j0, count = 0.0123456789, -11, 23
    n = np.arange(57)
    j = np.arange(j0, j0 + count)
    ref = c @ np.exp(2j * np.pi * ratio * np.outer(n, j))
    # measured 3.4e-15 of the largest term; 2e-14 is a 6x margin (was 1e-12)
    np.testing.assert_allclose(_chirp_sum(c, ratio, j0, count), ref, rtol=0, atol=2e-14 * np.abs(ref).max())


@pytest.mark.parametrize("grid", [GRID, ALIASED], ids=["plain", "aliased-ends"])
@pytest.mark.parametrize("path", ["products", "chirp"])
@pytest.mark.parametrize("speed", [0.0, 0.05, 40.0])
def test_fast_kernels_match_direct_summation(speed, path, grid, monkeypatch):
    """Every block, steady rolling with inertia included, by both transforms (matrix
    products on small grids, chirp-z beyond 128 nodes a side), and with the end modes at
    half weight: 1e-14 relative to the block (measured 0.8-1.8e-15 by products, 2.1-2.6e-15
    by chirp-z: a margin of 4 or more; the earlier 1e-12 was 400 times looser than the
    error)."""
    import bem.spectral

    monkeypatch.setattr(bem.spectral, "_MATMUL_NODES", 128 if path == "products" else 0)
    fast = influence_kernels(grid, VISCO, speed, blocks=BLOCKS)
    direct = influence_kernels_direct(grid, VISCO, speed, blocks=BLOCKS)
    for b in BLOCKS:
        scale = np.abs(direct[b]).max()
        assert np.abs(fast[b] - direct[b]).max() <= 1e-14 * scale, b


def test_stationary_elastic_operator_is_symmetric():
    """Reciprocity: C_WW(M, N) = C_WW(N, M) at rest; and the normal-tangential blocks
    satisfy C_WU = C_UW^T."""
    k = influence_kernels(GRID, ELASTIC, 0.0, blocks=("ww", "wu", "uw", "uu"))
    ww = ComplianceOperator(GRID, k["ww"]).dense()
    np.testing.assert_allclose(ww, ww.T, rtol=0, atol=1e-13 * np.abs(ww).max())
    wu = ComplianceOperator(GRID, k["wu"]).dense()
    uw = ComplianceOperator(GRID, k["uw"]).dense()
    np.testing.assert_allclose(wu, uw.T, rtol=0, atol=1e-13 * np.abs(ww).max())


def test_rolling_operator_is_not_symmetric():
    ww = ComplianceOperator(GRID, influence_kernels(GRID, VISCO, 0.05)["ww"]).dense()
    assert np.abs(ww - ww.T).max() > 1e-3 * np.abs(ww).max()


def test_operator_products_match_dense_matrix():
    op = ComplianceOperator(GRID, influence_kernels(GRID, VISCO, 0.05)["ww"])
    D = op.dense()
    f = np.random.default_rng(3).normal(size=GRID.shape)
    np.testing.assert_allclose(op.apply(f).ravel(), D @ f.ravel(), rtol=0, atol=1e-13 * np.abs(D).max())
    np.testing.assert_allclose(op.apply_transpose(f).ravel(), D.T @ f.ravel(), rtol=0, atol=1e-13 * np.abs(D).max())
    idx = np.array([3, 5, 17, 40])
    np.testing.assert_array_equal(op.dense(idx), D[np.ix_(idx, idx)])


def test_grid_validation_messages():
    with pytest.raises(ValueError, match="spacing_x must be > 0 m, got -0.001"):
        Grid(-1e-3, 1e-3, 0.1, 0.1, 100, 100, 5, 5)
    with pytest.raises(ValueError, match="truncation_x must be >= period_x/\\(2 spacing_x\\) = 667"):
        Grid(0.15e-3, 0.15e-3, 0.2, 0.2, 500, 1000, 5, 5)
    with pytest.raises(ValueError, match="must be < period_y"):
        Grid(1e-3, 1e-3, 0.1, 0.01, 100, 100, 5, 11)
    g = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (2000, 2000), (5e-3, 5e-3))
    assert g.shape == (41, 41) and g.x[20] == 0.0 and np.isclose(g.x[-1], 5e-3)


@pytest.mark.parametrize("speed", [0.005, 0.05, 0.5])
def test_moving_load_leaves_a_trailing_depression(speed):
    """Physics, not the code's convention: a load moving along +x over a viscoelastic
    layer (the material streams towards -x in its frame) leaves the surface behind it
    (dx < 0) more depressed than ahead, at every distance, because the material recovers
    with delay; at rest the kernel is even. This fixes the sign of the modes' frequency
    omega_m = -nu_x V, which the fast and the direct sums share (a flipped sign mirrors
    the kernel and passes the comparison of the two)."""
    Ky, Kx = GRID.nodes_y, GRID.nodes_x
    for fn in (influence_kernels, influence_kernels_direct):
        row = fn(GRID, VISCO, speed)["ww"][Ky - 1]
        behind, ahead = np.abs(row[Kx - 2 :: -1][:3]), np.abs(row[Kx:][:3])  # dx = -1..-3, +1..+3
        assert np.all(behind > 1.005 * ahead), (fn.__name__, behind, ahead)
    rest = influence_kernels(GRID, VISCO, 0.0)["ww"][Ky - 1]
    np.testing.assert_allclose(rest, rest[::-1], rtol=0, atol=1e-14 * np.abs(rest).max())


def test_normal_kernel_alone_matches_direct_summation():
    """The fast path for the normal block alone (the contact solver's) against the direct
    sum, for a viscoelastic layer with inertia and an elastic one (a real modulus) with
    inertia below the shear-wave speed: 1e-14 relative (measured ~2e-15)."""
    elastic_inertia = Layer(5e-3, Elastic(3.0e6), density=1000.0)  # c_s = 54.8 m/s
    for layer, speed in ((VISCO, 0.05), (elastic_inertia, 30.0), (ELASTIC, 0.0)):
        fast = influence_kernels(GRID, layer, speed)["ww"]
        direct = influence_kernels_direct(GRID, layer, speed)["ww"]
        assert np.abs(fast - direct).max() <= 1e-14 * np.abs(direct).max()
        if layer is elastic_inertia:
            allb = influence_kernels(GRID, layer, speed, blocks=BLOCKS)
            alld = influence_kernels_direct(GRID, layer, speed, blocks=BLOCKS)
            for b in BLOCKS:
                assert np.abs(allb[b] - alld[b]).max() <= 1e-14 * np.abs(alld[b]).max(), b


@pytest.mark.parametrize("layer, speed, blocks", [(VISCO, 0.05, ("ww", "uu")),  # with inertia: batched sums
                                                  (Layer(0.05, Elastic(3.0e6)), 0.0, ("ww", "uv", "vv", "wu"))])
def test_more_modes_than_one_batch(layer, speed, blocks):
    """N_tx = 300 > 256 modes per batch of symbols: every batch is evaluated once and in
    place, with inertia (symbols summed batch by batch) and without (half-space split):
    fast against direct, 1e-14 relative."""
    grid = Grid(0.7e-3, 0.9e-3, 0.02, 0.025, 300, 30, 7, 6)
    fast = influence_kernels(grid, layer, speed, blocks=blocks)
    direct = influence_kernels_direct(grid, layer, speed, blocks=blocks)
    for b in blocks:
        assert np.abs(fast[b] - direct[b]).max() <= 1e-14 * np.abs(direct[b]).max(), b


def test_glassy_limit_is_computed_without_floating_point_warnings():
    """At a speed where nu_x V overflows (|omega| = inf: the glassy modulus, finite) and
    with the direct sum's m = 0 and n = 0 terms (0/0 replaced by a / L), no overflow,
    divide or invalid warning escapes: the kernels are finite and equal (1e-14)."""
    import warnings

    layer = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fast = influence_kernels(GRID, layer, 1e306)["ww"]
        direct = influence_kernels_direct(GRID, layer, 1e306)["ww"]
    assert np.isfinite(fast).all()
    assert np.abs(fast - direct).max() <= 1e-14 * np.abs(direct).max()


def test_blocks_and_speed_are_validated():
    for blocks in (("xx",), ("ww", "wz"), ()):
        with pytest.raises(ValueError, match=r"^blocks must be among \['uu', 'uv', 'uw', 'vu', 'vv', 'vw', 'wu', 'wv', 'ww'\], got "):
            influence_kernels(GRID, ELASTIC, 0.0, blocks=blocks)
        with pytest.raises(ValueError, match=r"^blocks must be among "):
            influence_kernels_direct(GRID, ELASTIC, 0.0, blocks=blocks)
    for speed in (-1.0, np.inf, np.nan):
        with pytest.raises(ValueError, match=r"^speed must be finite and >= 0 m/s, got "):
            influence_kernels(GRID, ELASTIC, speed)


@pytest.mark.parametrize("shape", [(57,), (2, 3, 57)])
def test_chirp_sum_on_any_leading_shape(shape):
    """The sum runs over the last axis whatever the number of leading axes."""
    rng = np.random.default_rng(1)
    c = rng.normal(size=shape) + 1j * rng.normal(size=shape)
    ratio, j0, count = 0.0123456789, -11, 23
    ref = c @ np.exp(2j * np.pi * ratio * np.outer(np.arange(57), np.arange(j0, j0 + count)))
    np.testing.assert_allclose(_chirp_sum(c, ratio, j0, count), ref, rtol=0, atol=2e-14 * np.abs(ref).max())


class _BrokenAboveMHz:
    """A material model that breaks down above 1e6 rad/s."""

    def modulus(self, omega):
        omega = np.asarray(omega, float)
        return np.where(np.abs(omega) > 1e6, np.nan, 3e6).astype(complex)


@pytest.mark.filterwarnings("ignore:invalid value:RuntimeWarning")
def test_non_finite_kernels_are_all_named():
    with pytest.raises(ValueError, match=r"^the influence kernels ww, uu are not finite at speed = 1000 m/s on the grid "):
        influence_kernels(GRID, Layer(5e-3, _BrokenAboveMHz()), 1e3, blocks=("ww", "uu"))


# a thick layer on the test grid: all but the modes with m, n <= 3 see no base (k H > 60)
THICK_VISCO = Layer(0.05, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0))
THICK_ELASTIC = Layer(0.05, Elastic(3.0e6))


@pytest.mark.parametrize("grid", [GRID, ALIASED], ids=["plain", "aliased-ends"])
@pytest.mark.parametrize("path", ["products", "chirp"])
@pytest.mark.parametrize("layer, speed", [(THICK_VISCO, 0.05), (THICK_ELASTIC, 0.0), (VISCO, 0.0)])
def test_halfspace_split_matches_direct_summation(layer, speed, path, grid, monkeypatch):
    """Without inertia the kernels are the half-space modes' sum (real symbols, ``1 / G``
    per row, vv = 3 ww - uu) plus the exact-less-half-space symbols of the modes that see
    the base: every block against the paper's direct sum to 1e-14 of the block (measured
    0.1-2.3e-15 on the issue-11 grids against the former all-complex sums)."""
    import bem.spectral

    monkeypatch.setattr(bem.spectral, "_MATMUL_NODES", 128 if path == "products" else 0)
    fast = influence_kernels(grid, layer, speed, blocks=BLOCKS)
    direct = influence_kernels_direct(grid, layer, speed, blocks=BLOCKS)
    for b in BLOCKS:
        assert np.abs(fast[b] - direct[b]).max() <= 1e-14 * np.abs(direct[b]).max(), b


@pytest.mark.parametrize("truncation, spacing, period, end", [
    (2000, 0.25e-3, 0.2, 0.5),  # 2 N_t a / L = 5 (the paper's section 11 grid)
    (400, 0.5e-3, 0.4, 0.5),    # 1
    (800, 0.25e-3, 0.2, 1.0),   # 2: even, sinc(N_t a / L) = 0 at the end modes already
    (801, 0.25e-3, 0.2, 1.0),   # not an integer: no two kept modes alias exactly
    (40, 0.7e-3, 0.02, 1.0),
])
def test_end_modes_that_alias_onto_nyquist_take_half_weight(truncation, spacing, period, end):
    w = end_weights(truncation, spacing, period)
    assert w.shape == (truncation + 1,)
    assert w[-1] == end and np.all(w[:-1] == 1.0)


@pytest.mark.parametrize("multiple, tail", [(1, 3e-4), (3, 2e-5)])
def test_kernel_has_no_lasting_nyquist_term_along_y(multiple, tail):
    """On nodes ``a`` apart the kernel's symbol is the alias sum over the kept modes
    ``n = n0 (mod L / a)``. With N_t an odd multiple of L / (2 a) and the end modes at half
    weight every lattice frequency takes the same number of modes; the truncation then
    leaves a kink of the folded symbol at Nyquist, whose (-1)^dy term in the kernel decays
    like dy^-2. Counting both end modes in full (a spike at Nyquist) left a term that does
    not decay: (-1)^dy part of K(0, dy) over K(0, 0) 2.8-3.2e-3 (N_t = L / 2a) and
    3.8-4.0e-4 (3 L / 2a) at dy = 10..18, growing with dy. Measured now at dy = 18: 2.2e-4 and
    1.0e-5, a third of the value at dy = 10 (dy^-2: 0.31); gated at 1.5 and 2 times that,
    and at 0.45 of dy = 10 (a decay faster than dy^-1.3)."""
    a, L = 1e-3, 0.1
    N = round(L / (2 * a))
    grid = Grid(a, a, L, L, multiple * N, multiple * N, 41, 41)
    col = influence_kernels(grid, Layer(0.02, Elastic(1e6)), 0.0)["ww"][grid.nodes_y - 1:, grid.nodes_x - 1]
    j = np.arange(2, col.size - 2)  # dy; the binomial high pass keeps (-1)^dy with gain 1, cubics not at all
    alt = (-1.0) ** j * (col[:-4] - 4 * col[1:-3] + 6 * col[2:-2] - 4 * col[3:-1] + col[4:]) / 16 / col[0]
    assert abs(alt[j == 18][0]) < tail
    assert abs(alt[j == 18][0]) < 0.45 * abs(alt[j == 10][0])


def test_halfspace_symbols_are_the_layer_compliance_of_deep_modes():
    """G C_PQ of the half-space formulas against the layer's closed form (bem.layer) at
    k H from 60 to 3000, where the base is invisible: 1e-14 relative (measured ~2e-16);
    the normal-tangential entries vanish there (below 1e-14 of ww)."""
    from bem.layer import compliance_blocks
    from bem.halfspace_sums import halfspace_symbols

    H, G = 0.05, 3.0e6
    nu_x = np.linspace(-6e4, 6e4, 41)
    nu_y = np.linspace(0.0, 5e4, 23)
    kx, ky = np.meshgrid(nu_x, nu_y, indexing="ij")
    deep = np.hypot(kx, ky) * H > 60
    ref = compliance_blocks(kx, ky, np.full(kx.shape, G, complex), 0.0, H, BLOCKS)
    hs = halfspace_symbols(nu_x, nu_y)
    hs["vv"], hs["vu"] = 3 * hs["ww"] - hs["uu"], hs["uv"]
    for b in BLOCKS:
        mine = hs.get(b, np.zeros(kx.shape)) / G
        scale = np.abs(ref["ww"][deep])
        assert np.all(np.abs(mine - ref[b])[deep] <= 1e-14 * scale), b


@pytest.mark.parametrize("span", [10.0, 2121.0, 1e5])
def test_inverse_powers_as_sums_of_gaussians(span):
    """k^-p = sum_q c_q exp(-alpha_q k^2) to 2e-15 relative on [k_min, k_max] for every
    power of the half-space's and the inertia series' sums (measured 0.6-1.8e-15, the
    rounding of the sum), span = k_max / k_min up to 1e5 (2121: the paraboloid's 61 x 61
    grid, N_t = 1500), on shared exponents, fewer than 250 of them (119-212)."""
    from bem.halfspace_sums import inverse_power_gaussians

    k_min, powers = 2 * np.pi / 0.6, (1, 3, 4, 5, 6, 8)
    alpha, c = inverse_power_gaussians(k_min, span * k_min, powers)
    k = k_min * np.geomspace(1.0, span, 4001)
    for p in powers:
        approx = np.exp(-np.outer(k * k, alpha)) @ c[p]
        assert np.abs(approx * k**p - 1).max() <= 2e-15, p
    assert alpha.size < 250


@pytest.mark.parametrize("p", [1, 3, 5])
def test_gaussian_sums_converge_at_the_trapezoidal_rate(p, monkeypatch):
    """The trapezoidal rule in s = log t on an integrand analytic in |Im s| < pi / 4: the
    error falls as exp(-pi^2 / (2 h)). From h = 0.2 to 0.15 that is 2.7e-4; measured 2.8e-4
    (p = 1), 3.6e-4 (p = 3) and 4.8e-4 (p = 5; the prefactor grows with p): within a
    factor 2 of it."""
    import bem.halfspace_sums as hs

    k = np.geomspace(1.0, 2000.0, 4001)
    errors = []
    for step in (0.2, 0.15):
        monkeypatch.setattr(hs, "GAUSSIAN_STEP", step)
        alpha, c = hs.inverse_power_gaussians(1.0, 2000.0, (p,))
        errors.append(np.abs((np.exp(-np.outer(k * k, alpha)) @ c[p]) * k**p - 1).max())
    rate = np.exp(-np.pi**2 / 2 * (1 / 0.15 - 1 / 0.2))
    assert 0.5 * rate < errors[1] / errors[0] < 2 * rate


# square grids: the same spacing, period and truncation along x and y. On the first
# L = 2 N_t a (the phases pi n j / N_t: DCT-I and DST-I), on the second not.
SQUARE_LATTICE = Grid(1e-3, 1e-3, 0.06, 0.06, 30, 30, 9, 9)
SQUARE = Grid(0.7e-3, 0.7e-3, 0.02, 0.02, 40, 40, 8, 8)


@pytest.mark.parametrize("grid", [SQUARE_LATTICE, SQUARE], ids=["lattice", "square"])
@pytest.mark.parametrize("path", ["products", "chirp"])
@pytest.mark.parametrize("layer, speed", [(THICK_ELASTIC, 0.0), (ELASTIC, 1.0), (THICK_VISCO, 0.05)])
def test_square_grids_match_direct_summation(layer, speed, path, grid, monkeypatch):
    """A constant modulus on a square grid: the half-space sums as separable sums of
    Gaussians (bem.halfspace_sums.square_sums) with products, by DCT-I / DST-I on the
    lattice, by chirp-z off it; a modulus that varies with m by the general sums: every
    block against the direct sum, 1e-14 of the block (measured 0.8-1.6e-15)."""
    import bem.spectral

    monkeypatch.setattr(bem.spectral, "_MATMUL_NODES", 128 if path == "products" else 0)
    fast = influence_kernels(grid, layer, speed, blocks=BLOCKS)
    direct = influence_kernels_direct(grid, layer, speed, blocks=BLOCKS)
    for b in BLOCKS:
        assert np.abs(fast[b] - direct[b]).max() <= 1e-14 * np.abs(direct[b]).max(), b


# a little inertia, rho V^2 / G = 8.3e-7 (the paper's section 11): every deep mode (k H > 50)
# by the series of bem.halfspace_sums.INERTIA_SERIES. On the thick layer the modes k > 1000
# rad/m are deep on every test grid; FINE reaches k H = 94 on the 5 mm layer.
THICK_ROLLING = Layer(0.05, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), density=1000.0)
FINE = Grid(0.5e-3, 0.6e-3, 0.02, 0.024, 60, 50, 7, 6)


@pytest.mark.parametrize("grid, layer", [(GRID, THICK_ROLLING), (ALIASED, THICK_ROLLING), (SQUARE_LATTICE, THICK_ROLLING),
                                         (FINE, VISCO), (FINE, Layer(5e-3, Elastic(3.0e6), density=1000.0))],
                         ids=["plain", "aliased-ends", "lattice", "fine", "fine-elastic"])
@pytest.mark.parametrize("path", ["products", "chirp"])
def test_kernels_with_a_little_inertia_by_the_series(grid, layer, path, monkeypatch):
    """With rho V^2 / |G| below 1e-6 every deep mode's compliance is the series of
    INERTIA_SERIES (the real arrays nu_x^a nu_y^b / k^p times factors of the row) and the
    modes k H <= 50 are exact: every block against the direct sum, and the power tables
    against the general route's, by products, DCT-I / DST-I on the lattice and chirp-z off
    it. The blocks of order one within the series' next term, 3/8 eps^2 (eps = rho V^2 / G
    = 8.3e-7: 2.6e-13) plus 1e-14 of the block (measured up to 6.6e-14 on the thick layer,
    where the deep modes make the tables, 0.4e-15 with the eps^2 terms added; up to 2.2e-14 on
    the 5 mm layers); the normal-tangential ones, to third order, within 1e-14 (measured
    0.1-2.0e-15)."""
    import bem.spectral
    from bem.spectral import kernels_with_power

    monkeypatch.setattr(bem.spectral, "_MATMUL_NODES", 128 if path == "products" else 0)
    assert bem.spectral._series_holds(grid, layer, 0.05)
    eps = layer.inertia(0.05) / layer.relaxed_modulus
    fast, power = kernels_with_power(grid, layer, 0.05, BLOCKS)
    direct = influence_kernels_direct(grid, layer, 0.05, BLOCKS)
    _, ref = bem.spectral._kernels_streamed(grid, layer, 0.05, tuple(BLOCKS), power=True)
    for b in BLOCKS:
        tol = 1e-14 if b in ("wu", "uw", "wv", "vw") else 3 / 8 * eps**2 + 1e-14
        assert np.abs(fast[b] - direct[b]).max() <= tol * np.abs(direct[b]).max(), b
        assert np.abs(power[b] - ref[b]).max() <= tol * np.abs(ref[b]).max(), b


def test_inertia_series_is_the_deep_modes_compliance():
    """INERTIA_SERIES against the layer's closed form at k H from 60 to 1500 and eps =
    c nu_x^2 / k^2 up to 9e-7 (c = rho V^2 / G, G complex): the blocks of order one, to
    first order, differ from it by their next terms (sympy, docs/derivations.md section 13),
    each below 3/8 |eps|^2 of 1 / (|G| k), to 2e-15 of 1 / (|G| k) (measured 4e-16); the
    normal-tangential ones, of order eps and to third order, agree within 1e-14 of their
    own size (the next term 1.5 eps^3 of it; measured 6.7e-16)."""
    from bem.halfspace_sums import INERTIA_SERIES, series_arrays, series_factor
    from bem.layer import compliance_blocks

    H, rho_V2 = 0.05, 3.0
    nu_x = np.array([1.2e3, 7e3, 3e4])
    nu_y = np.array([0.0, 900.0, 2e4, 3e4])
    X, Y = np.meshgrid(nu_x, nu_y, indexing="ij")
    k = np.hypot(X, Y)
    for G in (3e6 + 1.5e6j, 4.5e6 - 0.5e6j):
        exact = compliance_blocks(X, Y, G, rho_V2, H, BLOCKS)
        eps = rho_V2 / G * X**2 / k**2
        assert np.abs(eps).max() <= 1e-6 and (k * H).min() > 50
        nxt = {"ww": 11 / 32 * eps**2 / k, "uu": 3 / 32 * eps**2 * (X**2 + 4 * Y**2) / k**3,
               "vv": 3 / 32 * eps**2 * (4 * X**2 + Y**2) / k**3, "uv": -9 / 32 * eps**2 * X * Y / k**3}
        nxt["vu"] = nxt["uv"]
        for b in BLOCKS:
            terms = INERTIA_SERIES[b]
            arrays = series_arrays(nu_x, nu_y, [t[:3] for t in terms])
            mine = sum(series_factor(t[3], np.full(nu_x.size, G), rho_V2)[:, None] * arrays[i] * (Y if t[2] else 1.0)
                       for i, t in enumerate(terms))
            if b in nxt:
                assert np.all(np.abs(nxt[b]) <= 3 / 8 * np.abs(eps) ** 2 / k), b
                assert np.all(np.abs(mine + nxt[b] / G - exact[b]) <= 2e-15 / (abs(G) * k)), b
            else:
                assert np.all(np.abs(mine - exact[b]) <= 1e-14 * np.abs(exact[b])), b


def test_normal_tangential_blocks_are_antisymmetric_at_every_mode():
    """uw = -wu and vw = -wv mode by mode (the compliance in the axes (w, i u, i v) is
    symmetric), vu = uv, for every regime of the closed form (k H from 0 to 300), with and
    without inertia, G complex: within 1e-14 of the largest entry of the 3x3 compliance
    where the coupling is of that order (measured 3e-16; a thick layer's exponentially small
    base coupling rounds apart at 1e-5 of itself, which is why only the series' deep modes
    share these blocks, bem.spectral._MIRRORED)."""
    from bem.layer import compliance_blocks

    nu_x = np.array([-3e4, -900.0, 0.0, 150.0, 2e3, 6e4])
    nu_y = np.array([0.0, 40.0, 700.0, 5e3])
    X, Y = np.meshgrid(nu_x, nu_y, indexing="ij")
    for rho_V2 in (0.0, 2.5, 4e5):
        c = compliance_blocks(X, Y, 3e6 + 1e6j, rho_V2, 5e-3, BLOCKS)
        scale = np.max([np.abs(c[b]) for b in BLOCKS], axis=0)
        assert np.all(np.abs(c["uw"] + c["wu"]) <= 1e-14 * scale)
        assert np.all(np.abs(c["vw"] + c["wv"]) <= 1e-14 * scale)
        np.testing.assert_array_equal(c["vu"], c["uv"])


@pytest.mark.parametrize("speed, route", [(0.05, "_kernels_series"), (0.06, "_kernels_streamed"),
                                          (40.0, "_kernels_streamed"), (0.0, "_kernels_halfspace_split")])
def test_the_route_follows_the_series_bound(speed, route, monkeypatch):
    """rho V^2 / |G(omega_m)| <= 0.999e-6 on every row takes the series (8.3e-7 at 0.05
    m/s); 1.2e-6 at 0.06 m/s and 0.53 at 40 m/s the general route, no inertia the
    half-space split; each against the direct sum, 1e-14 of the block (the series: 3/8 eps^2
    more, its next term, test_kernels_with_a_little_inertia_by_the_series)."""
    import bem.spectral

    taken = []
    for name in ("_kernels_series", "_kernels_streamed", "_kernels_halfspace_split"):
        fn = getattr(bem.spectral, name)
        monkeypatch.setattr(bem.spectral, name, lambda *a, _fn=fn, _name=name, **k: taken.append(_name) or _fn(*a, **k))
    layer = THICK_ROLLING if speed else THICK_VISCO
    fast = influence_kernels(GRID, layer, speed, BLOCKS)
    assert taken == [route]
    direct = influence_kernels_direct(GRID, layer, speed, BLOCKS)
    tol = 1e-14 + (3 / 8 * (layer.inertia(speed) / layer.relaxed_modulus) ** 2 if route == "_kernels_series" else 0)
    for b in BLOCKS:
        assert np.abs(fast[b] - direct[b]).max() <= tol * np.abs(direct[b]).max(), b


@pytest.mark.parametrize("speed", [0.0, 0.05])
def test_a_layer_under_every_mode_takes_the_direct_route(speed, monkeypatch):
    """A layer thin enough that every mode sees the base (3 mm on GRID: nu_x H <= 37.7,
    nu_y H <= 22.6, both at most 50) takes the direct route, every mode's own symbol
    (_kernels_streamed), without inertia and with a little (the split and the series would
    take all their deep sums off again); 3.98 mm is the edge, 4.1 mm the split or the
    series again; each against the direct sum, 1e-14 of the block."""
    import bem.spectral

    taken = []
    for name in ("_kernels_series", "_kernels_streamed", "_kernels_halfspace_split"):
        fn = getattr(bem.spectral, name)
        monkeypatch.setattr(bem.spectral, name, lambda *a, _fn=fn, _name=name, **k: taken.append(_name) or _fn(*a, **k))
    layer = Layer(3e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), density=1000.0)
    fast = influence_kernels(GRID, layer, speed, BLOCKS)
    direct = influence_kernels_direct(GRID, layer, speed, BLOCKS)
    for b in BLOCKS:
        assert np.abs(fast[b] - direct[b]).max() <= 1e-14 * np.abs(direct[b]).max(), b
    for H in (3.97e-3, 4.1e-3):
        influence_kernels(GRID, Layer(H, layer.material, density=1000.0), speed, ("ww",))
    assert taken == ["_kernels_streamed"] * 2 + ["_kernels_series" if speed else "_kernels_halfspace_split"]


@pytest.mark.parametrize("layer, speed", [(VISCO, 0.05), (ELASTIC, 0.0), (Layer(5e-3, Elastic(3.0e6), density=1000.0), 30.0)],
                         ids=["series", "half-space split", "general"])
@pytest.mark.parametrize("blocks", [("vu",), ("uw", "vu"), ("vw",), ("uv", "vu")])
def test_blocks_that_share_their_sums_come_alone(layer, speed, blocks):
    """vu is computed as uv, and the series' uw, vw from wu, wv: asked alone or together,
    each route returns the blocks asked and no other, kernels and power tables, each equal
    to the direct sum within 1e-14 of the block (measured 0.5-1.2e-15)."""
    from bem.spectral import kernels_with_power

    fast, power = kernels_with_power(FINE, layer, speed, blocks)
    assert set(fast) == set(power) == set(blocks)
    direct = influence_kernels_direct(FINE, layer, speed, blocks)
    for b in blocks:
        assert np.abs(fast[b] - direct[b]).max() <= 1e-14 * np.abs(direct[b]).max(), b


@pytest.mark.parametrize("Q, modes", [(12, 13), (12, 9)])
def test_lattice_cosine_and_sine_sums(Q, modes):
    """DCT-I and DST-I against the sums written out, with the end mode n = Q in the sum
    (its cosine (-1)^j counted from both +-Q) and without."""
    from bem.mode_sums import cos_sums, lattice_half, sin_sums

    x = np.random.default_rng(2).normal(size=(3, modes))
    n, j = np.arange(modes), np.arange(7)
    ph = np.pi * np.outer(n, j) / Q
    wn = np.where(n == 0, 1.0, 2.0)[:, None]
    np.testing.assert_allclose(cos_sums(x, Q, 7), x @ (wn * np.cos(ph)), rtol=0, atol=1e-14 * np.abs(x).sum())
    np.testing.assert_allclose(sin_sums(x, Q, 7), x @ (2 * np.sin(ph)), rtol=0, atol=1e-14 * np.abs(x).sum())
    np.testing.assert_allclose(cos_sums(x.T, Q, 7, axis=0), (x @ (wn * np.cos(ph))).T, rtol=0,
                               atol=1e-14 * np.abs(x).sum())
    assert lattice_half(1 / (2 * Q), modes, 7) == Q
    assert lattice_half(1 / (2 * Q) * (1 + 1e-9), modes, 7) is None  # not a lattice
    assert lattice_half(1 / (2 * Q), 2 * Q, 7) is None  # modes beyond Q alias


@pytest.mark.parametrize("ratio", [1 / 3000, 1 / 3000 * (1 + 1e-9), 1 / 7])
def test_circle_table_reads_the_phases_on_their_lattice(ratio):
    """On the lattice ``ratio = 1 / P`` the table holds the cosine and sine of ``2 pi k / P``
    at the exact residues ``k = a b mod P``: the same as evaluating every reduced phase
    (whose reduction carries the rounding of ``ratio`` times ``a b``, up to 12 857 turns at
    1/7), exactly periodic in ``a`` with period ``P``, and negative products take their
    residues. Off the lattice (1e-9 off) and where ``P`` exceeds the table (1/7 with 3 x 2
    entries) the phases are evaluated."""
    from bem.mode_sums import circle_table, turns

    a, b = np.arange(-60, 1501), np.arange(61)
    reduction = 4 * np.pi * np.finfo(float).eps * ratio * 1500 * 60  # of turns(), in radians
    for odd, f in ((False, np.cos), (True, np.sin)):
        T = circle_table(ratio, a, b, odd)
        np.testing.assert_allclose(T, f(turns(ratio, a, b)), rtol=0, atol=reduction + 1e-15)
        if ratio == 1 / 3000:
            np.testing.assert_array_equal(circle_table(ratio, a + 3000, b, odd), T)
            assert T[60 + 750, 4] == (0.0 if odd else 1.0)  # a b = 3000: a whole turn
            if not odd:
                assert T[60 + 750, 2] == -1.0  # a b = 1500: half a turn
    small = circle_table(1 / 7, np.arange(3), np.arange(2), False)
    np.testing.assert_array_equal(small, np.cos(turns(1 / 7, np.arange(3), np.arange(2))))
