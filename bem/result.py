"""What a frictionless contact solve returns: the fields, the scalars, the physics of the
rolling contact (its dissipation, the pressure's power, the contact's edges) and how the
solve went.

:class:`NormalContact` is the result of :func:`bem.solve` without friction (and, with
the rolling figures left ``nan``, of :func:`bem.contact.solve_normal` on a prepared
operator); :class:`bem.plane.LineContact` extends it in plane strain and
:class:`bem.frictional.FrictionalContact` shares its figures (:class:`ContactFigures`)
and its scalar names (:data:`SHARED_SCALARS`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .grid import Grid

__all__ = ["SolveRecord", "ContactFigures", "NormalContact", "SHARED_SCALARS", "ROLLING_SCALARS",
           "pressure_centroid_x", "grid_summary"]

#: the scalars every BEM result reports under the same names (SI units)
SHARED_SCALARS = ("rolling_resistance", "indentation", "contact_radius", "load", "peak_pressure", "contact_area",
                  "pressure_centroid_x")
#: the figures of a frictionless rolling contact (SI units; ``nan`` where not computed)
ROLLING_SCALARS = ("speed", "rolling_resistance_energy", "dissipation", "pressure_power", "trailing_edge",
                   "leading_edge")


@dataclass(frozen=True)
class SolveRecord:
    """How a solve went, in the vocabulary of every solver of the project: active-set
    ``iterations``, ``history`` (contact-node counts per iteration), ``linear_solver``
    (``dense`` or ``gmres``) and its total ``linear_iterations``, the final
    complementarity ``residual`` ``max(|min(F, h)|)`` relative to the indentation scale,
    and ``times`` (s) of the solve's stages: ``kernel_s`` (the influence kernels, 0 when
    given), ``solve_s`` (the contact) and ``energy_s`` (the rolling figures); empty for a
    solve on a prepared operator."""

    iterations: int
    history: tuple
    linear_solver: str
    linear_iterations: int
    residual: float
    times: dict = field(default_factory=dict, compare=False)


class ContactFigures:
    """The figures of a contact result computed from its ``grid`` and its compressive nodal
    forces ``force`` (N): pressure, contact set, area, equivalent radius, peak pressure
    and the centre of pressure (shared by :class:`NormalContact` and
    :class:`bem.frictional.FrictionalContact`)."""

    @property
    def pressure(self) -> np.ndarray:
        """Nodal pressure ``force / (a_x a_y)`` (Pa)."""
        return self.force / self.grid.cell_area

    @property
    def contact(self) -> np.ndarray:
        """Nodes in contact (``force > 0``)."""
        return self.force > 0

    @property
    def contact_area(self) -> float:
        """Area of the contact patches, ``a_x a_y`` per contact node (m^2)."""
        return float(self.contact.sum()) * self.grid.cell_area

    @property
    def contact_radius(self) -> float:
        """Equivalent radius ``sqrt(area / pi)`` (m): the radius of the disc of the same
        area, which moves smoothly with the load instead of by whole node spacings."""
        return math.sqrt(self.contact_area / math.pi)

    @property
    def peak_pressure(self) -> float:
        """Largest nodal pressure (Pa)."""
        return float(self.pressure.max())

    @property
    def pressure_centroid_x(self) -> float:
        """``x`` of the resultant normal force (m); ``> 0`` means shifted to the leading edge."""
        return pressure_centroid_x(self.grid, self.force)


@dataclass(frozen=True, eq=False)
class NormalContact(ContactFigures):
    """Result of a frictionless contact solve; fields are ``(K_y, K_x)`` arrays.

    Attributes
    ----------
    grid : Grid
    force : ndarray
        Compressive nodal forces ``F`` (N).
    deflection : ndarray
        Downward surface displacement ``u = C F`` (m).
    gap : ndarray
        ``h = s - d + u`` (m), ``>= 0``.
    indentation : float
        ``d`` (m).
    load : float
        ``P = sum F`` (N).
    rolling_resistance : float
        ``R_r = sum F_i arm_i`` (N), the paper's ``sum F_i x_i / R`` for round indenters.
    record : SolveRecord
    coarse : NormalContact or None
        The same problem solved on the coarse level (every other node, or the middle of
        each pair along an even-sized axis: :func:`bem.coarse_levels.coarse_level`),
        whose contact set and forces started this solve; ``None`` when there was none. The
        frictional solver's own coarse levels reuse it instead of solving it again.
    speed : float
        ``V`` (m/s) of the indenter; ``nan`` for a solve on a prepared operator, which
        does not know it.
    dissipation : float
        ``P_visc`` (W): the power the layer dissipates, summed in Fourier space from its
        loss modulus (:func:`bem.energy.viscous_dissipation`; by FFTs from the power
        tables when the kernels carry them, :func:`bem.energy.layer_power`), independently
        of the nodal collocation and of the rolling arm; 0 at rest, ``nan`` when not computed.
    pressure_power : float
        ``V sum F_i ds/dx(x_i)`` (W): the power the pressure puts into the layer, with
        the indenter's exact slope (a central difference of its profile over a thousandth
        of the node spacing). In steady rolling it equals ``dissipation`` up to the
        discretization; ``R_r V`` is its small-slope form (the arm ``x / R`` for
        ``ds/dx``).
    trailing_edge, leading_edge : float
        The contact's edges on the line ``y = 0`` (m, ``x > 0`` ahead), read from the
        forces and gaps of that row (:func:`bem.plane.edges_along`); ``nan`` when the
        grid has no row on ``y = 0`` or no node of it carries load.
    """

    grid: Grid
    force: np.ndarray
    deflection: np.ndarray
    gap: np.ndarray
    indentation: float
    load: float
    rolling_resistance: float
    record: SolveRecord
    coarse: NormalContact | None = field(default=None, repr=False, compare=False)
    speed: float = math.nan
    dissipation: float = math.nan
    pressure_power: float = math.nan
    trailing_edge: float = math.nan
    leading_edge: float = math.nan

    @property
    def rolling_resistance_energy(self) -> float:
        """``P_visc / V`` (N): the energy figure of the rolling resistance, equal in steady
        rolling to the pressure's work rate over ``V`` (``pressure_power / V``); ``nan``
        at rest or when not computed."""
        return self.dissipation / self.speed if self.speed > 0 else math.nan

    def summary(self) -> dict:
        """The scalars (SI units), the grid and the solve record as a JSON-ready dict; the
        keys it shares with :meth:`bem.frictional.FrictionalContact.summary` and
        ``fem_reference``'s results name the same quantities."""
        r = self.record
        return {
            **{name: getattr(self, name) for name in SHARED_SCALARS + ROLLING_SCALARS},
            "grid": self.grid.summary(),
            "solver": {"iterations": r.iterations, "residual": r.residual, "history": list(r.history),
                       "linear_solver": r.linear_solver, "linear_iterations": r.linear_iterations},
        }


def pressure_centroid_x(grid: Grid, force: np.ndarray) -> float:
    """``x`` (m) of the resultant of the compressive nodal forces ``force`` (N) on ``grid``."""
    X, _ = grid.coordinates()
    return float((force * X).sum() / force.sum())


def grid_summary(grid: Grid) -> dict:
    """Nodes, spacing (m), period (m) and truncation of a grid (:meth:`bem.grid.Grid.summary`)."""
    return grid.summary()
