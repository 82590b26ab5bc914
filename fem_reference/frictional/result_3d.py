"""Result of the frictional steady rolling of a sphere on the 3D FEM half layer
(:mod:`fem_reference.frictional.three_d`). SI units."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .model import RollingScalars

__all__ = ["FrictionalSphereResult"]


@dataclass(frozen=True)
class FrictionalSphereResult(RollingScalars):
    """Steady frictional rolling of a rigid sphere on the layer.

    Nodal arrays on the candidate nodes of the half layer y >= 0 (``xy``, m; ``weights``
    m_i = int phi_i dS over y >= 0, m^2): ``normal`` N_i (N, compressive), ``tangential``
    (n, 2) S_i (N, on the layer along +x, +y), ``u`` (n, 3) surface displacements (m,
    u_z up), ``slip_velocity`` (n, 2) w_i (m/s, sphere relative to the layer), the masks
    ``contact``, ``stick`` and ``slip``. Nodal forces are the half layer's: a node on y =
    0 carries half the whole layer's force there.

    Scalars (totals over the whole layer): ``load`` P (N), ``indentation`` d (m),
    ``omega`` (rad/s), ``creepage`` xi = (V - Omega R) / V (-), ``driving_force`` Q = sum N
    arm + sum S_x (N, on the sphere along +x), ``torque`` T = -sum l S_x (N m),
    ``rolling_resistance`` R_r = Q + T Omega / V (N, paper eq. 1), ``friction_power`` sum S
    . w over the slip nodes (W), ``dissipation`` the dashpots' power from the FEM fields
    (W); ``rolling_resistance_friction``, ``rolling_resistance_energy`` (N) and
    ``energy_balance`` (-) from :class:`~.model.RollingScalars`.
    """

    xy: np.ndarray
    weights: np.ndarray
    normal: np.ndarray
    tangential: np.ndarray
    u: np.ndarray
    slip_velocity: np.ndarray
    contact: np.ndarray
    stick: np.ndarray
    slip: np.ndarray

    @property
    def contact_area(self) -> float:
        """2 sum m_i over the contact nodes (m^2)."""
        return 2.0 * float(self.weights[self.contact].sum())

    @property
    def stick_area(self) -> float:
        """2 sum m_i over the stick nodes (m^2)."""
        return 2.0 * float(self.weights[self.stick].sum())

    @property
    def stick_fraction(self) -> float:
        """stick_area / contact_area (-)."""
        return self.stick_area / self.contact_area

    @property
    def contact_edges(self):
        """(trailing, leading) x (m) of the contact nodes on y = 0."""
        on = self.contact & (self.xy[:, 1] <= 1e-12 * np.ptp(self.xy[:, 0]))
        xs = self.xy[on, 0]
        return (float(xs.min()), float(xs.max())) if xs.size else (math.nan, math.nan)
