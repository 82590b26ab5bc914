"""verification.metrics: Richardson extrapolation, exact on geometric sequences of any
ratio (a property, by hypothesis) and refusing sequences without an order; the contact
radius fit, exact for Hertz's edge; and the pressure metrics, on data built so that each
choice of the code (band, strict or loose inequalities, finite gaps, the peak search)
changes the answer.

Every expected value is computed here from the construction of the data, never from
the module.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from verification import analytic
from verification.metrics import Convergence, fit_contact_radius, pressure_difference, richardson

# ---------------------------------------------------------------------------- Richardson


@settings(max_examples=150, deadline=None)
@given(
    limit=st.floats(-10.0, 10.0),
    coef=st.floats(0.1, 10.0),
    sign=st.sampled_from([-1.0, 1.0]),
    order=st.floats(0.55, 4.9),
    ratio=st.floats(1.3, 3.0),
    h0=st.floats(0.2, 1.0),
)
def test_richardson_is_exact_on_any_geometric_sequence(limit, coef, sign, order, ratio, h0):
    """q_k = q* + C h_k^p with h_k = h0 / ratio^k: the observed order is p, the
    extrapolation q*, the finest error |C| h_2^p, whatever q*, C, p, ratio. Tolerance:
    the rounding of q (2e-16 |q|) amplified by 1 / |q3 - q2| in the order; 1e-9 relative
    to max(|q*|, |C|) over the smallest change, measured <= 2e-11 over these ranges."""
    h = [h0 / ratio**k for k in range(3)]
    q = [limit + sign * coef * x**order for x in h]
    c = richardson(q, ratio)
    scale = max(abs(limit), coef) / abs(q[2] - q[1])
    assert c.asymptotic
    assert c.values == tuple(q)
    assert abs(c.order - order) <= 1e-9 * scale
    assert abs(c.extrapolated - limit) <= 1e-9 * max(abs(limit), coef)
    assert abs(c.error_finest - coef * h[2] ** order) <= 1e-9 * max(abs(limit), coef)


def test_richardson_default_ratio_is_two():
    q = [1.0 + 0.5**k for k in range(3)]  # first order, ratio 2
    c = richardson(q)
    assert abs(c.order - 1.0) < 1e-12 and abs(c.extrapolated - 1.0) < 1e-12


def test_richardson_orders_at_the_bounds_are_accepted():
    """p = 0.5 (ratio 4, changes 2 then 1) and p = 5 (ratio 2, changes 32 then 1) are
    plausible: Richardson applies, with q* = q3 + d2 / (ratio^p - 1)."""
    lo = richardson([0.0, 2.0, 3.0], 4.0)
    assert lo.order == 0.5 and lo.asymptotic and lo.extrapolated == 4.0 and lo.error_finest == 1.0
    hi = richardson([0.0, 32.0, 33.0], 2.0)
    assert hi.order == 5.0 and hi.asymptotic and abs(hi.extrapolated - (33.0 + 1.0 / 31.0)) < 1e-14
    just_out = richardson([0.0, 32.5, 33.5], 2.0)  # order log2(32.5) > 5
    assert not just_out.asymptotic and just_out.extrapolated == 33.5 and just_out.error_finest == 3.0
    assert abs(just_out.order - math.log2(32.5)) < 1e-12


def test_richardson_on_sequences_without_an_order():
    stalled = richardson([1.0, 1.2, 1.2])  # converged at the last step: no order
    assert math.isnan(stalled.order) and not stalled.asymptotic
    assert stalled.extrapolated == 1.2 and stalled.error_finest == 0.0
    late = richardson([1.0, 1.0, 1.2])
    assert math.isnan(late.order) and late.extrapolated == 1.2 and abs(late.error_finest - 0.6) < 1e-12
    assert stalled.asymptotic is False and late.asymptotic is False  # a bool, as documented
    wobble = richardson([1.0, 1.2, 1.1])
    assert math.isnan(wobble.order) and abs(wobble.error_finest - 0.3) < 1e-12
    assert isinstance(wobble, Convergence) and wobble.values == (1.0, 1.2, 1.1)


@pytest.mark.parametrize("ratio", [2.0, 3.0, 1.5])
def test_richardson_recovers_order_and_limit_for_any_ratio(ratio):
    h = [0.4, 0.4 / ratio, 0.4 / ratio**2]
    q = [1.0 + 0.3 * x**1.7 for x in h]
    c = richardson(q, ratio)
    assert abs(c.order - 1.7) < 1e-9
    assert abs(c.extrapolated - 1.0) < 1e-12 and c.asymptotic
    assert abs(c.error_finest - 0.3 * h[-1] ** 1.7) < 1e-12  # the finest level's true error


def test_richardson_refuses_to_extrapolate_stagnant_or_oscillating_sequences():
    stagnant = richardson([4.5011, 4.5077, 4.5139])  # observed order 0.09
    assert not stagnant.asymptotic and stagnant.extrapolated == 4.5139
    assert abs(stagnant.error_finest - 3 * 0.0062) < 1e-12
    assert not richardson([1.0, 1.2, 1.1]).asymptotic  # non-monotone


# ------------------------------------------------------------------------ contact radius


def _hertz_gap(r, rc, c=0.7):
    return np.where(r > rc, c * np.clip(r - rc, 0, None) ** 1.5, 0.0)


def test_radius_fit_uses_exactly_the_band_of_three_spacings():
    """Open samples at rc + 0.5 s + j s: those within 3 s of the first (j = 0..3) are
    Hertzian, those beyond are not. A wider band would read the corrupt samples; a strict
    band edge would drop j = 3 and a second-degree fit would not be the line through the
    g^(2/3) samples; both change the radius."""
    rc, s = 2.0e-3, 0.1e-3
    r = np.concatenate([np.linspace(0, rc, 11), rc + 0.5 * s + s * np.arange(8)])
    gap = _hertz_gap(r, rc)
    gap[-4:] *= 3.0  # beyond the band: not Hertzian
    contact = r <= rc
    assert abs(fit_contact_radius(r, gap, contact, s) - rc) < 1e-15
    assert abs(fit_contact_radius(r, gap, contact, s, band=4.0) - rc) > 1e-6
    only_two = np.array([0.0, rc, rc + 0.5 * s, rc + 3.5 * s])  # the second open one on the band edge
    assert abs(fit_contact_radius(only_two, _hertz_gap(only_two, rc), only_two <= rc, s) - rc) < 1e-15
    with pytest.raises(ValueError, match="^fewer than two distinct open radii in the fitting band$"):
        fit_contact_radius(only_two, _hertz_gap(only_two, rc), only_two <= rc, s, band=2.9)


def test_radius_fit_of_a_quadratic_band_differs_from_a_line():
    """Three open samples of g^(2/3) on a parabola: the least-squares line's zero is not
    the parabola's root (a degree-2 fit would be exact)."""
    rc, s = 1.0e-3, 0.1e-3
    r = np.array([0.0, 0.5e-3, rc, rc + s, rc + 2 * s, rc + 3 * s])
    t = r - rc
    gap = np.where(r > rc, (t * (1 + t / s)) ** 1.5, 0.0)  # g^(2/3) = t + t^2 / s
    line = np.polyfit(r[3:], gap[3:] ** (2 / 3), 1)
    got = fit_contact_radius(r, gap, r <= rc, s)
    assert abs(got - (-line[1] / line[0])) < 1e-15
    assert abs(got - rc) > 1e-5


