"""What an earlier run left in the output folder and the cache, checked before it is used.

:func:`prepare` decides, for a sweep about to run in ``out``:

- a folder holding another sweep's table (another ``name`` in ``sweep.json``, or other
  axes in the table's header) is refused, unless ``overwrite`` (then that sweep's files
  are removed: the table, the summary, plots and fits);
- ``results.csv`` read back (:func:`sweeps.table.read_back`): the verified rows are kept;
  rows of another version of the sweep or of the code, a row cut short by an interrupted
  run and (by default) failed points are computed again, with a line saying so; a
  damaged row (edited, overwritten, bytes that are not the table's) is refused with the
  row named, or, when a point cache is in use, the table is rebuilt from its verified
  rows and the verified point cache;
- the point cache then serves the missing points whose entries check
  (:meth:`sweeps.kernels.PointCache.load`); an entry that does not is named and its point
  computed again.
"""

from __future__ import annotations

import json
from pathlib import Path

from .spec import Point, Sweep, SweepError
from .table import _cell, axes_of, read_back

__all__ = ["prepare", "claim", "MANIFEST", "TABLE", "SUMMARY"]

TABLE = "results.csv"
SUMMARY = "summary.json"
#: the sweep an output folder belongs to: ``{"name", "axes", "source"}``
MANIFEST = "sweep.json"
#: how many damaged rows a message lists (the rest are counted)
SHOWN = 5


def _listing(items: list[str]) -> str:
    more = f"; and {len(items) - SHOWN} more" if len(items) > SHOWN else ""
    return "; ".join(items[:SHOWN]) + more


def _owned(out: Path) -> list[Path]:
    return [out / TABLE, out / SUMMARY, out / MANIFEST, out / "fits.csv", out / "fits.json",
            *sorted(out.glob("plot-*.png"))]


def _check_folder(sweep: Sweep, out: Path, notes: list) -> tuple[list[str], list[str]]:
    """What says ``out`` holds another sweep (empty when it is this sweep's or new), and
    this sweep's axes."""
    if out.exists() and not out.is_dir():
        raise SweepError(f"--out {out}: exists and is not a folder")
    for f in (out / TABLE, out / MANIFEST, out / SUMMARY):
        if f.exists() and not f.is_file():
            raise SweepError(f"{f}: is a {'folder' if f.is_dir() else 'special file'}, not the sweep's file; "
                             "remove it or choose another --out")
    axes = [a.key for a in sweep.axes]
    found = []
    manifest = out / MANIFEST
    if manifest.exists():
        try:
            info = json.loads(manifest.read_text(encoding="utf-8"))
            name, other = info["name"], list(info["axes"])
        except (OSError, ValueError, KeyError, TypeError) as exc:
            notes.append(f"sweep {sweep.name}: {manifest} cannot be read ({type(exc).__name__}: {exc}); "
                         "written again (the table's header still says whose it is)")
            name, other = sweep.name, axes
        if name != sweep.name or other != axes:
            found.append(f"{out} holds the sweep {name!r} over {', '.join(other) or 'no axis'}; this is "
                         f"{sweep.name!r} over {', '.join(axes)}")
    return found, axes


def prepare(sweep: Sweep, points: list[Point], out: Path, header: list[str], done, keep_failed: bool,
            overwrite: bool) -> tuple[dict, list[str], list[Path]]:
    """The rows an earlier run (or the point cache) already holds, by point index, the
    notes to print (what is computed again and why) and the files to remove when the
    sweep starts (:func:`claim`; nothing is changed here).

    Raises
    ------
    SweepError
        ``out`` or its table is not a file where one is expected, the folder holds another
        sweep (without ``overwrite``), or the table is damaged and there is no point cache
        to rebuild it from.
    """
    notes = []
    found, axes = _check_folder(sweep, out, notes)
    table = out / TABLE
    back = None
    if table.exists():
        ids = {p.index: p.point_id for p in points}
        cells = {p.index: {k: _cell(v) for k, v in p.values.items()} for p in points}
        back = read_back(table, header, ids, cells)
        if back.header and back.header != header and axes_of(back.header) != axes:
            found.append(f"{table} is the table of a sweep over {', '.join(axes_of(back.header)) or 'no axis'}; "
                         f"this sweep's axes are {', '.join(axes)}")
    if found and not overwrite:
        raise SweepError(f"{found[0]}: not replaced; choose another --out, or pass --overwrite to replace it")
    remove = []
    if found or overwrite:
        remove = [f for f in _owned(out) if f.is_file()]
        if remove:
            what = found[0] if found else f"{out} holds this sweep's earlier run"
            notes.append(f"sweep {sweep.name}: --overwrite: {what}; its {len(remove)} file(s) are replaced")
        back = None
    prior = {}
    if back is not None:
        if back.header and back.header != header and not back.damage:
            notes.append(f"sweep {sweep.name}: {table} has other columns (written by another version of the code); "
                         "its rows are computed again")
        if back.damage and done is None:
            raise SweepError(f"{table} is damaged: {_listing(back.damage)}. It is not used: remove it, run with "
                             "--overwrite to start afresh, or with a cache to rebuild it from the verified points")
        if back.damage:
            notes.append(f"sweep {sweep.name}: {table} is damaged ({_listing(back.damage)}); rebuilt from its "
                         f"{len(back.rows)} verified row(s) and the verified point cache")
        if back.stale:
            notes.append(f"sweep {sweep.name}: {table}: computed again: {_listing(back.stale)}")
        failed = [i for i, r in back.rows.items() if r["status"] != "ok"]
        if failed and not keep_failed:
            notes.append(f"sweep {sweep.name}: {len(failed)} point(s) that failed in the earlier run computed again "
                         f"(points {', '.join(map(str, failed[:10]))}{', ...' if len(failed) > 10 else ''})")
        prior = {i: r for i, r in back.rows.items() if r["status"] == "ok" or keep_failed}
    if done is not None:
        for p in points:
            if p.index in prior:
                continue
            row, why = done.load(p.point_id)
            if why:
                notes.append(f"sweep {sweep.name}: point {p.index}: cached point {why}; computed again")
            if row is not None:
                prior[p.index] = {**row, "index": p.index, "point_id": p.point_id, **p.values}
    return prior, notes, remove


def claim(sweep: Sweep, out: Path, remove: list[Path]) -> None:
    """Make ``out`` this sweep's: remove the replaced files, write ``sweep.json``."""
    for f in remove:
        f.unlink(missing_ok=True)
    out.mkdir(parents=True, exist_ok=True)
    (out / MANIFEST).write_text(json.dumps({"name": sweep.name, "axes": [a.key for a in sweep.axes],
                                            "source": sweep.source}, indent=2))
