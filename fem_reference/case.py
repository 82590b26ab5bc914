"""Case files (the TOML schema shared with ``bem solve``, ``docs/case-files.md``) to
:class:`ContactProblem`.

:mod:`casefile` checks the file for ``fem-reference`` (unknown keys, types, and physics
this reference cannot solve, such as ``[friction]``, are errors; the BEM's ``[grid]`` is
ignored); this module turns the checked dict into the FEM's own objects: ``[layer]
thickness``, ``[material] model = "elastic"`` with ``shear_modulus``, ``[indenter]
shape`` ("sphere" | "paraboloid") and ``radius``, ``[loading] load`` or ``indentation``
(``speed`` must be 0) and the ``[fem]`` section. SI units.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, Iterable

import casefile

from .errors import InputError
from .problem import ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading

__all__ = ["load_case", "problem_from_dict"]


def problem_from_dict(data: Dict[str, Any]) -> ContactProblem:
    """Build and validate the problem from a case as a dict of sections.

    Raises
    ------
    InputError
        For anything :func:`casefile.validate` rejects, a non-zero speed, or any value
        that breaks its rule.
    """
    try:
        data = casefile.validate(data, "fem")
    except casefile.CaseFileError as exc:
        raise InputError(str(exc)) from None
    speed = data["loading"].get("speed", 0.0)
    if speed != 0:
        raise InputError(f"[loading] speed must be 0 m/s: fem-reference solves stationary contact "
                         f"only (bem solve rolls), got {speed!r}")
    loading = data["loading"]
    return ContactProblem(
        layer=Layer(thickness=data["layer"]["thickness"]),
        material=ElasticMaterial(shear_modulus=data["material"]["shear_modulus"]),
        indenter=Indenter(shape=data["indenter"]["shape"], radius=data["indenter"]["radius"]),
        loading=Loading(load=loading.get("load"), indentation=loading.get("indentation")),
        fem=FemSettings(**data.get("fem", {})),
    )


def load_case(path: str | Path, overrides: Iterable[str] = ()) -> ContactProblem:
    """Read a TOML case file, apply ``--set`` overrides (:func:`casefile.read`), return
    the problem."""
    try:
        data = casefile.read(path, overrides, tool="fem")
    except casefile.CaseFileError as exc:
        raise InputError(str(exc)) from None
    return problem_from_dict(data)
