"""fem_reference's weak forms on polynomial fields, and the solved fields against the
equilibrium of the layer.

The forms are assembled with scikit-fem on small structured meshes and applied to
displacements that the P2 elements represent exactly, so every integral has a closed
form computed here by hand (stated in each test); the quadrature is exact for these
polynomial integrands, so the tolerance is round-off (1e-12 relative).

The solved pressure field is checked by an identity the solver does not use: on the
bonded base ``u = 0``, so ``du_r/dr = u_r / r = 0`` and incompressibility gives
``du_z/dz = 0``; there ``sigma_zz = -p`` and the vertical equilibrium of the layer gives
``int_base p dA = P``, the load.
"""

import math

import numpy as np
import pytest
from skfem import (Basis, ElementTetP1, ElementTetP2, ElementTriP1, ElementTriP2, ElementVector,
                   FacetBasis, LinearForm, MeshTet, MeshTri, asm)

from fem_reference import ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading, solve
from fem_reference import forms

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


def test_axisymmetric_divergence_coupling_area_profile(axi):
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


def test_base_pressure_carries_the_load():
    """The returned pressure field p (positive in compression) integrated over the bonded
    base equals the load: 100 N within 3% (discretization error at h = 0.4 mm, measured
    +0.75%); a sign error gives -100 N. The contact pressures sum to the load too."""
    res = solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", 0.02),
                               Loading(load=100.0), FemSettings(element_size=4e-4)))
    mesh, p = res.fields["mesh"], res.fields["p"]
    fb = FacetBasis(mesh, ElementTriP1(), facets=mesh.boundaries["base"], intorder=4)

    @LinearForm
    def weight(v, w):
        return v * 2 * math.pi * w.x[0]

    carried = asm(weight, fb) @ p
    assert abs(carried - 100.0) <= 3.0, carried
    assert abs(res.load - 100.0) <= 1e-9
    # the pressure at the top of the axis is compressive and near the peak contact pressure
    top_axis = np.flatnonzero((mesh.p[0] == 0) & np.isclose(mesh.p[1], 5e-3))
    assert p[top_axis].min() > 0.5 * res.peak_pressure


def test_fem_contact_radius_fit_reads_the_stated_band():
    """fem_reference.postprocess.fit_contact_radius on the Hertz gap g = c (r - r_c)^(3/2)
    sampled at vertices r_last + j h: the band r_last < r <= r_last + (fit_nodes + 1/4) h
    holds j = 1..fit_nodes and the radius is r_c exactly; vertices at r_last (or within
    1e-6 h of it) and beyond the band carry corrupt gaps that must not be read."""
    from fem_reference.errors import ContactNotConvergedError
    from fem_reference.postprocess import fit_contact_radius as fem_fit

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


# --- fem_reference.solve: what the driver reports, checked against the mesh it returns ---

def _thick_problem(**fem):
    return ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", 0.02),
                          Loading(load=100.0), FemSettings(**fem))


def _top_vertices_of(mesh, H, on_line):
    """Vertices of the top surface z = H (and y = 0 in 3D), sorted by distance from the
    axis: recomputed from the mesh coordinates, not by the solver's facet lookup."""
    p = mesh.p
    top = np.flatnonzero(np.isclose(p[-1], H, rtol=0, atol=1e-12 * H))
    if on_line:
        top = top[p[1, top] == 0.0]
    r = np.hypot(p[0, top], p[1, top]) if p.shape[0] == 3 else np.abs(p[0, top])
    return np.sort(r)


