"""The FEM method's case settings (:mod:`verification.methods.fem`): settings listed in
``scaled`` shrink with the level's element size, so the whole mesh is refined, and a
scaled setting that is not given, or not scalable, is refused."""

import pytest

from verification.methods import fem
from verification.results import Level
from verification.schema import CaseError


def test_scaled_fem_settings_refine_the_whole_mesh_with_the_element_size():
    settings = {"model": "3d", "grading": 0.2, "far_size": 5e-3, "scaled": ["grading", "far_size"]}
    level = Level(index=2, size=0.5e-3, settings=settings, sizes=(1e-3, 0.75e-3, 0.5e-3))
    got = fem._at_level(level)
    assert got == {"model": "3d", "grading": pytest.approx(0.1), "far_size": pytest.approx(2.5e-3)}
    problem = {"layer": {"thickness": 5e-3}, "material": {"model": "elastic", "shear_modulus": 3e6},
               "indenter": {"shape": "sphere", "radius": 0.02}, "loading": {"load": 150.0}}
    with pytest.raises(CaseError, match="'far_size' is scaled but not given"):
        fem.check({"element_sizes": [1e-3], "grading": 0.2, "scaled": ["grading", "far_size"]}, problem, "[fem]")
    with pytest.raises(CaseError, match="scaled"):
        fem.check({"element_sizes": [1e-3], "scaled": ["contact_zone"]}, problem, "[fem]")
