"""Steady-rolling kinematics at the contact interface (paper eqs. 6, 14-15).

In the frame moving with the indenter at ``V`` (m/s) in ``+x``, the layer's material
streams towards ``-x``; a surface particle's horizontal velocity relative to the frame
is ``(-V (1 + du/dx), -V dv/dx)`` (the material derivative is ``D/Dt = -V d/dx``, eq. 6).
The indenter turns at ``Omega`` (rad/s, positive clockwise seen with ``+x`` to the right
and ``+z`` up, i.e. the sense of forward rolling) about its axis along ``y``; its surface
moves along the circle of constant ``y`` of radius ``l(y)``, the distance from the axis
(``sqrt(R^2 - y^2)`` for a sphere), at speed ``Omega l(y)``, which is horizontal and equal
to ``-Omega l(y)`` along ``x`` to first order in the surface slope. The slip velocity, the
indenter's velocity relative to the layer's surface (eqs. 14-15), is

    w_x = V (1 + du/dx) - Omega l(y),      w_y = V dv/dx           (m/s)

Upwind derivative. ``d/dx`` enters through ``D/Dt = -V d/dx``: the displacement of the
particle now at node ``i`` was, one node spacing ``a_x`` of travel (``a_x / V`` seconds)
ago, the displacement at node ``i + 1`` (upstream, towards the leading edge), so the
backward-Euler rate is ``(u_i - u_{i+1}) V / a_x`` and

    (du/dx)_i = (u_{i+1} - u_i) / a_x .

This is Kalker's discretisation of the material derivative in steady rolling (CONTACT).
Information flows with the material, from the leading edge backwards: a stick node takes
its strain from its upstream neighbour, which gives the paper's continuity of ``du/dx``
and ``v`` across the leading edge of a stick zone (sec. 9). In a stick zone ``du/dx`` is
constant along ``x`` (``u`` linear), where the one-sided difference is exact; a centred
difference would also use the downstream node, which has no influence on the particle,
and lets odd and even nodes decouple.

Because the compliance depends on node offsets only, the differenced compliance is
again an offset table, ``Kd[dy, dx] = (K[dy, dx + 1] - K[dy, dx]) / a_x``, applied like
any kernel (by FFT or densely).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["upwind_table", "upwind_field", "rolling_radius", "indenter_radius"]


def upwind_table(kernel: np.ndarray, spacing_x: float) -> np.ndarray:
    """Upwind ``x``-difference of a kernel table (m/N -> 1/N).

    ``Kd[dy, dx] = (K[dy, dx + 1] - K[dy, dx]) / a_x``; the last column (offset
    ``K_x - 1``, needed only by nodes of the grid's leading edge, which never touch)
    repeats its neighbour.
    """
    out = np.empty_like(kernel)
    out[:, :-1] = (kernel[:, 1:] - kernel[:, :-1]) / spacing_x
    out[:, -1] = out[:, -2]
    return out


def upwind_field(field: np.ndarray, spacing_x: float) -> np.ndarray:
    """``(f_{i+1} - f_i) / a_x`` of a nodal field of shape ``(K_y, K_x)``; the grid's
    last column (the leading edge) repeats its neighbour."""
    f = np.asarray(field, float)
    out = np.empty_like(f)
    out[:, :-1] = (f[:, 1:] - f[:, :-1]) / spacing_x
    out[:, -1] = out[:, -2]
    return out


def indenter_radius(indenter, override: float | None = None) -> float:
    """Distance (m) from the indenter's axis to its lowest point: ``override`` if
    given, else the indenter's ``radius``."""
    R = override if override is not None else getattr(indenter, "radius", None)
    if R is None:
        raise ValueError("this indenter has no radius: give friction.radius (m), the distance "
                         "from its axis of rotation to its lowest point")
    if not (math.isfinite(R) and R > 0):
        raise ValueError(f"radius must be > 0 m, got {R!r}")
    return float(R)


def rolling_radius(indenter, Y: np.ndarray, override: float | None = None) -> np.ndarray:
    """Distance ``l(y)`` (m) from the axis of rotation (along ``y``, through the centre)
    to the contact surface: ``sqrt(R^2 - y^2)`` for a sphere or paraboloid of radius
    ``R`` (the paper's ``R(y)``, eq. 14), ``R`` for a cylinder or when only a radius is
    known (``override``, for height maps)."""
    R = indenter_radius(indenter, override)
    Y = np.asarray(Y, float)
    if override is None and type(indenter).__name__ in ("Sphere", "Paraboloid"):
        return np.sqrt(np.maximum(R * R - Y * Y, 0.0))
    return np.full(Y.shape, R)
