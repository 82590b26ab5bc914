"""The tidy result table: one CSV row per point, written as results arrive, and read back
checked.

Columns: ``index``, ``point_id`` (hash of the point's checked case), the axis values (one
column per axis key, ``case`` for the base case's file stem), ``status`` (``ok`` or
``failed``), ``error``, ``seconds`` (the point's wall time on its worker, s), the timings
``kernel_s`` (kernels formed inside the solve, 0 when the group's set was reused),
``solve_s``, ``energy_s`` (s), ``kernel_key``, the grid's ``nodes_x, nodes_y``, the
solver's ``iterations``, every scalar result of ``bem solve --json`` (:data:`RESULTS`,
SI units; empty where a point has none) plus ``friction_share``, then ``code`` (the
version of the code that computed the row, :func:`sweeps.integrity.code_version`) and
``checksum`` (SHA-256 of the row's other cells, 16 hex digits).

A table read back (:func:`read_back`) keeps a row only when its checksum matches, its
cells have their types (finite numbers, a known status, an index of this sweep), its
point is the sweep's point at that index and its code is today's; every other row is
reported, as *stale* (another version of the sweep or of the code: computed again) or
*damaged* (edited, cut or overwritten: the caller refuses the table or rebuilds it).
"""

from __future__ import annotations

import csv
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from bem.contact import SHARED_SCALARS

from .integrity import code_version, json_digest

__all__ = ["RESULTS", "FRICTION_SCALARS", "META", "RUN", "CHECK", "columns", "axes_of", "ResultTable", "read_back",
           "Readback", "check_values", "as_float"]

#: scalars a frictional result adds to the shared ones (``FrictionalContact.summary``)
FRICTION_SCALARS = ("rolling_resistance_friction", "rolling_resistance_viscous", "omega", "driving_force",
                    "driving_torque", "stick_fraction", "mu", "mode")
#: every result column: the scalars of ``bem solve --json``, the energy figure (computed for
#: frictionless rolling too) and the friction share
#: ``rolling_resistance_friction / rolling_resistance_energy`` (-)
RESULTS = (*SHARED_SCALARS, "rolling_resistance_energy", *FRICTION_SCALARS, "speed", "friction_share")
#: bookkeeping columns before the axes and after them
META = ("index", "point_id")
RUN = ("status", "error", "seconds", "kernel_s", "solve_s", "energy_s", "kernel_key", "nodes_x", "nodes_y",
       "iterations")
#: the code that computed a row and the row's checksum (the last columns)
CHECK = ("code", "checksum")
#: columns that hold a finite number or nothing
NUMERIC = ("seconds", "kernel_s", "solve_s", "energy_s", "nodes_x", "nodes_y", "iterations",
           *(r for r in RESULTS if r != "mode"))
_KNOWN = {*META, *RUN, *RESULTS, *CHECK}
_HEX16 = re.compile(r"[0-9a-f]{16}")


def columns(axis_keys) -> list[str]:
    """The table's header for a sweep with these axis keys."""
    return [*META, *axis_keys, *RUN, *RESULTS, *CHECK]


def axes_of(header: list[str]) -> list[str]:
    """The axis columns of a table's header (those that are not the table's own)."""
    return [c for c in header if c not in _KNOWN]


