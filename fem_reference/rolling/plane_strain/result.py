"""Result of a plane-strain steady-rolling solve (rigid cylinder, per unit length)."""

from __future__ import annotations

from dataclasses import dataclass

from ..result import RollingResult

__all__ = ["CylinderRollingResult"]


@dataclass(frozen=True)
class CylinderRollingResult(RollingResult):
    """Steady frictionless rolling of a rigid cylinder on the layer, per unit length along
    its axis y.

    The attributes of :class:`~fem_reference.rolling.result.RollingResult` per unit
    length: ``load`` and ``rolling_resistance`` (N/m), ``dissipation`` and
    ``pressure_power`` (W/m), ``rolling_resistance_energy`` D / V (N/m); the lines along
    x are the section's own. ``contact_radius`` = ``half_width`` is the half-width b of
    the contact strip, the BEM's ``contact_radius`` of a line contact. ``mesh.lateral``
    is None.
    """
