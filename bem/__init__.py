"""Spectral boundary-element method for contact on a bonded incompressible viscoelastic
layer in a moving frame (Zehil and Gavin 2013).

Layer compliance in Fourier space (:mod:`bem.layer`), influence kernels as the paper's
truncated Fourier sums (:mod:`bem.spectral`), the nodal compliance operator
(:mod:`bem.operator`), indenters, and the frictionless contact solver with its rolling
resistance (:mod:`bem.contact`, :mod:`bem.problem`). SI units throughout.

Entry points: :func:`solve_frictionless` (frictionless contact of a :class:`Problem`, at
rest or rolling; in plane strain, a :class:`LineCylinder` on a :class:`LineGrid`, it
calls :func:`solve_line` and returns a :class:`LineContact`, per unit length) and :func:`solve_friction` (steady rolling or sliding with Coulomb
friction, :class:`Friction`; the solver is the package :mod:`bem.frictional`); on
prepared operators, :func:`solve_normal` and :func:`bem.frictional.solve_rolling`. Both
solvers' linear solves go through :class:`bem.linear.LinearSolver`.
"""

from .contact import ContactAtEdge, ContactError, ContactNotConverged, NormalContact, solve_normal
from .grid import Grid
from .indenters import Cylinder, HeightMap, Paraboloid, Sphere
from .layer import Layer, surface_compliance, surface_compliance_expm
from .materials import Elastic, MasterCurveTable, Prony, ThreeParameterSolid
from .operator import ComplianceOperator
from .problem import Loading, Problem, solve_frictionless
from .spectral import influence_kernels, influence_kernels_direct
from .friction import Friction, FrictionalContact, FrictionNotConverged, LoadingUnreachable
from .frictional import solve_friction
from .energy import viscous_dissipation
from .indenters import LineCylinder
from .plane import LineContact, LineGrid, solve_line

__all__ = [
    "ComplianceOperator", "ContactAtEdge", "ContactError", "ContactNotConverged", "Cylinder",
    "Elastic", "Grid", "HeightMap", "Layer", "Loading", "MasterCurveTable", "NormalContact",
    "Paraboloid", "Problem", "Prony", "Sphere", "ThreeParameterSolid", "influence_kernels",
    "influence_kernels_direct", "solve_frictionless", "solve_normal", "surface_compliance",
    "surface_compliance_expm",
    "Friction", "FrictionalContact", "FrictionNotConverged", "LoadingUnreachable", "solve_friction",
    "viscous_dissipation",
    "LineContact", "LineCylinder", "LineGrid", "solve_line",
]
