"""fem_reference's inputs: validation messages that name the field, the value and the
rule; case files and their overrides; the indenter profiles; a missing pyamg found when
the settings are made."""

import pytest

from fem_reference import ElasticMaterial, FemSettings, Indenter, InputError, Layer, Loading
import casefile
from fem_reference.case import load_case, problem_from_dict

CASE = {
    "layer": {"thickness": 5e-3, "density": 0.0},
    "material": {"model": "elastic", "shear_modulus": 3e6},
    "indenter": {"shape": "sphere", "radius": 0.02},
    "loading": {"speed": 0.0, "load": 100.0},
    "grid": {"spacing": 0.25e-3},
}


def _case(**changes):
    data = {k: dict(v) for k, v in CASE.items()}
    for key, value in changes.items():
        if "__" not in key:  # a whole section
            data[key] = value
            continue
        section, name = key.split("__")
        data[section][name] = value
    return data


@pytest.mark.parametrize("make, message", [
    (lambda: Layer(-0.005), "layer.thickness must be > 0 m, got -0.005"),
    (lambda: ElasticMaterial(0.0), "material.shear_modulus must be > 0 Pa, got 0.0"),
    (lambda: Indenter("cone", 0.02), "indenter.shape must be one of"),
    (lambda: Indenter("sphere", -1.0), "indenter.radius must be > 0 m, got -1.0"),
    (lambda: Loading(), "exactly one of load"),
    (lambda: Loading(load=1.0, indentation=1e-4), "exactly one of load"),
    (lambda: Loading(load=-3.0), "loading.load must be > 0 N, got -3.0"),
    (lambda: FemSettings(element_size=0.0), "fem.element_size must be > 0 m, got 0.0"),
    (lambda: FemSettings(model="2d"), "fem.model must be one of"),
    (lambda: FemSettings(refine=-1), "fem.refine must be an integer >= 0, got -1"),
])
def test_bad_values_name_field_value_and_rule(make, message):
    with pytest.raises(InputError, match=message.replace("(", r"\(")):
        make()


def test_case_file_reads_the_shared_format(tmp_path):
    problem = problem_from_dict(_case())
    assert problem.layer.thickness == 5e-3
    assert problem.material.shear_modulus == 3e6
    assert problem.indenter == Indenter("sphere", 0.02)
    assert problem.loading == Loading(load=100.0)
    assert problem.fem == FemSettings(model="axisymmetric")  # the unset model filled in from the indenter


@pytest.mark.parametrize("change, message", [
    ({"material": {"model": "three_parameter", "G0": 3e6, "tau": 0.25, "f": 1.0}},
     'cannot solve \\[material\\] model = "three_parameter" with \\[indenter\\] shape = "sphere": '
     'the axisymmetric and 3d models are stationary and elastic'),
    ({"material": {"model": "table", "file": __file__}},
     'cannot solve \\[material\\] model = "table": a measured master curve G\\*\\(omega\\) has no '
     'time-domain form'),
    ({"loading__speed": 0.05}, "\\[loading\\] speed must be 0 m/s"),
    ({"indenter__shape": "cylinder", "indenter__length": 0.01},
     'cannot solve \\[indenter\\] shape = "cylinder" with fem.model = \'3d\' and loading.speed = 0.0: '
     'a roller is solved by the 3d rolling model only'),
    ({"indenter": {"shape": "heightmap", "file": __file__}},
     'cannot solve \\[indenter\\] shape = "heightmap"; it reads sphere, paraboloid, cylinder, line'),
])
def test_case_rejects_what_the_fem_cannot_do(change, message):
    with pytest.raises(InputError, match=message):
        problem_from_dict(_case(**change))


def test_unknown_fem_key_is_an_error():
    data = _case()
    data["fem"] = {"elementsize": 1e-4}
    with pytest.raises(InputError, match="\\[fem\\]: unknown key 'elementsize'; .*did you mean 'element_size'"):
        problem_from_dict(data)


def test_overrides_are_parsed_as_toml(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text('[layer]\nthickness = 5e-3\n[material]\nmodel = "elastic"\n'
                    'shear_modulus = 3e6\n[indenter]\nshape = "sphere"\nradius = 0.02\n'
                    '[loading]\nload = 100.0\n')
    problem = load_case(path, ['fem.model="3d"', "fem.element_size=2e-4", "loading.load=50"])
    assert problem.fem.model == "3d" and problem.fem.element_size == 2e-4
    assert problem.loading.load == 50
    with pytest.raises(InputError, match="section.key=value"):
        load_case(path, ["thickness=1"])
    # one parser for every tool: a bare word is a string where the key takes a string ...
    assert casefile.apply_overrides({}, ["fem.model=3d"]) == {"fem": {"model": "3d"}}
    # ... and an error, naming the key, where it takes a number
    with pytest.raises(InputError, match="\\[loading\\] load takes number"):
        load_case(path, ["loading.load=abc"])


def test_sphere_profile_is_exact_and_paraboloid_its_limit():
    import numpy as np

    r = np.array([0.0, 1e-3, 5e-3])
    R = 0.02
    assert np.allclose(Indenter("sphere", R).profile(r), R - np.sqrt(R * R - r * r),
                       rtol=1e-12, atol=1e-18)
    assert np.allclose(Indenter("paraboloid", R).profile(r), r * r / (2 * R))


def test_minres_without_pyamg_fails_at_the_input(monkeypatch):
    """The missing optional dependency is found when the settings are made, before any mesh."""
    import sys

    from fem_reference import MissingDependencyError

    monkeypatch.setitem(sys.modules, "pyamg", None)  # import pyamg raises ImportError
    with pytest.raises(MissingDependencyError, match="pip install 'viscolayer\\[minres\\]'"):
        FemSettings(solver="minres")
    assert FemSettings(solver="direct").solver == "direct"


