"""Identities of the layer's compliance and of its dissipation, for all inputs (hypothesis).

* Reciprocity at rest (Betti): ``C(nu)^T = C(-nu)`` for any wave vector and any complex
  modulus (a viscoelastic layer at one frequency is an elastic one with complex moduli).
* Reality in the moving frame: ``C(-nu, conj G) = conj C(nu, G)`` at any speed.
* Passivity: for a passive material (``G'' >= 0`` at ``omega > 0``) in steady motion at any
  subsonic speed, each mode absorbs power: ``nu_x Im(t^H C t) >= 0`` for every traction
  ``t`` (eq. of bem.energy), i.e. ``nu_x (C - C^H) / 2i`` is positive semidefinite; and
  the dissipation of any nodal forces, :func:`bem.energy.viscous_dissipation`, is
  ``>= 0``, and exactly 0 (to round-off) for an elastic layer, with or without inertia.

Tolerances: relative round-off of the closed form, measured below 1e-13 over these ranges
(stated per test, with a margin of about 10).
"""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from bem.energy import viscous_dissipation
from bem.grid import Grid
from bem.layer import Layer, surface_compliance
from bem.materials import Elastic, Prony, ThreeParameterSolid

H = 5e-3

wave = st.tuples(st.floats(-3.0, 3.0), st.floats(0.0, 2 * math.pi)).map(
    lambda t: (10 ** t[0] / H * math.cos(t[1]), 10 ** t[0] / H * math.sin(t[1]))
)
modulus = st.tuples(st.floats(5.0, 8.0), st.floats(0.0, 2.0)).map(lambda t: 10 ** t[0] * complex(1.0, t[1]))
three_parameter = st.builds(
    ThreeParameterSolid,
    G0=st.floats(1e5, 1e8),
    tau=st.floats(1e-4, 10.0),
    f=st.floats(0.0, 20.0),
)
prony = st.builds(
    lambda g_inf, parts: Prony(g_inf, tuple(p[0] for p in parts), tuple(p[1] for p in parts)),
    st.floats(1e5, 1e8),
    st.lists(st.tuples(st.floats(1e4, 1e8), st.floats(1e-4, 10.0)), min_size=1, max_size=3),
)
passive = st.one_of(three_parameter, prony)


@settings(max_examples=200, deadline=None)
@given(nu=wave, G=modulus, thickness=st.floats(1e-4, 1e-1))
def test_reciprocity_at_rest(nu, G, thickness):
    """Betti at rest: C(nu)^T = C(-nu); 1e-12 of the largest entry (measured 2e-15)."""
    C = surface_compliance(nu[0], nu[1], G, 0.0, thickness)
    Cm = surface_compliance(-nu[0], -nu[1], G, 0.0, thickness)
    np.testing.assert_allclose(C.T, Cm, rtol=0, atol=1e-12 * np.abs(C).max())


@settings(max_examples=200, deadline=None)
@given(nu=wave, G=modulus, speed_fraction=st.floats(0.0, 0.95))
def test_conjugate_mode_sees_the_conjugate_modulus(nu, G, speed_fraction):
    """C(-nu, conj G) = conj C(nu, G) at any subsonic rho V^2 = s Re G: the real
    relaxation function's modes pair up. 1e-12 of the largest entry (measured 1e-15)."""
    rho_V2 = speed_fraction * G.real
    C = surface_compliance(nu[0], nu[1], G, rho_V2, H)
    Cm = surface_compliance(-nu[0], -nu[1], np.conj(G), rho_V2, H)
    np.testing.assert_allclose(Cm, np.conj(C), rtol=0, atol=1e-12 * np.abs(C).max())


@settings(max_examples=200, deadline=None)
@given(nu=wave, material=passive, log_speed=st.floats(-4.0, 2.0), speed_fraction=st.floats(0.0, 0.95))
def test_every_mode_absorbs_power_for_a_passive_material(nu, material, log_speed, speed_fraction):
    """nu_x (C - C^H) / 2i >= 0 with G = G*(omega = -nu_x V) of a passive material, at
    any speed and any subsonic inertia rho V^2 = s G(0): the power 2 V nu_x Im(t^H C t)
    of every traction mode is >= 0. Eigenvalues >= -1e-12 |C| (round-off, measured 1e-16)."""
    V = 10.0**log_speed
    G = complex(material.modulus(-nu[0] * V))
    C = surface_compliance(nu[0], nu[1], G, speed_fraction * material.relaxed_modulus, H)
    loss = nu[0] * (C - C.conj().T) / 2j
    assert np.linalg.eigvalsh(loss).min() >= -1e-12 * abs(nu[0]) * np.abs(C).max()


