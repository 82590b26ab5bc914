"""The stationary quarter-cylinder 3D model agrees with the axisymmetric reference: on
the thick case against a fine axisymmetric solve, and on a coarse thin case with the
same mesh settings, carrying a quarter of the load and reporting the whole, its surface
profile the radial line y = 0."""

import numpy as np
import pytest

from fem_reference import ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading, solve


def _thick(**fem):
    return ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", 0.02),
                          Loading(load=100.0), FemSettings(**fem))


@pytest.fixture(scope="module")
def axisymmetric():
    return solve(_thick(element_size=5e-5))


def _compare(res, ref, tol_radius, tol_indentation, tol_peak):
    errs = {k: getattr(res, k) / getattr(ref, k) - 1
            for k in ("contact_radius", "indentation", "peak_pressure")}
    print(f"3d ({res.mesh.unknowns} unknowns, h = {res.mesh.element_size:.1e} m) vs "
          f"axisymmetric: " + ", ".join(f"{k} {v:+.3%}" for k, v in errs.items()))
    assert res.load == pytest.approx(100.0, rel=1e-10)
    assert abs(errs["contact_radius"]) < tol_radius
    assert abs(errs["indentation"]) < tol_indentation
    assert abs(errs["peak_pressure"]) < tol_peak


def test_3d_coarse_agrees(axisymmetric):
    """h = 0.6 mm = a/7.6: the axisymmetric model at that size is off by ~1 % in
    radius and ~0.3 % in peak pressure; allow the 3D model 1.5 %, and 0.3 % in the
    (integral, better converged) indentation."""
    _compare(solve(_thick(model="3d", element_size=6e-4)), axisymmetric, 0.015, 0.003, 0.015)


@pytest.mark.slow
def test_3d_finer_agrees(axisymmetric):
    """h = 0.3 mm (~34k unknowns, ~1 min): within 0.5 % in radius and peak pressure,
    0.1 % in indentation."""
    _compare(solve(_thick(model="3d", element_size=3e-4)), axisymmetric, 0.005, 0.001, 0.005)


def _top_vertices_of(mesh, H, on_line):
    """Vertices of the top surface z = H (and y = 0 in 3D), sorted by distance from the
    axis: recomputed from the mesh coordinates, not by the solver's facet lookup."""
    p = mesh.p
    top = np.flatnonzero(np.isclose(p[-1], H, rtol=0, atol=1e-12 * H))
    if on_line:
        top = top[p[1, top] == 0.0]
    r = np.hypot(p[0, top], p[1, top]) if p.shape[0] == 3 else np.abs(p[0, top])
    return np.sort(r)


def test_three_dimensional_quarter_matches_the_axisymmetric_solve():
    """The 3D quarter model carries a quarter of the load and reports the whole, and agrees
    with the axisymmetric model on the same coarse mesh settings (H = 2 mm, h = 0.8 mm,
    P = 5 N): contact radius measured -0.10% (0.5% allowed), indentation -0.7% (2%
    allowed). Its surface profile is the radial line y = 0 of the top surface."""
    kw = dict(element_size=0.8e-3, contact_zone=5e-3, domain_radius=12e-3, grading=0.6)

    def problem(**fem):
        return ContactProblem(Layer(2e-3), ElasticMaterial(3e6), Indenter("paraboloid", 0.02),
                              Loading(load=5.0), FemSettings(**fem, **kw))

    three = solve(problem(model="3d"))
    axi = solve(problem())
    assert three.mesh.model == "3d"
    assert abs(three.load - 5.0) <= 1e-12 * 5.0
    assert three.contact_radius == pytest.approx(axi.contact_radius, rel=5e-3)
    assert three.indentation == pytest.approx(axi.indentation, rel=2e-2)
    np.testing.assert_array_equal(three.surface_radius, _top_vertices_of(three.fields["mesh"], 2e-3, on_line=True))
    assert abs(three.surface_uz[0] + three.indentation) <= 2e-2 * three.indentation
