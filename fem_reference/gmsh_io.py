"""Run a gmsh model builder and bring the mesh into scikit-fem through meshio.

gmsh physical groups arrive as named boundaries (``mesh.boundaries[name]``) and
subdomains of the scikit-fem mesh.
"""

from __future__ import annotations

import contextlib
import io
import os
import tempfile
from typing import Callable

import meshio
import numpy as np
from skfem.io.meshio import from_meshio

from ._deps import import_gmsh
from .errors import MeshError

gmsh = import_gmsh()  # one clear ImportError if gmsh's system libraries are missing

__all__ = ["mesh_with_gmsh", "require_boundaries"]


def _drop_orphans(m: meshio.Mesh, volume_type: str) -> meshio.Mesh:
    """Keep only the points used by the cells of ``volume_type`` (renumbered)."""
    used = np.unique(m.cells_dict[volume_type])
    new_index = -np.ones(len(m.points), dtype=np.int64)
    new_index[used] = np.arange(len(used))
    cells = []
    for block in m.cells:
        data = new_index[block.data]
        if np.any(data < 0):
            raise MeshError(f"gmsh {block.type} cells use points outside the {volume_type} mesh")
        cells.append(meshio.CellBlock(block.type, data))
    return meshio.Mesh(m.points[used], cells, cell_sets=m.cell_sets)


def mesh_with_gmsh(build: Callable[[], None], volume_type: str, dim: int):
    """Build a gmsh model with ``build()``, mesh it in ``dim`` dimensions, return
    the scikit-fem mesh (first order) with named boundaries.

    Raises
    ------
    MeshError
        If gmsh fails, makes no ``volume_type`` cell, or a named group is empty.
    """
    started = not gmsh.isInitialized()
    if started:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.Verbosity", 1)
        gmsh.model.add("fem_reference")
        try:
            build()
            gmsh.model.mesh.generate(dim)
        except Exception as exc:  # gmsh reports its failures as plain Exception
            raise MeshError(f"gmsh failed to mesh the layer: {exc}") from exc
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "layer.msh")
            gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
            gmsh.write(path)
            with contextlib.redirect_stdout(io.StringIO()):  # meshio's msh reader prints a blank line
                m = meshio.read(path)
        gmsh.model.remove()
    finally:
        if started:
            gmsh.finalize()
    if volume_type not in m.cells_dict or len(m.cells_dict[volume_type]) == 0:
        raise MeshError(f"gmsh made no {volume_type} cells")
    mesh = from_meshio(_drop_orphans(m, volume_type))
    for name, facets in (mesh.boundaries or {}).items():
        if len(facets) == 0:
            raise MeshError(f"the named boundary {name!r} of the mesh is empty")
    return mesh


def require_boundaries(mesh, what: str, faces: dict) -> None:
    """Raise :class:`MeshError` if a named boundary of ``mesh`` is missing or empty.

    Parameters
    ----------
    mesh : skfem Mesh
    what : str
        The mesh's name in the message ("half-box", ...).
    faces : dict
        Boundary name -> (where it lies, the settings that shape it), both text.
    """
    for name, (where, settings) in faces.items():
        if len(mesh.boundaries.get(name, ())) == 0:
            raise MeshError(
                f"the {what} mesh has no facet on the boundary {name!r} ({where}): its face was "
                f"lost when the model's faces were sorted; the lengths that shape it are {settings}: "
                "change them (keep the candidate zone several elements inside the domain)")
