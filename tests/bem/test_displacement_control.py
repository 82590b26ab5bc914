"""Displacement control (``indentation`` given, no ``load``) of the BEM contact solvers.

Solving under load control for ``P`` and then under displacement control at the
resulting ``d`` is the same discrete complementarity problem twice: both must end on the
same contact set and give back ``P`` to the precision of the linear solves. Before the
fix, a prescribed ``d`` started the active set from every reachable node, where the
solve asks for upward displacements of up to the profile's height and so tension on
every node: the set emptied ("ContactNotConverged: the active set emptied") for every
small indentation (1 N here, d = 1e-5 to 5e-5 m).
"""

import numpy as np
import pytest

import bem.contact
import fem_reference as fr
from bem import solve
from bem.contact import solve_normal
from bem.frictional import Friction
from bem.grid import Grid
from bem.indenters import Cylinder, HeightMap, Paraboloid, Sphere
from bem.layer import Layer
from bem.materials import Elastic, ThreeParameterSolid
from bem.operator import ComplianceOperator
from bem.problem import Loading, Problem, compute_kernels
from bem.spectral import BLOCKS, influence_kernels

SOLID = ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0)
# 45 x 45 nodes: the multilevel (coarse-grid) start is used (>= 625 nodes, odd size)
GRID = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5.5e-3, 5.5e-3))
LAYERS = {  # (layer, speed m/s): elastic at rest, and the section 11 layer rolling
    "rest": (Layer(5e-3, Elastic(3e6)), 0.0),
    "rolling": (Layer(5e-3, SOLID, 1000.0), 0.05),
}


def _heightmap() -> HeightMap:
    """An elliptic bump (radii 20 and 40 mm) with a wavy surface: no symmetry used."""
    x = np.linspace(-6e-3, 6e-3, 121)
    X, Y = np.meshgrid(x, x)
    h = X**2 / 0.04 + Y**2 / 0.08 + 2e-5 * (1 + np.sin(X / 1e-3) * np.cos(Y / 1.5e-3))
    return HeightMap(x, x, h - h.min())


INDENTERS = {
    "sphere": Sphere(0.02),
    "paraboloid": Paraboloid(0.02),
    "cylinder": Cylinder(0.02, 8e-3),
    "heightmap": _heightmap(),
}

# Tolerances on |P(d) / P - 1|, from the measured agreement (45 x 45, P = 1 N, every
# indenter at rest and rolling): dense LU, <= 1.3e-15 (the two solves differ only by the
# round-off of the bordered and the plain linear system on the same set); GMRES
# (rtol 1e-11), <= 5.9e-12, i.e. the solver's tolerance.
DENSE_TOL = 1e-13
GMRES_TOL = 5e-11


@pytest.fixture(scope="module")
def operators():
    return {name: ComplianceOperator(GRID, influence_kernels(GRID, layer, speed)["ww"])
            for name, (layer, speed) in LAYERS.items()}


def _both(op, indenter, load, **kw):
    X, Y = GRID.coordinates()
    s = indenter.profile(X, Y)
    by_load = solve_normal(op, s, load=load, **kw)
    by_disp = solve_normal(op, s, indentation=by_load.indentation, **kw)
    return by_load, by_disp


@pytest.mark.parametrize("motion", LAYERS)
@pytest.mark.parametrize("kind", INDENTERS)
def test_displacement_control_gives_back_the_load(operators, kind, motion):
    by_load, by_disp = _both(operators[motion], INDENTERS[kind], 1.0)
    assert by_disp.record.linear_solver == "dense"
    assert abs(by_disp.load / by_load.load - 1) < DENSE_TOL
    np.testing.assert_array_equal(by_disp.contact, by_load.contact)
    np.testing.assert_allclose(by_disp.force, by_load.force, rtol=0, atol=DENSE_TOL * by_load.force.max())
    assert by_disp.indentation == by_load.indentation


@pytest.mark.parametrize("motion", LAYERS)
@pytest.mark.parametrize("load", [1.0, 50.0])
def test_displacement_control_on_the_gmres_path(operators, motion, load):
    by_load, by_disp = _both(operators[motion], Sphere(0.02), load, dense_limit=20)
    assert by_disp.record.linear_solver == "gmres"
    assert abs(by_disp.load / load - 1) < GMRES_TOL
    np.testing.assert_array_equal(by_disp.contact, by_load.contact)


def test_an_emptied_set_restarts_from_the_deepest_node(operators, monkeypatch):
    """The old first set (every reachable node) puts all 2025 nodes in tension at 1 N: the
    next set is the deepest node alone, from which the iteration reaches the contact."""
    by_load = _both(operators["rest"], Sphere(0.02), 1.0)[0]
    monkeypatch.setattr(bem.contact, "_coarse_start", lambda op, s, reachable, *args: (reachable.copy(), None))
    X, Y = GRID.coordinates()
    res = solve_normal(operators["rest"], Sphere(0.02).profile(X, Y), indentation=by_load.indentation)
    assert res.record.history[:2] == (GRID.nodes_x * GRID.nodes_y, 1)
    assert abs(res.load / by_load.load - 1) < DENSE_TOL
    np.testing.assert_array_equal(res.contact, by_load.contact)


def test_an_indentation_that_reaches_no_node_is_an_error(operators):
    X, Y = GRID.coordinates()
    lifted = Sphere(0.02).profile(X, Y) + 2e-6
    with pytest.raises(ValueError, match=r"indentation = 1e-06 m reaches no node: the indenter's lowest "
                                         r"node is 2e-06 m above its lowest point; increase loading.indentation"):
        solve_normal(operators["rest"], lifted, indentation=1e-6)


