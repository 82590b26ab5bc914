"""The typed schema of a verification case file, checked before anything is solved.

A case file is TOML with a header (``name``, ``title``, ``kind``, ``quick``, ``why``), a
``[problem]`` in the case-file schema of ``bem solve`` (:mod:`casefile`), the sections of
its kind, the sections of its methods and a non-empty list of ``[[gates]]``. Every key is
declared here or by the case's kind with its type and rule; anything else is an error that
names the file, the section or gate, the field and the rule, with a "did you mean" for
near misses. A typo can therefore never switch a gate off.
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from pathlib import Path

import casefile

__all__ = ["CaseError", "Field", "check_table", "close", "HEADER", "GATE", "SCALARS", "PRESSURE", "LEVELS"]

SCALARS = ("contact_radius", "indentation", "peak_pressure", "load", "rolling_resistance")
PRESSURE = ("pressure_rms_interior", "pressure_max_interior", "pressure_rms_edge", "pressure_max_edge")
LEVELS = ("finest", "extrapolated")


class CaseError(ValueError):
    """A verification case that breaks the schema (the CLI exits 2)."""


@dataclass(frozen=True)
class Field:
    """A key of a case file: its type (``string``, ``strings``, ``number``, ``numbers``,
    ``integer``, ``bool``, ``table``, ``tables``, ``cells``), whether it is required, the
    allowed values (``choices``) and whether numbers must be > 0."""

    kind: str
    required: bool = False
    choices: tuple | None = None
    positive: bool = False
    doc: str = ""


def close(word: str, known) -> str:
    """``"; did you mean 'x'?"`` for a near miss among ``known``, else ``""``."""
    hits = difflib.get_close_matches(str(word), [str(k) for k in known], n=1, cutoff=0.6)
    return f"; did you mean {hits[0]!r}?" if hits else ""


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _check_value(value, spec: Field, where: str) -> None:
    kind = spec.kind
    if kind == "string":
        if not isinstance(value, str) or not value.strip():
            raise CaseError(f"{where} must be a non-empty string, got {value!r}")
        if spec.choices is not None and value not in spec.choices:
            raise CaseError(f"{where}: unknown value {value!r}; known: {', '.join(map(str, spec.choices))}"
                            f"{close(value, spec.choices)}")
    elif kind == "strings":
        if not isinstance(value, list) or not value:
            raise CaseError(f"{where} must be a non-empty list of strings, got {value!r}")
        for i, v in enumerate(value):
            _check_value(v, Field("string", choices=spec.choices), f"{where}[{i}]")
    elif kind in ("number", "integer"):
        ok = isinstance(value, int) and not isinstance(value, bool) if kind == "integer" else _is_number(value)
        if not ok or not math.isfinite(value):
            raise CaseError(f"{where} must be a finite {kind}, got {value!r}")
        if spec.positive and not value > 0:
            raise CaseError(f"{where} must be > 0, got {value!r}")
    elif kind == "numbers":
        if not isinstance(value, list) or not value:
            raise CaseError(f"{where} must be a non-empty list of numbers, got {value!r}")
        for i, v in enumerate(value):
            _check_value(v, Field("number", positive=spec.positive), f"{where}[{i}]")
    elif kind == "bool":
        if not isinstance(value, bool):
            raise CaseError(f"{where} must be true or false, got {value!r}")
    elif kind == "table":
        if not isinstance(value, dict):
            raise CaseError(f"{where} must be a table, got {value!r}")
    elif kind == "tables":
        if not isinstance(value, list) or not value or not all(isinstance(v, dict) for v in value):
            raise CaseError(f"{where} must be a non-empty array of tables ([[...]]), got {value!r}")
    elif kind == "cells":
        if not isinstance(value, list) or not all(isinstance(c, list) and len(c) == 2 and all(map(_is_number, c))
                                                  for c in value):
            raise CaseError(f"{where} must be a list of [number, number] pairs, got {value!r}")
    else:  # pragma: no cover - a declaration error in the harness itself
        raise AssertionError(f"unknown field kind {kind!r}")


def check_table(data: dict, fields: dict[str, Field], where: str, open_: bool = False) -> dict:
    """Check ``data`` against ``fields``; return it. ``open_`` admits undeclared keys
    (a method's own settings, checked by the method)."""
    if not isinstance(data, dict):
        raise CaseError(f"{where} must be a table, got {data!r}")
    if not open_:
        for key in data:
            if key not in fields:
                raise CaseError(f"{where}: unknown key {key!r}; known: {', '.join(fields)}{close(key, fields)}")
    for key, spec in fields.items():
        if key not in data:
            if spec.required:
                raise CaseError(f"{where}: '{key}' is required ({spec.doc or spec.kind})")
            continue
        _check_value(data[key], spec, f"{where} {key}")
    return data


HEADER = {
    "name": Field("string", True, doc="the case's name, used in the report and on the command line"),
    "title": Field("string", True, doc="one line saying what is checked"),
    "kind": Field("string", True, doc="what the case runs"),
    "quick": Field("bool", doc="part of `verify --quick`"),
    "why": Field("string", doc="why this case and these tolerances"),
    "problem": Field("table", True, doc="the physical problem, in the schema of `bem solve`"),
    "gates": Field("tables", True, doc="at least one [[gates]] table: a case without gates checks nothing"),
}

GATE = {
    "quantity": Field("string", True, doc="the compared quantity"),
    "methods": Field("strings", doc="the methods held to the gate"),
    "against": Field("string", doc="the reference: 'analytic', 'published' or a method"),
    "levels": Field("strings", choices=LEVELS, doc="finest and/or extrapolated (Richardson)"),
    "tolerance": Field("number", True, positive=True, doc="the largest accepted error, > 0"),
    "reason": Field("string", True, doc="why this tolerance"),
    "report_only": Field("bool", doc="shown with its numbers, never fails"),
    "limit": Field("string", doc="the limit the gate belongs to (rolling-limits)"),
}


def check_problem(data, path: Path) -> dict:
    """The ``[problem]`` through :func:`casefile.validate` (paths against the case's folder)."""
    try:
        return casefile.validate(data, source=f"{path} [problem]", folder=path.parent)
    except casefile.CaseFileError as exc:
        raise CaseError(str(exc)) from None
