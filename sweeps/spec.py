"""The sweep file: a base case and the axes that vary it, and its expansion into points.

A sweep file is TOML (``docs/sweeps.md``)::

    case = "../paper-section11-friction.toml"   # or a list: an implicit axis "case"
    set = ["grid.truncation=500"]               # overrides of every base case
    combine = "product"                         # or "zip" (axes of equal length)

    [[axis]]
    key = "loading.load"                        # any case key, section.key
    values = [10, 50, 100, 150]                 # or start/stop/num (+ scale = "log")

    [output]
    x = "loading.load"                          # the plots' abscissa (default: first axis)
    plot = ["rolling_resistance"]               # results drawn against x

    [[fit]]
    law = "power"                               # or "two_exponential"
    y = "rolling_resistance"

Every point is the base case with the axis values set, checked by
:func:`casefile.validate` for the BEM before anything runs, so a bad value is an error
that names the point. Units are the case file's (SI).
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import casefile
from casefile.schema import section

__all__ = ["SweepError", "Axis", "FitRequest", "Sweep", "Point", "read_sweep", "expand", "LAWS"]

#: the fitted laws (``sweeps.fits``)
LAWS = ("power", "two_exponential")
_TOP = ("name", "case", "set", "combine", "axis", "output", "fit")


class SweepError(ValueError):
    """A sweep file, or a point it makes, that cannot run."""


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


@dataclass(frozen=True)
class Axis:
    """One varied case key and its values.

    Parameters
    ----------
    key : str
        ``"section.key"`` of the case schema (``docs/case-files.md``), or ``"case"`` (the
        base case file, made from a list ``case = [...]``).
    values : tuple
        The values, in the key's unit (SI), at least one.
    """

    key: str
    values: tuple

    def __post_init__(self) -> None:
        if not self.values:
            raise SweepError(f"axis {self.key!r}: no values (an empty list or range)")
        if self.key == "case":
            return
        sec, dot, name = self.key.partition(".")
        spec = section(sec)
        if not dot or spec is None:
            from casefile import SCHEMA

            raise SweepError(f"axis key {self.key!r} must be section.key with a known section "
                             f"({', '.join(s.name for s in SCHEMA)})")
        if not spec.all_keys(name):
            known = sorted({k.name for k in spec.keys} | {k.name for v in spec.variants.values() for k in v.keys})
            raise SweepError(f"axis key {self.key!r}: [{sec}] has no key {name!r}; known keys: {', '.join(known)}")

    @property
    def kinds(self) -> set:
        """The schema kinds the key takes."""
        sec, _, name = self.key.partition(".")
        return {k.kind for k in section(sec).all_keys(name)}


def _axis(where: str, table: dict) -> Axis:
    if not isinstance(table, dict):
        raise SweepError(f"{where} must be a table ([[axis]]), got {table!r}")
    unknown = set(table) - {"key", "values", "start", "stop", "num", "scale"}
    if unknown:
        raise SweepError(f"{where}: unknown key(s) {', '.join(sorted(unknown))}; an axis has key and either values "
                         "or start, stop, num (and scale = \"linear\" | \"log\")")
    key = table.get("key")
    if not isinstance(key, str):
        raise SweepError(f"{where} needs key = \"section.key\", got {key!r}")
    ranged = {"start", "stop", "num", "scale"} & set(table)
    if ("values" in table) == bool(ranged):
        raise SweepError(f"{where} ({key}): give either values = [...] or start, stop and num")
    if "values" in table:
        values = table["values"]
        if not isinstance(values, list) or not values:
            raise SweepError(f"{where} ({key}): values must be a non-empty list, got {values!r}")
        Axis(key, tuple(values))  # the key's own check first
        if key != "case" and {"number", "integer"} & Axis(key, tuple(values)).kinds:
            bad = [v for v in values if not _number(v) or not math.isfinite(v)]
            if bad:
                raise SweepError(f"{where} ({key}): values must be finite numbers, got {bad[0]!r}")
        return Axis(key, tuple(values))
    missing = [k for k in ("start", "stop", "num") if k not in table]
    if missing:
        raise SweepError(f"{where} ({key}): a range needs start, stop and num; missing {', '.join(missing)}")
    start, stop, num, scale = table["start"], table["stop"], table["num"], table.get("scale", "linear")
    for name, v in (("start", start), ("stop", stop)):
        if not _number(v) or not math.isfinite(v):
            raise SweepError(f"{where} ({key}): {name} must be a finite number, got {v!r}")
    if not isinstance(num, int) or isinstance(num, bool) or num < 1:
        raise SweepError(f"{where} ({key}): num must be an integer >= 1 (the number of values), got {num!r}")
    if scale not in ("linear", "log"):
        raise SweepError(f"{where} ({key}): scale must be \"linear\" or \"log\", got {scale!r}")
    if scale == "log" and not (start > 0 and stop > 0):
        raise SweepError(f"{where} ({key}): a log range needs start > 0 and stop > 0, got {start!r}, {stop!r}")
    if num > 1 and start == stop:
        raise SweepError(f"{where} ({key}): start = stop = {start!r} with num = {num} repeats one value")
    grid = np.geomspace(start, stop, num) if scale == "log" else np.linspace(start, stop, num)
    axis = Axis(key, tuple(float(v) for v in grid))
    if axis.kinds == {"integer"}:
        ints = tuple(dict.fromkeys(int(round(v)) for v in grid))
        axis = Axis(key, ints)
    elif not axis.kinds & {"number", "integer"}:
        raise SweepError(f"{where} ({key}): a range needs a numeric key; {key} takes {', '.join(sorted(axis.kinds))}")
    return axis


@dataclass(frozen=True)
class FitRequest:
    """A law fitted to ``y`` against the plots' ``x`` axis, one fit per curve."""

    law: str
    y: str

    def __post_init__(self) -> None:
        if self.law not in LAWS:
            raise SweepError(f"[[fit]] law must be one of {', '.join(LAWS)}, got {self.law!r}")


