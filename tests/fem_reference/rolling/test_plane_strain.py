"""fem_reference's steady rolling in plane strain: materials, inputs, the slow-speed limit
and the command line (coarse meshes; the converged checks are in
test_plane_strain_convergence.py, marked slow)."""

import json

import numpy as np
import pytest

import fem_reference as fr
from fem_reference.cli import main

G0, TAU, F = 3.0e6, 0.25, 1.0
R, P, H = 0.02, 500.0, 1.0e-3
COARSE = fr.FemSettings(element_size=1.0e-4)  # about b / 6: the coarsest mesh of the benchmark


def _problem(material, speed, fem=COARSE, density=0.0, thickness=H):
    return fr.ContactProblem(fr.Layer(thickness, density), material, fr.Indenter("line", R),
                             fr.Loading(load=P, speed=speed), fem)


def test_three_parameter_solid_is_the_one_branch_prony_series():
    """Eq. 71 written out against G_inf + G_1 i w tau_1 / (1 + i w tau_1) with G_inf = G0,
    G_1 = G0 f, tau_1 = tau / (1 + f)."""
    tp = fr.ThreeParameterMaterial(G0, TAU, F)
    prony = tp.prony()
    assert prony == fr.PronyMaterial(G0, (G0 * F,), (TAU / (1 + F),))
    w = np.logspace(-4, 4, 17) / TAU
    c, x = 1 + F, w * TAU
    eq71 = G0 * c * ((c + x ** 2) / (c ** 2 + x ** 2) + 1j * F * x / (c ** 2 + x ** 2))
    np.testing.assert_allclose(prony.modulus(w), eq71, rtol=1e-13)
    np.testing.assert_allclose(tp.modulus(w), eq71, rtol=1e-13)
    # the loss peak at w tau = 1 + f, the relaxed and glassy limits, the creep time tau
    loss = prony.modulus(np.linspace(0.5, 4.0, 3501) / TAU).imag
    assert abs(np.linspace(0.5, 4.0, 3501)[np.argmax(loss)] - (1 + F)) < 1e-3
    assert prony.relaxed_modulus == G0 and prony.glassy_modulus == G0 * (1 + F)
    assert prony.retardation_time == pytest.approx(TAU, rel=1e-15)
    assert fr.ThreeParameterMaterial(G0, TAU, 0.0).prony() == fr.ElasticMaterial(G0)


@pytest.mark.parametrize("make, message", [
    (lambda: _problem(fr.ThreeParameterMaterial(G0, TAU, F), 60.0, density=1000.0),
     "[loading] speed = 60.0 m/s is at or above the layer's shear-wave speed c_s = sqrt(G_inf / rho) = "
     "sqrt(3e+06 Pa / 1000 kg/m^3) = 54.7723 m/s"),
    (lambda: _problem(fr.ElasticMaterial(G0), 54.7723, density=1000.0), "lower [loading] speed"),
    (lambda: fr.PronyMaterial(G0, (1e6, 2e6), (0.1,)), "material.G and material.tau must have the same length"),
    (lambda: fr.PronyMaterial(G0, (1e6,), (-0.1,)), "material.tau[0] must be > 0 s, got -0.1"),
    (lambda: _problem(fr.ElasticMaterial(G0), 0.0, fr.FemSettings(model="axisymmetric")),
     "fem.model = 'axisymmetric' does not fit indenter.shape = 'line'"),
    (lambda: fr.ContactProblem(fr.Layer(H), fr.ElasticMaterial(G0), fr.Indenter("sphere", R),
                               fr.Loading(load=P), fr.FemSettings(model="plane_strain")),
     "fem.model = 'plane_strain' does not fit indenter.shape = 'sphere'"),
    (lambda: _problem(fr.ElasticMaterial(G0), 0.0, fr.FemSettings(domain_radius=0.01)),
     "fem.domain_radius is not used by the plane_strain model; remove it (the plane_strain model's "
     "extent is fem.upstream and fem.downstream)"),
    (lambda: fr.ContactProblem(fr.Layer(H), fr.ElasticMaterial(G0), fr.Indenter("sphere", R),
                               fr.Loading(load=P), fr.FemSettings(upstream=0.01)),
     "fem.upstream is not used by the axisymmetric model"),
])
def test_bad_rolling_input_is_refused_by_name(make, message):
    with pytest.raises(fr.InputError) as info:
        make()
    assert message in str(info.value)


@pytest.mark.parametrize("key, value, message", [
    ("upstream", 2.0e-3, "fem.upstream = 0.002 m is too short: the material must enter undeformed and relaxed"),
    ("downstream", 0.05, "fem.downstream = 0.05 m is too short for the material to relax before it leaves"),
])
def test_too_short_a_layer_names_the_setting(key, value, message):
    from fem_reference.rolling.plane_strain.discretization import resolve_plane

    problem = _problem(fr.ThreeParameterMaterial(G0, TAU, F), 0.1, fr.FemSettings(**{key: value}))
    with pytest.raises(fr.InputError) as info:
        resolve_plane(problem)
    text = str(info.value)
    assert message in text and f"raise fem.{key}" in text
    if key == "downstream":  # V t_r = 0.1 m/s x 0.25 s
        assert "V t_r = 0.025 m" in text


