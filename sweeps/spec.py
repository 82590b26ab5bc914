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

The keys of each table are declared below (:data:`TOP`, :data:`AXIS`, :data:`OUTPUT`,
:data:`FIT`) and checked by the case files' validation engine
(:func:`casefile.validation.check_table`): an unknown key, a wrong type or a missing
base case is a :class:`SweepError` in the same words as a case-file error. Every point is
the base case with the axis values set, checked by :func:`casefile.validate` for the BEM
before anything runs, so a bad value is an error that names the point. Units are the case
file's (SI).
"""

from __future__ import annotations

import copy
import functools
import hashlib
import itertools
import json
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import casefile
from casefile.schema import section
from casefile.validation import InputError, Key, check_table, check_value, did_you_mean

from .integrity import input_files
from .table import RESULTS

__all__ = ["SweepError", "Axis", "FitRequest", "Sweep", "Point", "read_sweep", "expand", "count", "LAWS",
           "MAX_POINTS", "TOP", "AXIS", "OUTPUT", "FIT"]

#: the most points a sweep expands to (a larger one is refused before any point is built:
#: checking a point costs about a millisecond, so this bounds ``--check`` to seconds)
MAX_POINTS = 10_000

#: the fitted laws (``sweeps.fits``)
LAWS = ("power", "two_exponential")

#: the top level of a sweep file
TOP = (
    Key("name", "string", doc="the sweep's name (default: the file's name without .toml)"),
    Key("case", "paths", doc="the base case file, or a list of them (an axis \"case\"), relative to the "
        "sweep file", required=True),
    Key("set", "strings", doc="overrides \"section.key=value\" of every base case"),
    Key("combine", "string", doc="how the axes combine", default="product", choices=("product", "zip")),
    Key("axis", "tables", doc="the varied keys, one [[axis]] each"),
    Key("output", "table", doc="the plots"),
    Key("fit", "tables", doc="laws fitted to the curves, one [[fit]] each"),
)
#: an ``[[axis]]``: ``key`` and either ``values`` or ``start``, ``stop``, ``num`` (``scale``)
AXIS = (
    Key("key", "string", doc="the varied case key, section.key", required=True),
    Key("values", "list", doc="the values, in the key's unit"),
    Key("start", "number", doc="first value of a range"),
    Key("stop", "number", doc="last value of a range"),
    Key("num", "integer", doc="number of values of a range", rule=">=1"),
    Key("scale", "string", doc="spacing of a range", default="linear", choices=("linear", "log")),
)


#: ``[output]``
OUTPUT = (
    Key("x", "string", doc="the plots' abscissa, an axis key (default: the first axis)"),
    Key("plot", "strings", doc="results drawn against x", choices=tuple(RESULTS)),
)
#: a ``[[fit]]``
FIT = (
    Key("law", "string", doc="the fitted law", required=True, choices=LAWS),
    Key("y", "string", doc="the fitted result", default="rolling_resistance", choices=tuple(RESULTS)),
)


class SweepError(InputError):
    """A sweep file, or a point it makes, that cannot run."""


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

            known = [s.name for s in SCHEMA]
            raise SweepError(f"axis key {self.key!r} must be section.key with a known section "
                             f"({', '.join(known)}){did_you_mean(sec, known) if dot else ''}")
        if not spec.all_keys(name):
            known = sorted({k.name for k in spec.keys} | {k.name for v in spec.variants.values() for k in v.keys})
            raise SweepError(f"axis key {self.key!r}: [{sec}] has no key {name!r}; known keys: {', '.join(known)}"
                             f"{did_you_mean(name, known)}")

    @property
    def kinds(self) -> set:
        """The schema kinds the key takes."""
        sec, _, name = self.key.partition(".")
        return {k.kind for k in section(sec).all_keys(name)}


def _axis(where: str, table: dict) -> Axis:
    if isinstance(table, dict) and isinstance(table.get("key"), str):
        where = f"{where} ({table['key']})"
    table = check_table(where, table, AXIS, error=SweepError)
    key = table["key"]
    ranged = {"start", "stop", "num", "scale"} & set(table)
    if ("values" in table) == bool(ranged):
        raise SweepError(f"{where}: give either values = [...] or start, stop and num")
    if "values" in table:
        values = table["values"]
        if isinstance(values, list) and len(values) > MAX_POINTS:
            raise SweepError(f"{where}: {len(values)} values; a sweep takes at most {MAX_POINTS} points "
                             "(MAX_POINTS): split it into several sweep files")
        axis = Axis(key, tuple(values))  # the key's own check first
        if key != "case" and {"number", "integer"} & axis.kinds:  # the range rules: when the points are checked
            unit = section(key.partition(".")[0]).all_keys(key.partition(".")[2])[0].unit
            check_value(f"{where} values", Key("values", "numbers", unit), values, error=SweepError)
        return axis
    missing = [k for k in ("start", "stop", "num") if k not in table]
    if missing:
        raise SweepError(f"{where}: a range needs start, stop and num; missing {', '.join(missing)}")
    start, stop, num, scale = table["start"], table["stop"], table["num"], table.get("scale", "linear")
    if num > MAX_POINTS:
        raise SweepError(f"{where}: num = {num} values; a sweep takes at most {MAX_POINTS} points (MAX_POINTS): "
                         "split it into several sweep files")
    if scale == "log" and not (start > 0 and stop > 0):
        raise SweepError(f"{where}: a log range needs start > 0 and stop > 0, got {start!r}, {stop!r}")
    if num > 1 and start == stop:
        raise SweepError(f"{where}: start = stop = {start!r} with num = {num} repeats one value")
    grid = np.geomspace(start, stop, num) if scale == "log" else np.linspace(start, stop, num)
    axis = Axis(key, tuple(float(v) for v in grid))
    if axis.kinds == {"integer"}:
        ints = tuple(dict.fromkeys(int(round(v)) for v in grid))
        axis = Axis(key, ints)
    elif not axis.kinds & {"number", "integer"}:
        raise SweepError(f"{where}: a range needs a numeric key; {key} takes {', '.join(sorted(axis.kinds))}")
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

    @functools.cached_property
    def point_id(self) -> str:
        """A hash of the checked case and of the content of the files it names (a
        master-curve table, a height map): two points with the same physics and grid
        share it; an edited input file makes a new point."""
        what = {"case": self.config, "files": input_files(self.config)}
        return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()[:16]

    @property
    def friction(self) -> bool:
        return "friction" in self.config


def _check_name(src: str, name: str) -> None:
    """A name is a relative path that stays inside the output root (``out/sweeps/NAME``)."""
    parts = name.replace("\\", "/").split("/")
    if (not name.strip() or Path(name).is_absolute() or name.startswith(("/", "\\")) or re.match(r"[A-Za-z]:", name)
            or ".." in parts or any(ord(c) < 32 for c in name)):
        raise SweepError(f"{src}: name = {name!r} must be a relative name inside the output folder "
                         "(not absolute, no '..', no drive, no control characters)")


def count(sweep: Sweep) -> int:
    """The number of points of ``sweep``, from its axes' lengths (no point is built)."""
    n = 1
    varied = [len(a.values) for a in sweep.axes if a.key != "case"]
    cases = [len(a.values) for a in sweep.axes if a.key == "case"]
    if sweep.combine == "zip" and varied:
        n = varied[0]
    else:
        for v in varied:
            n *= v
    for c in cases:
        n *= c
    return n


