"""3D steady rolling of a rigid sphere (fem_reference, fem.model = "3d" with a speed).

Fast tests: the algebra of the five traceless components, the bad inputs, and coarse
solves checked against independent values (the stationary elastic layer, the relaxed
and glassy limits, the load and moment sums). Slow tests: the paper's section 11 case
against its energy balance and the BEM's R_r.
"""

from __future__ import annotations

import numpy as np
import pytest

from fem_reference import (ContactProblem, ElasticMaterial, FemSettings, Indenter, InputError,
                           Layer, Loading, ThreeParameterMaterial, solve)
from fem_reference.case import problem_from_dict
from fem_reference.rolling.three_d import forms as rf
from fem_reference.rolling.three_d.result import SphereRollingResult

H, R, P = 5e-3, 0.02, 150.0
MAT = ThreeParameterMaterial(G0=3e6, tau=0.25, f=1.0)
#: a coarse mesh on a short box for the fast tests (6-8k unknowns, about 100 candidate
#: nodes; the lengths fit V = 0.01 m/s, creep length V tau = 2.5 mm)
COARSE = dict(model="3d", element_size=1.5e-3, contact_zone=9.5e-3, grading=0.5, fit_nodes=2,
              upstream=0.03, downstream=0.03, domain_radius=0.022)
#: the stationary elastic contact (G = 3 MPa, P = 150 N) by the axisymmetric model at its
#: default mesh (contact radius 5.0337 mm, indentation 0.72408 mm)
AXI_RADIUS, AXI_INDENTATION = 5.033719e-3, 0.7240766e-3


def _problem(material=MAT, speed=0.05, density=1000.0, load=P, **fem):
    settings = dict(COARSE)
    settings.update(fem)
    return ContactProblem(Layer(H, density), material, Indenter("sphere", R),
                          Loading(load=load, speed=speed), FemSettings(**settings))


class _Field:
    def __init__(self, grad):
        self.grad = grad


def test_components_rebuild_the_tensor_products():
    """sum_k w_k P_k(v) = eps_v : eps(v), E_k(u) are dev eps(u)'s components, and the
    five-component inner product is the Frobenius product of the full tensors."""
    rng = np.random.default_rng(1)
    gu, gv = rng.standard_normal((3, 3)), rng.standard_normal((3, 3))
    u, v = _Field(gu), _Field(gv)
    w = rng.standard_normal(5)
    ev = np.array([[w[0], w[2], w[3]], [w[2], w[1], w[4]], [w[3], w[4], -w[0] - w[1]]])
    eps_v = 0.5 * (gv + gv.T)
    assert sum(w[k] * rf.conjugate(v, k) for k in range(5)) == pytest.approx(np.sum(ev * eps_v),
                                                                              rel=1e-13)
    eps_u = 0.5 * (gu + gu.T)
    dev = eps_u - np.trace(eps_u) / 3.0 * np.eye(3)
    comps = [rf.deviator(u, k) for k in range(5)]
    assert comps == pytest.approx([dev[0, 0], dev[1, 1], dev[0, 1], dev[0, 2], dev[1, 2]], rel=1e-13)
    assert rf.traceless_inner(comps, w) == pytest.approx(np.sum(dev * ev), rel=1e-13)


@pytest.mark.parametrize("fem, message", [
    (dict(upstream=5e-3), "fem.upstream = 0.005 m is too short: the material must enter undeformed"),
    (dict(downstream=3e-2), "fem.downstream = 0.03 m is too short for the material to relax"),
    (dict(domain_radius=1e-2), "fem.domain_radius = 0.01 m \\(the lateral extent y"),
])
def test_short_domain_is_an_error_naming_the_setting(fem, message):
    settings = dict(COARSE, upstream=None, downstream=None, domain_radius=None)
    settings.update(fem)
    with pytest.raises(InputError, match=message):
        solve(_problem(**settings))


def test_speed_at_the_shear_wave_speed_is_an_error():
    with pytest.raises(InputError, match="at or above the layer's shear-wave speed c_s"):
        _problem(speed=60.0)  # c_s = sqrt(3e6 / 1000) = 54.8 m/s


