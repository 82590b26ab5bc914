"""Result of a 3D steady-rolling solve (rigid sphere or roller, half layer y >= 0)."""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..result import RollingResult

__all__ = ["SphereRollingResult"]


@dataclass(frozen=True)
class SphereRollingResult(RollingResult):
    """Steady frictionless rolling of a rigid sphere (or a roller: the same fields, its axis
    the centre's line) on the layer: totals over the
    whole layer (both halves), in N, W and m.

    The attributes of :class:`~fem_reference.rolling.result.RollingResult` as totals:
    ``load`` (N), ``rolling_resistance``
    R_r = sum_j F_j x_j / R (N, the BEM's definition, paper section 2: the moment of the
    contact forces about the sphere's centre over R), ``pressure_centroid`` x_c = int p x
    dS / int p dS (m), ``dissipation`` (W) and ``pressure_power`` V int p ds/dx dS (W),
    ``rolling_resistance_energy`` D / V (N). ``leading_edge`` and ``trailing_edge`` (m)
    are the contact edges on the symmetry line y = 0, fitted as in plane strain;
    ``pressure_x``, ``pressure`` the multiplier nodes on y = 0 (m, Pa, increasing x);
    ``surface_x``, ``surface_uz`` the top-surface vertices on y = 0 (m).

    Attributes
    ----------
    zone_xy : ndarray (n_c, 2)
        (x, y) (m) of every multiplier node of the candidate half disk (y >= 0).
    zone_pressure : ndarray (n_c,)
        Contact pressure (Pa) at those nodes.
    lateral_edge : float
        Largest y (m) of a node in contact: the half-width of the contact across the
        rolling direction, to one element size.
    peak_memory : float
        Peak resident memory of the process (bytes) when the solve ended.
    factor_memory : float
        The sparse factorization's own memory report (bytes; nan for SuperLU).
    """

    zone_xy: np.ndarray = None
    zone_pressure: np.ndarray = None
    lateral_edge: float = float("nan")
    peak_memory: float = float("nan")
    factor_memory: float = float("nan")

    def summary(self):
        """Scalars, mesh and solver record as a JSON-ready dict (SI units)."""
        out = super().summary()
        out["mesh"] = asdict(self.mesh)
        out["lateral_edge"] = self.lateral_edge
        out["peak_memory"] = self.peak_memory
        out["factor_memory"] = None if not np.isfinite(self.factor_memory) else self.factor_memory
        return out
