"""Case files (TOML, shared with ``bem solve``) to :class:`ContactProblem`.

fem_reference reads ``[layer] thickness``; ``[material] model = "elastic"``,
``shear_modulus``; ``[indenter] shape``, ``radius``; ``[loading] load`` or
``indentation`` (``speed``, if given, must be 0) and the ``[fem]`` section
(keys in the package docstring). Other sections (``[grid]``) and
``layer.density`` are for ``bem`` and ignored. SI units.
"""

from __future__ import annotations

import tomllib
from dataclasses import fields
from pathlib import Path
from typing import Any, Dict, Iterable

from .errors import InputError
from .problem import ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading

__all__ = ["load_case", "problem_from_dict", "apply_override"]


def apply_override(data: Dict[str, Any], assignment: str) -> None:
    """Apply ``section.key=value`` (value parsed as TOML) to ``data`` in place."""
    name, sep, text = assignment.partition("=")
    section, dot, key = name.strip().partition(".")
    if not sep or not dot or not section or not key:
        raise InputError(f"--set must look like section.key=value, got {assignment!r}")
    try:
        value = tomllib.loads(f"v = {text.strip()}")["v"]
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"--set {name}: the value {text.strip()!r} is not TOML ({exc}); "
                         "quote strings as '\"3d\"'") from exc
    data.setdefault(section, {})[key] = value


def _section(data, name):
    sec = data.get(name)
    if not isinstance(sec, dict):
        raise InputError(f"the case file needs a [{name}] section")
    return sec


def _need(sec, section, key):
    if key not in sec:
        raise InputError(f"the case file needs {section}.{key}")
    return sec[key]


def problem_from_dict(data: Dict[str, Any]) -> ContactProblem:
    """Build and validate the problem from a parsed case file (module docstring).

    Raises
    ------
    InputError
        For a missing key, a model other than "elastic", a non-zero speed, an
        unknown ``[fem]`` key or any value that breaks its rule.
    """
    layer = _section(data, "layer")
    material = _section(data, "material")
    indenter = _section(data, "indenter")
    loading = _section(data, "loading")
    model = material.get("model", "elastic")
    if model != "elastic":
        raise InputError(f"material.model must be 'elastic' for fem_reference (the FEM "
                         f"reference is elastic and stationary only), got {model!r}")
    speed = loading.get("speed", 0.0)
    if speed != 0:
        raise InputError(f"loading.speed must be 0 m/s for fem_reference (the FEM reference "
                         f"is elastic and stationary only), got {speed!r}")
    fem = dict(data.get("fem", {}))
    known = {f.name for f in fields(FemSettings)}
    unknown = sorted(set(fem) - known)
    if unknown:
        raise InputError(f"unknown [fem] key(s) {unknown}; known: {sorted(known)}")
    return ContactProblem(
        layer=Layer(thickness=_need(layer, "layer", "thickness")),
        material=ElasticMaterial(shear_modulus=_need(material, "material", "shear_modulus")),
        indenter=Indenter(shape=_need(indenter, "indenter", "shape"),
                          radius=_need(indenter, "indenter", "radius")),
        loading=Loading(load=loading.get("load"), indentation=loading.get("indentation")),
        fem=FemSettings(**fem),
    )


def load_case(path, overrides: Iterable[str] = ()) -> ContactProblem:
    """Read a TOML case file, apply ``--set`` overrides, return the problem."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text())
    except FileNotFoundError as exc:
        raise InputError(f"case file {str(path)!r} not found") from exc
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"case file {str(path)!r} is not valid TOML: {exc}") from exc
    for item in overrides:
        apply_override(data, item)
    return problem_from_dict(data)
