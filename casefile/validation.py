"""The one validation engine of the project's input files: case files
(:mod:`casefile.schema`), verification cases (:mod:`verification.schema` and the fields its
kinds and methods declare) and sweep files (:mod:`sweeps.spec`).

A table is declared as a tuple of :class:`Key` (name, kind, unit, rule, choices, whether it
is required); :func:`check_table` checks a parsed TOML table against it and
:func:`check_value` one value. Every failure is an :class:`InputError` (or the subclass the
caller names) in one style: the place (the file, then the section or table), the key, the
rule, the unit and the value with its type where the type is the point::

    case.toml [layer] thickness must be > 0 m, got -0.005
    case.toml [loading] load must be a number (N), got true (a boolean)
    case.toml [layer]: unknown key 'thicknes'; known keys: thickness, density; did you mean 'thickness'?
    case.toml [indenter] needs radius (m): radius R of the indenter

Why this engine and not a library such as pydantic: the case-file package may import the
standard library only (``bem`` and ``fem_reference`` share it and nothing else), and what
the three file types need is small and specific: TOML values that are already typed (no
coercion wanted: a boolean is never a number, an integer key takes no ``1.0``), the unit
in the message, a "did you mean" for a misspelt key, paths resolved against the file that
gives them, sections whose keys depend on a selector (``[material] model``), and the same
declarations turned into the Markdown tables of ``docs/case-files.md``. Pydantic would add
a compiled dependency to every package, coerce by default, and need a translation of its
error list into these messages and of its models into those tables; the whole engine
here is shorter than that glue.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable

__all__ = ["InputError", "Key", "KINDS", "RULES", "check_table", "check_value", "did_you_mean", "show",
           "unknown"]


class InputError(ValueError):
    """An input file, or an option that overrides it, that breaks its declared schema.

    The base of :class:`casefile.CaseFileError` (case files and output paths),
    :class:`verification.schema.CaseError` (verification cases) and
    :class:`sweeps.SweepError` (sweep files): a command line catches this one class to
    report any bad input with exit status 2.
    """


#: value kinds, as the messages name them
KINDS = {
    "number": "a number",  # finite, int or float, never a boolean
    "integer": "an integer",
    "string": "a string",  # not empty
    "numbers": "a non-empty list of numbers",
    "strings": "a non-empty list of strings",
    "list": "a non-empty list",  # of any values
    "path": "a path",  # to an existing file, relative to the folder of the file that gives it
    "paths": "a path or a non-empty list of paths",
    "bool": "true or false",
    "table": "a table",
    "tables": "a non-empty array of tables ([[...]])",
    "cells": "a list of [number, number] pairs",
}
#: range rules (on numbers, integers and each element of a list of numbers), as messages write them
RULES = {"": "", ">0": "> 0", ">=0": ">= 0", ">=1": ">= 1"}


@dataclass(frozen=True)
class Key:
    """One key of a table.

    Parameters
    ----------
    name : str
        The key as written in the file.
    kind : str
        One of :data:`KINDS`.
    unit : str
        SI unit of the value, ``"-"`` for none (named in the messages and the docs).
    doc : str
        What the key means (said when a required key is missing).
    readers : tuple
        The programs that read the key (case files: ``"bem"``, ``"fem"``); empty: every
        program that reads its table.
    required : bool
        A missing key is an error unless it has a ``default``.
    default : object
        The value a missing key takes; ``None``: the reader decides, as ``default_doc``
        says.
    default_doc : str
        The default in words, where it is computed.
    rule : str
        One of :data:`RULES`.
    choices : tuple
        The allowed values of a string (or of each string of a list).
    """

    name: str
    kind: str
    unit: str = "-"
    doc: str = ""
    readers: tuple = ()
    required: bool = False
    default: object = None
    default_doc: str = ""
    rule: str = ""
    choices: tuple = ()

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"key {self.name}: kind must be one of {', '.join(KINDS)}, got {self.kind!r}")
        if self.rule not in RULES:
            raise ValueError(f"key {self.name}: rule must be one of {', '.join(map(repr, RULES))}, got {self.rule!r}")


def show(value) -> str:
    """A value as TOML writes it, with its type when that is the point."""
    if isinstance(value, bool):
        return f"{str(value).lower()} (a boolean)"
    if isinstance(value, str):
        return f"{value!r} (a string)"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return f"{value!r} (a list)"
    return repr(value)


def did_you_mean(word, known: Iterable) -> str:
    """``"; did you mean 'x'?"`` for a near miss of ``word`` among ``known``, else ``""``."""
    import difflib  # on a bad key only: 1 ms of every command's start otherwise

    hits = difflib.get_close_matches(str(word), [str(k) for k in known], n=1, cutoff=0.6)
    return f"; did you mean {hits[0]!r}?" if hits else ""


def unknown(where: str, name, known: Iterable, what: str = "key", context: str = "",
            error: type[InputError] = InputError) -> InputError:
    """The error for an undeclared ``name`` at ``where``: the known names and a near miss.

    ``context`` follows the name (``' for model = "prony"'``)."""
    known = [str(k) for k in known]
    return error(f"{where}: unknown {what} {str(name)!r}{context}; known {what}s: {', '.join(known)}"
                 f"{did_you_mean(name, known)}")


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _unit(key: Key, brackets: bool) -> str:
    if key.unit == "-":
        return ""
    return f" ({key.unit})" if brackets else f" {key.unit}"


def _scalar(where: str, key: Key, value, error) -> None:
    """A number or an integer: its type, finite, its rule."""
    integer = key.kind == "integer"
    if not _is_number(value) or (integer and not isinstance(value, int)):
        raise error(f"{where} must be {'an integer' if integer else 'a number'}{_unit(key, True)}, got {show(value)}")
    if not math.isfinite(value):
        raise error(f"{where} must be finite{_unit(key, True)}, got {value!r}")
    if (key.rule == ">0" and not value > 0) or (key.rule == ">=0" and not value >= 0) or (
            key.rule == ">=1" and not value >= 1):
        raise error(f"{where} must be {'an integer ' if integer else ''}{RULES[key.rule]}{_unit(key, False)}, "
                    f"got {value!r}")


def _string(where: str, key: Key, value, error) -> None:
    if not isinstance(value, str) or not value.strip():
        raise error(f"{where} must be a non-empty string, got {show(value)}")
    if key.choices and value not in key.choices:
        options = ", ".join(f'"{c}"' for c in key.choices)
        raise error(f"{where} must be one of {options}, got {value!r}{did_you_mean(value, key.choices)}")


def _path(where: str, value, folder: Path, error) -> str:
    if not isinstance(value, str) or not value.strip():
        raise error(f"{where} must be a path, got {show(value)}")
    path = (folder / value).resolve()
    if not path.exists():
        raise error(f"{where}: file {str(path)!r} not found (paths in a file are relative to its folder)")
    if not path.is_file():
        raise error(f"{where}: {str(path)!r} is a folder, not a file")
    return str(path)


def _list(where: str, key: Key, value, error) -> list:
    if not isinstance(value, list) or not value:
        raise error(f"{where} must be {KINDS[key.kind]}{_unit(key, True)}, got {show(value)}")
    return value


def check_value(where: str, key: Key, value, folder: str | Path = ".", error: type[InputError] = InputError):
    """``value`` checked against ``key``; returns it, paths resolved to absolute ones.

    Parameters
    ----------
    where : str
        The place and the key, as messages start (``"case.toml [layer] thickness"``).
    key : Key
        The declaration.
    value : object
        The parsed TOML value.
    folder : path
        The folder relative paths resolve against (that of the file that gives them).
    error : type
        The :class:`InputError` subclass to raise.

    Raises
    ------
    InputError
        Wrong type (a boolean is not a number), not finite, out of range, not one of the
        choices, an empty list, a file that does not exist.
    """
    kind = key.kind
    if kind in ("number", "integer"):
        _scalar(where, key, value, error)
    elif kind == "string":
        _string(where, key, value, error)
    elif kind == "numbers":
        for i, v in enumerate(_list(where, key, value, error)):
            _scalar(f"{where}[{i}]", Key(key.name, "number", key.unit, rule=key.rule), v, error)
    elif kind == "strings":
        for i, v in enumerate(_list(where, key, value, error)):
            _string(f"{where}[{i}]", key, v, error)
    elif kind == "list":
        _list(where, key, value, error)
    elif kind == "path":
        return _path(where, value, Path(folder), error)
    elif kind == "paths":
        if isinstance(value, list):
            values = _list(where, key, value, error)
            return [_path(f"{where}[{i}]", v, Path(folder), error) for i, v in enumerate(values)]
        return _path(where, value, Path(folder), error)
    elif kind == "bool":
        if not isinstance(value, bool):
            raise error(f"{where} must be true or false, got {show(value)}")
    elif kind == "table":
        if not isinstance(value, dict):
            raise error(f"{where} must be a table, got {show(value)}")
    elif kind == "tables":
        if not isinstance(value, list) or not value or not all(isinstance(v, dict) for v in value):
            raise error(f"{where} must be {KINDS[kind]}, got {show(value)}")
    elif kind == "cells":
        if not isinstance(value, list) or not all(
                isinstance(c, list) and len(c) == 2 and all(map(_is_number, c)) for c in value):
            raise error(f"{where} must be {KINDS[kind]}, got {show(value)}")
    return value


def check_table(where: str, table, keys: Iterable[Key], *, folder: str | Path = ".", open_: bool = False,
                context: str = "", one_of: tuple = (), error: type[InputError] = InputError) -> dict:
    """``table`` checked against the declared ``keys``; returns a checked copy.

    Parameters
    ----------
    where : str
        The file and the table, as messages start (``"case.toml [layer]"``).
    table : dict
        The parsed TOML table.
    keys : iterable of Key
        The declaration.
    folder : path
        The folder relative paths resolve against.
    open_ : bool
        Admit undeclared keys (settings that another part checks).
    context : str
        Said after an unknown key's name (``' for model = "prony"'``).
    one_of : tuple of tuples
        Groups of keys of which exactly one must be given.
    error : type
        The :class:`InputError` subclass to raise.

    Raises
    ------
    InputError
        Not a table, an unknown key (with the known keys and a near miss), a missing
        required key, a value :func:`check_value` refuses, a group of ``one_of`` not given
        exactly once.
    """
    if not isinstance(table, dict):
        raise error(f"{where} must be a table, got {show(table)}")
    keys = {k.name: k for k in keys}
    out = dict(table)
    for name, value in table.items():
        if name not in keys:
            if open_:
                continue
            raise unknown(where, name, keys, context=context, error=error)
        out[name] = check_value(f"{where} {name}", keys[name], value, folder, error)
    for key in keys.values():
        if key.required and key.name not in table and key.default is None:
            raise error(f"{where} needs {key.name}{_unit(key, True)}: {key.doc or KINDS[key.kind]}")
    for group in one_of:
        given = [k for k in group if k in table]
        if len(given) != 1:
            raise error(f"{where} needs exactly one of {' and '.join(group)}, "
                        f"got {', '.join(given) if given else 'neither'}")
    return out
