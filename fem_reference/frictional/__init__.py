"""Frictional steady rolling on the plane-strain FEM layer: an independent reference for
the BEM's frictional model. The moving-frame FEM layer condensed to its normal and
tangential surface compliance (:mod:`.compliance`), and a dense active-set solver of
Coulomb friction with stick and slip on it (:mod:`.solve`); inputs and result in
:mod:`.model`. Per unit length along y, SI units. The rolling sphere in 3D: the half
layer's condensed compliance (:mod:`.compliance_3d`) and a semi-smooth Newton Coulomb
solver on it (:mod:`.three_d`, result :mod:`.result_3d`), totals in N."""

from .compliance import SurfaceCompliance, surface_compliance
from .model import FrictionalRollingResult, RollingFriction
from .compliance_3d import SurfaceCompliance3D, surface_compliance_3d
from .result_3d import FrictionalSphereResult
from .solve import solve_frictional
from .three_d import solve_frictional_3d

__all__ = ["FrictionalRollingResult", "FrictionalSphereResult", "RollingFriction", "SurfaceCompliance",
           "SurfaceCompliance3D", "solve_frictional", "solve_frictional_3d", "surface_compliance",
           "surface_compliance_3d"]
