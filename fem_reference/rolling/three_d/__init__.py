"""Steady rolling of a rigid sphere or a roller of finite length (``indenter.shape =
"cylinder"``) on the half layer y >= 0 in 3D (``fem.model = "3d"`` with a speed): sizes
(:mod:`.discretization`), weak forms of the five traceless viscous-strain components
(:mod:`.forms`), the assembled half layer (:mod:`.system`) and the result
(:mod:`.result`)."""

from .discretization import BoxDiscretization, resolve_box
from .result import SphereRollingResult
from .system import BoxSystem, build_box_system

__all__ = ["BoxDiscretization", "BoxSystem", "SphereRollingResult", "build_box_system",
           "resolve_box"]
