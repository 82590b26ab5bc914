"""Plane strain: a rigid cylinder in line contact with the layer, per unit length along ``y``.

The two-dimensional analogue of the paper's formulation (derivation in
``docs/derivations.md``, section "Plane strain"). Every field is uniform along ``y``, so
only the ``n = 0`` modes (``nu_y = 0``) of the layer's compliance remain, and a line load
``q`` (N/m) spread uniformly over the patch ``|x - x_N| <= a/2`` of node ``N`` deflects
the surface at node ``M`` by

    w(M) = q  sum_{|m| <= N_t}  sinc(m a / L) / L  C_ww(nu_m, 0; G*(-nu_m V))  exp(i nu_m (x_M - x_N))

with ``nu_m = 2 pi m / L`` (the end modes ``m = +-N_t`` at half weight when ``2 N_t a / L``
is an odd integer, :func:`bem.spectral.end_weights`): the 3D kernel of eqs. 56-62 with the
``n``-sum reduced to ``n = 0`` and the ``1 / L_y`` dropped (one unit of length along ``y``
instead of a patch ``a_y``). The same steady moving frame, complex modulus at ``omega_m = -nu_m V`` and
inertia ``rho V^2`` as in 3D (:mod:`bem.layer`).

:class:`LineGrid` is a grid of one row that offers the attributes
:class:`bem.operator.ComplianceOperator` and :func:`bem.contact.solve_normal` read (its
``cell_area`` is the spacing: the patch area per unit length, m), so the 3D contact
solver runs unchanged on it; forces are then per unit length (N/m) and pressures in Pa.
:func:`bem.solve` solves a :class:`bem.problem.Problem` whose indenter is a
:class:`bem.indenters.LineCylinder` on a :class:`LineGrid` and returns a
:class:`LineContact`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._checks import integer, real
from .layer import Layer, compliance_blocks, normal_compliance_outer, surface_compliance
from .mode_sums import chirp_sum
from .result import NormalContact
from .spectral import BLOCKS, end_weights

__all__ = [
    "LINE_DENSE_LIMIT", "LineGrid", "LineContact", "line_mode_symbols", "line_kernel", "line_kernel_direct",
    "line_kernels", "line_dissipation", "contact_edges", "edges_along",
]


#: contact sets of a line contact (one row of nodes) up to this many nodes are solved by
#: dense LU, frictionless (one unknown a node) and frictional (three a node): a row's sets
#: are short, and LU of a few thousand unknowns takes a fraction of a second
LINE_DENSE_LIMIT = 3000


def _positive(name: str, value, unit: str) -> None:
    real(name, value, unit)


@dataclass(frozen=True)
class LineGrid:
    """A row of ``nodes`` nodes along ``x``, centred on the cylinder's axis (plane strain).

    Node ``i`` sits at ``x_i = (i - (nodes - 1)/2) spacing`` and carries the uniform line
    load of its patch ``|x - x_i| <= spacing / 2`` (N/m spread over the patch). The layer is
    periodic in ``x`` with period ``period`` and the Fourier series keeps ``|m| <=
    truncation``.

    Parameters
    ----------
    spacing : float
        Node spacing ``a`` (m), > 0.
    period : float
        Period ``L`` (m), > the span of the nodes; need not be a multiple of ``a``.
    truncation : int
        ``N_t >= L / (2 a)``, so that the modes resolve the node spacing.
    nodes : int
        Node count ``K``, >= 1.

    Notes
    -----
    For :func:`bem.contact.solve_normal` and :class:`bem.operator.ComplianceOperator` it
    looks like a :class:`bem.grid.Grid` of one row: ``shape = (1, K)``, ``nodes_x = K``,
    ``nodes_y = 1``, ``y = [0]`` and ``cell_area = spacing`` (m^2 per m of length).
    """

    spacing: float
    period: float
    truncation: int
    nodes: int

    def __post_init__(self) -> None:
        for name in ("spacing", "period"):
            object.__setattr__(self, name, real(name, getattr(self, name), "m"))
        for name in ("truncation", "nodes"):
            object.__setattr__(self, name, integer(name, getattr(self, name)))
        if (self.nodes - 1) * self.spacing >= self.period:
            raise ValueError(
                f"nodes = {self.nodes} at spacing = {self.spacing} m span {(self.nodes - 1) * self.spacing} m, "
                f"which must be < period = {self.period} m"
            )
        need = math.ceil(self.period / (2 * self.spacing) - 1e-9)
        if self.truncation < need:
            raise ValueError(
                f"truncation must be >= period/(2 spacing) = {need} so that the Fourier modes resolve "
                f"the node spacing, got {self.truncation}"
            )

    @classmethod
    def centred(cls, spacing: float, period: float, truncation: int, half_width: float) -> "LineGrid":
        """Grid with a node on the axis and nodes at ``|x| <= half_width`` (m)."""
        _positive("spacing", spacing, "m")
        _positive("half_width", half_width, "m")
        return cls(spacing, period, truncation, 2 * int(math.floor(half_width / spacing + 1e-9)) + 1)

    # --- the Grid interface the contact solver and the operator read -------------------
    @property
    def shape(self) -> tuple[int, int]:
        """Field shape ``(1, nodes)``."""
        return (1, self.nodes)

    @property
    def nodes_x(self) -> int:
        return self.nodes

    @property
    def nodes_y(self) -> int:
        return 1

    @property
    def spacing_x(self) -> float:
        return self.spacing

    @property
    def period_x(self) -> float:
        return self.period

    @property
    def truncation_x(self) -> int:
        return self.truncation

    @property
    def x(self) -> np.ndarray:
        """Node abscissae (m), shape ``(nodes,)``."""
        return (np.arange(self.nodes) - (self.nodes - 1) / 2) * self.spacing

    @property
    def y(self) -> np.ndarray:
        """``[0.0]``: the one row."""
        return np.zeros(1)

    @property
    def cell_area(self) -> float:
        """Patch area per unit length along ``y``: the spacing ``a`` (m)."""
        return self.spacing

    def coordinates(self) -> tuple[np.ndarray, np.ndarray]:
        """``X, Y`` (m), each of shape ``(1, nodes)``."""
        return self.x[None, :], np.zeros((1, self.nodes))

    def summary(self) -> dict:
        """Nodes, spacing (m), period (m) and truncation, each a list of one entry (``x``)."""
        return {"nodes": [self.nodes], "spacing": [self.spacing], "period": [self.period],
                "truncation": [self.truncation]}


# ---------------------------------------------------------------------------------------
# kernel


def line_mode_symbols(grid: LineGrid, layer: Layer, speed: float, block: str = "ww") -> np.ndarray:
    """Fourier weights ``g_m = e_m sinc(m a / L) C_PQ(nu_m, 0) / L`` of one compliance block
    (``"ww"``, ``"wu"``, ... as :data:`bem.spectral.BLOCKS`) for ``m = 0 .. N_t``, ``e_m``
    the :func:`bem.spectral.end_weights` (those of the 3D kernels along ``x``).

    Complex, shape ``(N_t + 1,)``, in m/(N/m) = m^2/N; ``C_PQ`` of the layer at
    ``G*(-nu_m V)`` with the inertia ``rho V^2`` (``speed`` is ``V``, m/s). The modes
    ``-m`` are the complex conjugates (a real relaxation function). At ``nu_y = 0`` the
    blocks coupling ``v`` to ``w, u`` vanish and ``vv`` is the antiplane compliance.
    """
    return _symbols(grid, layer, speed, (block,))[block]


def _symbols(grid: LineGrid, layer: Layer, speed: float, blocks: tuple) -> dict:
    """:func:`line_mode_symbols` of several blocks, the layer's modes evaluated once."""
    g = grid
    m = np.arange(g.truncation + 1)
    nu = 2 * np.pi * m / g.period
    with np.errstate(over="ignore"):  # |omega| = inf is the glassy limit, finite in every material
        G = np.asarray(layer.material.modulus(-nu * speed), dtype=complex)
    weight = np.sinc(m * g.spacing / g.period) / g.period * end_weights(g.truncation, g.spacing, g.period)
    if blocks == ("ww",):
        return {"ww": normal_compliance_outer(nu, np.zeros(1), G, layer.inertia(speed), layer.thickness)[:, 0]
                * weight}
    C = compliance_blocks(nu, np.zeros_like(nu), G, layer.inertia(speed), layer.thickness, blocks)
    return {b: C[b] * weight for b in blocks}