def test_models_that_cannot_roll_a_sphere_say_so():
    with pytest.raises(InputError, match="speed must be 0 m/s: .*\\(a sphere rolls in \\[fem\\] "
                                         "model = \"3d\""):
        _problem(model="axisymmetric", element_size=None, upstream=None, downstream=None)
    with pytest.raises(InputError, match="the 3d rolling model .* takes a sphere or a cylinder$"):
        ContactProblem(Layer(H), MAT, Indenter("paraboloid", R), Loading(load=P, speed=0.05),
                       FemSettings(model="3d"))
    with pytest.raises(InputError, match="3d rolling system is not symmetric"):
        _problem(solver="minres")


def test_master_curve_table_is_refused_for_the_3d_rolling_model():
    data = {"layer": {"thickness": H}, "material": {"model": "table", "file": __file__},
            "indenter": {"shape": "sphere", "radius": R},
            "loading": {"load": P, "speed": 0.05}, "fem": {"model": "3d"}}
    with pytest.raises(InputError, match="has no time-domain form"):
        problem_from_dict(data)


#: the progress lines of the coarse fixture's solve
PROGRESS = []


@pytest.fixture(scope="module")
def coarse():
    """The section 11 layer at V = 0.01 m/s on the coarse mesh (its progress lines in
    ``PROGRESS``)."""
    PROGRESS.clear()
    return solve(_problem(speed=0.01), PROGRESS.append)


def test_result_sums_and_fields(coarse):
    r = coarse
    assert isinstance(r, SphereRollingResult)
    assert r.load == pytest.approx(P, rel=1e-10)  # both halves carry the load
    # R_r = P x_c / R and the moment from the returned nodal field (F_j = m_j lam_j)
    assert r.rolling_resistance == pytest.approx(P * r.pressure_centroid / R, rel=1e-12)
    system = r.fields["system"]
    assert 2.0 * system.mx @ r.zone_pressure / R == pytest.approx(r.rolling_resistance, rel=1e-12)
    assert np.all(r.zone_xy[:, 1] >= 0) and np.all(r.zone_pressure >= 0)
    assert np.all(np.diff(r.pressure_x) > 0)
    assert np.all(r.pressure_x ** 2 <= r.mesh.contact_zone ** 2 * (1 + 1e-12))
    # the odd strain components vanish on the symmetry plane, u_y too
    wb, ub = system.wbasis, system.ubasis
    on_plane = wb.get_dofs("sym_y").all()
    for comps in r.fields["w"]:
        assert np.all(comps[2][on_plane] == 0) and np.all(comps[4][on_plane] == 0)
        assert np.max(np.abs(comps[0][on_plane])) > 0
    assert np.all(r.fields["u"][ub.get_dofs("sym_y").all("u^2")] == 0)
    # the viscoelastic contact leads: shifted forward, R_r > 0, pressure power > 0
    assert r.rolling_resistance > 0 and r.contact_centre > 0 and r.pressure_power > 0
    assert r.trailing_edge < 0 < r.leading_edge
    # the energy balance holds to the coarse mesh's error (measured +7.4% here; -0.02% on
    # the 154k-unknown mesh of the section 11 case, BENCHMARKS.md)
    assert abs(r.energy_balance) < 0.15
    # the caller's progress hears every stage, the last with the returned R_r
    assert PROGRESS[0].startswith("3d rolling: meshing the half box (h = 1.500e-03 m")
    assert any(line.startswith("contact iteration") for line in PROGRESS)
    assert PROGRESS[-1].startswith(f"done: R_r {r.rolling_resistance:.6e} N (D/V ")


