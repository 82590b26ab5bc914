"""``fem-reference solve`` refuses, before meshing, a mesh too large to solve or too fine for
gmsh, and a MINRES tolerance too loose for a reference (exit 2, the estimate in the
message); the estimate is a lower bound of the measured mesh."""

from __future__ import annotations

import re

import pytest

from fem_reference import solve
from fem_reference.cli import main
from fem_reference.errors import InputError
from fem_reference.materials import ElasticMaterial
from fem_reference.problem import MAX_RTOL, ContactProblem, FemSettings, Indenter, Layer, Loading
from fem_reference.sizing import MAX_UNKNOWNS, estimate_size

CASE = """
[layer]
thickness = 5e-3
[material]
model = "elastic"
shear_modulus = 3e6
[indenter]
shape = "sphere"
radius = 0.02
[loading]
load = 100.0
"""


@pytest.fixture
def case(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(CASE)
    return path


@pytest.mark.parametrize("override, message", [
    ("fem.element_size=1e-9", r"the mesh would have at least ~4.67e\+07 elements and ~2.1e\+08 unknowns \(element "
                              r"size 1e-09 m .* above the 2e\+05 unknowns a 2D solve accepts"),
    ("fem.refine=8", r"at least ~1.29e\+07 elements .* fem.refine = 8\), above the 2e\+05 unknowns"),
    ("layer.thickness=1e-9", r"layer.thickness = 1e-09 m, fem.refine = 0\), above the 2e\+05 unknowns"),
    ("layer.thickness=1e300", r"the mesh would span 4.8e\+303 element sizes .* more than the 1e\+08"),
    ("indenter.radius=1e300", r"the mesh would span 2.09e\+51 element sizes"),
    ("loading.load=1e-300", r"the mesh would span 1.11e\+102 element sizes"),
    ("fem.rtol=0.5", r"fem.rtol must be <= 1e-06, got 0.5: MINRES stops at this relative residual"),
])
def test_sizes_and_tolerances_beyond_the_bounds_exit_2_before_meshing(case, capsys, override, message):
    assert main(["solve", str(case), "--quiet", "--set", override]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fem-reference: error: ") and re.search(message, err), err


def test_the_estimate_is_a_lower_bound_of_the_mesh():
    """Axisymmetric sphere on a 5 mm layer, h = 0.8 mm: 38 elements, 171 unknowns
    estimated; the mesh has 155 and 743 (measured), 4.3 times more. The bound holds with
    one uniform refinement (x 4 in 2D)."""
    for refine in (0, 1):
        problem = ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("sphere", 0.02), Loading(load=100.0),
                                 FemSettings(element_size=8e-4, refine=refine))
        result = solve(problem)
        _, elements, unknowns = estimate_size(problem, result.mesh.contact_zone, 8e-4)
        assert elements <= result.mesh.elements and unknowns <= result.mesh.unknowns
        assert result.mesh.unknowns < 6 * unknowns  # a useful bound: within a small factor
    assert MAX_UNKNOWNS[2] > 20 * 743


def test_rtol_bound_is_stated_and_enforced_in_the_api():
    FemSettings(rtol=MAX_RTOL)
    with pytest.raises(InputError, match=r"^fem.rtol must be <= 1e-06, got 0.001"):
        FemSettings(rtol=1e-3)