def _check_speed(speed: float) -> None:
    if not (isinstance(speed, (int, float)) and math.isfinite(speed) and speed >= 0):
        raise ValueError(f"speed must be finite and >= 0 m/s, got {speed!r}")


def line_kernel(grid: LineGrid, layer: Layer, speed: float, block: str = "ww") -> np.ndarray:
    """Kernel table of the line grid: ``K[0, j + K - 1]`` is the deflection (m, positive
    upwards, the paper's sign) at offset ``j a`` from a unit line load (N/m, in tension)
    on a patch, for ``j = -(K-1) .. K-1``; shape ``(1, 2 K - 1)``. Another ``block``
    (:data:`bem.spectral.BLOCKS`, displacement then load direction) gives that block's
    table in the same layout: the ``n = 0`` row of the 3D kernel per unit length, which
    :func:`line_kernels` gathers for the frictional solver.

    Evaluated as ``Re(g_0 + 2 sum_{m >= 1} g_m exp(2 pi i m j a / L))`` by one chirp-z
    (Bluestein) transform, ``O(N_t log N_t)``. Raises ``ValueError`` for a bad speed or a
    non-finite kernel (naming the speed and the grid).
    """
    _check_speed(speed)
    return _tables(grid, _symbols(grid, layer, speed, (block,)), speed)[block]


