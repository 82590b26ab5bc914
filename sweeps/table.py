"""The tidy result table: one CSV row per point, written as results arrive.

Columns: ``index``, ``point_id`` (hash of the point's checked case), the axis values (one
column per axis key, ``case`` for the base case's file stem), ``status`` (``ok`` or
``failed``), ``error``, ``seconds`` (the point's wall time on its worker, s), the timings
``kernel_s`` (kernels formed inside the solve, 0 when the group's set was reused),
``solve_s``, ``energy_s`` (s), ``kernel_key``, the grid's ``nodes_x, nodes_y``, the
solver's ``iterations``, and every scalar result of ``bem solve --json`` (:data:`RESULTS`,
SI units; empty where a point has none) plus ``friction_share``.
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path

from bem.contact import SHARED_SCALARS

__all__ = ["RESULTS", "FRICTION_SCALARS", "META", "columns", "ResultTable", "read_rows", "as_float"]

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


def columns(axis_keys) -> list[str]:
    """The table's header for a sweep with these axis keys."""
    return [*META, *axis_keys, *RUN, *RESULTS]


def as_float(value) -> float:
    """A table cell as a float (``nan`` when empty or not a number)."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def read_rows(path: str | Path, header: list[str]) -> list[dict]:
    """Complete rows of a table written with ``header`` (a row cut short by an interrupted
    run, or a table of another header, is left out)."""
    path = Path(path)
    if not path.exists():
        return []
    with open(path, newline="", encoding="utf-8") as fh:
        reader = csv.reader(fh)
        first = next(reader, None)
        if first != header:
            return []
        rows = []
        for cells in reader:
            if len(cells) == len(header) and cells[header.index("status")] in ("ok", "failed"):
                rows.append(dict(zip(header, cells)))
    return rows


class ResultTable:
    """The CSV of a sweep, appended a row at a time and flushed (an interrupted sweep keeps
    every finished row); :meth:`finish` rewrites it sorted by point index."""

    def __init__(self, path: str | Path, header: list[str], keep: list[dict] = ()):
        self.path = Path(path)
        self.header = header
        self.rows = {int(r["index"]): {k: _cell(r.get(k)) for k in header} for r in keep}
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._write_all(sorted(self.rows.values(), key=lambda r: int(r["index"])))
        self._fh = open(self.path, "a", newline="", encoding="utf-8")
        self._csv = csv.DictWriter(self._fh, fieldnames=header, extrasaction="ignore")

    def _write_all(self, rows) -> None:
        tmp = self.path.with_suffix(".csv.tmp")
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.DictWriter(fh, fieldnames=self.header, extrasaction="ignore")
            w.writeheader()
            w.writerows(rows)
        os.replace(tmp, self.path)

    def add(self, row: dict) -> None:
        cells = {k: _cell(row.get(k)) for k in self.header}
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
    return str(value)
