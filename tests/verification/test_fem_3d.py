"""The quarter-cylinder 3D model agrees with the axisymmetric reference (thick case)."""

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
