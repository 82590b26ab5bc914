"""Carter's steady rolling contact (:mod:`verification.analytic.carter`).

Checked against its limits (full stick as Q -> 0, full slip at Q = mu P), the force
balance of its traction, the inverse pair xi(Q) / Q(xi), Coulomb's cone, and against the
plane-strain surface strain of the half-space evaluated by direct quadrature of the
Cauchy integral (Johnson 1985, eq. 2.25b with nu = 0.5): uniform and equal to ``-xi``
in the stick zone, with the slip velocity along the traction in the slip zone."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from verification.analytic import hertz_line_contact
from verification.analytic.carter import carter_rolling, carter_rolling_from_creepage

P, R, G, MU = 2.0e4, 0.05, 1.0e6, 0.3  # N/m, m, Pa, -


def _strain(sol, x):
    """du/dx (-) of the surface at x (m): -(2 / (pi E*)) PV int q(s) / (x - s) ds, E* = 4 G."""
    a = sol.half_width
    pv = quad(lambda s: float(sol.traction(s)), -a, a, weight="cauchy", wvar=x, limit=400)[0]  # int q / (s - x)
    return 2.0 * pv / (math.pi * 4.0 * sol.shear_modulus)


def test_normal_part_is_hertz_line_contact():
    sol, h = carter_rolling(P, R, G, MU, 0.5 * MU * P), hertz_line_contact(P, R, G)
    assert sol.half_width == pytest.approx(math.sqrt(P * R / (math.pi * G)), rel=1e-15)
    assert sol.peak_pressure == pytest.approx(h.peak_pressure, rel=1e-14)
    assert quad(lambda x: float(sol.pressure(x)), -sol.half_width, sol.half_width)[0] == pytest.approx(P, rel=1e-9)


@pytest.mark.parametrize("frac", [-0.9, -0.3, 1e-3, 0.25, 0.6, 0.99, 1.0])
def test_traction_integrates_to_Q_and_stays_in_the_cone(frac):
    sol = carter_rolling(P, R, G, MU, frac * MU * P)
    a = sol.half_width
    pts = [sol.stick_centre - sol.stick_half_width] if sol.stick_half_width > 0 else None
    total = quad(lambda x: float(sol.traction(x)), -a, a, points=pts, limit=200)[0]
    assert total == pytest.approx(frac * MU * P, rel=1e-8)
    x = np.linspace(-a, a, 2001)
    assert np.all(np.abs(sol.traction(x)) <= MU * sol.pressure(x) * (1 + 1e-12) + 1e-9 * sol.peak_pressure)
    # the traction has the sign of Q everywhere and reaches mu p outside the stick zone
    assert np.all(np.sign(frac) * sol.traction(x) >= -1e-9 * sol.peak_pressure)
    slip = ~sol.in_stick(x)
    np.testing.assert_allclose(np.abs(sol.traction(x[slip])), MU * sol.pressure(x[slip]), rtol=1e-12, atol=1e-9)


def test_limits_full_stick_and_full_slip():
    small = carter_rolling(P, R, G, MU, 1e-9 * MU * P)
    assert small.stick_half_width == pytest.approx(small.half_width, rel=1e-9)
    assert abs(small.creepage) < 1e-9 * MU * small.half_width / R
    assert np.abs(small.traction(np.linspace(-1, 1, 101) * small.half_width)).max() < 1e-4 * MU * small.peak_pressure
    full = carter_rolling(P, R, G, MU, MU * P)
    assert full.stick_half_width == 0.0
    assert full.creepage == pytest.approx(MU * full.half_width / R, rel=1e-15)
    x = np.linspace(-1, 1, 101) * full.half_width
    np.testing.assert_allclose(full.traction(x), MU * full.pressure(x), rtol=1e-15)
    beyond = carter_rolling_from_creepage(P, R, G, MU, 5 * full.creepage)
    assert beyond.tangential_force == MU * P and beyond.stick_half_width == 0.0


@pytest.mark.parametrize("frac", [-0.7, 0.001, 0.3, 0.8, 0.999])
def test_creepage_law_inverse_pair(frac):
    sol = carter_rolling(P, R, G, MU, frac * MU * P)
    back = carter_rolling_from_creepage(P, R, G, MU, sol.creepage)
    assert back.tangential_force == pytest.approx(sol.tangential_force, rel=1e-9)
    assert back.stick_half_width == pytest.approx(sol.stick_half_width, rel=1e-9)
    # small creepage: Q ~ 2 mu P xi R / (mu a) = 2 P R xi / a (linear, Carter's creep coefficient)
    tiny = carter_rolling_from_creepage(P, R, G, MU, 1e-8)
    assert tiny.tangential_force == pytest.approx(2 * P * R * 1e-8 / tiny.half_width, rel=1e-6)


@pytest.mark.parametrize("frac", [0.3, 0.8, -0.5])
def test_stick_zone_strain_is_minus_creepage_and_slip_follows_the_traction(frac):
    """The kinematics of the solution, from the half-space's own Green function: in the
    stick zone ``w_x / V = 1 + du/dx - Omega R / V = du/dx + xi = 0``; in the slip zone
    ``w_x`` has the sign of the traction on the half-space (eq. 18, slip along S)."""
    sol = carter_rolling(P, R, G, MU, frac * MU * P)
    a, c, d = sol.half_width, sol.stick_half_width, sol.stick_centre
    for x in d + c * np.array([-0.9, -0.5, 0.0, 0.5, 0.9]):
        assert _strain(sol, x) + sol.creepage == pytest.approx(0.0, abs=1e-6 * abs(sol.creepage))
    for x in np.linspace(-a, d - c, 7)[1:-1]:
        slip = _strain(sol, x) + sol.creepage
        assert np.sign(slip) == np.sign(sol.tangential_force) and abs(slip) > 1e-6 * abs(sol.creepage)


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match=r"tangential_force must satisfy \|Q\| <= mu P"):
        carter_rolling(P, R, G, MU, 1.01 * MU * P)
    with pytest.raises(ValueError, match="mu must be > 0"):
        carter_rolling(P, R, G, 0.0, 0.0)
    with pytest.raises(ValueError, match="load must be > 0 N/m"):
        carter_rolling_from_creepage(-P, R, G, MU, 1e-3)
    with pytest.raises(TypeError, match="creepage must be a real number"):
        carter_rolling_from_creepage(P, R, G, MU, "0.1")
