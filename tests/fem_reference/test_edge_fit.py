"""The contact edge fitted from the gap just outside the contact
(:func:`fem_reference.edge_fit.fit_contact_radius`): exact on the Hertz gap, reading the
stated band of vertices and nothing beyond it, and refusing a band too thin or a gap
that does not open."""

import numpy as np
import pytest


def test_the_fit_reads_only_the_vertices_of_its_band():
    """fit_contact_radius on the Hertz gap g = c (r - r_c)^(3/2)
    sampled at vertices r_last + j h: the band r_last < r <= r_last + (fit_nodes + 1/4) h
    holds j = 1..fit_nodes and the radius is r_c exactly; vertices at r_last (or within
    1e-6 h of it) and beyond the band carry corrupt gaps that must not be read."""
    from fem_reference.edge_fit import fit_contact_radius as fem_fit
    from fem_reference.errors import ContactNotConvergedError

    h, rc = 1e-4, 2.0e-3
    r_last = rc - 0.3 * h
    r = r_last + h * np.array([-1.0, 0.0, 0.4e-6, 1.0, 2.0, 3.0, 4.0, 5.0])
    gap = np.where(r > rc, 0.7 * np.clip(r - rc, 0, None) ** 1.5, 0.0)
    gap[1:3] = 1e-3  # at r_last, and within 1e-6 h of it
    gap[6:] = 1e-3  # beyond the band of 3 vertices
    assert abs(fem_fit(r_last, r, gap, h, 3) - rc) < 1e-15
    assert abs(fem_fit(r_last, r, gap, h, 4) - rc) > 1e-6  # a wider band reads the corrupt vertex
    r_edge = np.append(r, r_last + 1e-6 * h)  # exactly on the inner limit: excluded
    assert abs(fem_fit(r_last, r_edge, np.append(gap, 1e-3), h, 3) - rc) < 1e-15
    two = np.array([r_last, r_last + h, r_last + (1 + 0.25) * h])  # the second exactly on the outer limit
    g_two = 0.7 * np.clip(two - rc, 0, None) ** 1.5
    assert abs(fem_fit(r_last, two, g_two, h, 1) - rc) < 1e-15  # two vertices are enough
    g2 = gap.copy()
    g2[4] = -1e-30  # round-off below zero inside the band counts as 0 (no NaN)
    assert np.isfinite(fem_fit(r_last, r, g2, h, 3))
    with pytest.raises(ContactNotConvergedError, match=r"^only 1 surface vertex\(es\) within 1 element sizes outside "
                       r"the contact: the contact radius cannot be fitted$"):
        fem_fit(r_last, r, gap, h, 1)
    with pytest.raises(ContactNotConvergedError, match=r"^the gap does not open outside the contact: the contact "
                       r"radius cannot be fitted \(refine fem.element_size\)$"):
        fem_fit(r_last, r, np.zeros_like(r), h, 3)  # touching everywhere: a flat line
