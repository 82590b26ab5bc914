"""Kalker's linear theory of rolling contact: a rigid sphere rolling on a very thick
elastic layer at low speed, Omega prescribed slightly off free rolling.

For a circular contact of radius ``a`` the longitudinal creep force is
``F_x = -G* a^2 C11 xi`` with ``xi = (V - Omega R) / V`` and, at Poisson's ratio 0.5,
``C11 = 5.20`` (Kalker 1967/1990, table of creepage coefficients, ``a/b = 1``). The
combined shear modulus of a rigid body on a body of modulus ``G`` is ``G* = 2G``
(``1/G* = (1/G1 + 1/G2)/2``) and the combined Poisson ratio is 0.5; the normal and
tangential problems decouple (Kalker's difference parameter vanishes for a rigid body
on an incompressible one), so the linear theory applies exactly in the half-space limit.

Set-up: ``G = 3`` MPa, ``H = 30`` mm (``H/a = 13``; raising ``H`` to 100 mm changes
``C11`` by 0.2 %), ``R = 20`` mm, ``P = 10`` N (Hertz ``a = 2.32`` mm), ``V = 0.01`` m/s
(``rho V^2 / G = 3e-8``), ``l(y) = R`` (``Friction.radius``, so the rigid creepage is the
same on every row), ``mu = 100`` (full stick). ``C11`` is taken from the difference of the
forces at ``xi = +-1e-3`` (cancelling the small free-rolling offset of the layer's
normal-tangential coupling) with ``a`` the discrete contact radius ``sqrt(area / pi)``,
the area that carries the creep force.

Measured C11 (grid spacing, Nt = L / 2a): 5.484 (0.5 mm), 5.398 (0.35 mm),
5.332 (0.25 mm), 5.321 (0.18 mm), 5.271 (0.15 mm), 5.271 (0.125 mm): about O(h) from
above (the trailing edge's square-root traction singularity of the linear theory is
resolved by the upwind scheme to first order), 1.4 % above 5.20 at the finest grids.
Large creepage ``xi = 0.3`` (``mu = 0.3``): every node slips and ``|F_x| = 0.99992 mu P``,
the rest being the lateral slip component ``w_y = V dv/dx`` that turns each force slightly.
"""

import pytest

from bem import Elastic, Grid, Layer, Loading, Problem, Sphere, influence_kernels
from bem.frictional import Friction
from bem.frictional import solve_friction
from bem.spectral import BLOCKS

G, H, R, P, V, L = 3.0e6, 30e-3, 0.02, 10.0, 0.01, 0.2
C11_KALKER = 5.20
LAYER = Layer(H, Elastic(G), 1000.0)


def _problem(spacing):
    nt = int(round(L / (2 * spacing)))
    grid = Grid.centred((spacing, spacing), (L, L), (nt, nt), (3.5e-3, 3.5e-3))
    return Problem(LAYER, Sphere(R), grid, Loading(V, load=P)), influence_kernels(grid, LAYER, V, blocks=BLOCKS)


def _creep_force(problem, kernels, xi, mu):
    res, _ = solve_friction(problem, Friction(mu, "omega", omega=V * (1 - xi) / R, radius=R),
                            kernels=kernels, energy=False)
    return -float(res.force_x.sum()), res  # force on the sphere (N)


def measured_c11(spacing, xi=1e-3):
    problem, kernels = _problem(spacing)
    fp, rp = _creep_force(problem, kernels, xi, 100.0)
    fm, rm = _creep_force(problem, kernels, -xi, 100.0)
    assert rp.stick_fraction == 1.0 and rm.stick_fraction == 1.0  # linear regime: full stick
    assert fp < 0 < fm  # braking creepage (V > Omega R) resists the motion
    return (fm - fp) / (2 * xi * 2 * G * rp.contact_radius**2)


def test_kalker_c11_coarse_grids():
    """O(h) from above: 5.48 at 0.5 mm, 5.33 at 0.25 mm; 3.5 % at 0.25 mm is the measured
    2.5 % error with room for round-off in the discrete contact set, below the coarse
    grid's 5.5 %, so the test fails if the trend stops."""
    coarse, fine = measured_c11(0.5e-3), measured_c11(0.25e-3)
    assert fine < coarse
    assert C11_KALKER < fine < C11_KALKER * 1.035


@pytest.mark.slow
def test_kalker_c11_fine_grid():
    """a = 0.125 mm (57 x 57 nodes, 1070 in contact, 1.8 s): 5.271, 1.4 % above Kalker's
    5.20 (the 0.15 mm grid gives the same); 2 % leaves room for the contact set's
    pixelation, which moves C11 by about 0.5 % from grid to grid."""
    assert abs(measured_c11(0.125e-3) / C11_KALKER - 1) < 0.02


def test_large_creepage_saturates_at_mu_p():
    problem, kernels = _problem(0.5e-3)
    mu = 0.3
    for xi in (0.3, -0.3):
        f, res = _creep_force(problem, kernels, xi, mu)
        assert res.stick_fraction == 0.0
        assert f * xi < 0
        # |F_x| <= mu P exactly (|S| = mu N per node); measured 0.99992 mu P
        assert 0.9995 * mu * P < abs(f) <= mu * P * (1 + 1e-9)
