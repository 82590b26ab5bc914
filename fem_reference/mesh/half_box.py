"""Half-box mesh of the layer for 3D steady rolling: x in [-L, L], y in [0, lateral],
z in [0, H] (the half y >= 0 of the layer, symmetric about y = 0), mirror-symmetric about
x = 0.

gmsh meshes the quarter x >= 0 (unstructured tetrahedra, the size h = min(h_c + grading *
dist, h_far) graded from the candidate quarter disk, :func:`.gmsh_io.size_field`);
the quarter and its mirror image x -> -x are glued on the plane x = 0, whose triangles
they share. So the mesh near the contact is its own mirror image, as the plane-strain
strip is (:mod:`.plane_strain_strip`): a symmetric (elastic) contact then has no
spurious rolling resistance. On an unsymmetric gmsh mesh of the whole half box an elastic layer showed
R_r = -0.12 N at h = 1 mm (4% of the section 11 case's viscoelastic R_r).

Named boundaries (facet centroids): ``base`` (z = 0, bonded), ``inflow`` (x = L: the
material enters), ``outflow`` (x = -L: it leaves), ``sym_y`` (y = 0, the symmetry
plane), ``lateral`` (y = lateral, traction free), ``zone`` (z = H, x^2 + y^2 <= Z^2: the
candidate contact half disk of a sphere; a roller's is the rectangle |x| <= Z, y <= Z_y,
``zone_y`` = its half length) and ``free`` (the rest of z = H). Lengths in m.
"""

from __future__ import annotations

import numpy as np
from skfem import MeshTet

from .._deps import import_gmsh
from ..errors import MeshError
from .gmsh_io import GradedSizes, mesh_with_gmsh, require_boundaries, size_field

gmsh = import_gmsh()  # one clear ImportError if gmsh's system libraries are missing

__all__ = ["half_box_mesh", "mirror_x"]

NAMES = ("base", "inflow", "outflow", "sym_y", "lateral", "zone", "free")


def _quarter(H: float, Z: float, length: float, lateral: float, sizes: GradedSizes, zone_y=None):
    def build():
        occ = gmsh.model.occ
        body = occ.addBox(0.0, 0.0, 0.0, length, lateral, H)
        if zone_y is None:
            disk = occ.addDisk(0.0, 0.0, H, Z, Z)
            quarter = occ.addRectangle(0.0, 0.0, H, Z, Z)
            cut, _ = occ.intersect([(2, disk)], [(2, quarter)])
        else:
            cut = [(2, occ.addRectangle(0.0, 0.0, H, Z, zone_y))]
        occ.fragment([(3, body)], cut)
        occ.synchronize()
        # OCC pads bounding boxes by 1e-7 m: a tolerance far above that and far below
        # any length of the model
        tol = 1e-3 * min(H, Z)
        zone = []
        for _, tag in gmsh.model.getEntities(2):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, tag)
            if z0 > H - tol and x1 < Z + tol and y1 < (Z if zone_y is None else zone_y) + tol:
                zone.append(tag)
        if len(zone) != 1:
            raise MeshError(f"the quarter box has {len(zone)} candidate-zone faces, not 1")
        gmsh.model.addPhysicalGroup(2, zone, name="zone")
        vols = [tag for _, tag in gmsh.model.getEntities(3)]
        gmsh.model.addPhysicalGroup(3, vols, name="layer")
        size_field(dim_tags=("SurfacesList", zone), disc=sizes)

    return mesh_with_gmsh(build, "tetra", 3)


def mirror_x(mesh: MeshTet, tol: float) -> MeshTet:
    """The tetrahedral mesh of x >= 0 glued to its mirror image x -> -x on x = 0 (vertices
    with |x| <= ``tol`` m are shared; the mirrored tetrahedra keep a positive orientation)."""
    p, t = mesh.p, mesh.t
    if np.any(p[0] < -tol):
        raise MeshError("mirror_x needs a mesh of x >= 0")
    on_plane = np.abs(p[0]) <= tol
    p = p.copy()
    p[0, on_plane] = 0.0
    off = np.flatnonzero(~on_plane)
    index = np.arange(p.shape[1])
    index[off] = p.shape[1] + np.arange(len(off))
    pm = p[:, off].copy()
    pm[0] *= -1.0
    tm = index[t][[1, 0, 2, 3]]  # a reflection flips the orientation: swap two vertices
    return MeshTet(np.hstack([p, pm]), np.hstack([t, tm]))


def half_box_mesh(thickness: float, zone: float, length: float, lateral: float,
                  sizes: GradedSizes, zone_y: float | None = None):
    """First-order tetrahedral mesh (skfem ``MeshTet``) of the half layer x in [-length,
    length] (module docstring); ``sizes`` has ``mesh_size``, ``grading`` and ``far_size``;
    ``zone_y`` (m) makes the candidate zone the rectangle |x| <= zone, y <= zone_y.

    Raises
    ------
    MeshError
        If gmsh fails or a named boundary comes out empty.
    """
    H, Z, L = thickness, zone, length
    tol = 1e-6 * min(H, Z)
    mesh = mirror_x(_quarter(H, Z, L, lateral, sizes, zone_y), tol)
    if zone_y is None:
        def in_zone(x):
            return np.hypot(x[0], x[1]) < Z
    else:
        def in_zone(x):
            return (np.abs(x[0]) < Z) & (x[1] < zone_y)
    mesh = mesh.with_boundaries({
        "base": lambda x: np.abs(x[2]) < tol,
        "inflow": lambda x: np.abs(x[0] - L) < tol,
        "outflow": lambda x: np.abs(x[0] + L) < tol,
        "sym_y": lambda x: np.abs(x[1]) < tol,
        "lateral": lambda x: np.abs(x[1] - lateral) < tol,
        "zone": lambda x: (np.abs(x[2] - H) < tol) & in_zone(x),
        "free": lambda x: (np.abs(x[2] - H) < tol) & ~in_zone(x),
    })
    box = f"layer.thickness = {H:.6g} m, fem.upstream = fem.downstream = {L:.6g} m, " \
          f"fem.domain_radius = {lateral:.6g} m"
    zone_set = f"fem.contact_zone = {Z:.6g} m" + ("" if zone_y is None else f", half length {zone_y:.6g} m")
    require_boundaries(mesh, "half-box", {
        "base": ("the bonded base z = 0", box), "inflow": ("x = fem.upstream", box),
        "outflow": ("x = -fem.downstream", box), "sym_y": ("the symmetry plane y = 0", box),
        "lateral": ("y = fem.domain_radius", box), "zone": ("the candidate zone", zone_set),
        "free": ("the top outside the zone", f"{zone_set}, {box}")})
    return mesh
