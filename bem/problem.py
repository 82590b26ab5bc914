"""A contact problem as a composition: layer, indenter, grid and loading; and its solve."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Callable

from .contact import ContactAtEdge, NormalContact, solve_normal
from .grid import Grid
from .layer import Layer
from .indenters import LineCylinder
from .operator import ComplianceOperator
from .plane import LineGrid, solve_line
from .spectral import influence_kernels
from .speed import RAYLEIGH_RATIO, check_subsonic  # noqa: F401  (public here too)

__all__ = ["Loading", "Problem", "check_subsonic", "compute_kernels", "solve_frictionless", "auto_half_width"]


@dataclass(frozen=True)
class Loading:
    """Steady motion and normal loading.

    Parameters
    ----------
    speed : float
        ``V`` (m/s) of the indenter in ``+x``, ``>= 0`` (0: stationary contact).
    load : float, optional
        ``P`` (N), load control; per unit length (N/m) for a line contact
        (:class:`bem.indenters.LineCylinder`, plane strain).
    indentation : float, optional
        ``d`` (m), displacement control. Exactly one of ``load`` and ``indentation``.
    """

    speed: float = 0.0
    load: float | None = None
    indentation: float | None = None

    def __post_init__(self) -> None:
        if not (math.isfinite(self.speed) and self.speed >= 0):
            raise ValueError(f"speed must be >= 0 m/s, got {self.speed!r}")
        if (self.load is None) == (self.indentation is None):
            raise ValueError("loading needs exactly one of load (N) and indentation (m)")
        for name, unit in (("load", "N"), ("indentation", "m")):
            v = getattr(self, name)
            if v is not None and not (math.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be > 0 {unit}, got {v!r}")


@dataclass(frozen=True)
class Problem:
    """Rigid ``indenter`` on ``layer`` under ``loading``, discretized by ``grid``.

    A :class:`bem.indenters.LineCylinder` (plane strain, line contact) goes with a
    :class:`bem.plane.LineGrid` and a load per unit length (N/m); every other indenter with
    a :class:`bem.grid.Grid`. Raises ``ValueError`` when the speed is at or above the
    layer's shear-wave speed (see :func:`check_subsonic`), and ``TypeError`` when the
    indenter and the grid do not match.
    """

    layer: Layer
    indenter: object
    grid: Grid
    loading: Loading

    def __post_init__(self) -> None:
        line, line_grid = isinstance(self.indenter, LineCylinder), isinstance(self.grid, LineGrid)
        if line != line_grid:
            raise TypeError(
                f"a {type(self.indenter).__name__} indenter needs a {'LineGrid' if line else 'Grid'}, got a "
                f"{type(self.grid).__name__}: plane strain (LineCylinder) is solved on a LineGrid of one row, "
                "every 3D indenter on a Grid"
            )
        check_subsonic(self.layer, self.loading.speed)

    @property
    def plane_strain(self) -> bool:
        """Whether this is a line contact per unit length (a :class:`LineCylinder`)."""
        return isinstance(self.indenter, LineCylinder)


def auto_half_width(layer: Layer, indenter, loading: Loading, spacing: float) -> float:
    """Half-width (m) of a candidate region that should hold the contact.

    An upper estimate of the contact radius: Hertz on an incompressible half-space with
    the relaxed modulus ``G(0)`` (a bonded layer is stiffer, the moving contact too) under
    load control, or the radius where the profile reaches the indentation under
    displacement control; times 1.25, plus two spacings; at least half a roller's length.
    """
    R = getattr(indenter, "radius", None)
    if R is None:
        raise ValueError("give grid.half_width for an indenter without a radius")
    if isinstance(indenter, LineCylinder):  # 2D Hertz with G(0): b = sqrt(P R / (pi G0)), P in N/m
        G0 = abs(complex(layer.material.modulus(0.0)))
        if loading.load is not None:
            b = math.sqrt(loading.load * R / (math.pi * G0))
        else:
            b = math.sqrt(2 * R * loading.indentation)
        return min(1.25 * b + 2 * spacing, 0.9 * R)
    if loading.load is not None:
        G0 = abs(complex(layer.material.modulus(0.0)))
        a = (3 * loading.load * R / (16 * G0)) ** (1 / 3)
    else:
        a = math.sqrt(2 * R * loading.indentation)
    half = min(1.25 * a + 2 * spacing, 0.9 * R)
    length = getattr(indenter, "length", None)  # a roller spans its length along y
    return half if length is None else max(half, length / 2 + 2 * spacing)


def compute_kernels(problem: Problem, blocks, progress: Callable[[str], None] | None = None) -> tuple[dict, float]:
    """Kernel tables of ``blocks`` for the problem's grid, layer and speed, with one
    progress line; returns them and the seconds they took.

    Raises ``ValueError`` at or above the shear-wave speed (:func:`check_subsonic`) and
    when a kernel is not finite (:func:`bem.spectral.influence_kernels`)."""
    p = problem
    check_subsonic(p.layer, p.loading.speed)
    t0 = time.perf_counter()
    kernels = influence_kernels(p.grid, p.layer, p.loading.speed, blocks=blocks)
    seconds = time.perf_counter() - t0
    if progress:
        progress(f"compliance ({len(kernels)} block(s)): {p.grid.nodes_x} x {p.grid.nodes_y} nodes, "
                 f"Nt = {p.grid.truncation_x} x {p.grid.truncation_y}, {seconds:.2f} s")
    return kernels, seconds


def solve_frictionless(
    problem: Problem,
    progress: Callable[[str], None] | None = None,
    grow: bool = False,
    kernels: dict | None = None,
) -> tuple[NormalContact, dict]:
    """Frictionless stationary or steady rolling contact (a line contact per unit length,
    :func:`bem.plane.solve_line`, for a :class:`bem.indenters.LineCylinder`).

    Returns the contact result and the timings (s) of the kernel and of the solve. With
    ``grow=True`` (an automatically sized region) a contact that reaches the edge of the
    region widens it by half and solves again; otherwise that raises
    :class:`bem.contact.ContactAtEdge`. Pass ``kernels`` (at least the ``"ww"`` table of
    :func:`compute_kernels` for this grid, layer and speed) to reuse them; a widened
    region computes its own.
    """
    p = problem
    if p.plane_strain:
        return solve_line(p, progress=progress, grow=grow, kernels=kernels)
    given = kernels
    if given is not None and given["ww"].shape != (2 * p.grid.nodes_y - 1, 2 * p.grid.nodes_x - 1):
        raise ValueError(f"kernels['ww'] has shape {given['ww'].shape}, the grid of {p.grid.nodes_x} x "
                         f"{p.grid.nodes_y} nodes needs {(2 * p.grid.nodes_y - 1, 2 * p.grid.nodes_x - 1)}")
    while True:
        if given is not None:
            kernels, kernel_s, given = given, 0.0, None
        else:
            kernels, kernel_s = compute_kernels(p, ("ww",), progress)
        op = ComplianceOperator(p.grid, kernels["ww"])
        t1 = time.perf_counter()
        X, Y = p.grid.coordinates()
        try:
            res = solve_normal(
                op, p.indenter.profile(X, Y), load=p.loading.load,
                indentation=p.loading.indentation, arm=p.indenter.rolling_arm(X, Y),
                progress=progress,
            )
        except ContactAtEdge:
            g = p.grid
            cap = 0.95 * getattr(p.indenter, "radius", math.inf)  # the region stays under the indenter
            if not grow or max(g.x[-1], g.y[-1]) >= 0.9 * cap:
                raise
            bigger = Grid.centred(
                (g.spacing_x, g.spacing_y), (g.period_x, g.period_y),
                (g.truncation_x, g.truncation_y), (min(1.5 * g.x[-1], cap), min(1.5 * g.y[-1], cap)),
            )
            if progress:
                progress(f"contact reached the region's edge: widening to |x| <= {bigger.x[-1]:.4g} m")
            p = replace(p, grid=bigger)
            continue
        t2 = time.perf_counter()
        return res, {"kernel_s": kernel_s, "solve_s": t2 - t1}
