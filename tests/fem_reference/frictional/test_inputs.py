"""Bad input to the frictional FEM reference: a clear error naming the key."""

import pytest

from fem_reference import ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading
from fem_reference.errors import ContactZoneError, InputError
from fem_reference.frictional import RollingFriction, solve_frictional, surface_compliance
from tests.fem_reference.frictional.layers import elastic_problem


def test_a_3d_problem_is_refused_naming_fem_model():
    problem = ContactProblem(Layer(0.01), ElasticMaterial(1e6), Indenter("sphere", 0.02),
                             Loading(load=10.0, speed=0.01), FemSettings(model="3d"))
    with pytest.raises(InputError, match=r"fem\.model = '3d'.*plane strain"):
        surface_compliance(problem)
    with pytest.raises(InputError, match=r"fem\.model"):
        solve_frictional(problem, RollingFriction(0.3, creepage=1e-3))


def test_rolling_at_rest_is_refused_naming_the_speed():
    with pytest.raises(InputError, match=r"loading\.speed = 0\.0 m/s"):
        solve_frictional(elastic_problem(0.01, 2e-4, speed=0.0), RollingFriction(0.3, creepage=1e-3))


@pytest.mark.parametrize("kwargs, key", [
    (dict(mu=-0.1, creepage=0.0), "friction.mu"),
    (dict(mu=0.3, mode="sliding", creepage=0.0), "friction.mode"),
    (dict(mu=0.3, mode="omega"), "friction.creepage"),
    (dict(mu=0.3, mode="towed", creepage=0.01), "friction.creepage"),
    (dict(mu=0.3, mode="towed", driving_force=1.0), "friction.driving_force"),
    (dict(mu=0.3, creepage=0.0, kinematics="paper"), "friction.kinematics"),
    (dict(mu=0.0, mode="force"), "friction.mu = 0"),
    (dict(mu=0.3, creepage=float("nan")), "friction.creepage"),
    (dict(mu=0.3, creepage=0.0, max_iterations=0), "friction.max_iterations"),
])
def test_bad_friction_input_names_the_key(kwargs, key):
    with pytest.raises(InputError, match=key.replace(".", r"\.")):
        RollingFriction(**kwargs)


def test_a_contact_wider_than_the_zone_is_an_error():
    problem = ContactProblem(Layer(0.01), ElasticMaterial(1e6), Indenter("line", 0.05),
                             Loading(load=250.0, speed=0.01), FemSettings(element_size=2e-4, contact_zone=1.6e-3))
    with pytest.raises(ContactZoneError, match=r"fem\.contact_zone"):
        solve_frictional(problem, RollingFriction(0.3, creepage=1e-3))


def test_the_frictional_reference_does_not_import_bem():
    """An independent reference: importing and using it loads no module of bem."""
    import subprocess
    import sys

    code = ("import sys, fem_reference.frictional as f, fem_reference.frictional.solve, "
            "fem_reference.frictional.compliance; "
            "sys.exit(any(m == 'bem' or m.startswith('bem.') for m in sys.modules))")
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0
