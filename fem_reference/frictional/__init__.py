"""Frictional steady rolling on the plane-strain FEM layer: an independent reference for
the BEM's frictional model. The moving-frame FEM layer condensed to its normal and
tangential surface compliance (:mod:`.compliance`), and a dense active-set solver of
Coulomb friction with stick and slip on it (:mod:`.solve`); inputs and result in
:mod:`.model`. Per unit length along y, SI units."""

from .compliance import SurfaceCompliance, surface_compliance
from .model import FrictionalRollingResult, RollingFriction
from .solve import solve_frictional

__all__ = ["FrictionalRollingResult", "RollingFriction", "SurfaceCompliance", "solve_frictional",
           "surface_compliance"]
