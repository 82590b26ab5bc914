"""Result of a stationary contact solve."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any, Dict

import numpy as np

from ..record import SolverRecord

__all__ = ["MeshStats", "ContactResult"]


@dataclass(frozen=True)
class MeshStats:
    """Size of the discretization. Lengths in m."""

    model: str
    elements: int
    vertices: int
    displacement_dofs: int
    pressure_dofs: int
    unknowns: int
    contact_nodes: int
    element_size: float
    contact_zone: float
    domain_radius: float
    far_size: float


@dataclass(frozen=True)
class ContactResult:
    """Stationary frictionless contact on the layer.

    Attributes
    ----------
    load : float
        Total load P on the indenter (N), the whole layer (not the quarter model).
    indentation : float
        Downward rigid displacement d of the indenter (m).
    contact_radius : float
        Radius (m) where the least-squares line g^(2/3) = alpha + beta r through the
        gaps g of the ``fem.fit_nodes`` surface vertices just outside the contact
        vanishes (g ~ (r - r_c)^(3/2) at the edge of a smooth indenter); it does
        not jump with the node spacing. See :mod:`fem_reference.edge_fit`.
    peak_pressure : float
        Largest nodal contact pressure (Pa).
    radius, nodes, pressure : ndarray
        Multiplier nodes of the candidate zone: distance from the axis (m), surface
        coordinates (m; r, or x and y), contact pressure -sigma_zz (Pa) (the
        consistent P1 traction field, the Lagrange multiplier).
    surface_radius, surface_uz : ndarray
        Top-surface vertices along a radius (all of them in the axisymmetric model,
        those on y = 0 in 3D) and their vertical displacement u_z (m, up positive).
    mesh : MeshStats
    solver : SolverRecord
        How the solve went (:class:`~fem_reference.record.SolverRecord`).
    fields : dict
        ``mesh``, ``u`` and ``p`` (skfem mesh, nodal displacement m, pressure Pa)
        for export; not compared, not printed.
    """

    load: float
    indentation: float
    contact_radius: float
    peak_pressure: float
    radius: np.ndarray
    nodes: np.ndarray
    pressure: np.ndarray
    surface_radius: np.ndarray
    surface_uz: np.ndarray
    mesh: MeshStats
    solver: SolverRecord
    fields: Dict[str, Any] = field(default=None, repr=False, compare=False)

    def summary(self) -> Dict[str, Any]:
        """Scalars, mesh and solver record as a JSON-ready dict (SI units)."""
        return {
            "contact_radius": self.contact_radius,
            "indentation": self.indentation,
            "load": self.load,
            "peak_pressure": self.peak_pressure,
            "mesh": asdict(self.mesh),
            "solver": asdict(self.solver),
        }
