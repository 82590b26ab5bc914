"""Exactly incompressible finite-element reference for frictionless contact on a layer
bonded to a rigid base: stationary elastic indentation (axisymmetric or 3D), and steady
rolling on an elastic or viscoelastic (Prony, three-parameter) layer in the frame of the
indenter (one driver, :mod:`.rolling.solve`): of a rigid cylinder in plane strain
(docs/derivations.md section 7) and of a rigid sphere in 3D on the half layer y >= 0
(section 9; ``fem.model = "3d"`` with ``loading.speed`` > 0).

Taylor-Hood P2-P1 displacement-pressure elements (scikit-fem) on gmsh meshes
(read through meshio, named physical groups, refined around the contact), in an
axisymmetric (r, z) section (the high-accuracy reference) or a quarter cylinder
in 3D (a check of it). The contact pressure is a P1 Lagrange multiplier on a
refined candidate zone of the top surface (mortar coupling with u_z: a
consistent traction, no corner/mid-side oscillation of P2 nodal reactions); the
contact problem, condensed on that zone, is solved by an active-set method with
cycle detection (:mod:`.contact`). Load or displacement control. SI units.

The package in rooms: :mod:`.mesh` (one module per mesh), :mod:`.stationary` (the model
at rest), :mod:`.rolling` (steady rolling: :mod:`.rolling.plane_strain` and
:mod:`.rolling.three_d`, one driver), and the modules they share: the inputs
(:mod:`.problem`, :mod:`.materials`, :mod:`.case`), :mod:`.errors`, the linear solvers
(:mod:`.linsolve`), the contact solver (:mod:`.contact`), the contact-edge fit
(:mod:`.edge_fit`), the shared weak forms (:mod:`.shared_forms`), the a-priori sizes
(:mod:`.sizing`), the solver record (:mod:`.record`), the entry point :func:`solve`
(:mod:`.driver`), :mod:`.output` and :mod:`.cli`.

Python use::

    from fem_reference import (ContactProblem, Layer, ElasticMaterial, Indenter,
                               Loading, FemSettings, solve)
    result = solve(ContactProblem(Layer(5e-3), ElasticMaterial(3.0e6),
                                  Indenter("sphere", 0.02), Loading(load=100.0)))
    result.contact_radius, result.indentation, result.peak_pressure

Rolling (plane strain, per unit length)::

    result = solve(ContactProblem(Layer(1e-3), ThreeParameterMaterial(3e6, 0.25, 1.0),
                                  Indenter("line", 0.02), Loading(load=500.0, speed=0.01)))
    result.rolling_resistance, result.leading_edge, result.trailing_edge
    result.indentation, result.pressure_x, result.pressure, result.dissipation
    result.summary()

Rolling sphere (3D, totals in N; MKL Pardiso when ``pypardiso`` is installed)::

    result = solve(ContactProblem(Layer(5e-3, 1000.0), ThreeParameterMaterial(3e6, 0.25, 1.0),
                                  Indenter("sphere", 0.02), Loading(load=150.0, speed=0.05),
                                  FemSettings(model="3d")))
    result.rolling_resistance, result.rolling_resistance_energy, result.energy_balance
    result.leading_edge, result.trailing_edge          # on the symmetry line y = 0
    result.zone_xy, result.zone_pressure, result.peak_memory

Command line: ``fem-reference solve CASE.toml --json [--set fem.model='"3d"']
[--plot FILE.png] [--vtu FILE.vtu]``. The case file is the one of ``bem solve``
(docs/case-files.md); fem_reference reads ``[layer] thickness``,
``density``, ``[material] model = "elastic"`` with ``shear_modulus`` (and, for a
line, ``"three_parameter"`` or ``"prony"``), ``[indenter] shape`` ("sphere" |
"paraboloid" | "line") and ``radius``, ``[loading] load`` or ``indentation`` and
``speed`` (0 except for a line), and its own ``[fem]`` section:

=================  ==========================================================
``[fem]`` key      meaning (default)
=================  ==========================================================
``model``          "axisymmetric", "3d" (quarter cylinder) or "plane_strain"
                   (default: plane_strain for a line, else axisymmetric)
``element_size``   element size in the contact zone, m (axisymmetric
                   min(a_est/24, H/4); 3d min(a_est/8, H/2))
``contact_zone``   radius of the refined candidate contact zone, m (1.4 a_est)
``domain_radius``  lateral extent of the layer, m (contact_zone + 8 H; 3d
                   rolling: the half box's extent in y)
``upstream``       rolling: length ahead (inflow), m
``downstream``     rolling: length behind (outflow), m
``far_size``       largest element size, m (H/2 axisymmetric, H in 3d)
``grading``        size growth with distance from the zone, - (0.3)
``refine``         uniform refinements of the gmsh mesh (nested levels), (0)
``solver``         "direct" (SuperLU) or "minres" (AMG block preconditioner)
``rtol``           MINRES relative tolerance, - (1e-8)
``fit_nodes``      surface vertices outside the edge fitted for the radius (3)
``max_iterations`` active-set iteration limit (100)
=================  ==========================================================

a_est (m) is the smaller of the Hertz radius and the thin-layer asymptote
(:mod:`.sizing`). Every failure raises a subclass of
:class:`FemReferenceError`.
"""

import importlib

# Names are imported on first use (PEP 562), so that ``fem-reference --help`` answers
# without loading numpy, scipy and scikit-fem.
_EXPORTS = {
    "errors": ("ContactNotConvergedError", "ContactZoneError", "FemReferenceError", "InputError",
               "LinearSolverError", "MeshError", "MissingDependencyError"),
    "materials": ("ElasticMaterial", "PronyMaterial", "ThreeParameterMaterial"),
    "problem": ("ContactProblem", "FemSettings", "Indenter", "Layer", "Loading"),
    "rolling": ("RollingResult", "SphereRollingResult"),
    "driver": ("solve",),
    "stationary": ("ContactResult",),
}
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
        globals()[name] = value
        return value
    try:  # a submodule, as ``fem_reference.mesh`` after ``import fem_reference``
        return importlib.import_module(f".{name}", __name__)
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "solve", "ContactProblem", "Layer", "ElasticMaterial", "PronyMaterial",
    "ThreeParameterMaterial", "Indenter", "Loading", "FemSettings", "ContactResult",
    "RollingResult", "SphereRollingResult", "FemReferenceError", "InputError", "MeshError",
    "LinearSolverError", "ContactNotConvergedError", "ContactZoneError", "MissingDependencyError",
]