def test_radius_fit_ignores_open_samples_not_outside_every_contact_sample_and_infinite_gaps():
    """2D scatter: an open sample at the same radius as a contact sample (possible off a
    circle of symmetry) and samples with an infinite gap (outside a height map) are not
    read; a tiny negative gap (round-off) counts as 0."""
    rc, s = 2.0e-3, 0.1e-3
    r = np.concatenate([np.linspace(0, rc, 11), [rc, rc + s, rc + 1.5 * s], rc + s * np.arange(1, 4)])
    gap = _hertz_gap(r, rc)
    contact = np.zeros(r.size, bool)
    contact[:11] = True
    gap[11] = 5e-6  # open, at r = rc = the largest contact radius: must be skipped
    gap[12:14] = np.inf  # open but unreadable
    assert abs(fit_contact_radius(r, gap, contact, s) - rc) < 1e-15
    r2 = np.array([0.0, rc, rc, rc + s, rc + 2 * s])
    g2 = _hertz_gap(r2, rc)
    g2[2] = -1e-15  # open sample exactly at the edge radius, negative by round-off
    c2 = np.array([True, True, False, False, False])
    assert abs(fit_contact_radius(r2, g2, c2, s) - rc) < 1e-15
    r3 = np.array([0.0, rc, rc + s, rc + 2 * s])
    g3 = _hertz_gap(r3, rc)
    g3[2] = -1e-30  # below the band's first sample: 0 after clipping, the line then misses rc
    assert np.isfinite(fit_contact_radius(r3, g3, r3 <= rc, s))