def _tables(grid: LineGrid, symbols: dict, speed: float) -> dict:
    """The kernel tables of the blocks' ``symbols`` (:func:`line_kernel`)."""
    K = grid.nodes
    names = list(symbols)
    coef = 2 * np.stack([symbols[b] for b in names])
    coef[:, 0] /= 2
    tables = chirp_sum(coef, grid.spacing / grid.period, -(K - 1), 2 * K - 1).real  # one batched transform
    out = {}
    for block, table in zip(names, tables):
        _check_finite(table, block, grid, speed)
        out[block] = table[None, :]
    return out


def _check_finite(table: np.ndarray, block: str, grid: LineGrid, speed: float) -> None:
    K = grid.nodes
    if not np.isfinite(table).all():
        raise ValueError(
            f"the line kernel {block!r} is not finite at speed = {speed:g} m/s on the grid of {K} nodes "
            f"(a = {grid.spacing:g} m, L = {grid.period:g} m, N_t = {grid.truncation}): the material's "
            "modulus or the layer's compliance is not finite at some mode; use a lower loading.speed "
            "or check the material model"
        )


def line_kernel_direct(grid: LineGrid, layer: Layer, speed: float, block: str = "ww") -> np.ndarray:
    """The same table by summing every mode ``|m| <= N_t`` explicitly (``O(N_t K)``):
    the slow reference for :func:`line_kernel`."""
    _check_speed(speed)
    sym = line_mode_symbols(grid, layer, speed, block)
    full = np.concatenate([np.conj(sym[:0:-1]), sym])  # m = -N_t .. N_t
    m = np.arange(-grid.truncation, grid.truncation + 1)
    K = grid.nodes
    j = np.arange(-(K - 1), K)
    phase = 2 * np.pi * np.mod(np.outer(j, m) * (grid.spacing / grid.period), 1.0)
    return (np.exp(1j * phase) @ full).real[None, :]


