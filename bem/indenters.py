"""Rigid indenters: the gap of the unloaded surface below the indenter's lowest point.

Each indenter gives ``profile(X, Y)`` (m), the height of its lower surface above its
lowest point at the nodes (``+inf`` where it cannot touch), and ``rolling_arm(X, Y)`` (-),
the factor that turns nodal normal forces into a horizontal resisting force,
``R_r = sum_i F_i arm_i`` (paper sec. 9: ``arm = x / R`` for a body of radius ``R``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import RegularGridInterpolator

__all__ = ["Sphere", "Paraboloid", "Cylinder", "LineCylinder", "HeightMap"]


def _check_radius(radius: float) -> None:
    if not (isinstance(radius, (int, float)) and math.isfinite(radius) and radius > 0):
        raise ValueError(f"radius must be > 0 m, got {radius!r}")


@dataclass(frozen=True)
class Sphere:
    """Exact sphere of radius ``radius`` (m): ``g = R - sqrt(R^2 - r^2)`` (paper eq. 13)."""

    radius: float

    def __post_init__(self) -> None:
        _check_radius(self.radius)

    def profile(self, X, Y):
        r2 = np.asarray(X, float) ** 2 + np.asarray(Y, float) ** 2
        if np.any(r2 >= self.radius**2):
            raise ValueError(
                f"the grid reaches {math.sqrt(float(np.max(r2))):.4g} m from the axis, beyond the "
                f"sphere's radius {self.radius} m: reduce grid.half_width"
            )
        return r2 / (self.radius + np.sqrt(self.radius**2 - r2))  # R - sqrt(R^2 - r^2), no cancellation

    def rolling_arm(self, X, Y):
        return np.asarray(X, float) / self.radius


@dataclass(frozen=True)
class Paraboloid:
    """Paraboloid ``g = r^2 / (2 R)`` with ``R = radius`` (m), Hertz's approximation."""

    radius: float

    def __post_init__(self) -> None:
        _check_radius(self.radius)

    def profile(self, X, Y):
        return (np.asarray(X, float) ** 2 + np.asarray(Y, float) ** 2) / (2 * self.radius)

    def rolling_arm(self, X, Y):
        return np.asarray(X, float) / self.radius


@dataclass(frozen=True)
class Cylinder:
    """Circular roller of radius ``radius`` (m), axis along ``y``, flat ends at
    ``|y| = length / 2`` (m). The length must be finite: a roller longer than the candidate
    region would touch its edge, which the 3D model cannot represent (its contact would be
    a periodic line contact)."""

    radius: float
    length: float

    def __post_init__(self) -> None:
        _check_radius(self.radius)
        if not (isinstance(self.length, (int, float)) and math.isfinite(self.length) and self.length > 0):
            raise ValueError(f"length must be finite and > 0 m, got {self.length!r}")

    def profile(self, X, Y):
        X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
        if np.any(X**2 >= self.radius**2):
            raise ValueError(f"the grid reaches beyond the cylinder's radius {self.radius} m: reduce grid.half_width")
        g = X**2 / (self.radius + np.sqrt(self.radius**2 - X**2))
        return np.where(np.abs(Y) <= self.length / 2, g, np.inf)

    def rolling_arm(self, X, Y):
        return np.asarray(X, float) / self.radius


@dataclass(frozen=True)
class LineCylinder:
    """Rigid cylinder of radius ``radius`` (m) with its axis along ``y``, infinitely long:
    line contact in plane strain (:mod:`bem.plane`), loads per unit length (N/m).

    ``g = R - sqrt(R^2 - x^2)`` (exact circle), ``arm = x / R``; the nodes of a
    :class:`bem.plane.LineGrid` have ``Y = 0``, which the profile ignores.
    """

    radius: float

    def __post_init__(self) -> None:
        _check_radius(self.radius)

    def profile(self, X, Y=None):
        X = np.asarray(X, float)
        if np.any(X**2 >= self.radius**2):
            raise ValueError(
                f"the grid reaches |x| = {float(np.max(np.abs(X))):.4g} m, beyond the cylinder's radius "
                f"{self.radius} m: reduce grid.half_width"
            )
        return X**2 / (self.radius + np.sqrt(self.radius**2 - X**2))  # R - sqrt(R^2 - x^2), no cancellation

    def rolling_arm(self, X, Y=None):
        return np.asarray(X, float) / self.radius


@dataclass(frozen=True)
class HeightMap:
    """Any indenter given by its lower surface ``h(x, y) >= 0`` (m) on a rectangular table.

    ``x`` (m, increasing, shape ``(nx,)``), ``y`` (m, increasing, ``(ny,)``), ``h`` (m,
    ``(ny, nx)``), interpolated bilinearly at the nodes; every entry finite and ``>= 0``; outside the table the indenter
    cannot touch. The rolling arm is the slope ``dh/dx`` (the horizontal projection of a
    normal force), from centred differences of the table.
    """

    x: np.ndarray
    y: np.ndarray
    h: np.ndarray
    _interp: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        x, y, h = (np.asarray(a, float) for a in (self.x, self.y, self.h))
        if x.ndim != 1 or y.ndim != 1 or h.shape != (y.size, x.size):
            raise ValueError(f"h must have shape (len(y), len(x)) = {(y.size, x.size)}, got {h.shape}")
        for name, a in (("x", x), ("y", y)):
            if a.size < 2 or np.any(np.diff(a) <= 0):
                raise ValueError(f"{name} must be strictly increasing with >= 2 values")
        bad = np.argwhere(~(np.isfinite(h) & (h >= 0)))
        if bad.size:
            j, i = bad[0]
            raise ValueError(f"h must be finite and >= 0 m, got h[{j}, {i}] = {float(h[j, i])!r} "
                             f"at x = {float(x[i])!r} m, y = {float(y[j])!r} m")
        slope = np.gradient(h, x, axis=1)
        opts = dict(bounds_error=False, fill_value=np.inf)
        object.__setattr__(self, "_interp", (
            RegularGridInterpolator((y, x), h, **opts),
            RegularGridInterpolator((y, x), slope, bounds_error=False, fill_value=0.0),
        ))

    def profile(self, X, Y):
        X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
        return self._interp[0](np.stack([Y, X], axis=-1))

    def rolling_arm(self, X, Y):
        X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
        return self._interp[1](np.stack([Y, X], axis=-1))