@pytest.mark.parametrize(
    "r, gap, contact, message",
    [
        ([0.0, 1.0], [0.0, 1.0], [False, False], "^the contact radius needs samples both in and out of contact$"),
        ([0.0, 1.0], [0.0, 0.0], [True, True], "^the contact radius needs samples both in and out of contact$"),
        ([0.0, 1.0, 2.0], [0.0, 1.0, 0.0], [False, True, True], "^no open sample outside the contact$"),
        ([0.0, 1.0, 2.0], [0.0, 0.0, np.inf], [True, True, False], "^no open sample outside the contact$"),
        ([0.0, 1.0, 2.0, 2.0], [0.0, 0.0, 1.0, 1.0], [True, True, False, False], "^fewer than two distinct open radii in the fitting band$"),
        ([0.0, 1.0, 2.0, 3.0], [0.0, 0.0, 1.0, 0.5], [True, True, False, False], "^the gap does not open outward near the contact edge$"),
        # open samples touching (gap 0): the line is flat (beta = 0 exactly), no radius
        ([0.0, 1.0, 2.0, 3.0], [0.0, 0.0, 0.0, 0.0], [True, True, False, False], "^the gap does not open outward near the contact edge$"),
    ],
)
def test_radius_fit_refuses_unusable_data(r, gap, contact, message):
    with pytest.raises(ValueError, match=message):
        fit_contact_radius(np.array(r), np.array(gap), np.array(contact), 1.0)


def test_radius_fit_flattens_its_inputs():
    rc = 1.0
    r = np.array([[0.0, 0.5], [1.0, 1.5], [2.0, 2.5]])
    gap = _hertz_gap(r, rc)
    assert abs(fit_contact_radius(r.tolist(), gap.tolist(), (r <= rc).tolist(), 0.5) - rc) < 1e-14


def test_radius_fit_is_exact_for_the_hertz_edge():
    """g = c (r - r_c)^(3/2) outside the contact: the g^(2/3) line gives r_c exactly, from
    scattered 2D samples as from a line of samples."""
    rc = 2.3456e-3
    x = np.arange(-40, 41) * 0.1e-3
    X, Y = np.meshgrid(x, x)
    r = np.hypot(X, Y)
    gap = np.where(r > rc, 0.7 * np.clip(r - rc, 0, None) ** 1.5, 0.0)
    assert abs(fit_contact_radius(r, gap, r <= rc, 0.1e-3) - rc) < 1e-15
    line = np.linspace(0, 4e-3, 33)
    g = np.where(line > rc, 0.7 * np.clip(line - rc, 0, None) ** 1.5, 0.0)
    assert abs(fit_contact_radius(line, g, line <= rc, line[1]) - rc) < 1e-15


# ----------------------------------------------------------------------------- pressures


