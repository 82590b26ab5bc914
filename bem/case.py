"""Case files to BEM problems: the dict that :mod:`casefile` checked, translated into a
:class:`bem.problem.Problem` and a :class:`bem.friction.Friction` (schema in
``docs/case-files.md``)."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np

import casefile

from .grid import Grid
from .indenters import Cylinder, HeightMap, Paraboloid, Sphere
from .layer import Layer
from .materials import material_from_config
from .problem import Loading, Problem, auto_half_width

__all__ = ["read_case", "problem_from_config", "friction_from_config"]


def read_case(path: str | Path, overrides: list[str] = ()) -> dict:
    """Read, override and check a case file for the BEM (:func:`casefile.read`).

    Raises
    ------
    casefile.CaseFileError
        A key, a type, a value or a section that breaks the schema.
    """
    return casefile.read(path, overrides, tool="bem")


def _pair(section: dict, name: str, default=None) -> tuple:
    both = section.get(name, default)
    pair = (section.get(f"{name}_x", both), section.get(f"{name}_y", both))
    if None in pair:
        raise casefile.CaseFileError(f"[grid] needs {name} (or {name}_x and {name}_y)")
    return pair


def _height_map(file: str) -> HeightMap:
    try:
        with np.load(file) as data:
            missing = [k for k in ("x", "y", "h") if k not in data]
            if missing:
                raise casefile.CaseFileError(f"[indenter] file {file!r} lacks the array(s) {', '.join(missing)}; "
                                             "a height map holds x (m), y (m) and h (m)")
            arrays = data["x"], data["y"], data["h"]
    except (ValueError, OSError, zipfile.BadZipFile) as exc:
        if isinstance(exc, casefile.CaseFileError):
            raise
        raise casefile.CaseFileError(f"[indenter] file {file!r} is not an NPZ archive of x, y, h: {exc}") from None
    try:
        return HeightMap(*arrays)
    except ValueError as exc:
        raise casefile.CaseFileError(f"[indenter] file {file!r}: {exc}") from None


def _indenter(sec: dict):
    shape = sec["shape"]
    if shape == "heightmap":
        return _height_map(sec["file"])
    if shape == "cylinder":
        return Cylinder(sec["radius"], sec["length"])
    return {"sphere": Sphere, "paraboloid": Paraboloid}[shape](sec["radius"])


def problem_from_config(config: dict) -> tuple[Problem, bool]:
    """The problem of a case (a dict of sections, checked here by :func:`casefile.validate`
    if it was not already); the flag tells whether the region was sized automatically."""
    config = casefile.validate(config, "bem")
    lay, ld, g = config["layer"], config["loading"], config["grid"]
    layer = Layer(lay["thickness"], material_from_config(config["material"], Path(".")), lay.get("density", 0.0))
    indenter = _indenter(config["indenter"])
    loading = Loading(ld.get("speed", 0.0), ld.get("load"), ld.get("indentation"))
    spacing = _pair(g, "spacing")
    auto = not {"half_width", "half_width_x", "half_width_y"} & set(g)
    hw_default = auto_half_width(layer, indenter, loading, max(spacing)) if auto else g.get("half_width")
    grid = Grid.centred(spacing, _pair(g, "period"), _pair(g, "truncation"), _pair(g, "half_width", hw_default))
    return Problem(layer, indenter, grid, loading), auto


def friction_from_config(config: dict):
    """The ``[friction]`` section as :class:`bem.friction.Friction`, or ``None`` if absent."""
    from .friction import Friction

    sec = casefile.validate(config, "bem").get("friction")
    return None if sec is None else Friction(**sec)
