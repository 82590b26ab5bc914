"""A contact problem as a composition: layer, indenter, grid and loading; the size of an
automatic region and the kernels of a problem (solved by :func:`bem.solve`)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ._checks import real
from .grid import Grid
from .layer import Layer
from .indenters import LineCylinder
from .plane import LineGrid, line_kernels
from .energy import dissipates, power_key
from .spectral import influence_kernels, kernels_with_power
from .speed import RAYLEIGH_RATIO, check_subsonic  # noqa: F401  (public here too)
from .threads import with_one_blas_thread

__all__ = ["Loading", "Problem", "check_subsonic", "compute_kernels", "auto_half_width", "kernel_memory",
           "check_kernel_memory", "line_tables"]


def kernel_memory(grid, blocks=("ww",)) -> int:
    """A lower bound (bytes) of the memory the kernel tables of ``grid`` take to compute.

    3D (:func:`bem.spectral.influence_kernels`): per block the partial sums over ``n`` of
    every ``m``, ``(N_tx + 1) (2 K_y - 1)`` complex numbers (16 bytes); two batches of 256
    rows of ``m`` over every ``n``, ``2 x 256 (N_ty + 1)`` complex symbols and as many
    products; and the per-mode vectors, 48 bytes per ``m``. (At 7 x 7 nodes, ``N_t =
    20000``: 316 MiB estimated, 560 MiB peak resident measured for the whole command.) Plane strain
    (:func:`bem.plane.line_kernel`): four complex vectors over the ``N_t + 1`` modes.
    Python integers: exact for any truncation, however large.
    """
    if isinstance(grid, LineGrid):
        return 4 * 16 * (int(grid.truncation) + 1)
    mx, my = int(grid.truncation_x) + 1, int(grid.truncation_y) + 1
    return 16 * len(tuple(blocks)) * mx * (2 * int(grid.nodes_y) - 1) + 2 * 256 * my * 16 * 2 + 48 * mx


def _physical_memory() -> int:
    """Bytes of physical memory of this machine (``os.sysconf``); 0 if unknown."""
    import os

    try:
        return int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):
        return 0


def check_kernel_memory(grid, blocks=("ww",)) -> None:
    """Raise ``ValueError`` with the estimate when the kernel tables of ``grid`` need more
    memory (:func:`kernel_memory`, a lower bound) than the machine has, before allocating."""
    need, have = kernel_memory(grid, blocks), _physical_memory()
    if have and need > have:
        sizes = (f"truncation = {grid.truncation}" if isinstance(grid, LineGrid) else
                 f"truncation = {grid.truncation_x} x {grid.truncation_y}, {grid.nodes_x} x {grid.nodes_y} nodes")
        raise ValueError(f"the kernel tables of this grid ({sizes}) need at least {need / 2**30:.3g} GiB, more "
                         f"than this machine's {have / 2**30:.3g} GiB of memory: lower grid.truncation (it must "
                         "be >= period / (2 spacing)) or grid.period")


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
        object.__setattr__(self, "speed", real("speed", self.speed, "m/s", ">=0"))
        if (self.load is None) == (self.indentation is None):
            raise ValueError("loading needs exactly one of load (N) and indentation (m), "
                             f"got load = {self.load!r}, indentation = {self.indentation!r}")
        for name, unit in (("load", "N"), ("indentation", "m")):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, real(name, getattr(self, name), unit))


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
        for name, kind, what in (("layer", Layer, "a bem.layer.Layer"), ("grid", (Grid, LineGrid),
                                 "a bem.grid.Grid or a bem.plane.LineGrid"), ("loading", Loading, "a bem.problem.Loading")):
            if not isinstance(getattr(self, name), kind):
                raise TypeError(f"Problem.{name} must be {what}, got {getattr(self, name)!r}")
        if not all(callable(getattr(self.indenter, m, None)) for m in ("profile", "rolling_arm")):
            raise TypeError("Problem.indenter must have profile(X, Y) and rolling_arm(X, Y) (a bem.indenters "
                            f"shape), got {self.indenter!r}")
        line, line_grid = isinstance(self.indenter, LineCylinder), isinstance(self.grid, LineGrid)
        if line != line_grid:
            raise TypeError(
                f"a {type(self.indenter).__name__} indenter needs a {'LineGrid' if line else 'Grid'}, got a "
                f"{type(self.grid).__name__}: plane strain (LineCylinder) is solved on a LineGrid of one row, "
                "every 3D indenter on a Grid"
            )
        check_subsonic(self.layer, self.loading.speed)
        _check_resolvable(self)

    @property
    def plane_strain(self) -> bool:
        """Whether this is a line contact per unit length (a :class:`LineCylinder`)."""
        return isinstance(self.indenter, LineCylinder)


def _check_resolvable(p: Problem) -> None:
    """Raise ``ValueError`` when the loading is lost to rounding in the gap of the node next
    to the axis.

    That gap is ``g_1 = profile(a_x, 0)`` (m) less the indentation plus the deflection,
    both of which the loading sets: the deflection under a load ``P`` is at most about
    ``P / (G(0) a_x)`` (m; ``P / G(0)`` per unit length in plane strain, P in N/m), the
    compliance of one loaded patch on the relaxed half-space. Below ``eps g_1`` (``eps``
    the double precision's 2.2e-16) the gap is ``g_1`` to the last bit whatever the load:
    the solve would return a contact of one node whose figures say nothing of the load.
    """
    g1 = float(p.indenter.profile(np.array([[p.grid.spacing_x]]), np.array([[0.0]])).ravel()[0])
    if not (math.isfinite(g1) and g1 > 0):
        return
    G0 = abs(complex(p.layer.material.modulus(0.0)))
    if p.loading.load is not None:
        reach = p.loading.load / G0 / (1.0 if p.plane_strain else p.grid.spacing_x)
        name, value, unit = "load", p.loading.load, "N/m" if p.plane_strain else "N"
    else:
        reach, name, value, unit = p.loading.indentation, "indentation", p.loading.indentation, "m"
    eps = np.finfo(float).eps
    if reach < eps * g1:
        least = eps * g1 * (1.0 if name == "indentation" else G0 * (1.0 if p.plane_strain else p.grid.spacing_x))
        raise ValueError(
            f"loading.{name} = {value!r} {unit} is lost to rounding at the scale of this problem: it moves the "
            f"surface by at most {reach:.3g} m, below the double precision of the gap {g1:.3g} m of the node "
            f"next to the axis (eps = {eps:.3g}); give loading.{name} >= {least:.3g} {unit}, or a finer "
            "grid.spacing")


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


@with_one_blas_thread
def compute_kernels(problem: Problem, blocks, progress: Callable[[str], None] | None = None, *,
                    power: bool = False) -> tuple[dict, float]:
    """Kernel tables of ``blocks`` for the problem's grid, layer and speed, with one
    progress line; returns them and the seconds they took. With ``power``, and when the
    layer absorbs power at this speed (:func:`bem.energy.dissipates`), the same dict holds
    the power tables of those blocks as well, under :func:`bem.energy.power_key` (from the
    same mode symbols, :func:`bem.spectral.kernels_with_power`): the energy figure then
    costs a few FFTs (:func:`bem.energy.dissipation_from_tables`).

    Raises ``ValueError`` at or above the shear-wave speed (:func:`check_subsonic`) and
    when a kernel is not finite (:func:`bem.spectral.influence_kernels`)."""
    p = problem
    check_subsonic(p.layer, p.loading.speed)
    power = power and dissipates(p.grid, p.layer, p.loading.speed)
    check_kernel_memory(p.grid, tuple(blocks) * (2 if power else 1))
    t0 = time.perf_counter()
    if power:
        kernels, tables = kernels_with_power(p.grid, p.layer, p.loading.speed, blocks=blocks)
        kernels.update({power_key(b): t for b, t in tables.items()})
    else:
        kernels = influence_kernels(p.grid, p.layer, p.loading.speed, blocks=blocks)
    seconds = time.perf_counter() - t0
    if progress:
        what = f"{len(tuple(blocks))} block(s)" + (" and their power tables" if power else "")
        progress(f"compliance ({what}): {p.grid.nodes_x} x {p.grid.nodes_y} nodes, "
                 f"Nt = {p.grid.truncation_x} x {p.grid.truncation_y}, {seconds:.2f} s")
    return kernels, seconds


def line_tables(p: Problem, blocks, progress) -> tuple[dict, float]:
    """The line kernels (:func:`bem.plane.line_kernels`) of ``blocks`` for a plane-strain
    problem ``p``, and their seconds, with one progress line; raises ``ValueError`` at or
    above the shear-wave speed or beyond the machine's memory."""
    check_subsonic(p.layer, p.loading.speed)
    check_kernel_memory(p.grid, blocks)
    t0 = time.perf_counter()
    tables = line_kernels(p.grid, p.layer, p.loading.speed, tuple(blocks))
    seconds = time.perf_counter() - t0
    if progress:
        which = "" if tuple(blocks) == ("ww",) else f", {len(tuple(blocks))} blocks"
        progress(f"line compliance{which}: {p.grid.nodes} nodes, Nt = {p.grid.truncation}, {seconds:.2f} s")
    return tables, seconds
