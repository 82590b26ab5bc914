"""gmsh through meshio: a failure inside gmsh ends in a MeshError carrying gmsh's message."""

import gmsh
import pytest

from fem_reference import (ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading,
                           MeshError, solve)


def _thick(**fem):
    return ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", 0.02),
                          Loading(load=100.0), FemSettings(**fem))


def test_a_gmsh_failure_is_a_mesh_error_with_its_message(monkeypatch):
    def broken(dim=3):
        raise Exception("no elements in volume")

    monkeypatch.setattr(gmsh.model.mesh, "generate", broken)
    with pytest.raises(MeshError, match="gmsh failed to mesh the layer: no elements"):
        solve(_thick(element_size=4e-4))
