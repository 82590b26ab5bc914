"""The stationary contact model: an elastic layer indented at rest, in the axisymmetric
(r, z) section or in a quarter cylinder in 3D (Taylor-Hood P2-P1, a P1 contact
multiplier on the candidate zone). Sizes (:mod:`.discretization`), weak forms
(:mod:`.forms`), the assembled layer (:mod:`.system`), the driver (:mod:`.solve`) and
its result (:mod:`.result`)."""

from .result import ContactResult, MeshStats
from .solve import solve_stationary

__all__ = ["ContactResult", "MeshStats", "solve_stationary"]
