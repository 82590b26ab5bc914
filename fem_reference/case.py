"""Case files (the TOML schema shared with ``bem solve``, ``docs/case-files.md``) to
:class:`ContactProblem`.

:mod:`casefile` checks the file for ``fem-reference`` (unknown keys, types, and physics
this reference cannot solve, such as ``[friction]``, are errors; the BEM's ``[grid]`` is
ignored); this module turns the checked dict into the FEM's own objects: ``[layer]
thickness`` and ``density``, ``[material]`` ``model = "elastic"`` (``shear_modulus``),
``"three_parameter"`` (``G0``, ``tau``, ``f``) or ``"prony"`` (``G_inf``, ``G``, ``tau``),
``[indenter] shape`` ("sphere" | "paraboloid" | "line" | "cylinder") and ``radius`` (a
cylinder's ``length``, ``edge_radius``, ``crown_radius``), ``[loading]
load`` or ``indentation`` and ``speed`` (> 0 for a line, or for a sphere with ``[fem]
model = "3d"``), and the ``[fem]``
section. A measured master curve (``model = "table"``) has no time-domain form and is
refused. SI units.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, Iterable

import casefile

from .errors import InputError
from .materials import ElasticMaterial, PronyMaterial, ThreeParameterMaterial
from .problem import ContactProblem, FemSettings, Indenter, Layer, Loading

__all__ = ["load_case", "problem_from_dict"]


def problem_from_dict(data: Dict[str, Any]) -> ContactProblem:
    """Build and validate the problem from a case as a dict of sections.

    Raises
    ------
    InputError
        For anything :func:`casefile.validate` rejects, a master-curve table, a speed
        given to a stationary model (axisymmetric, or a paraboloid) or at or above the
        shear-wave speed, or
        any value that breaks its rule.
    """
    try:
        data = casefile.validate(data, "fem")
    except casefile.CaseFileError as exc:
        raise InputError(str(exc)) from None
    loading = data["loading"]
    return ContactProblem(
        layer=Layer(thickness=data["layer"]["thickness"], density=data["layer"].get("density", 0.0)),
        material=material_from_dict(data["material"]),
        indenter=_indenter(data["indenter"]),
        loading=Loading(load=loading.get("load"), indentation=loading.get("indentation"),
                        speed=loading.get("speed", 0.0)),
        fem=FemSettings(**data.get("fem", {})),
    )


def _indenter(table: Dict[str, Any]) -> Indenter:
    """The ``[indenter]`` table; a cylinder's ``length``, ``edge_radius``, ``crown_radius``."""
    if table["shape"] != "cylinder":
        return Indenter(shape=table["shape"], radius=table["radius"])
    return Indenter(shape="cylinder", radius=table["radius"], length=table["length"],
                    edge_radius=table.get("edge_radius", 0.0), crown_radius=table.get("crown_radius"))


def material_from_dict(table: Dict[str, Any]):
    """The ``[material]`` table as fem_reference's material.

    Raises
    ------
    InputError
        For ``model = "table"``: a measured master curve G*(omega) has no time-domain
        (Prony) form, which the moving-frame FEM integrates.
    """
    model = table["model"]
    if model == "elastic":
        return ElasticMaterial(shear_modulus=table["shear_modulus"])
    if model == "three_parameter":
        return ThreeParameterMaterial(G0=table["G0"], tau=table["tau"], f=table["f"])
    if model == "prony":
        return PronyMaterial(G_inf=table["G_inf"], G=tuple(table["G"]), tau=tuple(table["tau"]))
    raise InputError(
        f"fem-reference cannot solve [material] model = \"{model}\": a measured master curve "
        "G*(omega) has no time-domain form, and the FEM integrates the viscous strains of a "
        "generalized Maxwell solid along the flow; fit a Prony series to the curve and give "
        "model = \"prony\" (G_inf, G, tau), or use bem solve")


def load_case(path: str | Path, overrides: Iterable[str] = ()) -> ContactProblem:
    """Read a TOML case file, apply ``--set`` overrides (:func:`casefile.read`), return
    the problem."""
    try:
        data = casefile.read(path, overrides, tool="fem")
    except casefile.CaseFileError as exc:
        raise InputError(str(exc)) from None
    return problem_from_dict(data)
