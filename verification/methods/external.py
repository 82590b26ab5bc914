"""Results computed elsewhere (Abaqus, COMSOL, another code) as a verification method.

A results file is JSON, one per case, in explicit units::

    {"units": {"length": "mm", "pressure": "MPa", "force": "N"},
     "levels": [                                   # coarse to fine; one is enough
        {"size": 0.1,                              # element size, in the length unit
         "scalars": {"contact_radius": 4.53, "indentation": 0.61, "peak_pressure": 3.1, "load": 100},
         "pressure": "thick-layer-fine.csv"}]}     # optional; relative to the JSON file

The pressure CSV has a header line and either the columns ``r,pressure`` (samples along a
radius) or ``x,y,pressure`` (samples on a grid; the harness uses their distance from the
axis), in the same units. Scalars in the file: ``contact_radius`` and ``indentation``
(length), ``peak_pressure`` (pressure), ``load`` and ``rolling_resistance`` (force).
A folder of such files holds one per case, named ``<case>.json``.

Every number is read like user input: finite (JSON's ``NaN`` and ``Infinity`` are refused),
``size`` > 0, ``seconds`` >= 0, ``load`` > 0, ``contact_radius`` and ``peak_pressure``
>= 0; a file that breaks a rule is a :class:`verification.schema.CaseError` naming the
file and the field (``verify`` exits 2 before anything is solved).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np

from ..results import Level, MethodError, Run, check_scalar
from ..schema import CaseError, close

__all__ = ["UNITS", "read_results", "results_file", "ExternalResults"]

UNITS = {
    "length": {"m": 1.0, "mm": 1e-3, "um": 1e-6},
    "pressure": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6},
    "force": {"N": 1.0, "kN": 1e3, "mN": 1e-3},
}
SCALAR_UNITS = {"contact_radius": "length", "indentation": "length", "peak_pressure": "pressure",
                "load": "force", "rolling_resistance": "force"}


def _fail(path: Path, message: str):
    raise CaseError(f"{path}: {message}")


def _number(path: Path, where: str, name: str, value, what: str = "") -> float:
    """``value`` as :func:`check_scalar` reads it; a :class:`CaseError` naming the file."""
    try:
        return check_scalar(name, value, what)
    except MethodError as exc:
        _fail(path, f"{where}: {exc}")


def _read_csv(path: Path, length: float, pressure: float):
    if not path.is_file():
        _fail(path, "pressure file not found")
    with path.open(newline="") as fh:
        rows = [row for row in csv.reader(fh) if row and not row[0].lstrip().startswith("#")]
    if len(rows) < 2:
        _fail(path, "needs a header line and at least one row")
    head = [h.strip() for h in rows[0]]
    if head not in (["r", "pressure"], ["x", "y", "pressure"]):
        _fail(path, f"columns must be 'r,pressure' or 'x,y,pressure', got {','.join(head)!r}")
    try:
        data = np.array([[float(v) for v in row] for row in rows[1:]])
    except ValueError as exc:
        _fail(path, f"not a number: {exc}")
    if data.shape[1] != len(head) or not np.isfinite(data).all():
        _fail(path, "every row needs one finite number per column")
    r = data[:, 0] if len(head) == 2 else np.hypot(data[:, 0], data[:, 1])
    return r * length, data[:, -1] * pressure


def read_results(path: Path, method: str) -> list[Run]:
    """The runs (coarse to fine) of one results file, converted to SI."""
    path = Path(path)
    try:
        doc = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as exc:
        _fail(path, f"not a readable JSON file: {exc}")
    if not isinstance(doc, dict) or set(doc) - {"units", "levels", "comment"} or "levels" not in doc:
        _fail(path, "needs 'units' and 'levels' (and optionally 'comment')")
    units = doc.get("units")
    if not isinstance(units, dict) or set(units) != set(UNITS):
        _fail(path, f"'units' must give each of {', '.join(UNITS)} (e.g. {{\"length\": \"m\", "
                    f"\"pressure\": \"Pa\", \"force\": \"N\"}})")
    scale = {}
    for q, unit in units.items():
        if not isinstance(unit, str) or unit not in UNITS[q]:
            _fail(path, f"unknown {q} unit {unit!r}; known: {', '.join(UNITS[q])}{close(unit, UNITS[q])}")
        scale[q] = UNITS[q][unit]
    levels = doc["levels"]
    if not isinstance(levels, list) or not levels:
        _fail(path, "'levels' must be a non-empty list")
    runs = []
    for i, level in enumerate(levels):
        where = f"levels[{i}]"
        if not isinstance(level, dict) or set(level) - {"size", "scalars", "pressure", "seconds"}:
            _fail(path, f"{where}: keys are size, scalars, pressure, seconds")
        scalars = level.get("scalars", {})
        if not isinstance(scalars, dict) or not scalars:
            _fail(path, f"{where}: 'scalars' must be a non-empty table")
        si = {}
        for name, value in scalars.items():
            if name not in SCALAR_UNITS:
                _fail(path, f"{where}: unknown scalar {name!r}; known: {', '.join(SCALAR_UNITS)}"
                            f"{close(name, SCALAR_UNITS)}")
            si[name] = _number(path, where, name, value) * scale[SCALAR_UNITS[name]]
        size = level.get("size")
        if size is not None:
            size = _number(path, where, "size", size, "size")
            if not size > 0:
                _fail(path, f"{where}: size must be a number > 0, got {size!r}")
        seconds = _number(path, where, "seconds", level.get("seconds", 0.0), "seconds")
        if seconds < 0:
            _fail(path, f"{where}: seconds cannot be negative, got {seconds!r}")
        r, p = np.zeros(0), np.zeros(0)
        if "pressure" in level:
            if not isinstance(level["pressure"], str):
                _fail(path, f"{where}: pressure must be the name of a CSV file, got {level['pressure']!r}")
            r, p = _read_csv(path.parent / level["pressure"], scale["length"], scale["pressure"])
        runs.append(Run(method, None if size is None else size * scale["length"], si, r, p, seconds))
    return runs


def results_file(location: Path, case: str) -> Path:
    """The results file of ``case`` in ``location`` (a folder of ``<case>.json``, or one file)."""
    location = Path(location)
    return location / f"{case}.json" if location.is_dir() else location


class ExternalResults:
    """A method whose runs are read from results files instead of solved.

    ``location`` is a folder holding ``<case>.json`` per case, or one JSON file (for a
    case file that names it). The levels are those of the file.
    """

    def __init__(self, name: str, location: Path):
        self.name, self.location = name, Path(location)

    def sizes(self, case: str) -> list:
        path = results_file(self.location, case)
        return [run.size for run in read_results(path, self.name)] if path.is_file() else []

    def __call__(self, problem: dict, level: Level) -> Run:
        return read_results(results_file(self.location, level.case), self.name)[level.index]
