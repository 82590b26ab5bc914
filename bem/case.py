"""Case files: a TOML description of a problem (schema in README.md, "Case files")."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np

from .grid import Grid
from .indenters import Cylinder, HeightMap, Paraboloid, Sphere
from .layer import Layer
from .materials import material_from_config
from .problem import Loading, Problem, auto_half_width

__all__ = ["read_case", "apply_overrides", "problem_from_config", "friction_from_config"]

_SECTIONS = {
    "layer": {"thickness", "density"},
    "material": None,  # checked by bem.materials
    "indenter": {"shape", "radius", "length", "file"},
    "loading": {"speed", "load", "indentation"},
    "grid": {"spacing", "spacing_x", "spacing_y", "period", "period_x", "period_y", "truncation",
             "truncation_x", "truncation_y", "half_width", "half_width_x", "half_width_y"},
    "friction": {"mu", "mode", "omega", "radius", "max_iter", "direction_tol", "set_tol", "dense_limit"},
    "fem": None,  # read by fem_reference only
}


def apply_overrides(config: dict, overrides: list[str]) -> dict:
    """Apply ``section.key=value`` strings (value parsed as TOML) to ``config`` in place."""
    for item in overrides:
        key, sep, value = item.partition("=")
        section, dot, name = key.strip().partition(".")
        if not sep or not dot or not name:
            raise ValueError(f"--set expects section.key=value, got {item!r}")
        try:
            parsed = tomllib.loads(f"v = {value}")["v"]
        except tomllib.TOMLDecodeError:
            parsed = value  # a bare string
        config.setdefault(section, {})[name] = parsed
    return config


def read_case(path: str | Path, overrides: list[str] = ()) -> tuple[dict, Path]:
    """Parse a case file and apply overrides; returns the config and its folder."""
    path = Path(path)
    with path.open("rb") as fh:
        config = tomllib.load(fh)
    return apply_overrides(config, list(overrides)), path.parent


def _pair(section: dict, name: str, default=None):
    both = section.get(name, default)
    pair = (section.get(f"{name}_x", both), section.get(f"{name}_y", both))
    if None in pair:
        raise ValueError(f"[grid] needs {name} (or {name}_x and {name}_y)")
    return pair


def _indenter(sec: dict, base: Path):
    shape = sec.get("shape", "sphere")
    if shape == "heightmap":
        data = np.load(base / sec["file"])
        return HeightMap(data["x"], data["y"], data["h"])
    if "radius" not in sec:
        raise ValueError(f"[indenter] shape = {shape!r} needs radius (m)")
    if shape == "sphere":
        return Sphere(sec["radius"])
    if shape == "paraboloid":
        return Paraboloid(sec["radius"])
    if shape == "cylinder":
        if "length" not in sec:
            raise ValueError("[indenter] shape = \"cylinder\" needs length (m), the roller's length along y")
        return Cylinder(sec["radius"], sec["length"])
    raise ValueError(f"[indenter] shape must be sphere, paraboloid, cylinder or heightmap, got {shape!r}")


def problem_from_config(config: dict, base: Path = Path(".")) -> tuple[Problem, bool]:
    """Build the problem; the flag tells whether the region was sized automatically."""
    for name, sec in config.items():
        if name not in _SECTIONS:
            raise ValueError(f"unknown section [{name}]; known: {sorted(_SECTIONS)}")
        allowed = _SECTIONS[name]
        if allowed is not None:
            unknown = set(sec) - allowed
            if unknown:
                raise ValueError(f"unknown key(s) {sorted(unknown)} in [{name}]; allowed: {sorted(allowed)}")
    for required in ("layer", "material", "indenter", "loading", "grid"):
        if required not in config:
            raise ValueError(f"the case needs a [{required}] section")
    lay = config["layer"]
    if "thickness" not in lay:
        raise ValueError("[layer] needs thickness (m)")
    layer = Layer(lay["thickness"], material_from_config(config["material"], base), lay.get("density", 0.0))
    indenter = _indenter(config["indenter"], base)
    ld = config["loading"]
    loading = Loading(ld.get("speed", 0.0), ld.get("load"), ld.get("indentation"))
    g = config["grid"]
    spacing = _pair(g, "spacing")
    auto = "half_width" not in g and "half_width_x" not in g and "half_width_y" not in g
    hw_default = auto_half_width(layer, indenter, loading, max(spacing)) if auto else g.get("half_width")
    grid = Grid.centred(spacing, _pair(g, "period"), _pair(g, "truncation"), _pair(g, "half_width", hw_default))
    return Problem(layer, indenter, grid, loading), auto


def friction_from_config(config: dict):
    """The ``[friction]`` section as :class:`bem.friction.Friction`, or ``None`` if absent."""
    from .friction import Friction

    sec = config.get("friction")
    if sec is None:
        return None
    if "mu" not in sec:
        raise ValueError("[friction] needs mu (-)")
    return Friction(**sec)
