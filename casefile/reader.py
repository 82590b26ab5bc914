"""Read a case file, apply ``--set`` overrides, and check it against :data:`SCHEMA`.

Every error is a :class:`CaseFileError` naming the file, the section and the key, the
value and the rule. Relative paths in a file resolve against the file's folder; paths
given with ``--set`` resolve against the working folder (where the command was typed).
"""

from __future__ import annotations

import copy
import os
import tomllib
from pathlib import Path
from typing import Iterable

from .schema import SCHEMA, TOOLS, Section, readers, section
from .validation import InputError, check_table, check_value, show, unknown

__all__ = ["CaseFileError", "read", "validate", "parse_override", "apply_overrides", "check_output"]


class CaseFileError(InputError):
    """A case file, an override of it, or an output path that breaks the schema."""


def _check_section(source: str, spec: Section, table: dict, folder: Path) -> dict:
    where = f"{source} [{spec.name}]"
    variant = None
    if spec.selector is not None:
        sel = spec.key(spec.selector)
        chosen = table.get(spec.selector, sel.default)
        if chosen is None:
            raise CaseFileError(f"{where} needs {spec.selector} (one of {', '.join(spec.variants)})")
        variant = check_value(f"{where} {spec.selector}", sel, chosen, folder, CaseFileError)
    context = ""
    if variant:
        context = f' for {spec.selector} = "{variant}"'
        stray = next((name for name in table if spec.key(name, variant) is None), None)
        if stray is not None and spec.all_keys(stray):
            context += f"; {stray} belongs to another {spec.selector}"
    keys = spec.keys + (spec.variants[variant].keys if variant else ())
    out = check_table(where, table, keys, folder=folder, context=context, one_of=spec.one_of, error=CaseFileError)
    if variant:
        out[spec.selector] = variant  # a default selector is written out, so every reader sees it
    return out


def _for_tool(source: str, data: dict, tool: str) -> dict:
    """Keep what ``tool`` reads; an error for physics it cannot solve, never a silent drop."""
    command = TOOLS[tool]
    out = {}
    for spec in SCHEMA:
        if spec.name not in data:
            if tool in spec.required_by:
                raise CaseFileError(f"{source}: {command} needs a [{spec.name}] section ({spec.doc})")
            continue
        table = data[spec.name]
        if tool not in spec.readers:
            if spec.discretization:
                continue  # another tool's discretization
            others = " and ".join(TOOLS[t] for t in spec.readers)
            raise CaseFileError(f"{source}: {command} cannot solve [{spec.name}] ({spec.doc}); it is read by "
                                f"{others} only. Remove the section, or use {others}")
        if spec.selector is not None:
            variant = table.get(spec.selector, spec.key(spec.selector).default)
            if tool not in spec.variants[variant].readers:
                supported = [v for v, var in spec.variants.items() if tool in var.readers]
                raise CaseFileError(f"{source}: {command} cannot solve [{spec.name}] {spec.selector} = "
                                    f"\"{variant}\"; it reads {', '.join(supported)}")
        for name in table:
            key = spec.key(name, table.get(spec.selector) if spec.selector else None)
            if tool not in readers(key):
                raise CaseFileError(f"{source}: {command} does not read [{spec.name}] {name}; remove it")
        out[spec.name] = table
    return out


def validate(data: dict, tool: str | None = None, *, source: str = "case", folder: str | Path = ".") -> dict:
    """Check a parsed case against the schema and return a checked copy.

    Parameters
    ----------
    data : dict
        Sections as tables (the TOML structure).
    tool : {"bem", "fem"}, optional
        Also check what this tool needs and reads, and drop the other tool's
        discretization section.
    source : str
        What the errors name (the file).
    folder : path
        Folder that relative paths resolve against (the case file's).

    Raises
    ------
    CaseFileError
        Unknown section or key, wrong type (a boolean is not a number), value out of range,
        missing required key, a file that does not exist, physics the tool cannot solve.
    """
    if tool is not None and tool not in TOOLS:
        raise ValueError(f"tool must be one of {', '.join(TOOLS)}, got {tool!r}")
    if not isinstance(data, dict):
        raise CaseFileError(f"{source}: a case is a set of [sections], got {show(data)}")
    out = {}
    for name, table in data.items():
        spec = section(name)
        if spec is None:
            raise unknown(source, name, [s.name for s in SCHEMA], what="section", error=CaseFileError)
        if not isinstance(table, dict):
            raise CaseFileError(f"{source} [{name}] must be a table of keys, got {show(table)}")
        out[name] = _check_section(source, spec, table, Path(folder))
    return copy.deepcopy(_for_tool(source, out, tool) if tool else out)


