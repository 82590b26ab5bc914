"""Input checks shared by the analytic references: each error names the argument, its
value, its unit and the rule it breaks (``thickness must be > 0 m, got -0.005``)."""

from __future__ import annotations

import math

import numpy as np


def number(name: str, value, unit: str) -> float:
    """``value`` as a finite float; ``TypeError`` for anything but a real number (a bool
    included), ``ValueError`` for NaN or infinity. ``unit`` is named in the message."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a real number in {unit}, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return value


def positive(name: str, value, unit: str) -> float:
    """``value`` as a float > 0 (in ``unit``), else ``ValueError``."""
    v = number(name, value, unit)
    if not v > 0:
        raise ValueError(f"{name} must be > 0 {unit}, got {value!r}")
    return v


def poisson(value, allowed: str = "open") -> float:
    """Poisson's ratio (-): in (-1, 0.5], or exactly 0.5 when ``allowed`` is
    ``"incompressible"``."""
    v = number("poisson_ratio", value, "(-)")
    if allowed == "incompressible":
        if v != 0.5:
            raise ValueError(
                f"poisson_ratio must be 0.5 (the thin-layer solution assumes an "
                f"incompressible layer), got {value!r}"
            )
    elif not -1.0 < v <= 0.5:
        raise ValueError(f"poisson_ratio must be in (-1, 0.5], got {value!r}")
    return v


def wavenumbers(k) -> np.ndarray:
    """``k`` (rad/m, array_like) as a float array, each entry finite and >= 0."""
    k = np.asarray(k, dtype=float)
    bad = ~np.isfinite(k) | (k < 0)
    if bad.any():
        raise ValueError(f"wavenumber must be >= 0 rad/m and finite, got {k[bad].flat[0]!r}")
    return k


def disc(r, contact_radius: float, shape) -> np.ndarray:
    """``shape(1 - rho^2)`` for ``rho = |r| / a < 1``, 0 outside; ``r`` and the contact
    radius ``a`` in m (``shape = np.sqrt`` gives Hertz's profile)."""
    rho2 = (np.abs(np.asarray(r, dtype=float)) / contact_radius) ** 2
    inside = rho2 < 1.0
    return np.where(inside, shape(np.where(inside, 1.0 - rho2, 0.0)), 0.0)
