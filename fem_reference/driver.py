"""The one entry point, :func:`solve`: a problem goes to the driver of its model.

Stationary contact (``fem.model`` "axisymmetric", or "3d" at rest) is solved by
:func:`~fem_reference.stationary.solve.solve_stationary`; steady rolling (a line
indenter in plane strain, or a sphere with ``fem.model = "3d"`` and ``loading.speed`` >
0) by :func:`~fem_reference.rolling.solve.solve_rolling`.
"""

from __future__ import annotations

from typing import Callable, Optional, Union

from .problem import ContactProblem
from .rolling.result import RollingResult
from .rolling.solve import solve_rolling
from .stationary.result import ContactResult
from .stationary.solve import solve_stationary

__all__ = ["solve"]


def solve(problem: ContactProblem, progress: Optional[Callable[[str], None]] = None
          ) -> Union[ContactResult, RollingResult]:
    """Solve the frictionless contact of ``problem``: stationary (axisymmetric or 3D),
    or steady rolling: of a line indenter in plane strain, of a sphere in 3D
    (``fem.model = "3d"`` and ``loading.speed`` > 0).

    Parameters
    ----------
    problem : ContactProblem
        Layer, material, indenter, loading and ``fem`` settings (SI units).
    progress : callable, optional
        Receives one line of text per stage and per active-set iteration.

    Returns
    -------
    ContactResult or RollingResult
        A :class:`~fem_reference.stationary.result.ContactResult` at rest; when rolling a
        :class:`~fem_reference.rolling.result.RollingResult`: a
        :class:`~fem_reference.rolling.plane_strain.result.CylinderRollingResult` for a
        line indenter, a :class:`~fem_reference.rolling.three_d.result.SphereRollingResult`
        for a sphere.

    Raises
    ------
    InputError, MeshError, LinearSolverError, ContactNotConvergedError, ContactZoneError
        See :mod:`fem_reference.errors`.
    """
    model = problem.fem.model
    if model == "plane_strain" or (model == "3d" and problem.loading.speed > 0):
        return solve_rolling(problem, progress)
    return solve_stationary(problem, progress)
