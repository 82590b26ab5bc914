"""Result of a steady-rolling solve, what the plane-strain and 3D models have in common:
:class:`RollingResult` and :class:`RollingMeshStats`. Each model's result extends it:
:class:`~.plane_strain.result.CylinderRollingResult` (per unit length) and
:class:`~.three_d.result.SphereRollingResult` (whole-layer totals, with the contact
map)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any, Dict, Optional

import numpy as np

from ..record import SolverRecord

__all__ = ["RollingMeshStats", "RollingResult"]


@dataclass(frozen=True)
class RollingMeshStats:
    """Size of a steady-rolling discretization, plane strain or 3D (the half layer).
    Lengths in m.

    ``internal_dofs`` counts the viscous-strain unknowns (all branches and components),
    ``upstream`` and ``downstream`` the flow lengths ahead of and behind x = 0,
    ``far_size`` the largest element size, ``grading`` the growth of the size with the
    distance from the zone (-), ``lateral`` the half layer's extent in y (None in plane
    strain: per unit length).
    """

    model: str
    elements: int
    vertices: int
    displacement_dofs: int
    pressure_dofs: int
    internal_dofs: int
    unknowns: int
    contact_nodes: int
    element_size: float
    contact_zone: float
    upstream: float
    downstream: float
    lateral: Optional[float]
    far_size: float
    grading: float


@dataclass(frozen=True)
class RollingResult:
    """Steady frictionless rolling of a rigid indenter on the layer.

    Forces, moments and powers are per unit length along y in plane strain (N/m, W/m),
    totals over the whole layer in 3D (N, W); the 3D model's lines are those of the
    symmetry line y = 0.

    Attributes
    ----------
    speed : float
        V (m/s); the indenter moves in +x, the leading edge is at +x.
    load : float
        Normal load (N/m or N).
    indentation : float
        Downward rigid displacement d of the indenter's lowest point (m).
    rolling_resistance : float
        R_r = sum_j F_j x_j / R (N/m or N): the moment of the contact pressure about the
        indenter's centre divided by R (the BEM's definition, paper section 2), F_j = int
        phi_j lam the nodal contact forces.
    pressure_centroid : float
        x_c = int p x / int p (m); R_r = load x_c / R.
    leading_edge, trailing_edge : float
        x (m) of the contact's front (+x) and rear edges (on y = 0), each the zero of the
        least-squares line g^(2/3) = alpha + beta x through the gaps of the
        ``fem.fit_nodes`` surface vertices just outside it (:mod:`fem_reference.edge_fit`).
    contact_length : float
        leading_edge - trailing_edge (m).
    peak_pressure : float
        Largest nodal contact pressure (Pa).
    rolling_resistance_energy : float
        dissipation / V (N/m or N): the rolling resistance from the energy balance (the
        BEM's ``rolling_resistance_energy``); a bulk integral, it converges smoothly with
        the mesh where the pressure moment R_r carries the contact discretization's
        wobble (docs/derivations.md section 7). nan at rest.
    dissipation : float
        Power dissipated by the dashpots, integrated over the layer (W/m or W): the
        branch stresses times the dashpot strain rates, sum_i int 2 G_i (dev eps -
        eps_v,i) : (-V d eps_v,i / dx).
    pressure_power : float
        V int p ds/dx (W/m or W): the power the contact pressure puts into the layer
        (equals ``dissipation`` in steady state; R_r V is its small-slope form).
    energy_balance : float
        dissipation / pressure_power - 1 (-); nan for an elastic layer or at rest.
    pressure_x, pressure : ndarray
        Multiplier nodes x (m, increasing) and contact pressure (Pa) along x.
    surface_x, surface_uz : ndarray
        Top-surface vertices x (m) and their vertical displacement u_z (m, up positive).
    mesh : RollingMeshStats
    solver : SolverRecord
        How the solve went (:class:`~fem_reference.record.SolverRecord`).
    fields : dict
        ``mesh``, ``u``, ``p`` and the bases, for export; not compared, not printed.
    """

    speed: float
    load: float
    indentation: float
    rolling_resistance: float
    pressure_centroid: float
    leading_edge: float
    trailing_edge: float
    peak_pressure: float
    dissipation: float
    pressure_power: float
    pressure_x: np.ndarray
    pressure: np.ndarray
    surface_x: np.ndarray
    surface_uz: np.ndarray
    mesh: RollingMeshStats
    solver: SolverRecord
    fields: Dict[str, Any] = field(default=None, repr=False, compare=False)

    @property
    def contact_length(self) -> float:
        """leading_edge - trailing_edge (m)."""
        return self.leading_edge - self.trailing_edge

    @property
    def contact_radius(self) -> float:
        """Half the contact length, (leading - trailing) / 2 (m): the half-width b (the
        BEM's ``contact_radius`` of a line contact)."""
        return 0.5 * self.contact_length

    @property
    def half_width(self) -> float:
        """The same as :attr:`contact_radius` (m): a line contact's half-width b."""
        return self.contact_radius

    @property
    def contact_centre(self) -> float:
        """(leading + trailing) / 2 (m): the offset of the contact's middle from the axis."""
        return 0.5 * (self.leading_edge + self.trailing_edge)

    @property
    def rolling_resistance_energy(self) -> float:
        """dissipation / V (N/m); nan at rest."""
        return self.dissipation / self.speed if self.speed > 0 else float("nan")

    @property
    def energy_balance(self) -> float:
        """dissipation / pressure_power - 1 (-); nan when no power goes in."""
        if self.pressure_power == 0:
            return float("nan")
        return self.dissipation / self.pressure_power - 1.0

    def summary(self) -> Dict[str, Any]:
        """Scalars, mesh and solver record as a JSON-ready dict (SI units; energy_balance
        and rolling_resistance_energy None when undefined)."""
        eb = self.energy_balance
        rre = self.rolling_resistance_energy
        return {
            "speed": self.speed,
            "load": self.load,
            "indentation": self.indentation,
            "rolling_resistance": self.rolling_resistance,
            "rolling_resistance_energy": None if not np.isfinite(rre) else rre,
            "pressure_centroid_x": self.pressure_centroid,
            "leading_edge": self.leading_edge,
            "trailing_edge": self.trailing_edge,
            "contact_length": self.contact_length,
            "contact_radius": self.contact_radius,
            "half_width": self.half_width,
            "contact_centre": self.contact_centre,
            "peak_pressure": self.peak_pressure,
            "dissipation": self.dissipation,
            "pressure_power": self.pressure_power,
            "energy_balance": None if not np.isfinite(eb) else eb,
            "mesh": asdict(self.mesh),
            "solver": asdict(self.solver),
        }
