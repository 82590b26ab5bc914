"""Spectral boundary-element method for contact on a bonded incompressible viscoelastic
layer in a moving frame (Zehil and Gavin 2013). SI units throughout.

One entry point, :func:`solve`::

    from bem import Grid, Layer, Loading, Problem, Sphere, ThreeParameterSolid, solve

    layer = Layer(5e-3, ThreeParameterSolid(G0=3e6, tau=0.25, f=1.0), density=1000.0)
    grid = Grid.centred((2.5e-4, 2.5e-4), (0.2, 0.2), (400, 400), (5e-3, 5e-3))
    result = solve(Problem(layer, Sphere(0.02), grid, Loading(speed=0.05, load=150.0)))
    result.rolling_resistance, result.rolling_resistance_energy, result.leading_edge

A :class:`Problem` composes a :class:`Layer` (thickness, material, density), an indenter
(:class:`Sphere`, :class:`Paraboloid`, :class:`Cylinder`, :class:`HeightMap`; or a
:class:`LineCylinder` on a :class:`LineGrid` for a line contact in plane strain, per unit
length), a :class:`Grid` and a :class:`Loading` (speed, load or indentation). Without
friction :func:`solve` returns a :class:`NormalContact` (a :class:`LineContact` in plane
strain): the fields, the scalars, the rolling figures (dissipation, the pressure's power,
the contact's edges on ``y = 0``) and the solve record. With ``friction`` a
:class:`Friction` it returns a :class:`FrictionalContact` (steady rolling or sliding with
Coulomb friction, the solver of :mod:`bem.frictional`).

Modules: the layer's compliance in Fourier space (:mod:`bem.layer`), influence kernels as
the paper's truncated Fourier sums (:mod:`bem.spectral`), the nodal compliance operator
(:mod:`bem.operator`), the frictionless contact solver (:mod:`bem.contact`, and on
prepared operators :func:`bem.contact.solve_normal`), its results (:mod:`bem.result`),
plane strain (:mod:`bem.plane`), the layer's dissipation (:mod:`bem.energy`), the
frictional solver (:mod:`bem.frictional`, on prepared operators
:func:`bem.frictional.solve_rolling`) and the driver (:mod:`bem.driver`). Both contact
solvers' linear solves go through :class:`bem.linear.LinearSolver`, their transforms
through :mod:`bem.fft` (numpy.fft on one thread, scipy.fft on more).
"""

import importlib

# Names are imported on first use (PEP 562), so that ``bem --help`` answers without
# loading numpy and scipy; ``from bem import solve`` works as with eager imports.
_EXPORTS = {
    "contact": ("ContactAtEdge", "ContactError", "ContactNotConverged"),
    "driver": ("solve",),
    "energy": ("viscous_dissipation",),
    "frictional": ("Friction", "FrictionalContact", "FrictionNotConverged", "LoadingUnreachable"),
    "grid": ("Grid",),
    "indenters": ("Cylinder", "HeightMap", "LineCylinder", "Paraboloid", "Sphere"),
    "layer": ("Layer", "surface_compliance", "surface_compliance_expm"),
    "materials": ("Elastic", "MasterCurveTable", "Prony", "ThreeParameterSolid"),
    "operator": ("ComplianceOperator",),
    "plane": ("LineContact", "LineGrid"),
    "problem": ("Loading", "Problem"),
    "result": ("NormalContact",),
    "spectral": ("influence_kernels", "influence_kernels_direct"),
}
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
        globals()[name] = value
        return value
    try:  # a submodule, as ``bem.spectral`` after ``import bem``
        return importlib.import_module(f".{name}", __name__)
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "solve",
    "ComplianceOperator", "ContactAtEdge", "ContactError", "ContactNotConverged", "Cylinder",
    "Elastic", "Grid", "HeightMap", "Layer", "Loading", "MasterCurveTable", "NormalContact",
    "Paraboloid", "Problem", "Prony", "Sphere", "ThreeParameterSolid", "influence_kernels",
    "influence_kernels_direct", "surface_compliance", "surface_compliance_expm",
    "Friction", "FrictionalContact", "FrictionNotConverged", "LoadingUnreachable",
    "viscous_dissipation",
    "LineContact", "LineCylinder", "LineGrid",
]
