"""Inputs of a stationary, elastic, frictionless indentation problem.

Each input is a frozen dataclass validated in ``__post_init__``; a bad value
raises :class:`~fem_reference.errors.InputError` naming the field, the value and
the rule. SI units throughout (m, N, Pa).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from .errors import InputError

__all__ = ["Layer", "ElasticMaterial", "Indenter", "Loading", "FemSettings",
           "ContactProblem"]


def _positive(name: str, value, unit: str) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{name} must be a number in {unit}, got {value!r}")
    if not math.isfinite(value) or value <= 0:
        raise InputError(f"{name} must be > 0 {unit}, got {value!r}")


def _optional_positive(name: str, value, unit: str) -> None:
    if value is not None:
        _positive(name, value, unit)


@dataclass(frozen=True)
class Layer:
    """Layer of thickness ``thickness`` (m) bonded to a rigid base at z = 0.

    The free surface is z = H; the layer extends laterally without bound (the
    finite-element domain truncates it at ``FemSettings.domain_radius``).
    """

    thickness: float

    def __post_init__(self):
        _positive("layer.thickness", self.thickness, "m")


@dataclass(frozen=True)
class ElasticMaterial:
    """Incompressible linear elastic solid of shear modulus ``shear_modulus`` (Pa).

    Poisson's ratio is exactly 1/2; the plane-strain modulus of the half-space is
    E* = 4 G for a rigid indenter.
    """

    shear_modulus: float

    def __post_init__(self):
        _positive("material.shear_modulus", self.shear_modulus, "Pa")


@dataclass(frozen=True)
class Indenter:
    """Rigid axisymmetric indenter, ``shape`` "sphere" (exact, paper eq. 13) or
    "paraboloid", of radius ``radius`` (m).
    """

    shape: str
    radius: float

    SHAPES = ("sphere", "paraboloid")

    def __post_init__(self):
        if self.shape not in self.SHAPES:
            raise InputError(f"indenter.shape must be one of {self.SHAPES}, got {self.shape!r}")
        _positive("indenter.radius", self.radius, "m")

    def profile(self, r):
        """Height s(r) (m) of the indenter above its lowest point at radius r (m).

        Sphere: s = R - sqrt(R^2 - r^2) (paper eq. 13 with z_c = R); paraboloid:
        s = r^2 / (2 R).
        """
        r = np.asarray(r, dtype=float)
        R = self.radius
        if self.shape == "paraboloid":
            return r * r / (2.0 * R)
        if np.any(np.abs(r) >= R):
            raise InputError(f"sphere profile asked at |r| >= indenter.radius = {R} m")
        return r * r / (R + np.sqrt(R * R - r * r))  # = R - sqrt(R^2 - r^2), no cancellation


@dataclass(frozen=True)
class Loading:
    """Load control (``load``, N, total on the indenter) or displacement control
    (``indentation``, m, downward rigid displacement of the indenter): exactly one.
    """

    load: Optional[float] = None
    indentation: Optional[float] = None

    def __post_init__(self):
        if (self.load is None) == (self.indentation is None):
            raise InputError("loading needs exactly one of load (N) and indentation (m), "
                             f"got load={self.load!r}, indentation={self.indentation!r}")
        _optional_positive("loading.load", self.load, "N")
        _optional_positive("loading.indentation", self.indentation, "m")


@dataclass(frozen=True)
class FemSettings:
    """Discretization of the finite-element reference (the ``[fem]`` case section).

    Parameters
    ----------
    model : {"axisymmetric", "3d"}
        Axisymmetric (r, z) model, or a quarter cylinder in 3D (symmetry planes
        x = 0 and y = 0).
    element_size : float, optional
        Element size h_c (m) in the candidate contact zone. Default: axisymmetric
        min(a_est / 24, H / 4), 3D min(a_est / 8, H / 2), with a_est the estimated
        contact radius.
    contact_zone : float, optional
        Radius (m) of the refined candidate zone of the top surface that carries the
        contact multiplier. Default 1.4 a_est. The contact must stay inside it.
    domain_radius : float, optional
        Lateral extent (m) of the truncated layer (traction-free outer side).
        Default contact_zone + 8 H.
    far_size : float, optional
        Largest element size (m). Default H / 2 (axisymmetric), H (3D), at most
        domain_radius / 4.
    grading : float
        Growth of the element size with the distance from the contact zone,
        h = h_c + grading * distance (-). Default 0.3.
    refine : int
        Uniform refinements (each halves every element) of the gmsh mesh made with
        ``element_size``: nested meshes for convergence studies (>= 0, default 0).
    solver : {"direct", "minres"}
        Linear solver of the displacement-pressure system: sparse LU (SuperLU), or
        MINRES with an AMG / pressure-mass block preconditioner.
    rtol : float
        Relative (preconditioned) residual tolerance of MINRES (-), default 1e-8.
    fit_nodes : int
        Number of surface vertices (along a radius) just outside the contact used to
        fit g^(2/3) for the contact radius (>= 2); see :mod:`.postprocess`.
    max_iterations : int
        Limit of the active-set iteration (>= 1).
    """

    model: str = "axisymmetric"
    element_size: Optional[float] = None
    contact_zone: Optional[float] = None
    domain_radius: Optional[float] = None
    far_size: Optional[float] = None
    grading: float = 0.3
    refine: int = 0
    solver: str = "direct"
    rtol: float = 1e-8
    fit_nodes: int = 3
    max_iterations: int = 100

    MODELS = ("axisymmetric", "3d")
    SOLVERS = ("direct", "minres")

    def __post_init__(self):
        if self.model not in self.MODELS:
            raise InputError(f"fem.model must be one of {self.MODELS}, got {self.model!r}")
        if self.solver not in self.SOLVERS:
            raise InputError(f"fem.solver must be one of {self.SOLVERS}, got {self.solver!r}")
        if self.solver == "minres":  # fail at the input, not after meshing and assembly
            from ._deps import import_pyamg

            import_pyamg()
        for name in ("element_size", "contact_zone", "domain_radius", "far_size"):
            _optional_positive(f"fem.{name}", getattr(self, name), "m")
        _positive("fem.grading", self.grading, "(-)")
        _positive("fem.rtol", self.rtol, "(-)")
        for name, low in (("fit_nodes", 2), ("max_iterations", 1), ("refine", 0)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < low:
                raise InputError(f"fem.{name} must be an integer >= {low}, got {value!r}")


@dataclass(frozen=True)
class ContactProblem:
    """A layer, a material, an indenter, a loading and a discretization."""

    layer: Layer
    material: ElasticMaterial
    indenter: Indenter
    loading: Loading
    fem: FemSettings = field(default_factory=FemSettings)

    def __post_init__(self):
        for name, cls in (("layer", Layer), ("material", ElasticMaterial),
                          ("indenter", Indenter), ("loading", Loading),
                          ("fem", FemSettings)):
            if not isinstance(getattr(self, name), cls):
                raise InputError(f"{name} must be a {cls.__name__}, got {getattr(self, name)!r}")
