"""The three solvers' results speak one vocabulary: the quantities they share have the
same names in their summaries, and every solve record has iterations, residual, history."""

import json
import math

from bem import Elastic, Friction, Grid, Layer, Loading, Problem, Sphere, ThreeParameterSolid, solve
import fem_reference as fr

SHARED = {"load", "indentation", "contact_radius", "peak_pressure"}
BEM_SHARED = SHARED | {"rolling_resistance", "contact_area", "pressure_centroid_x", "grid"}
GRID = Grid.centred((1e-3, 1e-3), (0.2, 0.2), (100, 100), (5e-3, 5e-3))


def _check_record(solver: dict) -> None:
    assert {"iterations", "residual", "history"} <= set(solver)
    assert solver["iterations"] >= 1 and len(solver["history"]) >= 1 and math.isfinite(solver["residual"])


def test_shared_names_and_one_record_vocabulary():
    normal = solve(Problem(Layer(5e-3, Elastic(3e6)), Sphere(0.02), GRID, Loading(0.0, load=100.0)))
    rolling = Problem(Layer(5e-3, ThreeParameterSolid(3e6, 0.25, 1.0), 1000.0), Sphere(0.02), GRID,
                      Loading(0.05, load=150.0))
    frictional = solve(rolling, Friction(mu=0.2))
    fem = fr.solve(fr.ContactProblem(fr.Layer(5e-3), fr.ElasticMaterial(3e6), fr.Indenter("sphere", 0.02),
                                     fr.Loading(load=100.0), fem=fr.FemSettings(element_size=4e-4)))
    summaries = {"normal": normal.summary(), "frictional": frictional.summary(), "fem": fem.summary()}
    for name, s in summaries.items():
        assert SHARED <= set(s), name
        _check_record(s["solver"])
        json.dumps(s, default=float)  # JSON-ready
    assert BEM_SHARED <= set(summaries["normal"]) and BEM_SHARED <= set(summaries["frictional"])
    for key in SHARED:  # the same quantity under the same name: the attribute the summary reads
        assert summaries["normal"][key] == getattr(normal, key)
        assert summaries["fem"][key] == getattr(fem, key)
    # the same physical problem at rest: BEM (a = 1 mm) and FEM (h = 0.4 mm) agree roughly
    assert abs(summaries["normal"]["indentation"] / summaries["fem"]["indentation"] - 1) < 0.02