def test_elastic_layer_rolls_without_resistance_like_the_stationary_model():
    """Elastic layer, no inertia: rolling is the stationary contact. On the mirror-symmetric
    mesh R_r vanishes (measured 1.4e-8 N: the partial-solve round-off), the edges are
    symmetric, and indentation and contact radius match the axisymmetric model (measured
    +0.36% and -0.01% on this coarse mesh)."""
    e = solve(_problem(material=ElasticMaterial(3e6), density=0.0, speed=0.01))
    assert e.dissipation == 0.0
    a_line = 0.5 * e.contact_length
    assert abs(e.rolling_resistance) < 1e-7 * P * a_line / R
    assert abs(e.contact_centre) < 1e-6 * a_line
    assert e.indentation == pytest.approx(AXI_INDENTATION, rel=0.01)
    assert a_line == pytest.approx(AXI_RADIUS, rel=0.01)


def test_pardiso_partial_solve_equals_superlu(coarse, monkeypatch):
    """The Pardiso path (partial solves of W without matching, then defect correction on
    refined full solves) against SuperLU's plain solves on the same mesh: measured 1e-7
    at h = 1 mm on the section 11 case (6.6e-5 before the defect correction)."""
    pytest.importorskip("pypardiso")
    from fem_reference.rolling import solve as rolling_solve

    assert coarse.solver.linear_solver == "pardiso"
    monkeypatch.setattr(rolling_solve, "LINEAR_SOLVER", "superlu")
    s = solve(_problem(speed=0.01))
    assert s.solver.linear_solver == "direct"
    assert s.rolling_resistance == pytest.approx(coarse.rolling_resistance, rel=1e-6)
    assert s.indentation == pytest.approx(coarse.indentation, rel=1e-8)
    assert s.dissipation == pytest.approx(coarse.dissipation, rel=1e-6)
    assert np.max(np.abs(s.zone_pressure - coarse.zone_pressure)) < 1e-6 * coarse.peak_pressure


def test_vtu_and_plot_of_the_rolling_sphere(coarse, tmp_path):
    """The VTU of the half layer, read back with meshio, holds the returned fields
    exactly, and they mean what they say: u_y = 0 on the symmetry plane; on the top line
    y = 0 inside the fitted edges the vertical displacement follows the sphere, u_z =
    s(x) - d (measured within 1.26% of d on this coarse mesh, whose mortar contact holds
    the gap weakly: 3% allowed); the hydrostatic pressure at the top vertex under the
    peak is compressive, of the order of the contact pressure (measured 0.78 of it).
    The figure is a PNG of the size asked (7 x 10 in at 120 dpi) with something drawn."""
    import matplotlib.image
    import meshio

    from fem_reference.output import plot_result, write_vtu

    r = coarse
    vtu, png = tmp_path / "sphere.vtu", tmp_path / "sphere.png"
    write_vtu(r, vtu)
    plot_result(r, png)
    m = meshio.read(vtu)
    mesh, ub, pb, wb = (r.fields[k] for k in ("mesh", "ubasis", "pbasis", "wbasis"))
    np.testing.assert_array_equal(m.points, mesh.p.T)
    np.testing.assert_array_equal(m.cells_dict["tetra"], mesh.t.T)
    u = m.point_data["displacement"]
    for k in range(3):
        np.testing.assert_array_equal(u[:, k], r.fields["u"][ub.nodal_dofs[k]])
    np.testing.assert_array_equal(m.point_data["pressure"], r.fields["p"][pb.nodal_dofs[0]])
    (comps,) = r.fields["w"]  # one Maxwell branch, five components
    np.testing.assert_array_equal(m.point_data["viscous_strain_1"],
                                  np.column_stack([c[wb.nodal_dofs[0]] for c in comps]))
    pts = m.points
    assert pts[:, 1].min() == 0.0 and np.all(u[pts[:, 1] == 0.0, 1] == 0.0)
    line = (pts[:, 2] == H) & (pts[:, 1] == 0.0)
    inside = line & (pts[:, 0] > r.trailing_edge) & (pts[:, 0] < r.leading_edge)
    x = pts[inside, 0]
    assert inside.sum() >= 4
    s = x * x / (R + np.sqrt(R * R - x * x))
    assert np.max(np.abs(u[inside, 2] - (s - r.indentation))) < 3e-2 * r.indentation
    below_peak = np.flatnonzero(line)[np.argmin(np.abs(pts[line, 0] - r.pressure_x[np.argmax(r.pressure)]))]
    assert 0.5 * r.peak_pressure < m.point_data["pressure"][below_peak] < 1.5 * r.peak_pressure
    image = matplotlib.image.imread(png)
    assert image.shape[:2] == (1200, 840) and image[..., :3].std() > 0.05


