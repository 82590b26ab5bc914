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

Rolling geometry (:func:`rolling_geometry`, ``[friction] kinematics``). The frictional
solve needs, at every node, the gap profile ``g`` (m), the arm (-) that turns a normal
force ``N`` (its vertical component, the one loading the layer) into its horizontal
projection ``N arm`` on the indenter, and the rolling radius ``l`` (m) that sets the
indenter's horizontal surface speed ``Omega l`` in ``w_x`` and the moment arm of a
tangential force. The energy balance of the rolling body (docs/derivations.md, section
"Rolling kinematics") closes exactly when ``arm = dg/dx`` and ``l`` is the same in the
slip velocity and the torque; three consistent or reproducible choices:

* ``paper``: the paper as printed: exact profile (eq. 13), ``arm = x / R`` (sec. 9),
  ``l = sqrt(R^2 - y^2)`` (eq. 14, the distance from the axis, not its horizontal part).
  The equilibrium figure misses the energy one by ``sum N (dg/dx - x / R)``, about
  ``r^2 / 2 R^2`` of ``R_r`` (1.3 % in the paper's section 11).
* ``small_slope``: everything to first order in the slope: the profile's ``x`` part
  ``x^2 / 2R`` (a sphere becomes the paraboloid ``r^2 / 2R``), ``arm = x / R``, ``l = R``.
* ``exact``: the body's own surface: for a body of revolution about the ``y`` axis
  (sphere, roller) at the depth ``D = R - g = sqrt(rho(y)^2 - x^2)`` below the axis, a
  radial normal force with vertical component ``N`` has the horizontal one ``N x / D``
  (``arm = x / D = dg/dx``), and the surface moves horizontally at ``Omega D`` (``l = D``).
  The layer (small strain) is loaded as in the paper by ``N`` vertically and by the
  friction forces horizontally; the horizontal part ``N x / D`` of the normal force acts
  on the body's equilibrium and does no work (the relative velocity along the normal is
  zero to the small-strain order). A paraboloid is itself the small-slope body (its
  normals do not meet one axis) and a height map has only its given arm: for both,
  ``exact`` is ``small_slope`` with their own profile.

A line contact (:class:`bem.indenters.LineCylinder`, plane strain) is the circle of
radius ``R``: ``exact`` takes the circle with ``arm = x / D`` and ``l = D = sqrt(R^2 -
x^2)``, ``small_slope`` the parabola with ``x / R`` and ``R``, ``paper`` the circle with
``x / R`` and ``R`` (docs/derivations.md, section 8).

``paper`` is the default, for now: the frictionless solver uses the same exact profile
with the arm ``x / R``, so ``mu -> 0`` gives back the frictionless solution, and the
paper's figures are reproduced. ``exact`` solves the body the user described (eq. 13 for
a sphere) with two rolling-resistance figures that agree to the discretisation error;
it is not the default yet because the frictionless solver does not share its arm (a
frictional solve at ``mu -> 0`` then differs from the frictionless one by the slope
term) and the towed mode at very small ``mu`` can cycle between stick/slip sets.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["KINEMATICS", "DEFAULT_KINEMATICS", "upwind_table", "upwind_field", "rolling_radius",
           "indenter_radius", "rolling_geometry"]

#: the rolling kinematics of the frictional solve (module docstring)
KINEMATICS = ("paper", "small_slope", "exact")
#: the default: the paper's kinematics, the frictionless solver's geometry (module docstring)
DEFAULT_KINEMATICS = "paper"


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


#: bodies of revolution about the ``y`` axis through the centre (depth ``R - g`` below it)
_REVOLUTION = ("Sphere", "Cylinder", "LineCylinder")


def rolling_geometry(indenter, X, Y, kinematics: str = DEFAULT_KINEMATICS, override: float | None = None):
    """``(profile, arm, ell)`` at the nodes ``X, Y`` (m) for one of :data:`KINEMATICS`
    (module docstring): the gap profile (m, ``inf`` where the body cannot touch), the
    horizontal projection of a unit vertical normal force (-) and the rolling radius (m).
    ``override`` (m): the radius for indenters without one (height maps); the body is then
    treated as a height map."""
    if kinematics not in KINEMATICS:
        raise ValueError(f"kinematics must be one of {', '.join(KINEMATICS)}, got {kinematics!r}")
    R = indenter_radius(indenter, override)
    X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
    name = type(indenter).__name__ if override is None else "HeightMap"
    if kinematics == "paper":
        return indenter.profile(X, Y), indenter.rolling_arm(X, Y), rolling_radius(indenter, Y, override)
    if name not in _REVOLUTION:
        return indenter.profile(X, Y), indenter.rolling_arm(X, Y), np.full(X.shape, R)
    if kinematics == "small_slope":
        if name == "Sphere":  # its paraboloid, written as bem.indenters.Paraboloid writes it
            g = (X**2 + Y**2) / (2 * R)
        else:
            g = X**2 / (2 * R) + (indenter.axial_drop(Y) if name == "Cylinder" else 0.0)
        return g, X / R, np.full(X.shape, R)
    g = indenter.profile(X, Y)
    depth = np.where(np.isfinite(g), R - g, R)  # D = sqrt(rho^2 - x^2); R where it cannot touch
    with np.errstate(divide="ignore", invalid="ignore"):
        arm = np.where(np.isfinite(g) & (depth > 0), X / depth, 0.0)
    return g, arm, depth