def test_pressure_difference_splits_interior_and_edge_at_the_stated_radii():
    """A unit error at one sample: at r = 0.9 r_c exactly it belongs to the edge band, at
    r = r_c to neither; the RMS is over the samples of the band (sqrt(1/n))."""
    rc = 2.0

    def ref(r):
        return np.ones_like(np.asarray(r, float))

    r = np.array([0.0, 0.5, 1.0, 0.9 * rc, 1.9, rc, 2.5])
    p = ref(r).copy()
    p[3] += 0.5  # r = 0.9 rc: edge
    p[5] -= 7.0  # r = rc: outside both
    p[6] += 9.0  # outside
    d = pressure_difference(r, p, ref, rc)
    assert d.max_interior == 0.0 and d.rms_interior == 0.0
    assert d.max_edge == 0.5 and abs(d.rms_edge - 0.5 / math.sqrt(2)) < 1e-15
    assert d.peak_reference == 1.0
    p[1] -= 0.25  # interior, negative: absolute value
    d = pressure_difference(r, p, ref, rc)
    assert d.max_interior == 0.25 and abs(d.rms_interior - 0.25 / math.sqrt(3)) < 1e-15
    wide = pressure_difference(r, p, ref, rc, edge_fraction=0.5)  # edge band [1, 2): r = 1, 1.8, 1.9
    assert wide.max_interior == 0.25 and abs(wide.rms_interior - 0.25 / math.sqrt(2)) < 1e-15
    assert wide.max_edge == 0.5 and abs(wide.rms_edge - 0.5 / math.sqrt(3)) < 1e-15


def test_pressure_difference_relative_to_an_off_axis_peak():
    """A reference peaking at r = r_c / 2 (a ring), sharply: the peak is found (the search
    grid of 401 points holds r_c / 2) and the differences are relative to it."""
    rc = 1.0

    def ring(r):
        return 4e6 * np.clip(1 - np.abs(np.asarray(r, float) - 0.5) / 0.05, 0, None)

    r = np.array([0.1, 0.5, 0.95])
    d = pressure_difference(r, ring(r) + np.array([2e6, 0.0, 1e6]), ring, rc)
    assert d.peak_reference == 4e6
    assert d.max_interior == 0.5 and d.max_edge == 0.25


def test_pressure_difference_with_empty_bands_is_nan():
    d = pressure_difference(np.array([0.1, 0.2]), np.array([1.0, 1.0]), lambda r: np.ones_like(r), 1.0)
    assert math.isnan(d.max_edge) and math.isnan(d.rms_edge)
    assert d.max_interior == 0.0
    d = pressure_difference([[1.5]], [[1.0]], lambda r: np.full(np.shape(r), 2.0), 1.0)
    assert math.isnan(d.max_interior) and math.isnan(d.rms_interior) and d.peak_reference == 2.0


def test_pressure_difference_evaluates_the_reference_in_double():
    """Radii given in float32 reach the reference as float64 (the same values): a
    reference evaluated in the dtype of its argument gives the float64 answer."""
    rc = 1.0

    def ref(r):
        return 3e6 * np.sqrt(np.clip(1 - r * r, 0, None)).astype(np.asarray(r).dtype)

    r32 = np.linspace(0.05, 0.95, 7).astype(np.float32)
    p = 3e6 * np.sqrt(1 - r32.astype(float) ** 2) * 1.01
    a = pressure_difference(r32, p, ref, rc)
    b = pressure_difference(r32.astype(float), p, ref, rc)
    assert a == b


def test_pressure_difference_of_a_scaled_field_is_known_exactly():
    """p = (1 + eps) p_Hertz: the difference over the peak is eps sqrt(1 - r^2/a^2), so its
    largest interior value is eps at the centre and its edge RMS is the RMS of that
    function over the edge samples."""
    eps = 0.013
    h = analytic.hertz_contact(10.0, 0.02, 12e6)
    a = h.contact_radius
    r = np.linspace(0, a, 201)
    d = pressure_difference(r, (1 + eps) * h.pressure(r), h.pressure, a)
    assert abs(d.max_interior - eps) < 1e-14
    edge = (r >= 0.9 * a) & (r < a)
    expect = eps * np.sqrt(np.mean(1 - (r[edge] / a) ** 2))
    assert abs(d.rms_edge - expect) < 1e-14
    assert abs(d.peak_reference - h.peak_pressure) < 1e-9 * h.peak_pressure
