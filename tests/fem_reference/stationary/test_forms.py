"""The stationary model's weak forms on polynomial fields (the shared 3D multiplier forms
and pressure mass among them).

The forms are assembled with scikit-fem on small structured meshes and applied to
displacements that the P2 elements represent exactly, so every integral has a closed
form computed here by hand (stated in each test); the quadrature is exact for these
polynomial integrands, so the tolerance is round-off (1e-12 relative).
"""

import math

import numpy as np
import pytest
from skfem import (Basis, ElementTetP1, ElementTetP2, ElementTriP1, ElementTriP2, ElementVector,
                   FacetBasis, MeshTet, MeshTri, asm)

from fem_reference.stationary import forms

G = 3.0e6
R, H = 2.0e-3, 1.5e-3


@pytest.fixture(scope="module")
def axi():
    mesh = MeshTri.init_tensor(np.linspace(0, R, 5), np.linspace(0, H, 4)).with_boundaries(
        {"top": lambda x: np.isclose(x[1], H)})
    ub = Basis(mesh, ElementVector(ElementTriP2()), intorder=4)
    pb = Basis(mesh, ElementTriP1(), intorder=4)
    fbu = FacetBasis(mesh, ElementVector(ElementTriP2()), facets=mesh.boundaries["top"], intorder=6)
    fbl = FacetBasis(mesh, ElementTriP1(), facets=mesh.boundaries["top"], intorder=6)
    return ub, pb, fbu, fbl


def _axi_field(ub, ur, uz):
    return ub.project(lambda x: np.array([ur(x[0], x[1]), uz(x[0], x[1])]))


def test_axisymmetric_stiffness_on_exact_fields(axi):
    """u = (r z, z^2): eps_rr = z, eps_zz = 2z, eps_tt = u_r/r = z, eps_rz = r/2, so
    a(u, u) = 2G int (6 z^2 + r^2/2) 2 pi r dr dz = 4 pi G (H^3 R^2 + R^4 H / 8);
    u = (r, -2z) (uniform, volume-preserving): a = 2G (1 + 4 + 1) pi R^2 H; a rigid
    lift u = (0, 1) stores nothing; a(u, v) is symmetric."""
    ub = axi[0]
    A = asm(forms.axi_stiffness, ub, G=G)
    u = _axi_field(ub, lambda r, z: r * z, lambda r, z: z * z)
    expect = 4 * math.pi * G * (H**3 * R**2 + R**4 * H / 8)
    assert abs(u @ A @ u - expect) <= 1e-12 * expect
    v = _axi_field(ub, lambda r, z: r, lambda r, z: -2 * z)
    expect_v = 2 * G * 6 * math.pi * R**2 * H
    assert abs(v @ A @ v - expect_v) <= 1e-12 * expect_v
    # cross term a(u, v) = 2G int (z*1 + 2z*(-2) + z*1) 2 pi r = 2G * (-2) * 2 pi (H^2/2)(R^2/2)
    cross = 2 * G * (-2) * 2 * math.pi * (H**2 / 2) * (R**2 / 2)
    assert abs(u @ A @ v - cross) <= 1e-12 * abs(cross) and abs(v @ A @ u - cross) <= 1e-12 * abs(cross)
    lift = _axi_field(ub, lambda r, z: 0 * r, lambda r, z: 1 + 0 * r)
    assert abs(lift @ A @ lift) <= 1e-14 * abs(A).sum() * (lift @ lift)  # cancellation of the entries only