def test_cli_solves_a_rolling_sphere_with_plot_and_vtu(coarse, tmp_path, capsys):
    """fem-reference solve with fem.model = "3d" and a speed (the 3D FEM through the
    command line): the same result as the Python call (the coarse fixture, within 1e-9),
    the text lines name the load and R_r in N, the figure and the half layer's VTU are
    written."""
    import json

    import meshio

    from fem_reference.cli import main

    case = tmp_path / "sphere.toml"
    case.write_text(f'[layer]\nthickness = {H}\ndensity = 1000.0\n[material]\nmodel = "three_parameter"\n'
                    f'G0 = 3.0e6\ntau = 0.25\nf = 1.0\n[indenter]\nshape = "sphere"\nradius = {R}\n'
                    f'[loading]\nspeed = 0.01\nload = {P}\n')
    sets = [f"fem.{k}={v!r}" if not isinstance(v, str) else f'fem.{k}="{v}"' for k, v in COARSE.items()]
    png, vtu = tmp_path / "s.png", tmp_path / "s.vtu"
    args = ["solve", str(case), "--quiet", "--plot", str(png), "--vtu", str(vtu)]
    for item in sets:
        args += ["--set", item]
    assert main(args + ["--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["mesh"]["model"] == "3d" and out["mesh"]["lateral"] == COARSE["domain_radius"]
    assert out["load"] == pytest.approx(P, rel=1e-12)
    assert out["rolling_resistance"] == pytest.approx(coarse.rolling_resistance, rel=1e-9)
    assert out["indentation"] == pytest.approx(coarse.indentation, rel=1e-9)
    assert png.stat().st_size > 0
    assert len(meshio.read(vtu).points) == out["mesh"]["vertices"] == coarse.mesh.vertices


@pytest.mark.slow
def test_section_11_energy_balance_and_bem():
    """The paper's section 11 case on the finest mesh of benchmarks/fem_rolling_3d.py
    (h = 0.5 mm, 172k unknowns, about 3 minutes): the energy balance, and the BEM's
    R_r = sum F x / R = 3.0257 N (paper's Table 1, reproduced by bem solve) and its
    horizontal force sum F ds/dx = 3.0761 N, which D/V equals in the continuum. Measured:
    balance +9e-5, R_r -0.10%, D/V -0.09%, indentation -0.01% (BEM 0.58153 mm); the
    coarser levels of rolling-sphere-3d are 0.26% and 0.43% below the BEM's R_r."""
    r = solve(ContactProblem(Layer(H, 1000.0), MAT, Indenter("sphere", R),
                             Loading(load=P, speed=0.05),
                             FemSettings(model="3d", element_size=5e-4, grading=0.1,
                                         far_size=2.5e-3)))
    assert abs(r.energy_balance) < 3e-3
    assert r.rolling_resistance == pytest.approx(3.0257, rel=3e-3)
    assert r.rolling_resistance_energy == pytest.approx(3.0761, rel=3e-3)
    assert r.indentation == pytest.approx(0.58153e-3, rel=2e-3)


def test_without_pardiso_a_large_3d_rolling_system_is_refused_by_name(monkeypatch):
    """Without Pardiso, SuperLU's 3D fill (3.2 GB at 51k unknowns) would exhaust memory on
    the case's finest level: a system above SUPERLU_LIMIT unknowns is refused before the
    factorization, with what to install or change."""
    from fem_reference.errors import LinearSolverError
    from fem_reference.rolling import solve as rolling_solve

    monkeypatch.setattr(rolling_solve, "LINEAR_SOLVER", "superlu")
    monkeypatch.setattr(rolling_solve, "SUPERLU_LIMIT", 1000)
    with pytest.raises(LinearSolverError, match=r"too many for SuperLU in 3D.*pip install pypardiso.*element_size"):
        solve(_problem(speed=0.01))