def line_kernels(grid: LineGrid, layer: Layer, speed: float, blocks=tuple(BLOCKS)) -> dict:
    """:func:`line_kernel` of each of ``blocks`` (default all nine), a dict of tables of
    shape ``(1, 2 K - 1)`` (m/(N/m)): the line grid's counterpart of
    :func:`bem.spectral.influence_kernels` for the frictional solver. In plane strain
    ``wv, vw, uv, vu`` are zero (``nu_y = 0``) and ``vv`` is the antiplane compliance."""
    _check_speed(speed)
    return _tables(grid, _symbols(grid, layer, speed, tuple(blocks)), speed)


def line_dissipation(grid: LineGrid, layer: Layer, speed: float, force: np.ndarray,
                     force_x: np.ndarray | None = None) -> float:
    """Power dissipated per unit length (W/m) by compressive nodal line loads ``force``
    (N/m, shape ``(nodes,)`` or ``(1, nodes)``) and, if given, tangential ones ``force_x``
    (N/m on the layer along ``+x``) in steady motion at ``speed`` (m/s).

    The 1-D form of :func:`bem.energy.viscous_dissipation` (``n = 0`` only):
    ``P = 2 V L sum_{m > 0} nu_m Im(t_m^H C(nu_m, 0) t_m)`` with ``t_m = sinc(m a / L) / L
    sum_N (-F_N, S_N) exp(-i nu_m x_N)`` the Fourier coefficients of the traction
    (``sigma_z`` in tension, ``tau_xz``) and ``C`` the ``(w, u)`` block of the surface
    compliance, the term ``m = N_t`` times its end weight as in the kernel
    (:func:`bem.spectral.end_weights`); normal loads alone, ``|t_m|^2 Im C_ww``. It
    integrates the layer's continuous fields, independently of the nodal collocation and of the rolling arm;
    ``P / V`` is the energy figure of the rolling resistance (N/m).
    """
    g = grid
    F = np.asarray(force, float).reshape(-1)
    S = None if force_x is None else np.asarray(force_x, float).reshape(-1)
    m = np.arange(1, g.truncation + 1)
    nu = 2 * np.pi * m / g.period
    with np.errstate(over="ignore"):
        G = np.asarray(layer.material.modulus(-nu * speed), dtype=complex)
    # t_m by chirp-z: sum_N F_N exp(-2 pi i m x_N / L), x_N = (N - (K-1)/2) a
    K = g.nodes
    shift = np.exp(2j * np.pi * np.mod(m * (K - 1) / 2 * g.spacing / g.period, 1.0))
    weight = shift * np.sinc(m * g.spacing / g.period) / g.period
    rows = np.stack([-F] if S is None or not S.any() else [-F, S]).astype(complex)
    t = chirp_sum(rows, -g.spacing / g.period, 1, g.truncation) * weight
    if t.shape[0] == 1:
        C = normal_compliance_outer(nu, np.zeros(1), G, layer.inertia(speed), layer.thickness)[:, 0]
        quad = np.abs(t[0]) ** 2 * C
    else:
        C = surface_compliance(nu, np.zeros_like(nu), G, layer.inertia(speed), layer.thickness)[:, :2, :2]
        quad = np.einsum("im,mij,jm->m", t.conj(), C, t)
    ends = end_weights(g.truncation, g.spacing, g.period)[1:]
    return float(2 * speed * g.period * np.sum(nu * ends * quad.imag))


# ---------------------------------------------------------------------------------------
# results


def contact_edges(grid: LineGrid, force: np.ndarray, gap: np.ndarray | None = None) -> tuple[float, float]:
    """Trailing and leading edges (m) of the contact ``[x_t, x_l]`` from the nodal line
    loads ``force`` (N/m) and, if given, the gap ``gap`` (m) of a solve.

    At the edges of a smooth frictionless contact the pressure vanishes like
    ``sqrt(distance)`` and the gap opens like ``distance^(3/2)``. Each edge is where the
    line through ``h^(2/3)`` at the first two free nodes beyond the outermost loaded node
    reaches zero (clamped to the spacing between the outermost loaded node and the first
    free one); without a gap, or without two free nodes, where the line through ``p^2`` at
    the outermost loaded node and its inner neighbour does. Measured against 2D Hertz
    (``docs/derivations.md``, plane strain) both are within 0.13 spacings of the edge, the
    gap's within 0.10; a single loaded node gives its patch, ``x +/- a/2``.
    """
    return edges_along(grid.x, grid.spacing, force, gap)