@dataclass(frozen=True)
class Sweep:
    """A checked sweep: base cases, axes, how they combine, and the outputs asked for.

    ``cases`` are the base case files (absolute paths); ``overrides`` the ``set`` list
    (``section.key=value``) applied to each; ``combine`` is ``"product"`` or ``"zip"`` (the
    ``case`` axis always multiplies the others).
    """

    name: str
    source: str
    cases: tuple
    overrides: tuple
    axes: tuple
    combine: str = "product"
    x: str = ""
    plot: tuple = ("rolling_resistance",)
    fits: tuple = ()
    raw_cases: dict = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.combine not in ("product", "zip"):
            raise SweepError(f"{self.source}: combine must be \"product\" or \"zip\", got {self.combine!r}")
        keys = [a.key for a in self.axes]
        dup = {k for k in keys if keys.count(k) > 1}
        if dup:
            raise SweepError(f"{self.source}: the axis {sorted(dup)[0]!r} is given twice")
        varied = [a for a in self.axes if a.key != "case"]
        if self.combine == "zip" and len({len(a.values) for a in varied}) > 1:
            sizes = ", ".join(f"{a.key}: {len(a.values)}" for a in varied)
            raise SweepError(f"{self.source}: combine = \"zip\" needs axes of equal length, got {sizes}")
        if self.x and self.x not in keys:
            raise SweepError(f"{self.source}: [output] x = {self.x!r} is not an axis ({', '.join(keys)})")

    @property
    def x_axis(self) -> str:
        """The plots' abscissa: ``[output] x``, else the first axis other than ``case``."""
        return self.x or next((a.key for a in self.axes if a.key != "case"), self.axes[0].key)


@dataclass(frozen=True)
class Point:
    """One case of a sweep: its position, the axis values, and the checked case dict."""

    index: int
    values: dict
    config: dict

    @property
    def point_id(self) -> str:
        """A hash of the checked case: two points with the same physics and grid share it."""
        return hashlib.sha256(json.dumps(self.config, sort_keys=True).encode()).hexdigest()[:16]

    @property
    def friction(self) -> bool:
        return "friction" in self.config


