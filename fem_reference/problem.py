"""Inputs of a frictionless contact problem: stationary elastic indentation
(axisymmetric or 3D), or steady rolling of a rigid cylinder in plane strain on an
elastic or viscoelastic layer (``Indenter("line", R)``).

Each input is a frozen dataclass validated in ``__post_init__``; a bad value
raises :class:`~fem_reference.errors.InputError` naming the field, the value and
the rule. SI units throughout (m, N, Pa).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from .errors import InputError
from .materials import ElasticMaterial, PronyMaterial, ThreeParameterMaterial

__all__ = ["Layer", "ElasticMaterial", "PronyMaterial", "ThreeParameterMaterial", "Indenter",
           "Loading", "FemSettings", "ContactProblem"]


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
    finite-element domain truncates it at ``FemSettings.domain_radius``, or at the
    upstream and downstream lengths in plane strain). ``density`` rho (kg/m^3, >= 0)
    brings the steady moving-frame inertia rho V^2 d2u/dx2 of a rolling solve; 0
    neglects it.
    """

    thickness: float
    density: float = 0.0

    def __post_init__(self):
        _positive("layer.thickness", self.thickness, "m")
        if isinstance(self.density, bool) or not isinstance(self.density, (int, float)) or \
                not math.isfinite(self.density) or self.density < 0:
            raise InputError(f"layer.density must be a number >= 0 kg/m^3, got {self.density!r}")


@dataclass(frozen=True)
class Indenter:
    """Rigid indenter of radius ``radius`` (m): axisymmetric, ``shape`` "sphere"
    (exact, paper eq. 13) or "paraboloid"; "line", a rigid circular cylinder with its
    axis along y in plane strain (exact circle s = R - sqrt(R^2 - x^2); the load is then
    per unit length, N/m); or "cylinder", a roller of ``length`` L (m) with its axis along
    y, rolling in the 3d model.

    The roller is the surface of revolution about its axis of radius rho(y) = R - e(y):
    e = 0 on |y| <= L/2 - r_e and e = r_e - sqrt(r_e^2 - (|y| - L/2 + r_e)^2) beyond (an
    arc of ``edge_radius`` r_e, m, tangent to the flat and square to the end face; 0 <=
    r_e <= L/2, r_e < R), or with ``crown_radius`` R_c (m, >= L/2) one arc end to end, e =
    R_c - sqrt(R_c^2 - y^2). Its height above its lowest point is s = R - sqrt(rho(y)^2 -
    x^2) on |y| <= L/2; the 3d model's candidate zone ends at |y| = L/2.
    """

    shape: str
    radius: float
    length: Optional[float] = None
    edge_radius: float = 0.0
    crown_radius: Optional[float] = None

    SHAPES = ("sphere", "paraboloid", "line", "cylinder")

    def __post_init__(self):
        if self.shape not in self.SHAPES:
            raise InputError(f"indenter.shape must be one of {self.SHAPES}, got {self.shape!r}")
        _positive("indenter.radius", self.radius, "m")
        if self.shape != "cylinder":
            if self.length is not None or self.edge_radius or self.crown_radius is not None:
                raise InputError(f"indenter.length, edge_radius and crown_radius belong to a cylinder, "
                                 f"not to indenter.shape = {self.shape!r}")
            return
        _positive("indenter.length", self.length, "m")
        r_e = self.edge_radius
        if isinstance(r_e, bool) or not isinstance(r_e, (int, float)) or not math.isfinite(r_e) or r_e < 0:
            raise InputError(f"indenter.edge_radius must be a number >= 0 m, got {r_e!r}")
        if r_e > self.length / 2:
            raise InputError(f"indenter.edge_radius must be <= indenter.length / 2 = {self.length / 2!r} m "
                             f"(the two end roundings meet at mid-length), got {r_e!r}")
        if r_e >= self.radius:
            raise InputError(f"indenter.edge_radius must be < indenter.radius = {self.radius!r} m, got {r_e!r}")
        if self.crown_radius is not None:
            _positive("indenter.crown_radius", self.crown_radius, "m")
            if r_e > 0:
                raise InputError("give indenter.crown_radius or indenter.edge_radius, not both: a crowned "
                                 "roller's profile is one arc end to end")
            if self.crown_radius < self.length / 2:
                raise InputError(f"indenter.crown_radius must be >= indenter.length / 2 = "
                                 f"{self.length / 2!r} m, got {self.crown_radius!r}")

    def profile(self, r):
        """Height s(r) (m) of the indenter above its lowest point at radius r (m) (at
        abscissa x = r for a line contact, and for a cylinder on its mid-plane y = 0).

        Sphere, line and cylinder: s = R - sqrt(R^2 - r^2) (paper eq. 13 with z_c = R);
        paraboloid: s = r^2 / (2 R).
        """
        r = np.asarray(r, dtype=float)
        R = self.radius
        if self.shape == "paraboloid":
            return r * r / (2.0 * R)
        if np.any(np.abs(r) >= R):
            raise InputError(f"sphere profile asked at |r| >= indenter.radius = {R} m")
        return r * r / (R + np.sqrt(R * R - r * r))  # = R - sqrt(R^2 - r^2), no cancellation

    def axial_drop(self, y):
        """e(y) (m) of a cylinder (class docstring), for |y| <= L/2."""
        a = np.abs(np.asarray(y, dtype=float))
        if self.crown_radius is not None:
            rc, s = self.crown_radius, np.minimum(a, self.crown_radius)
        else:
            rc = self.edge_radius
            s = np.clip(a - (0.5 * self.length - rc), 0.0, rc)
        if rc == 0:
            return np.zeros_like(a)
        return s * s / (rc + np.sqrt(np.maximum(rc * rc - s * s, 0.0)))

    def surface(self, x, y):
        """Height s(x, y) (m) above the lowest point of a sphere (R - sqrt(R^2 - x^2 -
        y^2)) or a cylinder (class docstring) at the point (x, y) (m) of the surface."""
        x, y = np.asarray(x, float), np.asarray(y, float)
        if self.shape == "cylinder":
            e = self.axial_drop(y)
            rho = self.radius - e
            return e + x * x / (rho + np.sqrt(rho * rho - x * x))
        r2 = x * x + y * y
        return r2 / (self.radius + np.sqrt(self.radius ** 2 - r2))

    def slope(self, x, y):
        """ds/dx (-) at (x, y) (m): x / sqrt(rho^2 - x^2), rho = sqrt(R^2 - y^2) for a
        sphere, R - e(y) for a cylinder."""
        x, y = np.asarray(x, float), np.asarray(y, float)
        rho2 = (self.radius - self.axial_drop(y)) ** 2 if self.shape == "cylinder" else self.radius ** 2 - y * y
        return x / np.sqrt(rho2 - x * x)