def test_solve_reports_its_mesh_record_and_progress():
    """h = 0.1 mm: 70 candidate nodes, so the surface compliance takes two blocks of 64.

    MeshStats and the surface arrays against counts recomputed from the returned mesh:
    bonded base (both components of the P2 displacement on its Vb vertices and Vb - 1 edge
    midpoints) and axis (u_r on its Va vertices and Va - 1 midpoints, the corner shared)
    are the fixed dofs. The solver record against what the solve did: primal-dual
    iterations = entries of the history, direct solver (no iterations), complementarity
    and linear residuals at round-off (measured 6e-15 and 1.5e-14), stage times that add
    up within the total, the total within the wall time; one progress line per stage and
    per block of 64 compliance columns, numbers as in the result. (One solve in the test
    itself, not in a shared fixture, so that every check runs on each mutant of solve.)"""
    import time

    from fem_reference.discretization import resolve

    lines = []
    problem = _thick_problem(element_size=1e-4)
    t0 = time.perf_counter()
    res = solve(problem, lines.append)
    wall = time.perf_counter() - t0
    disc = resolve(problem)

    mesh, ub, pb = (res.fields[k] for k in ("mesh", "ubasis", "pbasis"))
    assert set(res.fields) == {"mesh", "u", "p", "ubasis", "pbasis"}
    Vb = int(np.sum(mesh.p[1] == 0.0))
    Va = int(np.sum(mesh.p[0] == 0.0))
    fixed = 2 * (2 * Vb - 1) + (2 * Va - 1) - 1
    s = res.mesh
    assert (s.model, s.elements, s.vertices) == ("axisymmetric", mesh.t.shape[1], mesh.p.shape[1])
    assert (s.displacement_dofs, s.pressure_dofs) == (ub.N, pb.N) == (res.fields["u"].size, res.fields["p"].size)
    assert s.unknowns == ub.N + pb.N - fixed
    assert s.contact_nodes == res.radius.size == res.pressure.size == res.nodes.shape[0] == 70
    np.testing.assert_array_equal(res.nodes[:, 0], res.radius)  # axisymmetric nodes are (r,)
    assert (s.element_size, s.contact_zone, s.domain_radius, s.far_size) == (
        1e-4, disc.contact_zone, disc.domain_radius, disc.far_size)
    # the surface profile: top vertices by radius, closed gap at the centre (d + u_z = 0;
    # measured 2e-4 relative at h = 0.1 mm, 2e-3 allowed)
    np.testing.assert_array_equal(res.surface_radius, _top_vertices_of(mesh, 5e-3, on_line=False))
    assert res.surface_uz.shape == res.surface_radius.shape
    assert abs(res.surface_uz[0] + res.indentation) <= 2e-3 * res.indentation

    r = res.solver
    assert r.method == "primal-dual" and r.iterations == len(r.history) >= 2
    assert r.history[-1] == int(np.sum(res.pressure > 0))
    assert 0 <= r.residual < 1e-12 and 0 <= r.linear_residual < 1e-12
    assert (r.linear_solver, r.linear_iterations) == ("direct", 0)
    assert r.factor_nonzeros >= s.unknowns
    stages = ("mesh", "assembly", "factorization", "compliance", "contact", "fields")
    assert set(r.times) == set(stages) | {"total"}
    assert all(0 <= r.times[k] <= r.times["total"] for k in stages)
    assert sum(r.times[k] for k in stages) <= r.times["total"] <= wall
    assert all(isinstance(line, str) for line in lines)
    assert lines[0] == (f"axisymmetric: meshing (h = 1.000e-04 m in the zone r <= {disc.contact_zone:.3e} m, "
                        f"domain radius {disc.domain_radius:.3e} m)")
    assert lines[1] == f"{s.elements} elements, {s.unknowns} unknowns, 70 contact candidate nodes"
    assert lines[2:4] == ["surface compliance: 64/70 columns", "surface compliance: 70/70 columns"]
    assert sum(line.startswith("contact iteration ") for line in lines) == r.iterations
    assert lines[-1].startswith(f"done: contact radius {res.contact_radius:.5e} m, indentation "
                                f"{res.indentation:.5e} m, peak pressure {res.peak_pressure:.5e} Pa (")
    assert lines[-1] == lines[-1][:lines[-1].rindex("(")] + f"({r.times['total']:.1f} s)"


def test_the_contact_keeps_clear_of_the_zone_edge():
    """The rule of the candidate zone: a solve raises ContactZoneError exactly when its last
    contact node lies more than Z - (fit_nodes + 1/2) h out (room for the gap fit of the
    radius), checked both ways on zones Z placed 3.0, 3.6 and 4.0 elements beyond the
    contact of the default zone (the mesh, hence the last node, moves with Z: each
    outcome is checked against its own node, read from the result or the message)."""
    import re

    from fem_reference import ContactZoneError

    h = 4e-4
    r0 = solve(_thick_problem(element_size=h))
    r0_last = r0.radius[r0.pressure > 0].max()
    outcomes = set()
    for extra in (3.0, 3.6, 4.0):
        Z = r0_last + extra * h
        try:
            res = solve(_thick_problem(element_size=h, contact_zone=Z))
        except ContactZoneError as err:
            m = re.fullmatch(r"the contact reaches the edge of the candidate zone r = (\S+) m \(contact node at "
                             r"r = (\S+) m, less than (\S+) m inside\): raise fem.contact_zone or lower the load",
                             str(err))
            assert m, str(err)
            zone, last, margin = (float(g) for g in m.groups())
            assert zone == pytest.approx(Z, rel=1e-4) and margin == pytest.approx(3.5 * h, rel=1e-3)
            assert last > Z - 3.5 * h * (1 + 1e-3)
            outcomes.add("raised")
        else:
            assert res.radius[res.pressure > 0].max() <= Z - 3.5 * h
            outcomes.add("solved")
    assert outcomes == {"raised", "solved"}


