"""What makes a cached or tabulated result trustworthy: the version of the code that made
it and a checksum of its content.

:func:`code_version` is the package version plus a content hash of the source files that
shape a result (the numerical modules of :mod:`bem` and :mod:`sweeps.point`, which builds
a row), read once per process: a change to the solver changes it, so every result made
before is computed again instead of served. A kernel set carries the SHA-256 of each
table's dtype, shape and bytes; a cached point and a table row the SHA-256 of their
canonical JSON; a mismatch means the entry was edited, damaged or cut short, and it is
never used.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
from importlib import metadata
from pathlib import Path

import numpy as np

__all__ = ["code_version", "array_digest", "json_digest", "input_files", "point_envelope", "open_envelope",
           "CODE_FILES_SKIPPED"]

#: files of :mod:`bem` that do not enter a number (command line, plots)
CODE_FILES_SKIPPED = ("cli.py", "plots.py", "__main__.py")


def _code_files() -> list[Path]:
    import bem

    root = Path(bem.__file__).resolve().parent
    files = [p for p in sorted(root.rglob("*.py")) if p.name not in CODE_FILES_SKIPPED]
    return [*files, Path(__file__).resolve().with_name("point.py")]


@functools.cache
def code_version() -> str:
    """``"<package version>+<12 hex digits>"``: the version of ``viscolayer`` and a SHA-256
    of the bytes of the numerical source files (:func:`_code_files`), with their paths
    relative to the package root (a renamed module counts as a change)."""
    try:
        version = metadata.version("viscolayer")
    except metadata.PackageNotFoundError:
        version = "0"
    h = hashlib.sha256()
    for path in _code_files():
        h.update(f"{path.parent.name}/{path.name}\0".encode())
        h.update(path.read_bytes())
        h.update(b"\0")
    return f"{version}+{h.hexdigest()[:12]}"


def array_digest(array: np.ndarray) -> str:
    """SHA-256 of an array's dtype, shape and bytes (C order)."""
    a = np.ascontiguousarray(array)
    h = hashlib.sha256(f"{a.dtype.str}{a.shape}".encode())
    h.update(a.tobytes())
    return h.hexdigest()


def json_digest(value) -> str:
    """SHA-256 of the canonical JSON of ``value`` (sorted keys, no spaces)."""
    return hashlib.sha256(json.dumps(value, sort_keys=True, separators=(",", ":")).encode()).hexdigest()


def input_files(config) -> dict:
    """``{path: sha256}`` of every file a checked case names (a master-curve table, a
    height map): the content of those files enters a point's identity, not only their
    path."""
    found = {}

    def walk(v):
        if isinstance(v, dict):
            for x in v.values():
                walk(x)
        elif isinstance(v, (list, tuple)):
            for x in v:
                walk(x)
        elif isinstance(v, str) and len(v) < 4096 and Path(v).is_absolute() and Path(v).is_file():
            found[v] = hashlib.sha256(Path(v).read_bytes()).hexdigest()

    walk(config)
    return found


def point_envelope(point_id: str, row: dict) -> dict:
    """A finished point as the cache stores it: the row, the code version and the row's
    checksum."""
    clean = {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in row.items()}
    return {"point_id": point_id, "code": code_version(), "sha256": json_digest(clean), "row": clean}


def open_envelope(data, point_id: str) -> tuple[dict | None, str]:
    """The row of a cached point, or ``(None, why)`` when it cannot be trusted: not an
    object of the cached-point form, another point's, made by another version of the code,
    a checksum that does not match, or not a finished point."""
    if not isinstance(data, dict):
        return None, f"holds a JSON {type(data).__name__}, not a cached point"
    missing = [k for k in ("point_id", "code", "sha256", "row") if k not in data]
    if missing:
        return None, (f"is not a cached point of this form (no {', '.join(missing)}): written by an earlier "
                      "version of the code, or edited")
    row = data["row"]
    if data["point_id"] != point_id:
        return None, f"belongs to point {data['point_id']!r}, not {point_id!r}"
    if data["code"] != code_version():
        return None, f"was computed by another version of the code ({data['code']}, now {code_version()})"
    if not isinstance(row, dict) or json_digest(row) != data["sha256"]:
        return None, "does not match its checksum (edited or damaged)"
    if row.get("status") != "ok":
        return None, f"is not a finished point (status {row.get('status')!r})"
    return row, ""
