"""The typed schema of a verification case file, checked before anything is solved.

A case file is TOML with a header (``name``, ``title``, ``kind``, ``quick``, ``why``), a
``[problem]`` in the case-file schema of ``bem solve`` (:mod:`casefile`), the sections of
its kind, the sections of its methods and a non-empty list of ``[[gates]]``. Every key is
declared here or by the case's kind or method as a :class:`Field`; :func:`check_table`
checks a table with the validation engine of the case files
(:func:`casefile.validation.check_table`), so anything undeclared or mistyped is a
:class:`CaseError` that names the file, the section or gate, the field, the value and the
rule, with a "did you mean" for near misses. A typo can therefore never switch a gate off.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import casefile
from casefile.validation import InputError, Key
from casefile.validation import check_table as _check_table
from casefile.validation import did_you_mean

__all__ = ["CaseError", "Field", "check_table", "close", "HEADER", "GATE", "SCALARS", "PRESSURE", "LEVELS"]

SCALARS = ("contact_radius", "indentation", "peak_pressure", "load", "rolling_resistance")
PRESSURE = ("pressure_rms_interior", "pressure_max_interior", "pressure_rms_edge", "pressure_max_edge")
LEVELS = ("finest", "extrapolated")


class CaseError(InputError):
    """A verification case that breaks the schema (the CLI exits 2)."""


@dataclass(frozen=True)
class Field:
    """A key of a case file: its kind (``string``, ``strings``, ``number``, ``numbers``,
    ``integer``, ``bool``, ``table``, ``tables``, ``cells``: :data:`casefile.validation.KINDS`),
    whether it is required, the allowed values (``choices``) and whether numbers must be
    > 0. The name is the key of the dict that declares it."""

    kind: str
    required: bool = False
    choices: tuple | None = None
    positive: bool = False
    doc: str = ""

    def key(self, name: str) -> Key:
        """The field as a :class:`casefile.validation.Key` called ``name``."""
        return Key(name, self.kind, doc=self.doc, required=self.required, choices=tuple(self.choices or ()),
                   rule=">0" if self.positive else "")


#: ``"; did you mean 'x'?"`` for a near miss among the known names, else ``""``
close = did_you_mean


def check_table(data: dict, fields: dict[str, Field], where: str, open_: bool = False) -> dict:
    """Check ``data`` against ``fields`` (name -> :class:`Field`); return it.

    ``where`` starts the messages (``"case.toml [bem]"``); ``open_`` admits undeclared
    keys (a method's own settings, checked by the method).

    Raises
    ------
    CaseError
        Not a table, an unknown key, a missing required key, a value of the wrong kind,
        not one of the choices, or not > 0 where the field is positive.
    """
    _check_table(where, data, [spec.key(name) for name, spec in fields.items()], open_=open_, error=CaseError)
    return data


HEADER = {
    "name": Field("string", True, doc="the case's name, used in the report and on the command line"),
    "title": Field("string", True, doc="one line saying what is checked"),
    "kind": Field("string", True, doc="what the case runs"),
    "quick": Field("bool", doc="part of `verify --quick`"),
    "full": Field("bool", doc="run only by `verify --full` or when named with --case (its finer levels cost more)"),
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
