"""Case files to BEM problems: the dict that :mod:`casefile` checked, translated into a
:class:`bem.problem.Problem` and a :class:`bem.frictional.Friction` (schema in
``docs/case-files.md``)."""

from __future__ import annotations

import pathlib
from pathlib import Path

import numpy as np

import casefile

from .grid import Grid
from .indenters import Cylinder, HeightMap, LineCylinder, Paraboloid, Sphere
from .layer import Layer
from .materials import Elastic, Material, MasterCurveTable, Prony, ThreeParameterSolid
from .plane import LineGrid
from .problem import Loading, Problem, auto_half_width

__all__ = ["read_case", "problem_from_config", "friction_from_config", "material_from_config"]


def read_case(path: str | Path, overrides: list[str] = ()) -> dict:
    """Read, override and check a case file for the BEM (:func:`casefile.read`).

    Raises
    ------
    casefile.CaseFileError
        A key, a type, a value or a section that breaks the schema.
    """
    return casefile.read(path, overrides, tool="bem")


def _pair(section: dict, name: str, default=None) -> tuple:
    given = [k for k in (f"{name}_x", f"{name}_y") if k in section]
    if name in section and given:
        raise casefile.CaseFileError(f"[grid] gives both {name} and {given[0]}: {name} sets the x and y values at "
                                     f"once, {given[0]} one of them; keep one")
    both = section.get(name, default)
    pair = (section.get(f"{name}_x", both), section.get(f"{name}_y", both))
    if None in pair:
        raise casefile.CaseFileError(f"[grid] needs {name} (or {name}_x and {name}_y)")
    return pair


def _height_map(file: str) -> HeightMap:
    import zipfile  # 5 ms of every start-up, with shutil, bz2 and lzma

    try:
        data = np.load(file)
        if not isinstance(data, np.lib.npyio.NpzFile):  # a .npy file holds one array
            raise casefile.CaseFileError(f"[indenter] file {file!r} holds one array, not an NPZ archive of "
                                         "x (m), y (m) and h (m) (numpy.savez)")
        with data:
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
        try:
            return Cylinder(sec["radius"], sec["length"], sec.get("edge_radius", 0.0), sec.get("crown_radius"))
        except ValueError as exc:  # the rules between keys, which the schema checks one by one
            raise casefile.CaseFileError(f"[indenter] {exc}") from None
    if shape == "line":
        return LineCylinder(sec["radius"])
    return {"sphere": Sphere, "paraboloid": Paraboloid}[shape](sec["radius"])


_GRID_KEYS = ("spacing", "period", "truncation", "half_width")


def _line_grid(g: dict, layer: Layer, indenter: LineCylinder, loading: Loading) -> tuple[LineGrid, bool]:
    """The one-row grid of a line case from ``[grid]``: ``spacing``, ``period``,
    ``truncation``, ``half_width`` (or their ``_x`` forms); a ``_y`` key is an error."""
    ys = sorted(k for k in g if k.endswith("_y"))
    if ys:
        raise casefile.CaseFileError(
            f"[grid] {', '.join(ys)}: a line case ([indenter] shape = \"line\", plane strain) has a grid of "
            "one row along x and no y keys; remove them (give spacing, period, truncation and half_width, "
            "or their _x forms)"
        )
    vals = {}
    for name in _GRID_KEYS:
        if name in g and f"{name}_x" in g:
            raise casefile.CaseFileError(f"[grid] gives both {name} and {name}_x; keep one")
        vals[name] = g.get(name, g.get(f"{name}_x"))
    missing = [n for n in _GRID_KEYS[:3] if vals[n] is None]
    if missing:
        raise casefile.CaseFileError(f"[grid] needs {', '.join(missing)} (or the _x form) for a line case")
    auto = vals["half_width"] is None
    hw = auto_half_width(layer, indenter, loading, vals["spacing"]) if auto else vals["half_width"]
    return LineGrid.centred(vals["spacing"], vals["period"], vals["truncation"], hw), auto


def _dma_material(sec: dict):
    """The :class:`bem.dma.case.CaseMaterial` of ``[material] model = "dma"``, else ``None``
    (the file path is already absolute: :func:`casefile.validate` resolved it)."""
    if sec["model"] != "dma":
        return None
    from .dma.case import dma_material

    return dma_material(sec, Path("."))


def _check_band(dma, loading: Loading, spacing_x: float, period_x: float) -> None:
    """The frequency band of the case against the DMA data's range (:func:`bem.dma.case.check_band`)."""
    if dma is not None:
        from .dma.case import check_band

        check_band(dma, loading.speed, spacing_x, period_x)


