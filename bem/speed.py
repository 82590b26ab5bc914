"""The speed limit of steady motion on a layer: below its shear-wave speed (with inertia),
below its Rayleigh speed when it is lossless. Used by the 3D and the plane-strain solvers."""

from __future__ import annotations

import math

from .layer import Layer
from .materials import Elastic

__all__ = ["RAYLEIGH_RATIO", "check_subsonic"]


def _rayleigh_ratio() -> float:
    """``c_R / c_s`` of an incompressible solid: the root in (0, 1) of the Rayleigh equation
    ``(2 - xi^2)^4 = 16 (1 - xi^2)`` (Poisson's ratio 1/2), 0.9553."""
    # with s = xi^2: (2 - s)^4 - 16 (1 - s) = s (s^3 - 8 s^2 + 24 s - 16), one real root in (0, 1);
    # Newton's method from s = 1: the cubic is increasing and concave on (0, 1), so the first
    # step lands below the root and the next rise to it, quadratically (error 0.09 at s = 1:
    # eight steps are more than enough; numpy.roots' eigenvalues took 2 ms of every start-up)
    s = 1.0
    for _ in range(8):
        s -= (((s - 8.0) * s + 24.0) * s - 16.0) / ((3.0 * s - 16.0) * s + 24.0)
    return math.sqrt(s)


RAYLEIGH_RATIO = _rayleigh_ratio()


def check_subsonic(layer: Layer, speed: float) -> None:
    """Raise ``ValueError`` unless ``speed`` (m/s) is below the layer's critical speed.

    With inertia (``layer.density > 0``) steady motion of the unbounded layer is subsonic
    only below the slowest shear-wave speed ``c_s = sqrt(G(0) / rho)``
    (:attr:`bem.layer.Layer.shear_wave_speed`); at or above it the steady state radiates
    waves, which the periodic model would only imitate with results that depend on the
    period. A lossless (elastic) layer resonates earlier, at the speed of its slowest
    free surface waves: the Rayleigh speed ``c_R = 0.9553 c_s`` (the short-wave limit of
    the bonded layer's guided waves, which are faster at long wavelengths); a loss modulus
    damps that resonance. Without inertia (``density = 0``) there is no limit.
    """
    c_s = layer.shear_wave_speed
    wave = (f"shear-wave speed c_s = sqrt(G(0) / rho) = sqrt({layer.relaxed_modulus:g} Pa / "
            f"{layer.density:g} kg/m^3) = {c_s:.3g} m/s")
    limit, name, symbol = c_s, wave, "c_s"
    if isinstance(layer.material, Elastic):
        limit = RAYLEIGH_RATIO * c_s
        name = f"Rayleigh speed c_R = {RAYLEIGH_RATIO:.4f} c_s = {limit:.3g} m/s (lossless; {wave})"
        symbol = "c_R"
    if speed >= limit:
        raise ValueError(
            f"loading.speed = {speed:g} m/s is at or above the layer's {name}: steady motion is "
            f"subsonic only for speed < {symbol} (faster, the steady state radiates waves that the "
            "periodic model would only imitate, with results that depend on the period); use a "
            f"loading.speed below {limit:.3g} m/s, or layer.density = 0 to neglect inertia"
        )