def _clip(text: str, limit: int = 80) -> str:
    """``text`` quoted, cut to ``limit`` characters with its length said when longer."""
    return repr(text) if len(text) <= limit else f"{text[:limit]!r}... ({len(text)} characters)"


def parse_override(text: str) -> tuple[str, str, object]:
    """``"section.key=value"`` as ``(section, key, value)``; the value is parsed as TOML,
    or kept as a bare string where the key takes a string or a path.

    Raises
    ------
    CaseFileError
        A malformed assignment, or a bare word where the key takes a number.
    """
    name, sep, raw = text.partition("=")
    sec, dot, key = name.strip().partition(".")
    if not sep or not dot or not sec or not key or "." in key:
        raise CaseFileError(f"--set expects section.key=value (one dot in the name), got {_clip(text)}")
    raw = raw.strip()
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        spec = section(sec)
        kinds = {k.kind for k in spec.all_keys(key)} if spec else set()
        if not kinds or kinds <= {"string", "path"}:
            value = raw  # a bare word for a string key (an unknown key is reported later)
        else:
            raise CaseFileError(f"--set {sec}.{key}={raw}: [{sec}] {key} takes "
                                f"{' or '.join(sorted(kinds))}, and {raw!r} is not one") from None
    spec = section(sec)
    if spec is not None and isinstance(value, str) and {k.kind for k in spec.all_keys(key)} == {"path"}:
        value = str(Path(value).resolve())  # a path typed on the command line: the working folder's
    return sec, key, value


def apply_overrides(data: dict, overrides: Iterable[str]) -> dict:
    """``data`` with each ``section.key=value`` of ``overrides`` set (a new dict)."""
    out = {name: dict(table) if isinstance(table, dict) else table for name, table in data.items()}
    for text in overrides:
        sec, key, value = parse_override(text)
        table = out.setdefault(sec, {})
        if not isinstance(table, dict):
            raise CaseFileError(f"--set {text}: [{sec}] is not a table")
        table[key] = value
    return out


def read(path: str | Path, overrides: Iterable[str] = (), tool: str | None = None) -> dict:
    """Read the case file at ``path``, apply ``overrides`` (``section.key=value``) and
    :func:`validate` it (for ``tool`` if given)."""
    path = Path(path)
    if not path.exists():
        raise CaseFileError(f"case file {str(path)!r} not found")
    if not path.is_file():
        raise CaseFileError(f"case file {str(path)!r} is a folder, not a file")
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise CaseFileError(f"{path}: not a UTF-8 text file (TOML is UTF-8; byte {exc.object[exc.start]:#04x} at "
                            f"offset {exc.start}); save it as UTF-8") from None
    except OSError as exc:
        raise CaseFileError(f"{path}: cannot be read: {exc.strerror}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseFileError(f"{path}: not a valid TOML file: {exc}") from None
    except RecursionError:
        raise CaseFileError(f"{path}: its arrays or inline tables are nested too deeply to read; a case file "
                            "nests a few levels at most") from None
    try:
        data = apply_overrides(data, overrides)
    except CaseFileError as exc:
        raise CaseFileError(f"{path}: {exc}") from None
    try:
        return validate(data, tool, source=str(path), folder=path.parent)
    except RecursionError:
        raise CaseFileError(f"{path}: its tables are nested too deeply to check; a case file nests a few "
                            "levels at most") from None


def check_output(path: str | Path | None, suffixes: tuple, option: str) -> Path | None:
    """Check, before any work, that an output file can be written at ``path``: a known
    suffix, not a folder, a writable folder (created if missing).

    Raises
    ------
    CaseFileError
        Naming ``option`` (``--plot``), the path and what is wrong.
    """
    if path is None:
        return None
    path = Path(path)
    if path.suffix.lower() not in suffixes:
        raise CaseFileError(f"{option} {str(path)!r}: the file must end in {' or '.join(suffixes)}")
    if path.is_dir():
        raise CaseFileError(f"{option} {str(path)!r} is a folder; give a file name")
    folder = path.parent
    blocking = next((a for a in (folder, *folder.parents) if a.exists() and not a.is_dir()), None)
    if blocking is not None:
        raise CaseFileError(f"{option} {str(path)!r}: {str(blocking)!r} is a file, not a folder")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CaseFileError(f"{option} {str(path)!r}: cannot create the folder {str(folder)!r} ({exc.strerror})") from None
    if not os.access(folder, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise CaseFileError(f"{option} {str(path)!r}: not writable")
    return path