def problem_from_config(config: dict) -> tuple[Problem, bool]:
    """The problem of a case (a dict of sections, checked here by :func:`casefile.validate`
    if it was not already); the flag tells whether the region was sized automatically.

    A line case (``[indenter] shape = "line"``: plane strain, load per unit length in N/m)
    gets a :class:`bem.plane.LineGrid` (``_y`` grid keys are errors there); its
    ``[friction]`` is solved per unit length too. A ``[material] model = "dma"`` case is
    built at its service temperature and its frequency band checked against the data
    (:mod:`bem.dma.case`)."""
    config = casefile.validate(config, "bem")
    lay, ld, g = config["layer"], config["loading"], config["grid"]
    dma = _dma_material(config["material"])
    material = dma.material if dma else material_from_config(config["material"], Path("."))
    layer = Layer(lay["thickness"], material, lay.get("density", 0.0))
    indenter = _indenter(config["indenter"])
    loading = Loading(ld.get("speed", 0.0), ld.get("load"), ld.get("indentation"))
    if isinstance(indenter, LineCylinder):
        grid, auto = _line_grid(g, layer, indenter, loading)
        _check_band(dma, loading, grid.spacing, grid.period)
        return Problem(layer, indenter, grid, loading), auto
    spacing = _pair(g, "spacing")
    auto = not {"half_width", "half_width_x", "half_width_y"} & set(g)
    hw_default = auto_half_width(layer, indenter, loading, max(spacing)) if auto else g.get("half_width")
    grid = Grid.centred(spacing, _pair(g, "period"), _pair(g, "truncation"), _pair(g, "half_width", hw_default))
    _check_band(dma, loading, grid.spacing_x, grid.period_x)
    return Problem(layer, indenter, grid, loading), auto


def friction_from_config(config: dict):
    """The ``[friction]`` section as :class:`bem.frictional.Friction`, or ``None`` if absent."""
    from .frictional.model import Friction

    checked = casefile.validate(config, "bem")
    sec, own = checked.get("friction"), checked["indenter"].get("radius")
    if sec is not None and "radius" in sec and own is not None and sec["radius"] != own:
        # the radius is the axis-to-lowest-point distance of a body that has none of its own (a height
        # map); a body with a radius rolls on it (bem.kinematics), so another one would be a second body
        raise casefile.CaseFileError(
            f"[friction] radius = {sec['radius']!r} m differs from [indenter] radius = {own!r} m: the friction "
            "radius is for an indenter without one (shape = \"heightmap\"); remove it, the indenter's is used")
    return None if sec is None else Friction(**sec)


_MODELS = {
    "elastic": (Elastic, ("shear_modulus",)),
    "three_parameter": (ThreeParameterSolid, ("G0", "tau", "f")),
    "prony": (Prony, ("G_inf", "G", "tau")),
    "table": (MasterCurveTable.from_csv, ("file",)),
}


def _dma(section: dict, base_dir) -> Material:
    """A ``model = "dma"`` table checked against the case schema, then built at its
    service temperature."""
    from casefile import CaseFileError, check_table
    from casefile.schema import section as schema_section

    from .dma.case import dma_material

    spec = schema_section("material")
    keys = spec.keys + spec.variants["dma"].keys
    checked = check_table("[material]", section, keys, folder=base_dir, context=' for model = "dma"',
                          error=CaseFileError)
    return dma_material(checked, base_dir).material


def material_from_config(section: dict, base_dir: pathlib.Path) -> Material:
    """Build a material from the ``[material]`` table of a TOML case file.

    Parameters
    ----------
    section : dict
        ``{"model": "elastic", "shear_modulus": ...}``, ``{"model": "three_parameter",
        "G0", "tau", "f"}``, ``{"model": "prony", "G_inf", "G", "tau"}`` or
        ``{"model": "table", "file": ...}`` or ``{"model": "dma", "file": ...,
        "reference_temperature": ..., "temperature": ...}`` (SI units, temperatures in K;
        keys in ``docs/case-files.md``). A ``"dma"`` table gives the material at its
        service temperature (:func:`bem.dma.case.dma_material`; the frequency band check
        needs the grid and the speed, so :func:`bem.case.problem_from_config` makes it).
    base_dir : pathlib.Path
        Directory that a table's ``file`` is relative to (the case file's directory).

    Raises
    ------
    ValueError
        Unknown model, unknown or missing key (naming it and the allowed ones), or
        invalid values; for ``"dma"`` a :class:`bem.dma.DMAError` naming the key or the
        file's line.
    """
    allowed = ", ".join((*_MODELS, "dma"))
    if "model" not in section:
        raise ValueError(f"material.model is missing (allowed: {allowed})")
    model = section["model"]
    if model == "dma":
        return _dma(section, base_dir)
    if model not in _MODELS:
        raise ValueError(f"material.model must be one of {allowed}, got {model!r}")
    build, keys = _MODELS[model]
    for key in section:
        if key != "model" and key not in keys:
            raise ValueError(
                f"unknown key material.{key} for model {model!r} (allowed keys: model, {', '.join(keys)})"
            )
    for key in keys:
        if key not in section:
            raise ValueError(f"material.{key} is missing for model {model!r} (required keys: {', '.join(keys)})")
    if model == "table":
        if not isinstance(section["file"], str):
            raise ValueError(f"material.file must be a path string, got {section['file']!r}")
        return build(pathlib.Path(base_dir) / section["file"])
    return build(**{key: section[key] for key in keys})
