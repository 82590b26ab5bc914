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

from ._checks import real

__all__ = ["Sphere", "Paraboloid", "Cylinder", "LineCylinder", "HeightMap"]


def _check_radius(indenter, name: str = "radius") -> None:
    """Check the length ``name`` (m, > 0) of ``indenter`` and store it as a float."""
    object.__setattr__(indenter, name, real(name, getattr(indenter, name), "m"))


@dataclass(frozen=True)
class Sphere:
    """Exact sphere of radius ``radius`` (m): ``g = R - sqrt(R^2 - r^2)`` (paper eq. 13)."""

    radius: float

    def __post_init__(self) -> None:
        _check_radius(self)

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
        _check_radius(self)

    def profile(self, X, Y):
        return (np.asarray(X, float) ** 2 + np.asarray(Y, float) ** 2) / (2 * self.radius)

    def rolling_arm(self, X, Y):
        return np.asarray(X, float) / self.radius


def _positive_length(indenter, name: str, rule: str = ">0") -> None:
    """Check the length ``name`` (m, finite, ``rule``) of ``indenter``; store it as a float."""
    value = getattr(indenter, name)
    try:
        object.__setattr__(indenter, name, real(name, value, "m", rule))
    except ValueError as exc:  # NotANumber too: the same words, its type kept
        words = "> 0" if rule == ">0" else ">= 0"
        raise type(exc)(f"{name} must be finite and {words} m, got {value!r}") from None


@dataclass(frozen=True)
class Cylinder:
    """Roller of radius ``radius`` R (m) and length ``length`` L (m), its axis along ``y``
    through the centre: a surface of revolution about that axis whose radius ``rho(y) = R -
    e(y)`` falls off towards the ends by the axial drop ``e(y)`` (m) of its profile.

    ``edge_radius`` r_e (m, ``0 <= r_e <= L / 2``, default 0): flat (``e = 0``) over ``|y|
    <= y_0 = L/2 - r_e``, then a circular arc of radius ``r_e`` tangent to the flat at
    ``y_0`` and meeting the end face ``|y| = L/2`` at a right angle::

        e(y) = r_e - sqrt(r_e^2 - s^2),   s = max(|y| - y_0, 0),

    so ``e`` and its slope ``de/dy = s / sqrt(r_e^2 - s^2)`` are 0 on both sides of
    ``y_0`` (the blend is tangent); ``r_e = 0`` is a flat-ended cylinder.
    ``crown_radius`` R_c (m, ``>= L / 2``): instead, the generating line is one arc of
    radius R_c over the whole length, ``e(y) = R_c - sqrt(R_c^2 - y^2)`` (``y^2 / 2 R_c``
    to small slope); a crown and an edge radius together are refused.

    The gap below the lowest point is exact for that surface, ``g = R - sqrt(rho(y)^2 -
    x^2) = e(y) + x^2 / (rho + sqrt(rho^2 - x^2))`` (``x^2 / 2R + e(y)`` to small slope),
    and ``+inf`` beyond the ends ``|y| > L/2`` (the roller is absent: the contact solver
    never loads those nodes). With ``e = 0`` every row is the line contact's circle
    (:class:`LineCylinder`). The length must be finite: a roller longer than the candidate
    region would touch its edge, which the 3D model cannot represent (its contact would
    be a periodic line contact).

    Rolling: the roller turns about its own axis, so the rolling radius is R on every row
    (:func:`bem.kinematics.rolling_radius`), unlike a sphere's ``sqrt(R^2 - y^2)``; the
    ends' ``rho(y) = R - e(y)`` differs from R by at most the indentation there, a
    relative ``e / R`` far below the strains ``~ a / R`` that set the slip. The rolling
    arm is the paper's ``x / R`` (sec. 9).
    """

    radius: float
    length: float
    edge_radius: float = 0.0
    crown_radius: float | None = None

    def __post_init__(self) -> None:
        _check_radius(self)
        _positive_length(self, "length")
        _positive_length(self, "edge_radius", ">=0")
        if self.edge_radius > self.length / 2:
            raise ValueError(f"edge_radius must be <= length / 2 = {self.length / 2!r} m (the two end "
                             f"roundings meet at mid-length), got {self.edge_radius!r}")
        if self.edge_radius >= self.radius:
            raise ValueError(f"edge_radius must be < radius = {self.radius!r} m (an end rounding within the "
                             f"roller), got {self.edge_radius!r}")
        if self.crown_radius is not None:
            _positive_length(self, "crown_radius")
            if self.edge_radius > 0:
                raise ValueError("give crown_radius or edge_radius, not both: a crowned roller's profile is "
                                 f"one arc end to end (got crown_radius = {self.crown_radius!r} m, "
                                 f"edge_radius = {self.edge_radius!r} m)")
            if self.crown_radius < self.length / 2:
                raise ValueError(f"crown_radius must be >= length / 2 = {self.length / 2!r} m (an arc of radius "
                                 f"R_c spans at most 2 R_c), got {self.crown_radius!r}")

    def axial_drop(self, Y):
        """``e(y)`` (m): how far the roller's surface lies above its lowest line at ``y``
        (class docstring); ``+inf`` beyond the ends."""
        a = np.abs(np.asarray(Y, float))
        if self.crown_radius is not None:
            rc, s = self.crown_radius, np.minimum(a, self.crown_radius)
        else:
            rc, s = self.edge_radius, np.clip(a - (self.length / 2 - self.edge_radius), 0.0, self.edge_radius)
        e = s * s / (rc + np.sqrt(np.maximum(rc * rc - s * s, 0.0))) if rc > 0 else np.zeros_like(a)
        return np.where(a <= self.length / 2, e, np.inf)

    def profile(self, X, Y):
        X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
        e = self.axial_drop(Y)
        rho = self.radius - np.where(np.isfinite(e), e, 0.0)  # the radius of the row
        if np.any(X**2 >= rho**2):
            raise ValueError(f"the grid reaches beyond the cylinder's radius {self.radius} m: reduce grid.half_width")
        return np.where(np.isfinite(e), e + X**2 / (rho + np.sqrt(rho**2 - X**2)), np.inf)

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
        _check_radius(self)

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
        for name in ("x", "y", "h"):
            kind = np.asarray(getattr(self, name)).dtype.kind
            if kind not in "iuf":
                raise ValueError(f"{name} must hold real numbers (m), got an array of dtype "
                                 f"{np.asarray(getattr(self, name)).dtype}")
        x, y, h = (np.asarray(a, float) for a in (self.x, self.y, self.h))
        if x.ndim == 0 or y.ndim == 0:
            raise ValueError(f"x and y must be 1-D arrays (m), got x of shape {x.shape}, y of shape {y.shape}")
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
        from scipy.interpolate import RegularGridInterpolator  # here: 0.3 s of imports other indenters skip

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