def edges_along(x: np.ndarray, spacing: float, force: np.ndarray,
                gap: np.ndarray | None = None) -> tuple[float, float]:
    """:func:`contact_edges` on any evenly spaced row of nodes: positions ``x`` (m,
    increasing, ``spacing`` m apart), their nodal forces ``force`` (any unit, compressive
    positive) and gaps ``gap`` (m); for example the row ``y = 0`` of a 3D grid."""
    F = np.asarray(force, float).reshape(-1)
    idx = np.flatnonzero(F > 0)
    if idx.size == 0:
        raise ValueError("no node carries load: the contact has no edges")
    x, a = np.asarray(x, float), float(spacing)
    if idx.size == 1:
        return float(x[idx[0]] - a / 2), float(x[idx[0]] + a / 2)
    h = None if gap is None else np.asarray(gap, float).reshape(-1)

    def edge(outer: int, step: int) -> float:
        first, second = outer + step, outer + 2 * step
        if h is not None and 0 <= second < x.size and 0 < h[first] < h[second] and np.isfinite(h[second]):
            r = (h[first] / h[second]) ** (2 / 3)
            e = (x[first] - r * x[second]) / (1 - r)
            lo, hi = sorted((x[outer], x[first]))
            return float(min(max(e, lo), hi))
        p2o, p2i = F[outer] ** 2, F[outer - step] ** 2
        frac = p2o / (p2i - p2o) if p2i > p2o else 1.0
        return float(x[outer] + step * a * min(frac, 1.0))

    return edge(idx[0], -1), edge(idx[-1], 1)


@dataclass(frozen=True, eq=False)
class LineContact(NormalContact):
    """Frictionless line contact per unit length (plane strain): a :class:`NormalContact`
    on a :class:`LineGrid`, fields of shape ``(1, K)``.

    Units change with the dimension: ``force`` is the nodal line load (N/m), ``load`` the
    load per unit length (N/m), ``rolling_resistance`` ``sum F x / R`` (N/m),
    ``contact_area`` the contact length (m: the loaded nodes' patches), ``dissipation``
    and ``pressure_power`` W/m (the dissipation from :func:`line_dissipation`),
    ``rolling_resistance_energy`` N/m; ``pressure`` stays in Pa and ``indentation``,
    ``deflection``, ``gap``, ``trailing_edge`` and ``leading_edge`` (:func:`contact_edges`)
    in m.
    """

    @property
    def contact_radius(self) -> float:
        """Half the contact length between the edges, ``(x_l - x_t) / 2`` (m): the
        half-width ``b`` of the line contact."""
        return 0.5 * (self.leading_edge - self.trailing_edge)

    @property
    def half_width(self) -> float:
        """The same as :attr:`contact_radius` (m)."""
        return self.contact_radius

    @property
    def contact_centre(self) -> float:
        """``(x_l + x_t) / 2`` (m): the offset of the contact's middle from the axis."""
        return 0.5 * (self.leading_edge + self.trailing_edge)

    @property
    def x(self) -> np.ndarray:
        """Node abscissae (m)."""
        return self.grid.x

    @property
    def pressure_profile(self) -> np.ndarray:
        """Nodal pressure along ``x`` (Pa), shape ``(K,)``."""
        return self.pressure[0]

    def summary(self) -> dict:
        """As :meth:`NormalContact.summary` (same names, forces per unit length in N/m),
        plus ``half_width`` and ``contact_centre`` (m), ``"model": "plane strain"`` and
        the grid as lists of one entry."""
        return {**super().summary(), "model": "plane strain", "half_width": self.half_width,
                "contact_centre": self.contact_centre}