def test_slow_rolling_is_the_relaxed_elastic_contact():
    """V -> 0: the viscous strains follow the strain (the branch equation becomes the L2
    projection), the stress is 2 G_inf eps: the same contact as the elastic G_inf layer on
    the same mesh up to the projection of the discontinuous strain onto the continuous P1
    viscous strains, an O(h) difference: measured 1.9e-3 b in the leading edge and 1e-4 in
    the indentation at h = b/6."""
    elastic = fr.solve(_problem(fr.ElasticMaterial(G0), 0.0))
    slow = fr.solve(_problem(fr.ThreeParameterMaterial(G0, TAU, F), 1e-9))
    b = elastic.contact_length / 2
    assert abs(slow.leading_edge - elastic.leading_edge) < 5e-3 * b
    assert abs(slow.trailing_edge - elastic.trailing_edge) < 5e-3 * b
    assert slow.indentation == pytest.approx(elastic.indentation, rel=5e-4)
    assert abs(slow.rolling_resistance) < 1e-4 * P * b / R
    assert elastic.load == pytest.approx(P, rel=1e-12)


def test_cli_rolls_a_line_case(tmp_path, capsys):
    """fem-reference solve on a line case: the JSON result, the rolling resistance and the
    pressure centroid (R_r = P x_c / R), the leading edge ahead, the energy balance of the
    coarse mesh (measured +0.8% at h = b/6; -0.2% at b/12, slow test). The VTU (the (x, z)
    section written as (x, y, 0)) agrees with the JSON: its vertices are the mesh's, and
    on the top surface inside the fitted edges u_z = s(x) - d with the JSON's indentation
    (measured within 1.27% of d at 13 vertices: the mortar contact holds the gap weakly;
    3% allowed); the figure is drawn."""
    import meshio

    case = tmp_path / "line.toml"
    case.write_text('[layer]\nthickness = 1.0e-3\ndensity = 1000.0\n[material]\nmodel = "three_parameter"\n'
                    'G0 = 3.0e6\ntau = 0.25\nf = 1.0\n[indenter]\nshape = "line"\nradius = 0.02\n'
                    '[loading]\nspeed = 0.01\nload = 500.0\n[fem]\nelement_size = 1.0e-4\n')
    png, vtu = tmp_path / "line.png", tmp_path / "line.vtu"
    assert main(["solve", str(case), "--json", "--quiet", "--plot", str(png), "--vtu", str(vtu)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert png.stat().st_size > 0
    m = meshio.read(vtu)
    assert len(m.points) == out["mesh"]["vertices"] and np.all(m.points[:, 2] == 0.0)
    assert set(m.point_data) == {"displacement", "pressure", "viscous_strain_1"}
    top = m.points[:, 1] == H
    inside = top & (m.points[:, 0] > out["trailing_edge"]) & (m.points[:, 0] < out["leading_edge"])
    x = m.points[inside, 0]
    s = x * x / (R + np.sqrt(R * R - x * x))
    err = np.max(np.abs(m.point_data["displacement"][inside, 1] - (s - out["indentation"])))
    assert inside.sum() >= 10 and err < 3e-2 * out["indentation"]
    assert out["mesh"]["model"] == "plane_strain" and out["load"] == pytest.approx(P, rel=1e-12)
    assert out["rolling_resistance"] == pytest.approx(P * out["pressure_centroid_x"] / R, rel=1e-12)
    assert out["rolling_resistance"] > 0 and out["leading_edge"] > -out["trailing_edge"] > 0
    assert abs(out["energy_balance"]) < 0.02
    assert out["rolling_resistance"] * 0.01 == pytest.approx(out["pressure_power"], rel=2e-3)
    assert out["rolling_resistance_energy"] == pytest.approx(out["dissipation"] / 0.01, rel=1e-12)
    # a table has no time-domain form; a speed above c_s is named with its setting
    assert main(["solve", str(case), "--quiet", "--set", "loading.speed=60.0"]) == 2
    assert "shear-wave speed c_s = sqrt(G_inf / rho)" in capsys.readouterr().err
    assert main(["solve", str(case), "--quiet", "--set", "fem.upstream=1e-3"]) == 2
    assert "raise fem.upstream" in capsys.readouterr().err


def test_contact_wider_than_the_candidate_zone_is_an_error_naming_it():
    """A candidate zone narrower than the contact (|x| <= 0.8 mm against a contact about
    2.3 mm long) stops the rolling solve with the zone, the node that reached it and the
    setting to raise, instead of a contact cut off at the zone's edge; the node named lies
    within the fit's room ((fit_nodes + 1/2) h = 0.35 mm) of the zone's edge."""
    import re

    with pytest.raises(fr.ContactZoneError, match=r"the contact reaches the edge of the candidate zone "
                       r"\(\|x\| <= 8.0000e-04 m\): a contact node at (\S+) m, less than 3.500e-04 m "
                       r"inside; raise fem.contact_zone or lower the load") as info:
        fr.solve(_problem(fr.ThreeParameterMaterial(G0, TAU, F), 0.01,
                          fr.FemSettings(element_size=1.0e-4, contact_zone=0.8e-3)))
    node = float(re.search(r"a contact node at (\S+) m", str(info.value)).group(1))
    assert 0.8e-3 - 3.5e-4 < node <= 0.8e-3
