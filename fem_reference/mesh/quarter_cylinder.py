"""Quarter-cylinder mesh of the layer: 0 <= x, 0 <= y, x^2 + y^2 <= r_d^2, 0 <= z <= H.

Named boundaries (gmsh physical groups): ``base`` (z = 0, bonded), ``sym_x``
(x = 0), ``sym_y`` (y = 0), ``outer`` (cylinder r = r_d, traction free), ``zone``
(z = H, r <= r_zone: the candidate contact zone) and ``free`` (z = H, r > r_zone).
Element size as in :mod:`.axisymmetric_section`, graded from the zone.

The faces of the gmsh model are sorted by their centres of mass, which OCC computes to
round-off: a plane face has its centre on its plane, and on the top the quarter disk's
centre lies 0.60 Z from the axis (4 sqrt(2) Z / (3 pi)), the quarter annulus's at least
0.90 Z (its limit as r_d -> Z), so 0.75 Z tells them apart. (Bounding boxes would not
do: they carry OCC's padding of 1e-7 m, so that with a tolerance of 1e-5 r_d the faces
x = 0 and z = H are lost at r_d = 10 mm.)
"""

from __future__ import annotations

import math

from .._deps import import_gmsh
from .gmsh_io import LayerSizes, mesh_with_gmsh, require_boundaries, size_field

gmsh = import_gmsh()  # one clear ImportError if gmsh's system libraries are missing

__all__ = ["quarter_cylinder_mesh"]


def _face_group(center, H: float, zone: float, tol: float) -> str:
    """Named boundary of a face of the quarter cylinder from its centre of mass (m)."""
    x, y, z = center
    if abs(z) <= tol:
        return "base"
    if abs(z - H) <= tol:
        return "zone" if math.hypot(x, y) < 0.75 * zone else "free"
    if abs(x) <= tol:
        return "sym_x"
    if abs(y) <= tol:
        return "sym_y"
    return "outer"


def quarter_cylinder_mesh(thickness: float, disc: LayerSizes):
    """First-order tetrahedral mesh (skfem ``MeshTet``) of the quarter layer (m).

    Raises
    ------
    MeshError
        If gmsh fails or a named boundary comes out empty (the message names it and the
        settings that shape it).
    """
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
        tol = 1e-6 * min(H, zone)  # the centres are exact to round-off of r_d
        for _, tag in gmsh.model.getEntities(2):
            groups[_face_group(occ.getCenterOfMass(2, tag), H, zone, tol)].append(tag)
        for name, tags in groups.items():
            if tags:
                gmsh.model.addPhysicalGroup(2, tags, name=name)
        vols = [tag for _, tag in gmsh.model.getEntities(3)]
        gmsh.model.addPhysicalGroup(3, vols, name="layer")
        size_field(dim_tags=("SurfacesList", groups["zone"]), disc=disc)

    mesh = mesh_with_gmsh(build, "tetra", 3)
    shaped = f"layer.thickness = {H:.6g} m, fem.domain_radius = {rd:.6g} m"
    require_boundaries(mesh, "quarter-cylinder", {
        "base": ("the bonded base z = 0", shaped),
        "sym_x": ("the symmetry plane x = 0", shaped),
        "sym_y": ("the symmetry plane y = 0", shaped),
        "outer": ("the cylinder r = fem.domain_radius", shaped),
        "zone": ("the candidate quarter disk", f"fem.contact_zone = {zone:.6g} m"),
        "free": ("the top outside the zone",
                 f"fem.contact_zone = {zone:.6g} m, fem.domain_radius = {rd:.6g} m"),
    })
    return mesh
