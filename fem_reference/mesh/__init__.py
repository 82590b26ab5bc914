"""Meshes of the layer, one module per mesh: gmsh meshes through meshio
(:mod:`.gmsh_io`) of the axisymmetric section, the quarter cylinder and the rolling half
box, and the structured plane-strain strip. Lengths in m; named boundaries ``base``,
``zone`` (the candidate contact zone), ``free`` and the model's own sides."""

from .axisymmetric_section import axisymmetric_mesh
from .half_box import half_box_mesh
from .plane_strain_strip import plane_mesh
from .quarter_cylinder import quarter_cylinder_mesh

__all__ = ["axisymmetric_mesh", "half_box_mesh", "plane_mesh", "quarter_cylinder_mesh"]
