"""A contact problem as a composition: layer, indenter, grid and loading; the size of an
automatic region and the kernels of a problem (solved by :func:`bem.solve`)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable

from .grid import Grid
from .layer import Layer
from .indenters import LineCylinder
from .plane import LineGrid
from .spectral import influence_kernels
from .speed import RAYLEIGH_RATIO, check_subsonic  # noqa: F401  (public here too)

__all__ = ["Loading", "Problem", "check_subsonic", "compute_kernels", "auto_half_width"]


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
