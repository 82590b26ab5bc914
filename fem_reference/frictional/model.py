"""Inputs and result of the frictional steady-rolling solve on the FEM layer (plane
strain, per unit length along y; see :mod:`fem_reference.frictional.solve`). SI units."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import InputError

__all__ = ["MODES", "KINEMATICS", "RollingFriction", "FrictionalRollingResult", "RollingScalars"]

#: loading modes: the row that closes the cylinder's equilibrium
MODES = ("omega", "force", "towed", "pushed_at_top")
#: rolling geometry: profile, arm of the normal forces, rolling radius
KINEMATICS = ("small_slope", "exact")


def _number(name: str, value, unit: str, low: Optional[float] = None, strict: bool = False) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(f"{name} must be a finite number in {unit}, got {value!r}")
    if low is not None and (value < low or (strict and value == low)):
        raise InputError(f"{name} must be {'>' if strict else '>='} {low} {unit}, got {value!r}")


@dataclass(frozen=True)
class RollingFriction:
    """Coulomb friction and the loading mode of the rolling cylinder.

    Parameters
    ----------
    mu : float
        Coulomb coefficient (-), >= 0 (0 only with mode "omega": with no friction the
        rotation is indeterminate).
    mode : str
        "omega": the creepage is given (``creepage``), the driving force Q' and torque T'
        come out; "force": the horizontal force Q' (N/m) on the cylinder along +x is given
        (``driving_force``; 0 is free rolling driven by a torque); "towed": no torque
        (T' = 0), pulled at the axle; "pushed_at_top": Q' applied at the top, T' = Q' R.
    creepage : float, optional
        xi = (V - Omega R) / V (-), mode "omega" only: positive when the cylinder's
        surface turns slower than it advances (braking).
    driving_force : float
        Q' (N/m), mode "force" only (default 0).
    kinematics : str
        "small_slope": profile x^2 / 2R, arm x / R, rolling radius R (Carter's theory);
        "exact": the circle s = R - sqrt(R^2 - x^2), arm s'(x), rolling radius
        D = sqrt(R^2 - x^2) (docs/derivations.md, section 10).
    max_iterations : int
        Limit of the active-set iteration (>= 1).
    """

    mu: float
    mode: str = "omega"
    creepage: Optional[float] = None
    driving_force: float = 0.0
    kinematics: str = "small_slope"
    max_iterations: int = 200

    def __post_init__(self):
        _number("friction.mu", self.mu, "(-)", 0.0)
        if self.mode not in MODES:
            raise InputError(f"friction.mode must be one of {', '.join(MODES)}, got {self.mode!r}")
        if self.kinematics not in KINEMATICS:
            raise InputError(f"friction.kinematics must be one of {', '.join(KINEMATICS)} in the FEM "
                             f"reference, got {self.kinematics!r}")
        if (self.mode == "omega") != (self.creepage is not None):
            raise InputError(f"friction.creepage (-) is given with friction.mode = \"omega\" and only "
                             f"then, got mode = {self.mode!r}, creepage = {self.creepage!r}")
        if self.creepage is not None:
            _number("friction.creepage", self.creepage, "(-)")
        _number("friction.driving_force", self.driving_force, "N/m")
        if self.driving_force != 0 and self.mode != "force":
            raise InputError(f"friction.driving_force = {self.driving_force!r} N/m belongs to "
                             f"friction.mode = \"force\", got mode = {self.mode!r}")
        if self.mu == 0 and self.mode != "omega":
            raise InputError(f"friction.mu = 0 with friction.mode = {self.mode!r}: without friction the "
                             "cylinder's rotation is indeterminate; give mu > 0 or mode = \"omega\"")
        if isinstance(self.max_iterations, bool) or not isinstance(self.max_iterations, int) or \
                self.max_iterations < 1:
            raise InputError(f"friction.max_iterations must be an integer >= 1, got {self.max_iterations!r}")


@dataclass(frozen=True, kw_only=True)
class RollingScalars:
    """The scalars of a frictional rolling result, plane strain or 3D (per unit length in
    plane strain: N/m, W/m, N m/m; totals in 3D: N, W, N m), and R_r^F, the energy figure and
    the balance from them: ``speed`` V (m/s), ``radius`` R (m), ``mu``, ``mode``,
    ``kinematics``, ``load``, ``indentation`` (m), ``omega`` (rad/s), ``creepage`` (-),
    ``driving_force``, ``torque``, ``rolling_resistance``, ``friction_power``,
    ``dissipation``, ``iterations`` and ``times`` (s per phase); keyword-only, after the
    nodal arrays of the result classes."""

    speed: float
    radius: float
    mu: float
    mode: str
    kinematics: str
    load: float
    indentation: float
    omega: float
    creepage: float
    driving_force: float
    torque: float
    rolling_resistance: float
    friction_power: float
    dissipation: float
    iterations: int
    times: dict

    @property
    def rolling_resistance_friction(self) -> float:
        """R_r^F = friction power / V (eq. 2)."""
        return self.friction_power / self.speed

    @property
    def rolling_resistance_energy(self) -> float:
        """(bulk dissipation + friction power) / V."""
        return (self.dissipation + self.friction_power) / self.speed

    @property
    def energy_balance(self) -> float:
        """R_r / rolling_resistance_energy - 1 (-): 0 for the exact solution."""
        return self.rolling_resistance / self.rolling_resistance_energy - 1.0


@dataclass(frozen=True)
class FrictionalRollingResult(RollingScalars):
    """Steady frictional rolling of a rigid cylinder on the FEM layer, per unit length.

    Nodal arrays on the candidate nodes (x increasing): ``normal`` N_i (N/m,
    compressive), ``tangential`` S_i (N/m, on the layer along +x), ``pressure`` and
    ``shear`` (their tractions N_i / m_i, S_i / m_i, Pa), ``u_x``, ``u_z`` (m, surface
    displacements, u_z up), ``slip_velocity`` w_i (m/s, cylinder relative to the layer,
    along +x), the masks ``contact``, ``stick`` and ``slip``.

    Scalars: ``load`` P' (N/m), ``indentation`` d (m), ``omega`` (rad/s),
    ``creepage`` xi = (V - Omega R) / V (-), ``driving_force`` Q' = sum N arm + sum S
    (N/m, on the cylinder along +x), ``torque`` T' = -sum l S (N m/m, clockwise),
    ``rolling_resistance`` R_r = Q' + T' Omega / V (N/m, eq. 1),
    ``friction_power`` sum S w (W/m), ``dissipation`` the bulk (dashpot) power from the
    FEM fields (W/m), ``stick_zone`` (trailing, leading) x of the stick nodes (m, nan if
    none), ``contact_edges`` (trailing, leading) x of the contact nodes (m).
    """

    x: np.ndarray
    normal: np.ndarray
    tangential: np.ndarray
    pressure: np.ndarray
    shear: np.ndarray
    u_x: np.ndarray
    u_z: np.ndarray
    slip_velocity: np.ndarray
    contact: np.ndarray
    stick: np.ndarray
    slip: np.ndarray

    @property
    def tangential_force(self) -> float:
        """sum S (N/m): the friction force on the layer along +x (Carter's Q)."""
        return float(self.tangential.sum())

    @property
    def stick_zone(self):
        """(trailing, leading) x (m) of the stick nodes; (nan, nan) in full slip."""
        xs = self.x[self.stick]
        return (float(xs.min()), float(xs.max())) if xs.size else (math.nan, math.nan)

    @property
    def contact_edges(self):
        """(trailing, leading) x (m) of the contact nodes."""
        xs = self.x[self.contact]
        return float(xs.min()), float(xs.max())
