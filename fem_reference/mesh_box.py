"""Half-box mesh of the layer for 3D steady rolling: x in [-downstream, upstream],
y in [0, lateral], z in [0, H] (the half y >= 0 of the layer, symmetric about y = 0).

Named boundaries (gmsh physical groups): ``base`` (z = 0, bonded), ``inflow``
(x = upstream: the material enters), ``outflow`` (x = -downstream: it leaves),
``sym_y`` (y = 0, the symmetry plane), ``lateral`` (y = lateral, traction free),
``zone`` (z = H, the half disk x^2 + y^2 <= Z^2, y >= 0: the candidate contact zone)
and ``free`` (the rest of z = H). Unstructured tetrahedra, the size
h = min(h_c + grading * dist, h_far) graded from the zone (:func:`.mesh_axisym.size_field`).
Lengths in m.
"""

from __future__ import annotations

from ._deps import import_gmsh
from .errors import MeshError
from .gmsh_io import mesh_with_gmsh
from .mesh_axisym import size_field

gmsh = import_gmsh()  # one clear ImportError if gmsh's system libraries are missing

__all__ = ["half_box_mesh"]

NAMES = ("base", "inflow", "outflow", "sym_y", "lateral", "zone", "free")


def half_box_mesh(thickness: float, zone: float, upstream: float, downstream: float,
                  lateral: float, sizes):
    """First-order tetrahedral mesh (skfem ``MeshTet``) of the half layer (module
    docstring); ``sizes`` has ``mesh_size``, ``grading`` and ``far_size``."""
    H, Z = thickness, zone

    def build():
        occ = gmsh.model.occ
        body = occ.addBox(-downstream, 0.0, 0.0, downstream + upstream, lateral, H)
        disk = occ.addDisk(0.0, 0.0, H, Z, Z)
        half = occ.addRectangle(-Z, 0.0, H, 2.0 * Z, Z)
        cut, _ = occ.intersect([(2, disk)], [(2, half)])
        occ.fragment([(3, body)], cut)
        occ.synchronize()
        groups = {name: [] for name in NAMES}
        # OCC pads bounding boxes by 1e-7 m: a tolerance far above that and far below
        # any length of the model
        tol = 1e-3 * min(H, Z)
        for _, tag in gmsh.model.getEntities(2):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, tag)
            if z1 < tol:
                groups["base"].append(tag)
            elif z0 > H - tol:
                inside = x0 > -Z - tol and x1 < Z + tol and y1 < Z + tol
                groups["zone" if inside else "free"].append(tag)
            elif x0 > upstream - tol:
                groups["inflow"].append(tag)
            elif x1 < -downstream + tol:
                groups["outflow"].append(tag)
            elif y1 < tol:
                groups["sym_y"].append(tag)
            else:
                groups["lateral"].append(tag)
        for name, tags in groups.items():
            gmsh.model.addPhysicalGroup(2, tags, name=name)
        vols = [tag for _, tag in gmsh.model.getEntities(3)]
        gmsh.model.addPhysicalGroup(3, vols, name="layer")
        size_field(dim_tags=("SurfacesList", groups["zone"]), disc=sizes)

    mesh = mesh_with_gmsh(build, "tetra", 3)
    missing = [name for name in NAMES if name not in (mesh.boundaries or {})]
    if missing:
        raise MeshError(f"the half-box mesh lacks the boundaries {missing}")
    return mesh