GRID = Grid(0.7e-3, 0.9e-3, 0.02, 0.025, 40, 30, 7, 6)


@settings(max_examples=25, deadline=None)
@given(material=passive, log_speed=st.floats(-3.0, 1.5), seed=st.integers(0, 2**32 - 1),
       density=st.sampled_from([0.0, 1000.0]))
def test_dissipation_of_any_forces_is_nonnegative(material, log_speed, seed, density):
    """Any nodal forces (normal and tangential, random signs) on a passive layer in steady
    motion: P_visc >= 0. Round-off bound: 1e-12 of the sum of |terms|, which is at most
    V L_x L_y sum |nu_x| |t|^2 |C|; here bounded by the same sum with |C| replaced by
    H / G(0)."""
    V = 10.0**log_speed
    if density and density * V**2 >= 0.95 * material.relaxed_modulus:
        density = 0.0
    layer = Layer(H, material, density)
    F = np.random.default_rng(seed).normal(size=(3, *GRID.shape))
    P = viscous_dissipation(GRID, layer, V, *F)
    scale = V * np.abs(F).sum() ** 2 * 2 * math.pi / GRID.spacing_x * H / material.relaxed_modulus
    assert P >= -1e-12 * scale


def test_an_elastic_layer_dissipates_nothing():
    """Elastic, with inertia: P_visc = 0 to round-off, while the same forces on a
    viscoelastic layer of the same static modulus dissipate: 1e-12 of that (measured
    3e-17 and 9e-17). The forces are far from symmetric, so no cancellation by symmetry helps."""
    F = np.random.default_rng(7).normal(size=(3, *GRID.shape))
    visco = viscous_dissipation(GRID, Layer(H, ThreeParameterSolid(3e6, 0.25, 1.0), 1000.0), 0.05, *F)
    assert visco > 0
    for density in (0.0, 1000.0):
        elastic = viscous_dissipation(GRID, Layer(H, Elastic(3e6), density), 0.05, *F)
        assert abs(elastic) <= 1e-12 * visco


def test_dissipation_equals_the_plain_parseval_sum_over_all_modes():
    """A second algorithm for bem.energy: P = V L_x L_y sum over every mode
    |m| <= N_tx, |n| <= N_ty of nu_x Im(t^H C t), with t the patch-force coefficients
    (eqs. 56-59) and C from the closed form at G*(-nu_x V), summed plainly (no pairing of
    m with -m, no y-mirror of the n < 0 half, no batches). Random normal and tangential
    forces, asymmetric in x and y, on a grid with more modes than one batch of the module
    (N_tx = 100 > 64), forces given flat: 1e-10 relative (measured ~1e-15). Here
    2 N_tx a_x / L_x = 7 is odd: the end modes |m| = N_tx alias onto the x Nyquist frequency
    and weigh 1/2 in the displacement's series, hence once in the power."""
    grid = Grid(0.7e-3, 0.9e-3, 0.02, 0.025, 100, 30, 7, 6)
    layer = Layer(H, ThreeParameterSolid(3e6, 0.25, 1.0), 1000.0)
    V = 0.05
    F = np.random.default_rng(11).normal(size=(3, *grid.shape))
    got = viscous_dissipation(grid, layer, V, *(f.ravel() for f in F))
    m = np.arange(-grid.truncation_x, grid.truncation_x + 1)
    n = np.arange(-grid.truncation_y, grid.truncation_y + 1)
    nu_x, nu_y = 2 * np.pi * m / grid.period_x, 2 * np.pi * n / grid.period_y
    X, Y = grid.coordinates()
    w = np.outer(np.sinc(m * grid.spacing_x / grid.period_x), np.sinc(n * grid.spacing_y / grid.period_y))
    w /= grid.period_x * grid.period_y
    phase = np.exp(-1j * (nu_x[:, None, None, None] * X + nu_y[None, :, None, None] * Y))  # (m, n, K_y, K_x)
    t = np.einsum("mnyx,cyx->mnc", phase, F) * w[..., None]
    G = layer.material.modulus(-nu_x * V)
    C = surface_compliance(nu_x[:, None], nu_y[None, :], G[:, None], layer.inertia(V), H)
    quad = np.einsum("mni,mnij,mnj->mn", t.conj(), C, t)
    ends = np.where(np.abs(m) == grid.truncation_x, 0.5, 1.0)
    expect = V * grid.period_x * grid.period_y * float((ends[:, None] * nu_x[:, None] * quad.imag).sum())
    assert expect > 0
    assert abs(got - expect) <= 1e-10 * expect