@dataclass(frozen=True)
class Loading:
    """Load control (``load``, N, total on the indenter; N/m per unit length for a
    line contact) or displacement control (``indentation``, m, downward rigid
    displacement of the indenter): exactly one. ``speed`` V (m/s, >= 0): the indenter
    moves in +x (the material flows at -V in its frame); only a line contact rolls.
    """

    load: Optional[float] = None
    indentation: Optional[float] = None
    speed: float = 0.0

    def __post_init__(self):
        if isinstance(self.speed, bool) or not isinstance(self.speed, (int, float)) or \
                not math.isfinite(self.speed) or self.speed < 0:
            raise InputError(f"loading.speed must be a finite number >= 0 m/s, got {self.speed!r}")
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
    model : {"axisymmetric", "3d", "plane_strain"}, optional
        Axisymmetric (r, z) model, a quarter cylinder in 3D (symmetry planes
        x = 0 and y = 0), or the plane-strain (x, z) section of a line contact. With
        ``loading.speed`` > 0, "3d" is steady rolling of a sphere on the half box
        y >= 0 (:mod:`.rolling.three_d`).
        Default: "plane_strain" for a line indenter, "axisymmetric" otherwise.
    element_size : float, optional
        Element size h_c (m) in the candidate contact zone. Default: axisymmetric
        min(a_est / 24, H / 4), 3D min(a_est / 8, H / 2) (3D rolling min(a_est / 10,
        H / 5): on the section 11 sphere 46k unknowns, 21 s, R_r 0.08% below the BEM;
        ``fem-reference solve --help``), plane strain min(a_est / 30, H / 8), with
        a_est the estimated contact radius (half-width).
    contact_zone : float, optional
        Radius (m) of the refined candidate zone of the top surface that carries the
        contact multiplier (plane strain: half-width, |x| <= contact_zone). Default
        1.4 a_est (plane strain 1.5 a_est). The contact must stay inside it.
    domain_radius : float, optional
        Lateral extent (m) of the truncated layer (traction-free outer side).
        Default contact_zone + 8 H. Not used in plane strain (see upstream and
        downstream). 3D rolling: the half box's extent in y, default contact_zone +
        max(6 H, 4 a_est).
    upstream : float, optional
        Rolling: length (m) of the layer ahead of the indenter (x > 0), where the
        material enters undeformed and relaxed (the inflow). Default contact_zone +
        max(8 H, 6 a_est) in plane strain, contact_zone + max(6 H, 4 a_est) in 3D.
    downstream : float, optional
        Rolling: length (m) of the layer behind the indenter (x < 0), where the
        material leaves. Default contact_zone + max(8 H, 6 a_est, 8 V t_r) in plane
        strain (3D: 6 H, 4 a_est, 6 V t_r), t_r the longest creep (retardation) time:
        the material recovers before it leaves. The 3D mesh is mirror-symmetric about
        x = 0: its upstream and downstream lengths are both the larger one.
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
        Relative (preconditioned) residual tolerance of MINRES (-), default 1e-8, at most
        :data:`MAX_RTOL` = 1e-6 (on a sphere on a layer, 743 unknowns, it moved the
        indentation by 7e-7 and the peak pressure by 2e-5 relative to sparse LU; 1e-4 moved
        the peak pressure by 3e-3, 1e-2 by 9e-2: measured).
    fit_nodes : int
        Number of surface vertices (along a radius) just outside the contact used to
        fit g^(2/3) for the contact radius (>= 2); see :mod:`.edge_fit`.
    max_iterations : int
        Limit of the active-set iteration (>= 1).
    """

    model: Optional[str] = None
    element_size: Optional[float] = None
    contact_zone: Optional[float] = None
    domain_radius: Optional[float] = None
    upstream: Optional[float] = None
    downstream: Optional[float] = None
    far_size: Optional[float] = None
    grading: float = 0.3
    refine: int = 0
    solver: str = "direct"
    rtol: float = 1e-8
    fit_nodes: int = 3
    max_iterations: int = 100

    MODELS = ("axisymmetric", "3d", "plane_strain")
    SOLVERS = ("direct", "minres")

    def __post_init__(self):
        if self.model is not None and self.model not in self.MODELS:
            raise InputError(f"fem.model must be one of {self.MODELS}, got {self.model!r}")
        if self.solver not in self.SOLVERS:
            raise InputError(f"fem.solver must be one of {self.SOLVERS}, got {self.solver!r}")
        if self.solver == "minres":  # fail at the input, not after meshing and assembly
            from ._deps import import_pyamg

            import_pyamg()
        for name in ("element_size", "contact_zone", "domain_radius", "upstream", "downstream",
                     "far_size"):
            _optional_positive(f"fem.{name}", getattr(self, name), "m")
        _positive("fem.grading", self.grading, "(-)")
        _positive("fem.rtol", self.rtol, "(-)")
        if self.rtol > MAX_RTOL:
            raise InputError(f"fem.rtol must be <= {MAX_RTOL:g}, got {self.rtol!r}: MINRES stops at this relative "
                             "residual, and the contact follows it (on a sphere on a layer, rtol 1e-4 moved the "
                             "peak pressure by 0.3 %, 1e-2 by 9 %, 1e-6 by 2e-5); a reference solve needs a tight one")
        for name, low in (("fit_nodes", 2), ("max_iterations", 1), ("refine", 0)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < low:
                raise InputError(f"fem.{name} must be an integer >= {low}, got {value!r}")


#: the loosest MINRES tolerance (-) a reference solve accepts (FemSettings.rtol)
MAX_RTOL = 1e-6

MATERIALS = (ElasticMaterial, PronyMaterial, ThreeParameterMaterial)
_MODEL_NAMES = {ElasticMaterial: "elastic", PronyMaterial: "prony",
                ThreeParameterMaterial: "three_parameter"}


@dataclass(frozen=True)
class ContactProblem:
    """A layer, a material, an indenter, a loading and a discretization.

    A sphere or a paraboloid is stationary elastic indentation (axisymmetric or 3D);
    a line indenter is plane strain and may roll (``loading.speed`` > 0) on an elastic,
    Prony or three-parameter layer; a sphere rolls (``loading.speed`` > 0), and a
    cylinder (a roller of finite length) only rolls, in the 3d model (half box y >= 0,
    ``fem.upstream``, ``fem.downstream`` and ``fem.domain_radius`` the lateral extent).
    ``fem.model`` left unset is filled in from the indenter ("3d" for a cylinder).

    Raises
    ------
    InputError
        A wrong type, a model that does not fit the indenter, a viscoelastic material
        or a speed given to the stationary models, or a speed at or above the
        shear-wave speed c_s = sqrt(G_inf / rho).
    """

    layer: Layer
    material: object
    indenter: Indenter
    loading: Loading
    fem: FemSettings = field(default_factory=FemSettings)

    def __post_init__(self):
        for name, cls in (("layer", Layer), ("material", MATERIALS),
                          ("indenter", Indenter), ("loading", Loading),
                          ("fem", FemSettings)):
            if not isinstance(getattr(self, name), cls):
                kind = cls.__name__ if isinstance(cls, type) else \
                    " or ".join(c.__name__ for c in cls)
                raise InputError(f"{name} must be a {kind}, got {getattr(self, name)!r}")
        line = self.indenter.shape == "line"
        roller = self.indenter.shape == "cylinder"
        model = self.fem.model or ("plane_strain" if line else "3d" if roller else "axisymmetric")
        if line != (model == "plane_strain"):
            raise InputError(f"fem.model = {model!r} does not fit indenter.shape = "
                             f"{self.indenter.shape!r}: a line indenter is solved in plane strain "
                             "(fem.model = \"plane_strain\", the default), a sphere or a paraboloid "
                             "by the axisymmetric or 3d model")
        if model != self.fem.model:
            object.__setattr__(self, "fem", replace(self.fem, model=model))
        if roller and (model != "3d" or not self.loading.speed > 0):
            raise InputError(
                f"fem-reference cannot solve [indenter] shape = \"cylinder\" with fem.model = {model!r} and "
                f"loading.speed = {self.loading.speed!r}: a roller is solved by the 3d rolling model only "
                f"(fem.model = \"3d\", loading.speed > 0); for "
                "a stationary roller give an elastic material, density 0 and any speed (its solution then "
                "does not depend on the speed)")
        rolling_3d = model == "3d" and self.loading.speed > 0
        unused = (("domain_radius", "upstream and downstream"),) if line else () if rolling_3d else \
            (("upstream", "domain_radius"), ("downstream", "domain_radius"))
        for name, instead in unused:
            if getattr(self.fem, name) is not None:
                raise InputError(f"fem.{name} is not used by the {model} model; remove it "
                                 f"(the {model} model's extent is fem.{instead.replace(' and ', ' and fem.')})")
        if line and self.fem.solver != "direct":
            raise InputError(f"fem.solver = {self.fem.solver!r}: the plane-strain rolling system is "
                             "not symmetric and is solved by sparse LU only; use fem.solver = \"direct\"")
        if rolling_3d and self.fem.solver != "direct":
            raise InputError(f"fem.solver = {self.fem.solver!r}: the 3d rolling system is not "
                             "symmetric and is solved by sparse LU only; use fem.solver = \"direct\"")
        if not line and not rolling_3d:
            if self.loading.speed != 0:
                raise InputError(
                    f"[loading] speed must be 0 m/s: fem-reference solves stationary contact only "
                    f"for [indenter] shape = \"{self.indenter.shape}\" in the {model} model (a sphere "
                    f"rolls in [fem] model = \"3d\", a line in plane strain), got {self.loading.speed!r}")
            if not isinstance(self.material, ElasticMaterial):
                raise InputError(
                    f"fem-reference cannot solve [material] model = "
                    f"\"{_MODEL_NAMES[type(self.material)]}\" with [indenter] shape = "
                    f"\"{self.indenter.shape}\": the axisymmetric and 3d models are stationary "
                    "and elastic; viscoelastic rolling is solved in plane strain (shape = \"line\") "
                    "or, for a sphere at [loading] speed > 0, by [fem] model = \"3d\"")
        if rolling_3d and self.indenter.shape not in ("sphere", "cylinder"):
            raise InputError(f"indenter.shape = {self.indenter.shape!r}: the 3d rolling model "
                             "(fem.model = \"3d\", loading.speed > 0) takes a sphere or a cylinder")
        rho, V = self.layer.density, self.loading.speed
        if rho > 0 and V > 0:
            c_s = self.shear_wave_speed
            if V >= c_s:
                raise InputError(
                    f"[loading] speed = {V!r} m/s is at or above the layer's shear-wave speed "
                    f"c_s = sqrt(G_inf / rho) = sqrt({self.material.relaxed_modulus:g} Pa / {rho:g} "
                    f"kg/m^3) = {c_s:.6g} m/s: the steady moving-frame problem is subsonic only; "
                    "lower [loading] speed (or set [layer] density = 0 to neglect inertia)")

    @property
    def shear_wave_speed(self) -> float:
        """c_s = sqrt(G_inf / rho) (m/s) of the relaxed layer; inf without inertia."""
        if self.layer.density == 0:
            return math.inf
        return math.sqrt(self.material.relaxed_modulus / self.layer.density)
