"""The stationary driver (:func:`fem_reference.stationary.solve.solve_stationary`, through
``fem_reference.solve``): what it reports (mesh counts, solver record, progress lines)
against the mesh it returns; the solved pressure field against the equilibrium of the
layer; load and displacement control; the rule of the candidate zone; the surface
compliance in blocks and its positivity; the iteration limit; MINRES against the direct
solver; and the errors of a contact wider than the zone or an indentation that reaches
no node.

The pressure field is checked by an identity the solver does not use: on the bonded
base ``u = 0``, so ``du_r/dr = u_r / r = 0`` and incompressibility gives ``du_z/dz =
0``; there ``sigma_zz = -p`` and the vertical equilibrium of the layer gives ``int_base
p dA = P``, the load.
"""

import math

import numpy as np
import pytest
from skfem import ElementTriP1, FacetBasis, LinearForm, asm

from fem_reference import (ContactProblem, ContactZoneError, ElasticMaterial, FemSettings,
                           Indenter, Layer, Loading, solve)


def _thick(**fem):
    return ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", 0.02),
                          Loading(load=100.0), FemSettings(**fem))


def test_a_contact_wider_than_the_candidate_zone_is_an_error():
    # contact radius ~4.5 mm, candidate zone 3 mm
    with pytest.raises(ContactZoneError, match="raise fem.contact_zone"):
        solve(_thick(element_size=2e-4, contact_zone=3e-3))


def test_indentation_control_inverts_load_control():
    by_load = solve(_thick(element_size=2e-4))
    by_disp = solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6),
                                   Indenter("paraboloid", 0.02),
                                   Loading(indentation=by_load.indentation),
                                   FemSettings(element_size=2e-4, contact_zone=7e-3)))
    assert by_disp.load == pytest.approx(100.0, rel=1e-8)
    assert by_disp.contact_radius == pytest.approx(by_load.contact_radius, rel=1e-8)


def test_indentation_that_reaches_no_node_is_an_error_naming_the_gap():
    """Displacement control below the first multiplier node: the rigid indenter touches
    no node, the contact problem's unique solution is lam = 0 (load 0), which is no
    result: it raises, naming the indentation and the gap to close.

    The gap named is the smallest weighted gap q_j / m_j of a node; at the axis node of
    the axisymmetric zone (hat function 1 - r / r1 on [0, r1], weight r dr, paraboloid
    s = r^2 / (2 R)) it is (r1^4 / (40 R)) / (r1^2 / 6) = 3 r1^2 / (20 R) exactly (the
    facet quadrature, order 6, is exact for this degree-4 integrand). Just above it the
    solve carries a load, just below it raises: the named value is the threshold."""
    import re

    from fem_reference import InputError

    R = 0.02

    def by_indentation(d):
        return solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", R),
                                    Loading(indentation=d),
                                    FemSettings(element_size=4e-4, contact_zone=3e-3)))

    with pytest.raises(InputError, match=r"loading.indentation = 1e-09 m reaches no node") as info:
        by_indentation(1e-9)
    message = str(info.value)
    assert "raise loading.indentation" in message and "fem.element_size" in message
    gap = float(re.search(r"would need to close ([0-9.e+-]+) m", message).group(1))
    with pytest.raises(InputError, match="reaches no node"):
        by_indentation(0.99 * gap)
    touching = by_indentation(1.02 * gap)
    assert touching.load > 0
    r1 = touching.radius[1]  # the first node off the axis (the radii are sorted)
    assert gap == pytest.approx(3.0 * r1 ** 2 / (20.0 * R), rel=1e-4)  # 5 digits printed


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
    per block of 64 compliance columns, numbers as in the result."""
    import time

    from fem_reference.stationary.discretization import resolve

    lines = []
    problem = _thick(element_size=1e-4)
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
    r0 = solve(_thick(element_size=h))
    r0_last = r0.radius[r0.pressure > 0].max()
    outcomes = set()
    for extra in (3.0, 3.6, 4.0):
        Z = r0_last + extra * h
        try:
            res = solve(_thick(element_size=h, contact_zone=Z))
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

    from fem_reference.stationary.solve import _compliance

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

    fs = importlib.import_module("fem_reference.stationary.solve")

    real = fs._compliance

    def broken(system, solver, progress):
        W = real(system, solver, progress)
        W[(3, 3) if corrupt == "diagonal" else (2, 5)] = value
        return W

    monkeypatch.setattr(fs, "_compliance", broken)
    with pytest.raises(FemReferenceError, match=r"^the surface compliance is not positive: the layer model is "
                       r"singular \(check the boundary conditions\)$"):
        solve(_thick(element_size=4e-4))


def test_the_active_set_iteration_limit_reaches_the_same_contact():
    """fem.max_iterations = 1 stops the primal-dual method after one step; the primal
    method then finishes (and says so in the record) at the same contact (1e-9)."""
    full = solve(_thick(element_size=4e-4))
    one = solve(_thick(element_size=4e-4, max_iterations=1))
    assert full.solver.method == "primal-dual" and full.solver.iterations > 1
    assert one.solver.method == "primal-dual, then primal (iteration limit)"
    assert one.contact_radius == pytest.approx(full.contact_radius, rel=1e-9)
    assert one.indentation == pytest.approx(full.indentation, rel=1e-9)


def test_minres_solve_matches_the_direct_solve():
    """fem.solver = "minres" (with pyamg) on the thick-layer case at h = 0.8 mm (the
    coarsest element size whose default candidate zone holds the contact: 743 unknowns,
    10 candidate nodes): the same contact as the direct solver within 1e-6 relative.
    Measured at rtol 1e-8: 1.5e-10 in radius, 5.9e-9 in peak pressure, 2.0e-10 in
    indentation (170 times inside the gate); a solve 1000 times looser (rtol 1e-5) is
    1.3e-4 off in peak pressure, so the gate tells a MINRES solve at its tolerance from a
    sloppy one. The setting reaches the solver: at rtol 1e-6 (the loosest accepted) MINRES
    stops after 4411 iterations against 5932 (measured)."""
    def run(solver, rtol=1e-8):
        return solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("sphere", 0.02),
                                    Loading(load=100.0),
                                    FemSettings(element_size=8e-4, solver=solver, rtol=rtol)))

    direct, iterative = run("direct"), run("minres")
    assert iterative.solver.linear_solver != direct.solver.linear_solver
    assert iterative.contact_radius == pytest.approx(direct.contact_radius, rel=1e-6)
    assert iterative.peak_pressure == pytest.approx(direct.peak_pressure, rel=1e-6)
    assert iterative.indentation == pytest.approx(direct.indentation, rel=1e-6)
    assert iterative.solver.linear_residual <= 1e-8
    loose = run("minres", rtol=1e-6)
    assert loose.solver.linear_iterations < iterative.solver.linear_iterations
