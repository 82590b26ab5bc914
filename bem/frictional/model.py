"""Steady rolling and sliding with Coulomb friction (paper eqs. 1-4, 14-18, 51, 63).

Unknowns (nodal fields, N): the compressive normal forces ``N >= 0``, the tangential
forces on the layer ``S = (S_x, S_y)`` (the paper's ``F_U, F_V``; the indenter receives
``-S``), the indentation ``d`` (m), the rotational speed ``Omega`` (rad/s) and the driving
load (``Q`` in N, ``T`` in N m). Displacements (eq. 51, ``F_W = -N``):

    delta = C_ww N - C_wu S_x - C_wv S_y      (downward, m)
    u     = -C_uw N + C_uu S_x + C_uv S_y,    v = -C_vw N + C_vu S_x + C_vv S_y

Contact: gap ``h = s - d + delta >= 0``, ``N >= 0``, ``N h = 0``. Friction (eqs. 16-18) with
the slip velocity ``w`` of :mod:`bem.kinematics` (upwind ``d/dx``): stick ``w = 0``,
``|S| <= mu N``; slip ``S = mu N w / |w|`` (the indenter drags the layer along its own
relative motion and is resisted by the opposite force).

Sphere equilibrium, small-slope contact on a body of revolution about the ``y`` axis
(the paper's sec. 2: normal stresses radial, tangential ones circumferential): a normal
force passes through the centre (no moment) and has the horizontal component
``N arm`` (``arm = dg/dx``, ``x / R`` to small slope as in the frictionless solver); a
tangential force acts at the rolling radius ``l`` (:func:`bem.kinematics.rolling_geometry`). With ``Q`` (N) applied at the height ``h_Q`` above
the centre (``R``: pushed at the top; 0: at the axle) and ``T_a`` (N m) at the axle:

    sum N = P,     Q = sum N arm + sum S_x,     T = T_a + h_Q Q = -sum l S_x

and ``R_r = Q + T Omega / V`` (eqs. 1, 63; eq. 63's ``sum F_U`` is the horizontal resultant
``sum N arm + sum S_x``). Loading modes close the system with one linear equation:
``pushed_at_top`` (``h_Q = R, T_a = 0``), ``towed`` (``h_Q = 0, T_a = 0``), ``torque``
(``Q = 0``), ``omega`` (``Omega`` given; ``Q`` and ``T`` both come out). Without friction
``S = 0``, ``T = 0`` and ``R_r = sum N arm``: the frictionless solution.

Energy: the rigid-body power ``R_r V`` equals the layer's power ``-V sum F . du/dx``
plus the friction power ``sum S . w`` plus ``V sum N (arm - dg/dx)`` (whatever ``l``, as
long as the slip velocity and the torque share it). The last term vanishes when the arm
is the profile slope: kinematics ``exact`` and ``small_slope``
(:func:`bem.kinematics.rolling_geometry`); with ``paper`` (arm ``x / R`` on the exact
sphere) it is ``O(r^2/R^2)`` of ``R_r`` (docs/derivations.md, "Rolling kinematics").

Solver: the package :mod:`bem.frictional` (Kalker's active set on contact, stick and slip sets;
entry point :func:`bem.solve_friction`).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field

import numpy as np

from ..contact import SHARED_SCALARS, ContactError, ContactFigures, ContactNotConverged, grid_summary
from .._checks import NotANumber, real
from ..grid import Grid
from ..plane import LineGrid, edges_along
from ..kinematics import DEFAULT_KINEMATICS, KINEMATICS

__all__ = [
    "MODES", "Friction", "FrictionRecord", "FrictionalContact", "FrictionNotConverged",
    "LoadingUnreachable",
]

#: loading modes that close the sphere's equilibrium
MODES = ("pushed_at_top", "towed", "torque", "omega")


class FrictionNotConverged(ContactNotConverged):
    """The stick/slip active set or the slip directions did not converge."""


class LoadingUnreachable(ContactError):
    """Friction cannot carry the load the loading mode asks for (e.g. ``mu`` too small
    to transmit the torque of a sphere pushed at the top)."""


@dataclass(frozen=True)
class Friction:
    """Coulomb friction and the loading mode of a rolling or sliding indenter.

    Parameters
    ----------
    mu : float
        Coefficient of sliding friction (-), ``>= 0``.
    mode : str
        One of :data:`MODES`: ``pushed_at_top`` (``Q`` at the top, ``T = Q R``; the paper's
        case, eq. 4), ``towed`` (``Q`` at the axle, ``T = 0``), ``torque`` (driven by a torque
        at the axle, ``Q = 0``), ``omega`` (``Omega`` prescribed).
    omega : float, optional
        ``Omega`` (rad/s), positive for forward rolling (clockwise with ``+x`` to the right
        and ``+z`` up); mode ``omega`` only (0 is pure sliding).
    radius : float, optional
        Distance (m) from the axis of rotation to the lowest point, for indenters
        without a radius (height maps); defaults to the indenter's radius.
    kinematics : str
        One of :data:`bem.kinematics.KINEMATICS`, the rolling geometry
        (:func:`bem.kinematics.rolling_geometry`): ``paper`` (the default: eq. 14 as printed
        with the arm ``x / R`` on the exact sphere, the frictionless solver's geometry, to
        reproduce the paper's figures; its equilibrium figure is about ``r^2 / 2R^2`` below
        the energy one), ``exact`` (the indenter's own
        surface for the gap, the arm of the normal forces and the rolling radius: the
        equilibrium and energy figures of ``R_r`` agree to the discretisation error),
        ``small_slope`` (all to first order in the slope: a sphere is solved as the
        paraboloid, arm ``x / R``, rolling radius ``R``; also consistent).
    max_iter : int
        Active-set iterations allowed (> 0).
    direction_tol : float
        Convergence of the slip law on slip nodes: largest of ``||S| / (mu N) - 1|`` and
        ``|sin|`` of the angle between ``S`` and ``w`` (-), > 0.
    dense_limit : int
        Largest linear system (unknowns, three per contact node) solved by dense LU; larger
        ones use GMRES with FFT products, preconditioned by exact solves on each grid row of
        contact nodes (:mod:`bem.frictional.preconditioner`), >= 0. The frictionless start
        is solved densely up to ``dense_limit // 3`` contact nodes.
    set_tol : float
        When the stick/slip sets alternate between two states (a node on the stick/slip
        border of the discrete problem), the state is accepted if a stick node exceeds the
        cone by less than ``set_tol mu N`` and a slip node's force opposes its slip velocity
        by less than ``set_tol V`` (-), >= 0; otherwise the solve raises.
    """

    mu: float
    mode: str = "pushed_at_top"
    omega: float | None = None
    radius: float | None = None
    kinematics: str = DEFAULT_KINEMATICS
    max_iter: int = 300
    direction_tol: float = 1e-7
    set_tol: float = 1e-2
    dense_limit: int = 600

    def __post_init__(self) -> None:
        # the number types first (booleans refused, numpy scalars taken as Python numbers),
        # then each field's rule
        for name, unit, rule in (("mu", "", ">=0"), ("omega", "rad/s", "any"), ("radius", "m", ">0"),
                                 ("direction_tol", "", ">0"), ("set_tol", "", ">=0")):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, real(name, getattr(self, name), unit, rule, finite=False))
        for name, least in (("max_iter", 1), ("dense_limit", 0)):
            value = getattr(self, name)
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
                raise NotANumber(f"{name} must be an integer {'> 0' if least else '>= 0'}, got {value!r}")
            object.__setattr__(self, name, int(value))
        if not (math.isfinite(self.mu) and self.mu >= 0):
            raise ValueError(f"mu must be >= 0, got {self.mu!r}")
        if self.mode not in MODES:
            raise ValueError(f"mode must be one of {', '.join(MODES)}, got {self.mode!r}")
        if (self.mode == "omega") != (self.omega is not None):
            raise ValueError(f"omega (rad/s) must be given with mode = 'omega' and only then, "
                             f"got mode = {self.mode!r}, omega = {self.omega!r}")
        if self.omega is not None and not math.isfinite(self.omega):
            raise ValueError(f"omega must be finite (rad/s), got {self.omega!r}")
        if self.radius is not None and not (math.isfinite(self.radius) and self.radius > 0):
            raise ValueError(f"radius must be > 0 m, got {self.radius!r}")
        if self.kinematics not in KINEMATICS:
            raise ValueError(f"kinematics must be one of {', '.join(KINEMATICS)}, got {self.kinematics!r}")
        if not (isinstance(self.max_iter, int) and self.max_iter > 0):
            raise ValueError(f"max_iter must be an integer > 0, got {self.max_iter!r}")
        if not (self.direction_tol > 0):
            raise ValueError(f"direction_tol must be > 0, got {self.direction_tol!r}")
        if not (isinstance(self.dense_limit, int) and self.dense_limit >= 0):
            raise ValueError(f"dense_limit must be an integer >= 0, got {self.dense_limit!r}")
        if not (self.set_tol >= 0):
            raise ValueError(f"set_tol must be >= 0, got {self.set_tol!r}")


@dataclass(frozen=True)
class FrictionRecord:
    """How the frictional solve went.

    ``iterations`` of the active set; ``history`` one tuple per iteration
    ``(contact nodes, stick nodes, largest slip-direction change, Omega)``;
    ``linear_solver`` (``dense`` or ``gmres``) and ``linear_iterations`` (GMRES, summed
    over the active-set iterations); all on the solve's own grid, not counting the
    coarse-grid start (whose lines the progress callback shows); residuals at the
    end: ``gap_residual`` (max ``|h|`` on contact and penetration elsewhere, relative to
    ``d``), ``stick_residual`` (max ``|w| / V`` on stick nodes), ``coulomb_residual``
    (max of ``|S| / (mu N) - 1`` on stick nodes and of the slip-direction misfit);
    ``times`` (s) of the stages of :func:`bem.solve` (``kernel_s``, ``solve_s``,
    ``energy_s``), empty for a solve on prepared operators.
    """

    iterations: int
    history: tuple
    linear_solver: str
    linear_iterations: int
    gap_residual: float
    stick_residual: float
    coulomb_residual: float
    times: dict = field(default_factory=dict, compare=False)

    @property
    def residual(self) -> float:
        """The largest of the three residuals (-), the figure every solver record has."""
        return max(self.gap_residual, self.stick_residual, self.coulomb_residual)


@dataclass(frozen=True, eq=False)
class FrictionalContact(ContactFigures):
    """Result of a frictional rolling/sliding solve; fields are ``(K_y, K_x)`` arrays.

    In plane strain (a :class:`bem.plane.LineGrid`, :attr:`plane_strain`) the fields are
    ``(1, K)`` and every force is per unit length along ``y``: nodal forces, ``load``,
    ``driving_force`` and the rolling resistances in N/m, ``driving_torque`` in N m/m,
    ``contact_area`` in m (the contact length); pressures and tractions stay in Pa,
    ``friction_power`` is in W/m; ``force_y``, ``displacement_y`` and ``slip_y`` vanish
    (the antiplane problem is unloaded: zero to rounding).

    Attributes
    ----------
    grid : Grid or LineGrid
    force : ndarray
        Compressive nodal normal forces ``N`` (N).
    force_x, force_y : ndarray
        Tangential nodal forces on the layer (N), along ``+x, +y``.
    deflection, displacement_x, displacement_y : ndarray
        Surface displacements (m): downward, along ``+x``, along ``+y``.
    gap : ndarray
        ``h`` (m).
    slip_x, slip_y : ndarray
        Slip velocity ``w`` (m/s), indenter relative to layer (eqs. 14-15); 0 off contact.
    stick : ndarray of bool
        Contact nodes in stick.
    indentation, load, omega, driving_force, driving_torque : float
        ``d`` (m), ``P`` (N), ``Omega`` (rad/s), ``Q`` (N), ``T`` (N m, about the centre).
    rolling_resistance, rolling_resistance_friction, rolling_resistance_viscous : float
        ``R_r`` (eq. 1), ``R_r^F`` (eq. 2), ``R_r^V = R_r - R_r^F`` (eq. 3), in N. ``R_r``
        is the equilibrium figure (eq. 63, ``Q + T Omega / V`` with the arm ``x / R``).
    rolling_resistance_energy : float
        The energy figure ``(P_visc + P_fric) / V`` (N): the layer's dissipation computed
        independently from its loss modulus (:func:`bem.energy.viscous_dissipation`) plus
        the friction power ``sum S . w``; ``nan`` when not computed. With kinematics
        ``exact`` or ``small_slope`` the two figures agree to the discretisation error
        (at most 0.23 % measured on the paper's section 11 from 0.5 to 0.0625 mm; exact at
        0.25 mm: ``R_r`` 3.080 N, energy 3.073 N). With ``paper`` they differ by
        ``sum N x (1/zeta - 1/R)``, ``zeta = sqrt(R^2 - r^2)``: the sphere's surface slope
        ``x / zeta`` does work on the layer, the arm ``x / R`` (sec. 9) enters the
        equilibrium; about ``r^2 / 2R^2`` of ``R_r`` (1.3 % at 0.25 mm: ``R_r`` = 3.035 N,
        energy 3.074 N, the paper's 3.07 N).
    speed, mu : float
        ``V`` (m/s), ``mu`` (-).
    mode : str
    record : FrictionRecord
    kinematics : str
        The rolling geometry solved (:data:`bem.kinematics.KINEMATICS`).
    """

    grid: Grid
    force: np.ndarray
    force_x: np.ndarray
    force_y: np.ndarray
    deflection: np.ndarray
    displacement_x: np.ndarray
    displacement_y: np.ndarray
    gap: np.ndarray
    slip_x: np.ndarray
    slip_y: np.ndarray
    stick: np.ndarray
    indentation: float
    load: float
    omega: float
    driving_force: float
    driving_torque: float
    rolling_resistance: float
    rolling_resistance_friction: float
    rolling_resistance_viscous: float
    speed: float
    mu: float
    mode: str
    record: FrictionRecord
    rolling_resistance_energy: float = math.nan
    kinematics: str = DEFAULT_KINEMATICS

    @property
    def slip(self) -> np.ndarray:
        """Contact nodes in slip."""
        return self.contact & ~self.stick

    @property
    def traction_x(self) -> np.ndarray:
        """``tau_xz`` on the layer (Pa)."""
        return self.force_x / self.grid.cell_area

    @property
    def traction_y(self) -> np.ndarray:
        """``tau_yz`` on the layer (Pa)."""
        return self.force_y / self.grid.cell_area

    @property
    def stick_fraction(self) -> float:
        """Stick nodes over contact nodes (-)."""
        n = int(self.contact.sum())
        return float((self.stick & self.contact).sum()) / n if n else math.nan

    @property
    def friction_power(self) -> float:
        """``sum S . w`` over the contact (W), eq. 2 times ``V``."""
        return float((self.force_x * self.slip_x + self.force_y * self.slip_y).sum())

    @property
    def contact_radius(self) -> float:
        """In 3D the equivalent radius ``sqrt(area / pi)`` (m); in plane strain the
        half-width ``(x_l - x_t) / 2`` (m) between the contact's edges
        (:func:`bem.plane.contact_edges`), as :attr:`bem.plane.LineContact.contact_radius`."""
        if not self.plane_strain:
            return super().contact_radius
        trailing, leading = edges_along(self.grid.x, self.grid.spacing, self.force[0], self.gap[0])
        return 0.5 * (leading - trailing)

    @property
    def plane_strain(self) -> bool:
        """Whether this is a line contact per unit length (a grid of one row,
        :class:`bem.plane.LineGrid`): forces then in N/m, torques in N m/m."""
        return isinstance(self.grid, LineGrid)

    def summary(self) -> dict:
        """The scalars (SI units), the grid and the solve record as a dict; the keys shared
        with :meth:`bem.contact.NormalContact.summary` name the same quantities (``nan``
        where a figure was not computed); ``"model": "plane strain"`` for a line contact
        (forces per unit length, N/m)."""
        r = self.record
        return {
            **{name: getattr(self, name) for name in SHARED_SCALARS},
            "rolling_resistance_friction": self.rolling_resistance_friction,
            "rolling_resistance_viscous": self.rolling_resistance_viscous,
            "rolling_resistance_energy": self.rolling_resistance_energy,
            "omega": self.omega,
            "driving_force": self.driving_force,
            "driving_torque": self.driving_torque,
            "stick_fraction": self.stick_fraction,
            "mu": self.mu,
            "mode": self.mode,
            "kinematics": self.kinematics,
            "speed": self.speed,
            **({"model": "plane strain"} if self.plane_strain else {}),
            "grid": grid_summary(self.grid),
            "solver": {"iterations": r.iterations, "residual": r.residual, "history": [list(h) for h in r.history],
                       "gap_residual": r.gap_residual, "stick_residual": r.stick_residual,
                       "coulomb_residual": r.coulomb_residual, "linear_solver": r.linear_solver,
                       "linear_iterations": r.linear_iterations},
        }
