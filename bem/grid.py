"""Nodal grid of the candidate contact region and the Fourier truncation (paper sec. 7-8)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._checks import integer, real

__all__ = ["Grid"]


def _positive(name: str, value: float, unit: str) -> None:
    real(name, value, unit)


@dataclass(frozen=True)
class Grid:
    """Uniform grid of ``nodes_x x nodes_y`` nodes centred on the indenter axis.

    Node ``(j, i)`` sits at ``x_i = (i - (nodes_x - 1)/2) spacing_x``,
    ``y_j = (j - (nodes_y - 1)/2) spacing_y``; nodal fields are arrays of shape
    ``(nodes_y, nodes_x)``, flattened row by row as in the paper's numbering
    ``N = (j - 1) K_x + i``. Each node carries the uniform traction of its
    ``spacing_x x spacing_y`` patch (eq. 52). The layer is periodic with periods
    ``period_x, period_y`` (eqs. 19-20), which need not be multiples of the spacing, and
    the Fourier series keep the modes ``|m| <= truncation_x``, ``|n| <= truncation_y``.
    When ``2 N_t a / L`` is an odd integer the two end modes ``+-N_t`` alias onto the
    lattice's Nyquist frequency ``pi / a`` and each takes half its term
    (:func:`bem.spectral.end_weights`). With ``N_t`` an odd multiple of ``L / (2 a)`` (``L`` a
    multiple of ``a``) every lattice frequency then takes the same number of modes, and the
    truncation's kink in the nodal operator's symbol sits at Nyquist, where only odd-even
    fields feel it (``docs/derivations.md``, section 8, "End modes").

    Parameters
    ----------
    spacing_x, spacing_y : float
        Node spacings ``a_x, a_y`` (m).
    period_x, period_y : float
        Spatial periods ``L_x, L_y`` (m).
    truncation_x, truncation_y : int
        Truncation orders ``N_tx, N_ty``: must resolve the grid,
        ``N_t >= L / (2 a)`` (the paper leaves the under-resolved cell of Table 1 empty).
    nodes_x, nodes_y : int
        Node counts ``K_x, K_y``; the region must fit in one period.
    """

    spacing_x: float
    spacing_y: float
    period_x: float
    period_y: float
    truncation_x: int
    truncation_y: int
    nodes_x: int
    nodes_y: int

    def __post_init__(self) -> None:
        for ax in "xy":
            for name, unit in ((f"spacing_{ax}", "m"), (f"period_{ax}", "m")):
                object.__setattr__(self, name, real(name, getattr(self, name), unit))
            for name in (f"truncation_{ax}", f"nodes_{ax}"):
                object.__setattr__(self, name, integer(name, getattr(self, name)))
            a, L = getattr(self, f"spacing_{ax}"), getattr(self, f"period_{ax}")
            nt, kk = getattr(self, f"truncation_{ax}"), getattr(self, f"nodes_{ax}")
            if (kk - 1) * a >= L:
                raise ValueError(
                    f"nodes_{ax} = {kk} at spacing_{ax} = {a} m spans {(kk - 1) * a} m, "
                    f"which must be < period_{ax} = {L} m"
                )
            need = math.ceil(L / (2 * a) - 1e-9)
            if nt < need:
                raise ValueError(
                    f"truncation_{ax} must be >= period_{ax}/(2 spacing_{ax}) = {need} so "
                    f"that the Fourier modes resolve the node spacing, got {nt}"
                )

    @classmethod
    def centred(
        cls,
        spacing: tuple[float, float],
        period: tuple[float, float],
        truncation: tuple[int, int],
        half_width: tuple[float, float],
    ) -> "Grid":
        """Grid with a node on the axis and nodes at ``|x| <= half_width_x`` (m)."""
        counts = []
        for a, hw, name in zip(spacing, half_width, ("half_width_x", "half_width_y")):
            _positive(name, hw, "m")
            _positive("spacing", a, "m")
            counts.append(2 * int(math.floor(hw / a + 1e-9)) + 1)
        return cls(*spacing, *period, *truncation, *counts)

    @property
    def shape(self) -> tuple[int, int]:
        """Field shape ``(nodes_y, nodes_x)``."""
        return (self.nodes_y, self.nodes_x)

    @property
    def x(self) -> np.ndarray:
        """Node abscissae (m), shape ``(nodes_x,)``."""
        return (np.arange(self.nodes_x) - (self.nodes_x - 1) / 2) * self.spacing_x

    @property
    def y(self) -> np.ndarray:
        """Node ordinates (m), shape ``(nodes_y,)``."""
        return (np.arange(self.nodes_y) - (self.nodes_y - 1) / 2) * self.spacing_y

    @property
    def cell_area(self) -> float:
        """Patch area ``a_x a_y`` (m^2)."""
        return self.spacing_x * self.spacing_y

    def coordinates(self) -> tuple[np.ndarray, np.ndarray]:
        """``X, Y`` (m), each of shape ``(nodes_y, nodes_x)``."""
        return np.meshgrid(self.x, self.y)

    def summary(self) -> dict:
        """Nodes, spacing (m), period (m) and truncation, as lists ``[x, y]``."""
        return {
            "nodes": [self.nodes_x, self.nodes_y],
            "spacing": [self.spacing_x, self.spacing_y],
            "period": [self.period_x, self.period_y],
            "truncation": [self.truncation_x, self.truncation_y],
        }