def as_float(value) -> float:
    """A table cell as a float (``nan`` when empty or not a number)."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def check_values(row: dict) -> str:
    """Why a row's values cannot be a computed point's (``""`` when they can): a result or
    timing that is not a finite number, or a finished point without its rolling
    resistance."""
    for k in NUMERIC:
        v = row.get(k)
        if v is None or v == "":
            continue
        if isinstance(v, bool) or not isinstance(v, (int, float, str)):
            return f"{k} = {v!r} is not a number"
        x = as_float(v)
        if not math.isfinite(x):
            return f"{k} = {v!r} is not a finite number"
    if row.get("status") == "ok" and row.get("rolling_resistance") in (None, ""):
        return "a finished point without its rolling_resistance"
    return ""


def _checksum(cells: dict, header: list[str]) -> str:
    return json_digest([cells.get(k, "") for k in header if k != "checksum"])[:16]


def _cells(row: dict, header: list[str]) -> dict:
    cells = {k: _cell(row.get(k)) for k in header if k not in CHECK}
    cells["code"] = code_version()
    cells["checksum"] = _checksum(cells, header)
    return cells


@dataclass
class Readback:
    """A table read back: the rows kept (by index, as cells), and notes on the others."""

    header: list = field(default_factory=list)
    rows: dict = field(default_factory=dict)
    stale: list = field(default_factory=list)
    damage: list = field(default_factory=list)


def _line_cells(line: bytes, number: int) -> tuple[list | None, str]:
    try:
        text = line.decode("utf-8")
    except UnicodeDecodeError:
        return None, f"line {number}: not UTF-8 text"
    if "\0" in text:
        return None, f"line {number}: holds NUL bytes"
    try:
        return next(csv.reader([text.rstrip("\r\n")]), []), ""
    except csv.Error as exc:
        return None, f"line {number}: not a CSV row ({exc})"


def read_back(path: str | Path, header: list[str], point_ids: dict, axis_cells: dict) -> Readback:
    """The rows of the table at ``path`` that can be kept for a sweep whose table has
    ``header`` and whose point ``i`` has ``point_ids[i]`` and axis cells
    ``axis_cells[i]``.

    A file whose header has other columns returns only ``header`` (the caller compares
    axes); an unreadable header is damage of line 1. A last line cut short (no newline,
    too few cells: an interrupted run) is stale, not damage.
    """
    out = Readback()
    data = Path(path).read_bytes()
    lines = data.split(b"\n")
    if lines and lines[-1] == b"":
        lines.pop()
    if not lines:
        out.damage.append("line 1: empty (no header)")
        return out
    first, why = _line_cells(lines[0], 1)
    if first is None:
        out.damage.append(why + " (the header)")
        return out
    out.header = first
    if first != header:
        return out
    ending = not data.endswith(b"\n")
    for number, line in enumerate(lines[1:], start=2):
        cells, why = _line_cells(line, number)
        if cells is None:
            out.damage.append(why)
            continue
        last = ending and number == len(lines)  # no newline after it: the run may have stopped mid-row
        if len(cells) != len(header):
            if last and len(cells) < len(header):
                out.stale.append(f"line {number}: cut short (an interrupted run)")
            else:
                out.damage.append(f"line {number}: {len(cells)} cells, the header has {len(header)}")
            continue
        row = dict(zip(header, cells))
        if last and row["checksum"] != _checksum(row, header) and _checksum(row, header).startswith(row["checksum"]):
            out.stale.append(f"line {number}: cut short (an interrupted run)")
            continue
        verdict, why = _judge(row, header, point_ids, axis_cells, out.rows)
        where = f"line {number}" + (f" (point {row['index']})" if row["index"].isdigit() else "")
        if verdict == "keep":
            out.rows[int(row["index"])] = row
        elif verdict == "stale":
            out.stale.append(f"{where}: {why}")
        else:
            out.damage.append(f"{where}: {why}")
    return out


def _judge(row: dict, header: list[str], point_ids: dict, axis_cells: dict, kept: dict) -> tuple[str, str]:
    if _checksum(row, header) != row["checksum"]:
        return "damage", "its cells do not match its checksum (edited or damaged)"
    if not row["index"].isdigit() or int(row["index"]) not in point_ids:
        return "damage", f"index {row['index']!r} is not a point of this sweep (0 to {len(point_ids) - 1})"
    i = int(row["index"])
    if i in kept:
        return "damage", f"point {i} is given twice"
    if row["status"] not in ("ok", "failed"):
        return "damage", f"status {row['status']!r} is neither ok nor failed"
    if not _HEX16.fullmatch(row["point_id"]):
        return "damage", f"point_id {row['point_id']!r} is not 16 hex digits"
    why = check_values(row)
    if why:
        return "damage", why
    if row["code"] != code_version():
        return "stale", f"computed by another version of the code ({row['code']}, now {code_version()})"
    if row["point_id"] != point_ids[i]:
        return "stale", "another point at this index (the sweep file changed)"
    wrong = [k for k, v in axis_cells[i].items() if row.get(k) != v]
    if wrong:
        return "damage", f"{wrong[0]} = {row.get(wrong[0])!r}, the point's value is {axis_cells[i][wrong[0]]!r}"
    return "keep", ""


class ResultTable:
    """The CSV of a sweep, appended a row at a time and flushed (an interrupted sweep keeps
    every finished row); :meth:`finish` rewrites it sorted by point index. Each row
    written carries today's code version and its checksum."""

    def __init__(self, path: str | Path, header: list[str], keep: list[dict] = ()):
        self.path = Path(path)
        self.header = header
        self.rows = {int(r["index"]): _cells(r, header) for r in keep}
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._write_all(sorted(self.rows.values(), key=lambda r: int(r["index"])))
        self._fh = open(self.path, "a", newline="", encoding="utf-8")
        self._csv = csv.DictWriter(self._fh, fieldnames=header, extrasaction="ignore", lineterminator="\n")

    def _write_all(self, rows) -> None:
        tmp = self.path.with_suffix(".csv.tmp")
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.DictWriter(fh, fieldnames=self.header, extrasaction="ignore", lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
        os.replace(tmp, self.path)

    def add(self, row: dict) -> None:
        cells = _cells(row, self.header)
        self.rows[int(row["index"])] = cells
        self._csv.writerow(cells)
        self._fh.flush()

    def finish(self) -> list[dict]:
        self._fh.close()
        rows = sorted(self.rows.values(), key=lambda r: int(r["index"]))
        self._write_all(rows)
        return rows


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return "" if not math.isfinite(value) else repr(value)
    return str(value).replace("\r", " ").replace("\n", " ")
