"""The Python API's inputs: every public bem constructor takes real numbers (numpy scalars
included) and refuses booleans, NaN and infinities with a message naming the field; a
problem with a missing part and kernels without the block a solve reads are clear errors."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import bem
from bem.grid import Grid
from bem.indenters import Cylinder, HeightMap, LineCylinder, Paraboloid, Sphere
from bem.layer import MAX_THICKNESS, Layer
from bem.materials import Elastic, MasterCurveTable, Prony, ThreeParameterSolid
from bem.plane import LineGrid
from bem.problem import Loading, Problem, check_kernel_memory, kernel_memory

MATERIAL = Elastic(1e6)
_X = np.array([-0.01, 0.0, 0.01])
_H = np.array([[1e-4, 5e-5, 1e-4], [5e-5, 0.0, 5e-5], [1e-4, 5e-5, 1e-4]])

# constructor, valid keyword arguments, the scalar fields (name -> "real" or "int") and how
# a field's message names it (an entry of a sequence is named "field[i]")
CASES = {
    "Layer": (Layer, dict(thickness=5e-3, material=MATERIAL, density=1000.0), {"thickness": "real", "density": "real"}),
    "Loading": (Loading, dict(speed=0.05, load=150.0), {"speed": "real", "load": "real"}),
    "Loading(indentation)": (Loading, dict(speed=0.0, indentation=1e-4), {"indentation": "real"}),
    "Grid": (Grid, dict(spacing_x=1e-3, spacing_y=1e-3, period_x=0.1, period_y=0.1, truncation_x=64,
                        truncation_y=64, nodes_x=5, nodes_y=5),
             {"spacing_x": "real", "spacing_y": "real", "period_x": "real", "period_y": "real",
              "truncation_x": "int", "truncation_y": "int", "nodes_x": "int", "nodes_y": "int"}),
    "LineGrid": (LineGrid, dict(spacing=1e-3, period=0.1, truncation=64, nodes=5),
                 {"spacing": "real", "period": "real", "truncation": "int", "nodes": "int"}),
    "Sphere": (Sphere, dict(radius=0.02), {"radius": "real"}),
    "Paraboloid": (Paraboloid, dict(radius=0.02), {"radius": "real"}),
    "LineCylinder": (LineCylinder, dict(radius=0.02), {"radius": "real"}),
    "Cylinder": (Cylinder, dict(radius=0.02, length=0.03, edge_radius=1e-3),
                 {"radius": "real", "length": "real", "edge_radius": "real"}),
    "Cylinder(crown)": (Cylinder, dict(radius=0.02, length=0.03, crown_radius=0.5), {"crown_radius": "real"}),
    "Elastic": (Elastic, dict(shear_modulus=1e6), {"shear_modulus": "real"}),
    "ThreeParameterSolid": (ThreeParameterSolid, dict(G0=3e6, tau=0.25, f=1.0), {"G0": "real", "tau": "real", "f": "real"}),
    "Prony": (Prony, dict(G_inf=1e6, G=[2e6, 1e6], tau=[0.1, 1.0]), {"G_inf": "real", "G[0]": "real", "tau[1]": "real"}),
    "MasterCurveTable": (MasterCurveTable, dict(omega=[1.0, 10.0], storage=[1e6, 2e6], loss=[1e5, 2e5]),
                         {"omega[0]": "real", "storage[1]": "real", "loss[0]": "real"}),
    "HeightMap": (HeightMap, dict(x=_X, y=_X, h=_H), {}),
}
FIELDS = [(case, name, kind) for case, (_, _, fields) in CASES.items() for name, kind in fields.items()]


def _build(case: str, name: str, value):
    """The constructor of ``case`` with field ``name`` (``"G[0]"``: an entry of G) set to ``value``."""
    cls, kwargs, _ = CASES[case]
    kwargs = dict(kwargs)
    if name.endswith("]"):
        key, index = name[:-1].split("[")
        seq = list(kwargs[key])
        seq[int(index)] = value
        kwargs[key] = seq
    else:
        kwargs[name] = value
    return cls(**kwargs)


def _valid(case: str, name: str):
    _, kwargs, _ = CASES[case]
    if name.endswith("]"):
        key, index = name[:-1].split("[")
        return kwargs[key][int(index)]
    return kwargs[name]


@settings(max_examples=150, deadline=None)
@given(field=st.sampled_from(FIELDS), bad=st.sampled_from([True, False, np.bool_(True), math.nan, math.inf,
                                                           -math.inf, np.float64("nan"), "1.0", None]))
def test_booleans_nan_inf_and_text_are_refused_naming_the_field(field, bad):
    case, name, kind = field
    if bad is None and name in ("load", "crown_radius"):
        return  # optional: None is their absence (Loading's one-of rule is tested in test_solve)
    with pytest.raises(ValueError) as info:  # NotANumber is a TypeError and a ValueError
        _build(case, name, bad)
    assert name.split("[")[0] in str(info.value), (case, name, str(info.value))


@settings(max_examples=150, deadline=None)
@given(field=st.sampled_from(FIELDS), dtype=st.sampled_from(["float32", "float64", "int64", "int32", "uint16"]))
def test_numpy_scalars_are_accepted_where_python_numbers_are(field, dtype):
    case, name, kind = field
    value = _valid(case, name)
    if (kind == "int") != np.issubdtype(np.dtype(dtype), np.integer):
        return  # a float is not an integer; an integer field wants an integer type
    if kind == "real" and value != int(value):
        return  # an integer dtype cannot hold this valid real value
    scalar = np.dtype(dtype).type(value)
    obj = _build(case, name, scalar)
    key = name.split("[")[0]
    stored = getattr(obj, key)
    stored = stored[int(name[:-1].split("[")[1])] if name.endswith("]") else stored
    assert type(stored) in (float, int) and stored == pytest.approx(float(scalar), rel=1e-7)


def test_height_map_arrays_refuse_booleans_and_take_float32():
    with pytest.raises(ValueError, match=r"^h must hold real numbers \(m\), got an array of dtype bool"):
        HeightMap(_X, _X, _H > 0)
    with pytest.raises(ValueError, match=r"^h must be finite and >= 0 m, got h\[1, 1\] = nan"):
        HeightMap(_X, _X, np.where(_H == 0.0, np.nan, _H))
    assert HeightMap(_X.astype(np.float32), _X, _H.astype(np.float32)).profile(0.0, 0.0) == 0.0


def test_layer_refuses_a_thickness_whose_cube_is_not_a_double():
    assert Layer(MAX_THICKNESS, MATERIAL).thickness == MAX_THICKNESS
    with pytest.raises(ValueError, match=r"^thickness must be <= 1e\+100 m .*got 1e\+300"):
        Layer(1e300, MATERIAL)


def _problem(**loading) -> Problem:
    grid = Grid.centred((1e-3, 1e-3), (0.1, 0.1), (64, 64), (3e-3, 3e-3))
    return Problem(Layer(1e-2, MATERIAL), Sphere(0.02), grid, Loading(0.0, **loading))


@pytest.mark.parametrize("part", ["layer", "indenter", "grid", "loading"])
def test_a_problem_without_a_part_names_it(part):
    p = _problem(load=1.0)
    parts = {"layer": p.layer, "indenter": p.indenter, "grid": p.grid, "loading": p.loading, part: None}
    with pytest.raises(TypeError, match=rf"^Problem\.{part} must "):
        Problem(**parts)


def test_kernels_without_the_block_a_solve_reads_are_named():
    p = _problem(load=1.0)
    with pytest.raises(ValueError, match=r"^kernels lacks the block\(s\) 'ww': a frictionless solve reads 'ww'"):
        bem.solve(p, kernels={})
    with pytest.raises(TypeError, match=r"^problem must be a bem.problem.Problem"):
        bem.solve(None)


def test_a_load_lost_to_rounding_is_refused_and_the_smallest_resolved_one_is_linear():
    """The gap of the node next to the axis is a^2 / (R + sqrt(R^2 - a^2)) = 2.5e-5 m; a
    load moves the surface by at most P / (G a) = 1e-3 m/N times P: refused below
    eps 2.5e-5 m, i.e. P < 5.6e-18 N. Just above, the one-node contact is linear in the
    load (indentation / load constant to rounding)."""
    with pytest.raises(ValueError, match=r"^loading.load = 1e-300 N is lost to rounding .* give loading.load >= 5.55e-18 N"):
        _problem(load=1e-300)
    with pytest.raises(ValueError, match=r"^loading.indentation = 1e-300 m is lost to rounding"):
        _problem(indentation=1e-300)
    small, smaller = bem.solve(_problem(load=1e-12)), bem.solve(_problem(load=1e-15))
    assert small.indentation / 1e-12 == pytest.approx(smaller.indentation / 1e-15, rel=1e-9)


def test_kernel_memory_is_estimated_before_allocating():
    """The estimate is exact integer arithmetic for any truncation (beyond int64 too), and
    a grid whose kernels outgrow the machine is refused with it."""
    grid = Grid.centred((1e-3, 1e-3), (0.1, 0.1), (10**30, 10**30), (3e-3, 3e-3))
    assert kernel_memory(grid) > 10**31
    with pytest.raises(ValueError, match=r"^the kernel tables of this grid \(truncation = 10+ x 10+, 7 x 7 nodes\) "
                                         r"need at least [0-9.e+]+ GiB, more than this machine's"):
        check_kernel_memory(grid)
    small = Grid.centred((1e-3, 1e-3), (0.1, 0.1), (64, 64), (3e-3, 3e-3))
    check_kernel_memory(small)
