"""The steady-rolling model: a viscoelastic (Prony) layer in the frame of the indenter,
the material flowing at -V along x through a truncated layer, the viscous strains
transported along the flow (SUPG). Two geometries, one driver (:mod:`.solve`): a rigid
cylinder on the plane-strain section (:mod:`.plane_strain`) and a rigid sphere on the
half layer y >= 0 (:mod:`.three_d`); what they share: the flow lengths
(:mod:`.flow_lengths`), weak forms (:mod:`.forms`), the assembly (:mod:`.assembly`) and
the result (:mod:`.result`)."""

from .plane_strain.result import CylinderRollingResult
from .result import RollingMeshStats, RollingResult
from .solve import solve_rolling
from .three_d.result import SphereRollingResult

__all__ = ["CylinderRollingResult", "RollingMeshStats", "RollingResult", "SphereRollingResult",
           "solve_rolling"]