def test_axisymmetric_divergence_coupling_area_and_profile_on_exact_fields(axi):
    """div u = du_r/dr + u_r/r + du_z/dz. u = (r z, z^2): div = 4z, int 4z 2 pi r =
    2 pi H^2 R^2; u = (r, -2z): div = 0. On the top z = H: int u_z 2 pi r dr = pi R^2 H^2
    for u_z = z^2; int 2 pi r dr = pi R^2; int s 2 pi r dr = pi R^4 / 2 for s = r^2;
    int 1 * 1 over the meridian section (the pressure mass, no 2 pi r) = R H."""
    ub, pb, fbu, fbl = axi
    B = asm(forms.axi_divergence, ub, pb)
    u = _axi_field(ub, lambda r, z: r * z, lambda r, z: z * z)
    one = np.ones(pb.N)
    assert abs(one @ B @ u - 2 * math.pi * H**2 * R**2) <= 1e-12 * 2 * math.pi * H**2 * R**2
    v = _axi_field(ub, lambda r, z: r, lambda r, z: -2 * z)
    assert abs(one @ B @ v) <= 1e-12 * 2 * math.pi * R**2 * H
    # a test function varying in r: q = r, div = 4z: int 4 z r 2 pi r = 8 pi (H^2/2)(R^3/3)
    q = pb.project(lambda x: x[0])
    assert abs(q @ B @ u - 8 * math.pi * H**2 / 2 * R**3 / 3) <= 1e-12 * 8 * math.pi * H**2 * R**3
    C = asm(forms.axi_coupling, fbu, fbl)
    ones_l = np.ones(fbl.N)
    assert abs(ones_l @ C @ u - math.pi * R**2 * H**2) <= 1e-12 * math.pi * R**2 * H**2
    radial = _axi_field(ub, lambda r, z: r + z, lambda r, z: 0 * r)  # no u_z: no coupling
    assert abs(ones_l @ C @ radial) <= 1e-12 * math.pi * R**3
    area = asm(forms.axi_area, fbl)
    assert abs(area.sum() - math.pi * R**2) <= 1e-12 * math.pi * R**2
    xq = np.asarray(fbl.global_coordinates())
    prof = asm(forms.axi_profile, fbl, s=xq[0] ** 2)
    assert abs(prof.sum() - math.pi * R**4 / 2) <= 1e-12 * math.pi * R**4
    M = asm(forms.pressure_mass, pb)
    assert abs(one @ M @ one - R * H) <= 1e-12 * R * H


def test_three_dimensional_forms_on_exact_fields():
    """Unit cube, u = (x z, y^2, x y): e_xx = z, e_yy = 2y, e_xz = (x + y)/2, e_yz = x/2,
    so int eps:eps = 1/3 + 4/3 + 7/12 + 1/6 = 29/12 and a = 2G 29/12; div u = z + 2y,
    int = 3/2; on the top z = 1: int u_z = int x y = 1/4, area 1, int (x^2 + y^2) = 2/3."""
    mesh = MeshTet.init_tensor(*(np.linspace(0, 1, 3),) * 3).with_boundaries(
        {"top": lambda x: np.isclose(x[2], 1.0)})
    ue = ElementVector(ElementTetP2())
    ub, pb = Basis(mesh, ue, intorder=4), Basis(mesh, ElementTetP1(), intorder=4)
    u = ub.project(lambda x: np.array([x[0] * x[2], x[1] ** 2, x[0] * x[1]]))
    a = u @ asm(forms.stiffness_3d, ub, G=G) @ u
    assert abs(a - 2 * G * 29 / 12) <= 1e-12 * G
    assert abs(np.ones(pb.N) @ asm(forms.divergence_3d, ub, pb) @ u - 1.5) <= 1e-12
    fbu = FacetBasis(mesh, ue, facets=mesh.boundaries["top"], intorder=6)
    fbl = FacetBasis(mesh, ElementTetP1(), facets=mesh.boundaries["top"], intorder=6)
    assert abs(np.ones(fbl.N) @ asm(forms.coupling_3d, fbu, fbl) @ u - 0.25) <= 1e-12
    assert abs(asm(forms.area_3d, fbl).sum() - 1.0) <= 1e-12
    xq = np.asarray(fbl.global_coordinates())
    assert abs(asm(forms.profile_3d, fbl, s=xq[0] ** 2 + xq[1] ** 2).sum() - 2 / 3) <= 1e-12