def read_sweep(path: str | Path) -> Sweep:
    """Read and check a sweep file (not yet its points: :func:`expand`).

    Raises
    ------
    SweepError
        Unknown top-level key, an axis on an unknown key, an empty or non-numeric range,
        a base case that is missing or unreadable.
    """
    path = Path(path)
    if not path.is_file():
        raise SweepError(f"sweep file {str(path)!r} not found")
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise SweepError(f"{path}: not a valid TOML file: {exc}") from None
    src = str(path)
    unknown = set(data) - set(_TOP)
    if unknown:
        raise SweepError(f"{src}: unknown key(s) {', '.join(sorted(unknown))}; a sweep file has {', '.join(_TOP)}")
    case = data.get("case")
    case_list = case if isinstance(case, list) else [case]
    if case is None or not case_list or not all(isinstance(c, str) for c in case_list):
        raise SweepError(f"{src}: case must be the path of a case file (or a list of them), got {case!r}")
    cases, raw = [], {}
    for c in case_list:
        p = (path.parent / c).resolve()
        if not p.is_file():
            raise SweepError(f"{src}: case file {str(p)!r} not found (paths are relative to the sweep file)")
        try:
            raw[str(p)] = tomllib.loads(p.read_text(encoding="utf-8"))
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
            raise SweepError(f"{src}: case file {str(p)!r} is not valid TOML: {exc}") from None
        cases.append(str(p))
    overrides = data.get("set", [])
    if not isinstance(overrides, list) or not all(isinstance(o, str) for o in overrides):
        raise SweepError(f"{src}: set must be a list of \"section.key=value\" strings, got {overrides!r}")
    for o in overrides:
        try:
            casefile.parse_override(o)
        except casefile.CaseFileError as exc:
            raise SweepError(f"{src}: set: {exc}") from None
    tables = data.get("axis", [])
    if not isinstance(tables, list):
        raise SweepError(f"{src}: axes are [[axis]] tables")
    axes = [_axis(f"{src}: [[axis]] #{i + 1}", t) for i, t in enumerate(tables)]
    if len(cases) > 1:
        axes.insert(0, Axis("case", tuple(cases)))
    if not axes:
        raise SweepError(f"{src}: no [[axis]] (and a single case): nothing to sweep")
    out = data.get("output", {})
    if not isinstance(out, dict) or set(out) - {"x", "plot"}:
        raise SweepError(f"{src}: [output] takes x (an axis key) and plot (a list of result names)")
    plot = out.get("plot", ["rolling_resistance"])
    if not isinstance(plot, list) or not all(isinstance(p, str) for p in plot):
        raise SweepError(f"{src}: [output] plot must be a list of result names, got {plot!r}")
    from .table import RESULTS

    for name in plot:
        if name not in RESULTS:
            raise SweepError(f"{src}: [output] plot: unknown result {name!r}; results: {', '.join(RESULTS)}")
    fits = []
    for i, f in enumerate(data.get("fit", [])):
        if not isinstance(f, dict) or set(f) - {"law", "y"} or "law" not in f:
            raise SweepError(f"{src}: [[fit]] #{i + 1} takes law ({', '.join(LAWS)}) and y (a result name)")
        y = f.get("y", "rolling_resistance")
        if y not in RESULTS:
            raise SweepError(f"{src}: [[fit]] #{i + 1}: unknown result {y!r}; results: {', '.join(RESULTS)}")
        fits.append(FitRequest(f["law"], y))
    return Sweep(
        name=data.get("name", path.stem), source=src, cases=tuple(cases), overrides=tuple(overrides),
        axes=tuple(axes), combine=data.get("combine", "product"), x=out.get("x", ""), plot=tuple(plot),
        fits=tuple(fits), raw_cases=raw,
    )


def _combinations(sweep: Sweep) -> list[dict]:
    case_axes = [a for a in sweep.axes if a.key == "case"]
    varied = [a for a in sweep.axes if a.key != "case"]
    if sweep.combine == "zip" and varied:
        inner = [dict(zip([a.key for a in varied], vals)) for vals in zip(*[a.values for a in varied])]
    else:
        inner = [dict(zip([a.key for a in varied], vals)) for vals in itertools.product(*[a.values for a in varied])]
    outer = [{"case": c} for c in case_axes[0].values] if case_axes else [{}]
    return [{**o, **i} for o in outer for i in inner]


def expand(sweep: Sweep) -> list[Point]:
    """Every point of the sweep, each case checked for the BEM (:func:`casefile.validate`).

    Raises
    ------
    SweepError
        The first point whose case breaks the schema, naming the point and the key.
    """
    points = []
    for index, values in enumerate(_combinations(sweep)):
        case = values.get("case", sweep.cases[0])
        data = copy.deepcopy(sweep.raw_cases[case])
        label = ", ".join(f"{k} = {Path(v).name if k == 'case' else v!r}" for k, v in values.items())
        where = f"{sweep.source}: point {index} ({label})"
        try:
            data = casefile.apply_overrides(data, sweep.overrides)
            for key, value in values.items():
                if key == "case":
                    continue
                sec, _, name = key.partition(".")
                table = data.setdefault(sec, {})
                table[name] = value
                if sec == "grid" and name in ("spacing", "period", "truncation", "half_width"):
                    for ax in "xy":  # a swept pair overrides the per-direction entries of the base case
                        table.pop(f"{name}_{ax}", None)
            config = casefile.validate(data, "bem", source=where, folder=Path(case).parent)
        except casefile.CaseFileError as exc:
            raise SweepError(str(exc) if str(exc).startswith(where) else f"{where}: {exc}") from None
        points.append(Point(index, {k: (Path(v).stem if k == "case" else v) for k, v in values.items()}, config))
    return points
