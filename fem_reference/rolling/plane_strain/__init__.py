"""Steady rolling of a rigid cylinder on the plane-strain (x, z) section of the layer, per
unit length: sizes (:mod:`.discretization`), weak forms (:mod:`.forms`), the assembled
section (:mod:`.system`) and the result (:mod:`.result`)."""

from .discretization import PlaneDiscretization, resolve_plane
from .result import CylinderRollingResult
from .system import StripSystem, build_rolling_system

__all__ = ["CylinderRollingResult", "PlaneDiscretization", "StripSystem", "build_rolling_system",
           "resolve_plane"]
