"""Linear viscoelastic materials in the time domain (fem_reference's own classes).

An incompressible generalized Maxwell (Prony) solid has the shear relaxation modulus

    G(t) = G_inf + sum_i G_i exp(-t / tau_i)          (Pa, t in s)

and the complex modulus G*(omega) = G_inf + sum_i G_i i omega tau_i / (1 + i omega tau_i).
Branch i is a spring G_i in series with a dashpot eta_i = G_i tau_i; its viscous
(dashpot) strain eps_v,i obeys d eps_v,i / dt = (eps - eps_v,i) / tau_i, and the
deviatoric stress is 2 G_inf eps + sum_i 2 G_i (eps - eps_v,i).

The paper's three-parameter solid (eq. 71: spring G1 in series with a Kelvin unit
G2 || eta; G0 = G1 G2 / (G1 + G2), tau = eta / G2, f = G1 / G2) is the one-branch
series G_inf = G0, G_1 = G0 f, tau_1 = tau / (1 + f): the relaxed modulus G*(0) = G0,
the glassy G*(inf) = G0 (1 + f), and the loss peak of eq. 71,
G'' = G0 (1 + f) f omega tau / ((1 + f)^2 + omega^2 tau^2), sits at omega tau = 1 + f,
i.e. at omega tau_1 = 1 (docs/derivations.md, section "Steady rolling FEM").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple

import numpy as np

from .errors import InputError

__all__ = ["ElasticMaterial", "PronyMaterial", "ThreeParameterMaterial", "as_prony"]


def _positive(name: str, value, unit: str, allow_zero: bool = False) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{name} must be a number in {unit}, got {value!r}")
    if not math.isfinite(value) or value < 0 or (value == 0 and not allow_zero):
        raise InputError(f"{name} must be {'>=' if allow_zero else '>'} 0 {unit}, got {value!r}")


@dataclass(frozen=True)
class ElasticMaterial:
    """Incompressible linear elastic solid of shear modulus ``shear_modulus`` (Pa).

    Poisson's ratio is exactly 1/2; the plane-strain modulus of the half-space is
    E* = 4 G for a rigid indenter.
    """

    shear_modulus: float

    def __post_init__(self):
        _positive("material.shear_modulus", self.shear_modulus, "Pa")

    @property
    def relaxed_modulus(self) -> float:
        """G (Pa)."""
        return float(self.shear_modulus)

    @property
    def glassy_modulus(self) -> float:
        """G (Pa)."""
        return float(self.shear_modulus)


@dataclass(frozen=True)
class PronyMaterial:
    """Generalized Maxwell solid: relaxed modulus ``G_inf`` (Pa), branch moduli ``G``
    (Pa) and relaxation times ``tau`` (s), one per branch (module docstring)."""

    G_inf: float
    G: Tuple[float, ...]
    tau: Tuple[float, ...]

    def __post_init__(self):
        _positive("material.G_inf", self.G_inf, "Pa")
        for name in ("G", "tau"):
            value = getattr(self, name)
            if isinstance(value, (str, bytes)) or np.ndim(value) != 1 or len(value) == 0:
                raise InputError(f"material.{name} must be a non-empty list of numbers, got {value!r}")
            object.__setattr__(self, name, tuple(value))
        if len(self.G) != len(self.tau):
            raise InputError(f"material.G and material.tau must have the same length (one per branch), "
                             f"got {len(self.G)} and {len(self.tau)}")
        for i, (g, t) in enumerate(zip(self.G, self.tau)):
            _positive(f"material.G[{i}]", g, "Pa")
            _positive(f"material.tau[{i}]", t, "s")

    @property
    def relaxed_modulus(self) -> float:
        """G(t -> inf) = G*(0) = G_inf (Pa)."""
        return float(self.G_inf)

    @property
    def glassy_modulus(self) -> float:
        """G(0) = G*(inf) = G_inf + sum G_i (Pa)."""
        return float(self.G_inf + sum(self.G))

    @property
    def retardation_time(self) -> float:
        """Upper bound (s) of the creep (retardation) times: max tau_i G_glassy / G_inf.

        Exact for one branch (the three-parameter solid's creep time tau); the creep
        compliance of a Prony solid has retardation times between the smallest tau_i
        and this bound.
        """
        return float(max(self.tau) * self.glassy_modulus / self.G_inf)

    def modulus(self, omega) -> np.ndarray:
        """G*(omega) (Pa, complex) at angular frequencies ``omega`` (rad/s)."""
        w = np.asarray(omega, dtype=float)
        out = np.full(w.shape, complex(self.G_inf))
        for g, t in zip(self.G, self.tau):
            iwt = 1j * w * t
            out = out + g * iwt / (1.0 + iwt)
        return out


@dataclass(frozen=True)
class ThreeParameterMaterial:
    """The paper's three-parameter solid (eq. 71): static modulus ``G0`` (Pa), creep
    time ``tau`` (s), ``f`` = G1 / G2 (-); see :func:`as_prony`."""

    G0: float
    tau: float
    f: float

    def __post_init__(self):
        _positive("material.G0", self.G0, "Pa")
        _positive("material.tau", self.tau, "s")
        _positive("material.f", self.f, "(-)", allow_zero=True)

    def prony(self):
        """The equivalent Prony series G_inf = G0, G_1 = G0 f, tau_1 = tau / (1 + f);
        elastic (G0) when f = 0."""
        if self.f == 0:
            return ElasticMaterial(self.G0)
        return PronyMaterial(self.G0, (self.G0 * self.f,), (self.tau / (1.0 + self.f),))

    @property
    def relaxed_modulus(self) -> float:
        """G0 (Pa)."""
        return float(self.G0)

    @property
    def glassy_modulus(self) -> float:
        """G0 (1 + f) (Pa)."""
        return float(self.G0 * (1.0 + self.f))

    def modulus(self, omega) -> np.ndarray:
        """G*(omega) (Pa, complex) of eq. 71 at ``omega`` (rad/s)."""
        w = np.asarray(omega, dtype=float)
        c, x = 1.0 + self.f, w * self.tau
        den = c * c + x * x
        return self.G0 * c * ((c + x * x) / den + 1j * self.f * x / den)


def as_prony(material):
    """``material`` as an :class:`ElasticMaterial` or a :class:`PronyMaterial`."""
    if isinstance(material, ThreeParameterMaterial):
        return material.prony()
    if isinstance(material, (ElasticMaterial, PronyMaterial)):
        return material
    raise InputError(f"material must be an ElasticMaterial, PronyMaterial or ThreeParameterMaterial, "
                     f"got {material!r}")