def test_the_section10_example_at_small_indentations():
    """The reported failure: examples/paper-section10-thick.toml (45 x 45 nodes, N_t = 2000)
    with indentation = 1e-5 and 1e-4 m ended in "the active set emptied". Now both solve,
    and load control at the load found gives the indentation back (measured 2.2e-16)."""
    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (2000, 2000), (5.5e-3, 5.5e-3))
    op = ComplianceOperator(grid, influence_kernels(grid, Layer(5e-3, Elastic(3e6)), 0.0)["ww"])
    X, Y = grid.coordinates()
    s = Sphere(0.02).profile(X, Y)
    for d in (1e-5, 1e-4):
        by_disp = solve_normal(op, s, indentation=d)
        by_load = solve_normal(op, s, load=by_disp.load)
        assert by_disp.load > 0 and by_disp.contact.sum() > 1
        assert abs(by_load.indentation / d - 1) < DENSE_TOL
        np.testing.assert_array_equal(by_load.contact, by_disp.contact)


# Section 10 thick layer (examples/paper-section10-thick.toml: exact sphere R = 20 mm,
# H = 5 mm, G = 3 MPa, L = 0.2 m, N_t = 2000) under displacement control, against the
# axisymmetric FEM, on the example's candidate region (|x|, |y| <= 5.5 mm; on the
# example's own 0.25 mm grid the active set emptied at 1e-4 m before the fix). Both discretizations are scaled with the
# contact radius r_c (4.1 mm at d = 5e-4 m, 1.6 mm at 1e-4 m): BEM a = r_c / 16 and
# r_c / 13, FEM h_c = r_c / 40 and r_c / 32 (element_size 1e-4 m is the example's [fem]
# section).
# Measured: d = 5e-4 m, BEM 68.8737 N, FEM 68.8530 N (+3.0e-4); d = 1e-4 m, BEM
# 3.33860 N, FEM 3.33834 N (+7.6e-5). The discretization errors, measured by refining
# each: BEM a = 0.5 / 0.25 / 0.125 mm at 5e-4 m: 68.947 / 68.874 / 68.845 N (the step
# from 0.25 to 0.125 mm is 4.1e-4); at 1e-4 m the BEM moves within +-4.5e-4 of the
# finest FEM under a = 0.125 / 0.1 / 0.0625 mm and N_t = 2000 / 4000; FEM h_c = 1e-4 /
# 5e-5 / 2.5e-5 m: 68.853 / 68.850 / 68.847 N (9e-5) and 3.3357 / 3.33834 / 3.33841 N
# (2e-5 from the 5e-5 m used). The tolerance, 1e-3, is those two errors (<= 4.5e-4 and
# <= 1e-4) with a margin of 2.
THICK = [  # d (m), BEM spacing a (m), FEM element size (m)
    (5e-4, 0.25e-3, 1e-4),
    (1e-4, 0.125e-3, 5e-5),
]


@pytest.mark.parametrize("d, spacing, element_size", THICK)
def test_thick_layer_under_displacement_control_matches_the_fem(d, spacing, element_size):
    grid = Grid.centred((spacing, spacing), (0.2, 0.2), (2000, 2000), (5.5e-3, 5.5e-3))
    problem = Problem(Layer(5e-3, Elastic(3e6)), Sphere(0.02), grid, Loading(0.0, indentation=d))
    bem_load = solve(problem).load
    fem = fr.solve(fr.ContactProblem(fr.Layer(5e-3), fr.ElasticMaterial(3e6), fr.Indenter("sphere", 0.02),
                                     fr.Loading(indentation=d), fr.FemSettings(element_size=element_size)))
    assert abs(bem_load / fem.load - 1) < 1e-3


def test_frictional_rolling_under_displacement_control():
    """The frictional solver takes ``indentation`` too (its normal start and its coarse
    start call the frictionless solver with it). Section 11 with mu = 0.2, pushed at the
    top, at 2 N (19 contact nodes, 2 slipping; the normal start emptied before the fix).
    Measured agreement 2e-16 on the load, 1.8e-15 on the rolling resistance (up to
    9.5e-13 at 150 N towed, 41 x 41): the stick/slip
    iteration ends on the same sets and directions; 1e-10 leaves room for the slip law's
    fixed point, which stops at misfits below direction_tol = 1e-7."""
    grid = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (500, 500), (5e-3, 5e-3))
    layer = Layer(5e-3, SOLID, 1000.0)
    friction = Friction(0.2)
    by_load_problem = Problem(layer, Sphere(0.02), grid, Loading(0.05, load=2.0))
    kernels, _ = compute_kernels(by_load_problem, BLOCKS)
    by_load = solve(by_load_problem, friction, kernels=kernels, energy=False)
    by_disp = solve(Problem(layer, Sphere(0.02), grid, Loading(0.05, indentation=by_load.indentation)),
                    friction, kernels=kernels, energy=False)
    assert abs(by_disp.load / 2.0 - 1) < 1e-10
    assert abs(by_disp.rolling_resistance / by_load.rolling_resistance - 1) < 1e-10
    assert 0 < by_load.stick.sum() < by_load.contact.sum()  # stick and slip both present
    np.testing.assert_array_equal(by_disp.contact, by_load.contact)
    np.testing.assert_array_equal(by_disp.stick, by_load.stick)
