"""Quarter-cylinder mesh of the layer: 0 <= x, 0 <= y, x^2 + y^2 <= r_d^2, 0 <= z <= H.

Named boundaries (gmsh physical groups): ``base`` (z = 0, bonded), ``sym_x``
(x = 0), ``sym_y`` (y = 0), ``outer`` (cylinder r = r_d, traction free), ``zone``
(z = H, r <= r_zone: the candidate contact zone) and ``free`` (z = H, r > r_zone).
Element size as in :mod:`.mesh_axisym`, graded from the zone.
"""

from __future__ import annotations

import math

from ._deps import import_gmsh
from .discretization import Discretization
from .gmsh_io import mesh_with_gmsh
from .mesh_axisym import size_field

gmsh = import_gmsh()  # one clear ImportError if gmsh's system libraries are missing

__all__ = ["quarter_cylinder_mesh"]


def quarter_cylinder_mesh(thickness: float, disc: Discretization):
    """First-order tetrahedral mesh (skfem ``MeshTet``) of the quarter layer (m)."""
    H, zone, rd = thickness, disc.contact_zone, disc.domain_radius

    def build():
        occ = gmsh.model.occ
        body = occ.addCylinder(0, 0, 0, 0, 0, H, rd, angle=math.pi / 2)
        disk = occ.addDisk(0, 0, H, zone, zone)
        quarter = occ.addRectangle(0, 0, H, zone, zone)
        cut, _ = occ.intersect([(2, disk)], [(2, quarter)])
        occ.fragment([(3, body)], cut)
        occ.synchronize()
        groups = {"base": [], "sym_x": [], "sym_y": [], "outer": [], "zone": [], "free": []}
        tol = 1e-5 * rd  # OCC bounding boxes carry a small tolerance
        for _, tag in gmsh.model.getEntities(2):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, tag)
            if z1 < tol:
                groups["base"].append(tag)
            elif z0 > H - tol:
                groups["zone" if max(x1, y1) < zone + tol else "free"].append(tag)
            elif x1 < tol:
                groups["sym_x"].append(tag)
            elif y1 < tol:
                groups["sym_y"].append(tag)
            else:
                groups["outer"].append(tag)
        for name, tags in groups.items():
            gmsh.model.addPhysicalGroup(2, tags, name=name)
        vols = [tag for _, tag in gmsh.model.getEntities(3)]
        gmsh.model.addPhysicalGroup(3, vols, name="layer")
        size_field(dim_tags=("SurfacesList", groups["zone"]), disc=disc)

    return mesh_with_gmsh(build, "tetra", 3)
