"""Run a gmsh model builder and bring the mesh into scikit-fem through meshio; the graded
size field of the gmsh meshes.

gmsh physical groups arrive as named boundaries (``mesh.boundaries[name]``) and
subdomains of the scikit-fem mesh. The meshes take their sizes from any object with the
attributes of :class:`GradedSizes` (and :class:`LayerSizes`): the models' resolved
discretizations.
"""

from __future__ import annotations

import contextlib
import io
import os
import signal
import threading
import tempfile
from typing import Callable, Protocol

import meshio
import numpy as np
from skfem.io.meshio import from_meshio

from .._deps import import_gmsh
from ..errors import MeshError

gmsh = import_gmsh()  # one clear ImportError if gmsh's system libraries are missing

__all__ = ["GradedSizes", "LayerSizes", "mesh_with_gmsh", "require_boundaries", "size_field"]


class GradedSizes(Protocol):
    """Sizes of a graded mesh: ``mesh_size`` h_c (m) on the candidate zone, ``grading``
    (-) the growth of the size with the distance from it, ``far_size`` h_far (m) the
    largest size."""

    mesh_size: float
    grading: float
    far_size: float


class LayerSizes(GradedSizes, Protocol):
    """Sizes of a stationary layer's mesh: those of :class:`GradedSizes`, the candidate
    zone's radius ``contact_zone`` (m) and the layer's lateral extent ``domain_radius``
    (m)."""

    contact_zone: float
    domain_radius: float


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
    main = threading.current_thread() is threading.main_thread()
    handlers = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)} if main else {}

    @contextlib.contextmanager
    def keep_handlers():
        """gmsh's library resets SIGINT and SIGTERM to their defaults when it starts and
        stops: hold them back meanwhile, then put the caller's handlers back."""
        blocked = signal.pthread_sigmask(signal.SIG_BLOCK, set(handlers)) if handlers else None
        try:
            yield
        finally:
            for s, handler in handlers.items():
                if handler is not None:
                    signal.signal(s, handler)
            if blocked is not None:
                signal.pthread_sigmask(signal.SIG_SETMASK, blocked)

    if started:
        with keep_handlers():
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
            with keep_handlers():
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


def size_field(dim_tags, disc: GradedSizes) -> None:
    """Make the background size field h = min(h_c + grading * dist, h_far) (m) of the
    current gmsh model, dist the distance to the entities ``dim_tags`` = (gmsh list
    name, tags); ``disc`` gives ``mesh_size`` h_c (m), ``grading`` (-) and
    ``far_size`` h_far (m). Sizes from points, boundaries and curvature are off."""
    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    field.setNumbers(dist, dim_tags[0], dim_tags[1])
    field.setNumber(dist, "Sampling", 200)
    size = field.add("MathEval")
    field.setString(size, "F", f"min({disc.mesh_size!r} + {disc.grading!r} * F{dist}, "
                               f"{disc.far_size!r})")
    field.setAsBackgroundMesh(size)
    for opt in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints",
                "Mesh.MeshSizeFromCurvature"):
        gmsh.option.setNumber(opt, 0)