def read_sweep(path: str | Path) -> Sweep:
    """Read and check a sweep file (not yet its points: :func:`expand`).

    Raises
    ------
    SweepError
        Unknown top-level key, an axis on an unknown key, an empty, non-numeric or
        too long range, a base case that is missing or unreadable, a ``name`` that is
        absolute or climbs out of the output folder (``..``).
    """
    path = Path(path)
    if not path.is_file():
        raise SweepError(f"sweep file {str(path)!r} not found")
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise SweepError(f"{path}: not a valid TOML file: {exc}") from None
    src = str(path)
    data = check_table(src, data, TOP, folder=path.parent, error=SweepError)  # resolves the case paths
    cases = data["case"] if isinstance(data["case"], list) else [data["case"]]
    raw = {}
    for p in cases:
        try:
            raw[p] = tomllib.loads(Path(p).read_text(encoding="utf-8"))
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
            raise SweepError(f"{src}: case file {p!r} is not valid TOML: {exc}") from None
    overrides = data.get("set", [])
    for o in overrides:
        try:
            casefile.parse_override(o)
        except casefile.CaseFileError as exc:
            raise SweepError(f"{src} set: {exc}") from None
    axes = [_axis(f"{src} [[axis]] #{i + 1}", t) for i, t in enumerate(data.get("axis", []))]
    if len(cases) > 1:
        axes.insert(0, Axis("case", tuple(cases)))
    if not axes:
        raise SweepError(f"{src}: no [[axis]] (and a single case): nothing to sweep")
    out = check_table(f"{src} [output]", data.get("output", {}), OUTPUT, error=SweepError)
    plot = out.get("plot", ["rolling_resistance"])
    fits = [check_table(f"{src} [[fit]] #{i + 1}", f, FIT, error=SweepError) for i, f in enumerate(data.get("fit", []))]
    fits = [FitRequest(f["law"], f.get("y", "rolling_resistance")) for f in fits]
    name = data.get("name", path.stem)
    _check_name(src, name)
    return Sweep(
        name=name, source=src, cases=tuple(cases), overrides=tuple(overrides),
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
        More than :data:`MAX_POINTS` points (counted before any is built), or the first
        point whose case breaks the schema, naming the point and the key.
    """
    n = count(sweep)
    if n > MAX_POINTS:
        sizes = " x ".join(f"{a.key} ({len(a.values)})" for a in sweep.axes)
        raise SweepError(f"{sweep.source}: {n} points ({sizes}, combined as {sweep.combine}); a sweep takes at most "
                         f"{MAX_POINTS} points (MAX_POINTS): split it into several sweep files")
    points = []
    for index, values in enumerate(_combinations(sweep)):
        case = values.get("case", sweep.cases[0])
        data = copy.deepcopy(sweep.raw_cases[case])
        label = ", ".join(f"{k} = {Path(v).name if k == 'case' else v!r}" for k, v in values.items())
        where = f"{sweep.source} point {index} ({label})"
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