@pytest.mark.parametrize("n_c", [1, 64, 65, 130])
def test_surface_compliance_in_blocks(n_c):
    """W = C S^-1 C^T, symmetrized, against a dense product, whatever the number of
    candidate nodes relative to the block of 64 columns; one progress line per block
    when there is more than one block."""
    from types import SimpleNamespace

    import scipy.sparse as sp

    from fem_reference.solve import _compliance

    rng = np.random.default_rng(n_c)
    n = 150
    S = rng.standard_normal((n, n))
    S = S @ S.T + n * np.eye(n)
    C = sp.random(n_c, n, density=0.2, random_state=rng, format="csr") + sp.eye(n_c, n, format="csr")
    lines = []
    W = _compliance(SimpleNamespace(C=C), SimpleNamespace(solve=lambda b: np.linalg.solve(S, b)), lines.append)
    Cd = C.toarray()
    ref = Cd @ np.linalg.solve(S, Cd.T)
    np.testing.assert_allclose(W, 0.5 * (ref + ref.T), rtol=1e-12, atol=1e-14 * np.abs(ref).max())
    stops = [min(b + 64, n_c) for b in range(0, n_c, 64)] if n_c > 64 else []
    assert lines == [f"surface compliance: {k}/{n_c} columns" for k in stops]


@pytest.mark.parametrize("corrupt, value", [("diagonal", 0.0), ("diagonal", -1e-9), ("off-diagonal", np.nan)])
def test_a_compliance_that_is_not_positive_is_an_error(monkeypatch, corrupt, value):
    """A zero or negative diagonal entry, or a non-finite entry, of the surface compliance
    (a singular layer model) stops the solve with the reason."""
    import importlib

    from fem_reference.errors import FemReferenceError

    fs = importlib.import_module("fem_reference.solve")  # the module (the package exports the function)

    real = fs._compliance

    def broken(system, solver, progress):
        W = real(system, solver, progress)
        W[(3, 3) if corrupt == "diagonal" else (2, 5)] = value
        return W

    monkeypatch.setattr(fs, "_compliance", broken)
    with pytest.raises(FemReferenceError, match=r"^the surface compliance is not positive: the layer model is "
                       r"singular \(check the boundary conditions\)$"):
        solve(_thick_problem(element_size=4e-4))


def test_the_active_set_iteration_limit_reaches_the_same_contact():
    """fem.max_iterations = 1 stops the primal-dual method after one step; the primal
    method then finishes (and says so in the record) at the same contact (1e-9)."""
    full = solve(_thick_problem(element_size=4e-4))
    one = solve(_thick_problem(element_size=4e-4, max_iterations=1))
    assert full.solver.method == "primal-dual" and full.solver.iterations > 1
    assert one.solver.method == "primal-dual, then primal (iteration limit)"
    assert one.contact_radius == pytest.approx(full.contact_radius, rel=1e-9)
    assert one.indentation == pytest.approx(full.indentation, rel=1e-9)


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


def test_rolling_problems_go_to_the_rolling_solver_with_progress():
    """A line indenter is solved by steady rolling in plane strain, which reports its
    stages to the caller's progress (elastic, V = 0: symmetric, R_r = 0)."""
    lines = []
    res = solve(ContactProblem(Layer(1e-3), ElasticMaterial(3e6), Indenter("line", 0.02),
                               Loading(load=500.0, speed=0.0), FemSettings(element_size=1e-4)), lines.append)
    assert lines[0].startswith("plane_strain: meshing (h = 1.000e-04 m")
    assert lines[-1].startswith("done: R_r ")
    assert res.load == pytest.approx(500.0, rel=1e-12)
    assert abs(res.leading_edge + res.trailing_edge) <= 1e-3 * res.contact_length
