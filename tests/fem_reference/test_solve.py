"""The one entry point ``fem_reference.solve``: a line indenter goes to the steady-rolling
driver, whose progress reaches the caller; each model answers with its own result
class, the rolling ones both a ``RollingResult``. (Each model's driver is checked with
its model.)"""

import pytest

from fem_reference import (ContactProblem, ContactResult, ElasticMaterial, FemSettings, Indenter,
                           Layer, Loading, RollingResult, SphereRollingResult, solve)
from fem_reference.rolling import CylinderRollingResult


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


def test_each_model_answers_with_its_result_class():
    """A line contact gives a CylinderRollingResult, a RollingResult (not a sphere's); a
    sphere at rest a ContactResult. The sphere's rolling result is checked in
    rolling/test_three_d.py. Both rolling results share RollingResult's summary keys, in
    its order (the command line's JSON)."""
    line = solve(ContactProblem(Layer(1e-3), ElasticMaterial(3e6), Indenter("line", 0.02),
                                Loading(load=500.0, speed=0.0), FemSettings(element_size=1e-4)))
    assert type(line) is CylinderRollingResult and isinstance(line, RollingResult)
    assert not isinstance(line, SphereRollingResult)
    assert issubclass(SphereRollingResult, RollingResult)
    assert not issubclass(SphereRollingResult, CylinderRollingResult)
    assert list(line.summary()) == ["speed", "load", "indentation", "rolling_resistance",
                                    "rolling_resistance_energy", "pressure_centroid_x", "leading_edge",
                                    "trailing_edge", "contact_length", "contact_radius", "half_width",
                                    "contact_centre", "peak_pressure", "dissipation", "pressure_power",
                                    "energy_balance", "mesh", "solver"]
    rest = solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("sphere", 0.02),
                                Loading(load=100.0), FemSettings(element_size=8e-4)))
    assert type(rest) is ContactResult
