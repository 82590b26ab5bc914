"""Axisymmetric (r, z) mesh of the layer: the rectangle [0, r_d] x [0, H].

Named boundaries (gmsh physical groups): ``base`` (z = 0, bonded), ``axis``
(r = 0), ``outer`` (r = r_d, traction free), ``zone`` (z = H, r <= r_zone: the
candidate contact zone) and ``free`` (z = H, r > r_zone). The element size is
h = min(h_c + grading * dist, h_far), with dist (m) the distance to the zone.
"""

from __future__ import annotations

from .._deps import import_gmsh
from .gmsh_io import LayerSizes, mesh_with_gmsh, size_field

gmsh = import_gmsh()  # one clear ImportError if gmsh's system libraries are missing

__all__ = ["axisymmetric_mesh"]


def axisymmetric_mesh(thickness: float, disc: LayerSizes):
    """First-order triangle mesh (skfem ``MeshTri``) of the (r, z) section (m)."""
    H, zone, rd = thickness, disc.contact_zone, disc.domain_radius

    def build():
        geo = gmsh.model.geo
        p = [geo.addPoint(0, 0, 0), geo.addPoint(rd, 0, 0), geo.addPoint(rd, H, 0),
             geo.addPoint(zone, H, 0), geo.addPoint(0, H, 0)]
        base = geo.addLine(p[0], p[1])
        outer = geo.addLine(p[1], p[2])
        free = geo.addLine(p[2], p[3])
        top = geo.addLine(p[3], p[4])
        axis = geo.addLine(p[4], p[0])
        loop = geo.addCurveLoop([base, outer, free, top, axis])
        surf = geo.addPlaneSurface([loop])
        geo.synchronize()
        for name, tag in (("base", base), ("outer", outer), ("free", free),
                          ("zone", top), ("axis", axis)):
            gmsh.model.addPhysicalGroup(1, [tag], name=name)
        gmsh.model.addPhysicalGroup(2, [surf], name="layer")
        size_field(dim_tags=("CurvesList", [top]), disc=disc)
        gmsh.option.setNumber("Mesh.Algorithm", 6)

    return mesh_with_gmsh(build, "triangle", 2)
