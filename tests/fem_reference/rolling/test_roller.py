"""3D steady rolling of a roller of finite length (fem_reference, indenter shape
"cylinder", the half box y >= 0 with a rectangular candidate zone).

The roller's surface against its geometry computed here (a circle in x of the row's radius
R - e(y), e the drop of the rounded end), its inputs' rules, the half box's rectangle, and
a coarse elastic solve against values of the independent spectral BEM (quoted, measured).
"""

from __future__ import annotations

import types

import numpy as np
import pytest

from fem_reference import ContactProblem, ElasticMaterial, FemSettings, Indenter, InputError, Layer, Loading, solve
from fem_reference.case import problem_from_dict

R, L, RE = 0.02, 0.006, 0.001
#: a coarse mesh on a short box (11k unknowns, 179 candidate nodes, 6 s)
COARSE = dict(element_size=4e-4, contact_zone=3.2e-3, grading=0.5, fit_nodes=2, upstream=0.02,
              downstream=0.02, domain_radius=0.016)


def test_roller_surface_is_the_row_circle_above_the_rounded_end():
    """s = e + rho - sqrt(rho^2 - x^2), rho = R - e, with e = 0 on the flat and the arc
    r_e - sqrt(r_e^2 - (|y| - y0)^2) beyond y0 = L/2 - r_e; ds/dx = x / sqrt(rho^2 - x^2)
    (against a centred difference, 1e-7 relative); a crowned roller's e = R_c - sqrt(R_c^2 -
    y^2)."""
    ind = Indenter("cylinder", R, length=L, edge_radius=RE)
    x = np.array([0.0, 1e-3, -2e-3, 1.5e-3, 1.5e-3])
    y = np.array([0.0, 1.9e-3, -2.5e-3, 3e-3, -2.9e-3])
    s = np.clip(np.abs(y) - (L / 2 - RE), 0, None)
    e = RE - np.sqrt(RE**2 - s**2)
    rho = R - e
    np.testing.assert_allclose(ind.surface(x, y), e + rho - np.sqrt(rho**2 - x**2), rtol=1e-10, atol=1e-18)
    assert ind.surface(0.0, L / 2) == pytest.approx(RE, rel=1e-12)
    d = 1e-7
    fd = (ind.surface(x + d, y) - ind.surface(x - d, y)) / (2 * d)
    np.testing.assert_allclose(ind.slope(x, y), fd, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(ind.profile(x), R - np.sqrt(R**2 - x**2), rtol=1e-10, atol=1e-18)  # y = 0
    crown = Indenter("cylinder", R, length=L, crown_radius=0.5)
    np.testing.assert_allclose(crown.axial_drop(y), 0.5 - np.sqrt(0.25 - y**2), rtol=1e-10, atol=1e-18)


@pytest.mark.parametrize("kwargs, message", [
    (dict(length=L, edge_radius=0.0031), r"^indenter\.edge_radius must be <= indenter\.length / 2 = 0\.003 m "
                                         r"\(the two end roundings meet at mid-length\), got 0\.0031$"),
    (dict(length=L, edge_radius=-1e-3), r"^indenter\.edge_radius must be a number >= 0 m, got -0\.001$"),
    (dict(length=None), r"^indenter\.length must be a number in m, got None$"),
    (dict(length=L, crown_radius=1e-3), r"^indenter\.crown_radius must be >= indenter\.length / 2 = 0\.003 m"),
    (dict(length=L, edge_radius=1e-3, crown_radius=1.0), r"^give indenter\.crown_radius or indenter\.edge_radius"),
])
def test_bad_roller_is_refused_naming_the_key(kwargs, message):
    with pytest.raises(InputError, match=message):
        Indenter("cylinder", R, **kwargs)


def test_roller_keys_belong_to_a_cylinder_and_it_rolls_in_3d_only():
    with pytest.raises(InputError, match=r"^indenter\.length, edge_radius and crown_radius belong to a cylinder"):
        Indenter("sphere", R, length=L)
    roller = Indenter("cylinder", R, length=L, edge_radius=RE)
    for fem, speed in ((FemSettings(model="axisymmetric"), 0.01), (FemSettings(), 0.0)):
        with pytest.raises(InputError, match=(r"^fem-reference cannot solve \[indenter\] shape = \"cylinder\" with "
                                              r"fem\.model = '(axisymmetric|3d)' and loading\.speed = (0\.01|0\.0): "
                                              r"a roller is solved by the 3d rolling model only")):
            ContactProblem(Layer(5e-3), ElasticMaterial(3e6), roller, Loading(load=6.0, speed=speed), fem)
    assert ContactProblem(Layer(5e-3), ElasticMaterial(3e6), roller, Loading(load=6.0, speed=0.01)).fem.model == "3d"


def test_case_file_roller_reaches_the_fem_and_its_edge_rule_names_the_key():
    case = {"layer": {"thickness": 5e-3}, "material": {"model": "elastic", "shear_modulus": 3e6},
            "indenter": {"shape": "cylinder", "radius": R, "length": L, "edge_radius": RE},
            "loading": {"load": 6.0, "speed": 0.01}}
    assert problem_from_dict(case).indenter == Indenter("cylinder", R, length=L, edge_radius=RE)
    case["indenter"]["edge_radius"] = 0.004
    with pytest.raises(InputError, match=r"^indenter\.edge_radius must be <= indenter\.length / 2"):
        problem_from_dict(case)


def test_half_box_with_a_rectangular_zone():
    """The candidate zone is the rectangle |x| <= Z, y <= Z_y on the top, the rest of the top
    is free, and the zone's facets tile its area 2 Z Z_y."""
    from fem_reference.mesh.half_box import half_box_mesh

    H, Z, Zy = 5e-3, 2e-3, 3e-3
    mesh = half_box_mesh(H, Z, 0.02, 0.015, types.SimpleNamespace(mesh_size=5e-4, grading=0.5, far_size=H), Zy)
    pts = mesh.p[:, mesh.facets[:, mesh.boundaries["zone"]]]
    assert np.allclose(pts[2], H) and np.all(np.abs(pts[0]) <= Z * (1 + 1e-9)) and np.all(pts[1] <= Zy * (1 + 1e-9))
    area = 0.0
    for f in mesh.boundaries["zone"]:
        (ax, ay), (bx, by), (cx, cy) = mesh.p[:2, mesh.facets[:, f]].T
        area += 0.5 * abs((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))
    assert area == pytest.approx(2 * Z * Zy, rel=1e-9)
    free = mesh.p[:, mesh.facets[:, mesh.boundaries["free"]]].reshape(3, 3, -1).mean(axis=1)
    assert np.all((np.abs(free[0]) >= Z * (1 - 1e-9)) | (free[1] >= Zy * (1 - 1e-9)))


def test_coarse_elastic_roller_against_the_bem():
    """An elastic layer (H = 5 mm, G = 3 MPa) under a roller (R = 2 cm, L = 6 mm, r_e = 1 mm)
    at 6 N, no inertia: rolling is the stationary contact, so R_r vanishes on the
    mirror-symmetric mesh. The spectral BEM (a = 0.05 mm) gives d = 0.096549 mm and the
    half-width on y = 0 1.4540 mm (1.4471 at a = 0.1 mm); this coarse mesh (h = 0.4 mm = b / 3.6)
    measured -0.25% and -0.63%: gated at 1% and 2% (the edge fit reads the gap to a tenth of h,
    2.8% of b)."""
    p = ContactProblem(Layer(5e-3, 0.0), ElasticMaterial(3e6), Indenter("cylinder", R, length=L, edge_radius=RE),
                       Loading(load=6.0, speed=0.01), FemSettings(**COARSE))
    r = solve(p)
    assert r.load == pytest.approx(6.0, rel=1e-10)
    assert abs(r.rolling_resistance) < 1e-9 * 6.0 * 1.45e-3 / R
    assert abs(r.contact_centre) < 1e-6 * r.contact_length
    assert r.indentation == pytest.approx(9.6549e-5, rel=0.01)
    assert r.half_width == pytest.approx(1.4540e-3, rel=0.02)
    xy = r.zone_xy
    assert np.all(np.abs(xy[:, 0]) <= 3.2e-3 * (1 + 1e-9)) and np.all(xy[:, 1] <= L / 2 * (1 + 1e-9))
    assert xy[:, 1].max() == pytest.approx(L / 2)  # the zone reaches the end face
    assert L / 2 - RE < r.lateral_edge < L / 2  # the contact ends on the rounding
