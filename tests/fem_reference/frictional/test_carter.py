"""Carter's rolling contact (verification/analytic/carter.py) on a thick elastic layer.

A bonded incompressible layer of finite thickness H couples the normal and tangential
problems (Carter's half-space does not): at a creepage of 1e-3 of full slip the creep
force came out about (2.05 a / H) mu P' above Carter's, measured 0.103, 0.028, 0.0069, 0.0017
mu P' at H = 20, 75, 300, 1200 a (a = 2 mm, h = 0.1 mm). The fast test takes H = 1200 a;
there the creep force over creepages 0.1-0.9 of full slip is within 0.0036 / 0.0027 /
0.0023 mu P' at h = 0.2 / 0.1 / 0.05 mm (the coupling 0.0017 and the mesh), and the stick
zone starts one node downstream of Carter's (its error 0.10 / 0.05 / 0.025 a = h: first
order, the upwind strain).
"""

import math

import numpy as np
import pytest

from fem_reference.frictional import RollingFriction, solve_frictional
from tests.fem_reference.frictional.layers import LOAD, MODULUS, RADIUS, assert_coulomb, elastic
from verification.analytic.carter import carter_rolling_from_creepage

MU = 0.3
FULL_SLIP = carter_rolling_from_creepage(LOAD, RADIUS, MODULUS, MU, 1e-9).full_slip_creepage


def _errors(thickness, h, fractions):
    problem, comp = elastic(thickness, h)
    rows = []
    for frac in fractions:
        r = solve_frictional(problem, RollingFriction(MU, creepage=frac * FULL_SLIP), compliance=comp)
        assert_coulomb(r)
        ref = carter_rolling_from_creepage(r.load, RADIUS, MODULUS, MU, frac * FULL_SLIP)
        force = (r.tangential_force - ref.tangential_force) / (MU * r.load)
        edge = (r.stick_zone[0] - (ref.stick_centre - ref.stick_half_width)) / ref.half_width
        rms = np.sqrt(np.mean((r.shear - ref.traction(r.x))[r.contact] ** 2)) / (MU * ref.peak_pressure)
        rows.append((force, edge, rms, r, ref))
    return rows


def test_creep_force_and_stick_zone_match_carter_on_a_thick_layer():
    """H = 1200 a, h = a / 20: creep force within 0.0027 mu P' measured (tolerance 0.004:
    1.5x), the stick zone's trailing end within 0.045-0.052 a (one node, tolerance 1.25 h),
    its leading end at the contact's leading node; the traction's RMS difference over the
    contact nodes within 0.0126 mu p0 (0.024 at h = a / 10: first order, the hat averages
    of the traction against its point values where it falls steeply), tolerance 0.02."""
    h = 1e-4
    for force, edge, rms, r, ref in _errors(2.4, h, (0.1, 0.3, 0.5, 0.7, 0.9)):
        assert abs(force) < 0.004
        assert rms < 0.02
        assert abs(edge) < 1.25 * h / ref.half_width
        assert r.stick_zone[1] == r.contact_edges[1]
        assert abs(r.contact_edges[1] - ref.half_width) < 1.5 * h


def test_full_slip_beyond_carters_onset():
    """Past xi = mu a / R the whole contact slips and Q' = mu P' (the slip law, exactly)."""
    problem, comp = elastic(2.4, 1e-4)
    r = solve_frictional(problem, RollingFriction(MU, creepage=1.2 * FULL_SLIP), compliance=comp)
    assert not r.stick.any()
    assert math.isclose(r.tangential_force, MU * r.load, rel_tol=1e-12)


@pytest.mark.slow
def test_layer_coupling_falls_as_one_over_thickness():
    """Creep force at xi = 1e-3 mu a / R over mu P' (Carter's: 1e-3 of it) at H = 75, 300
    and 1200 a: 0.0280, 0.0069, 0.0017, each step of 4 in H dividing it by 4.04 and 4.16
    (measured; 1/H within 5%), (H / a) times it 2.10, 2.08, 2.00."""
    errs = np.array([_errors(H, 1e-4, (1e-3,))[0][0] for H in (0.15, 0.6, 2.4)])
    assert np.all(np.abs(errs[:-1] / errs[1:] / 4.0 - 1.0) < 0.06)
    assert np.all(np.abs(errs * np.array([0.15, 0.6, 2.4]) / 1.995e-3 - 2.05) < 0.1)


@pytest.mark.slow
def test_stick_zone_converges_at_first_order():
    """The stick zone's trailing end, h = 0.2, 0.1, 0.05 mm at H = 1200 a: errors 0.10,
    0.05, 0.025 a (measured), order 1 within 0.2."""
    errs = [abs(_errors(2.4, h, (0.5,))[0][1]) for h in (2e-4, 1e-4, 5e-5)]
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(np.abs(orders - 1.0) < 0.2)
