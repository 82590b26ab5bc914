"""Whose folder ``--out`` is: ``verify`` replaces or removes only a folder it can prove it
wrote.

A report folder carries a marker file, :data:`MARKER`, naming the tool, the report format
and the version that wrote it. The report is built beside ``--out`` and renamed into
place (:func:`replace`); the folder it replaces is removed only when it carries the marker
(or is empty). Anything else there is someone's work: :func:`check` refuses it before
anything is solved unless ``--overwrite`` is given, and even then it is not deleted but
kept beside the report, renamed ``<out>.kept-<date>-<time>``.

Never admitted, with or without ``--overwrite`` (:func:`never`): the working folder, the
home folder, the folder of the cases (and of any case file named on the command line),
or a folder holding one of them, since renaming the report into place would move it
away.
"""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

__all__ = ["MARKER", "FORMAT", "OutFolderError", "marker_text", "is_report", "never", "check", "replace"]

MARKER = ".verification-report"
#: the layout of a report folder and its metrics.json; a baseline of another format is refused
FORMAT = 1


class OutFolderError(ValueError):
    """``--out`` names a place the report must not replace (the command exits 2)."""


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("viscolayer")
    except PackageNotFoundError:
        return "unknown"


def marker_text() -> str:
    """The marker's content: its first line says the tool and the report format."""
    return (f"verify report format {FORMAT}\nwritten by verify (viscolayer {_version()}).\n"
            "verify replaces this folder, with everything in it, because this file is here.\n")


def marker_format(folder: Path) -> int | None:
    """The report format named by the marker in ``folder``; ``None`` without a marker,
    ``0`` for a marker whose first line cannot be read."""
    path = Path(folder) / MARKER
    if path.is_symlink() or not path.is_file():
        return None
    try:
        first = path.read_text(errors="replace").splitlines()[:1]
    except OSError:
        return 0
    words = first[0].split() if first else []
    if words[:3] == ["verify", "report", "format"] and len(words) == 4 and words[3].isdigit():
        return int(words[3])
    return 0


def is_report(folder: Path) -> bool:
    """Whether ``folder`` is a report folder ``verify`` wrote (it carries the marker)."""
    return Path(folder).is_dir() and marker_format(folder) is not None


def _real(path) -> Path:
    return Path(os.path.realpath(os.path.abspath(path)))


def never(out: Path, folders=()) -> Path:
    """``out`` resolved (symlinks followed), or an :class:`OutFolderError` if it is, or
    holds, the working folder, the home folder or one of ``folders`` (the cases')."""
    real = _real(out)
    places = [("the working folder", Path.cwd()), ("your home folder", Path.home())]
    places += [("the folder of the cases", Path(f)) for f in folders]
    for what, place in places:
        place = _real(place)
        if real == place or real in place.parents:
            how = "is" if real == place else "holds"
            raise OutFolderError(
                f"--out {str(out)!r} {how} {what} ({place}): the report is renamed into place, which would move "
                f"{'it' if real == place else 'that folder'} away. Name a folder of its own, "
                "e.g. --out verification-report")
    return real


def check(out: Path, folders=(), overwrite: bool = False) -> Path:
    """``--out`` before anything is solved: :func:`never`, and an existing folder that
    holds files but no :data:`MARKER` refused unless ``overwrite``; returns it resolved."""
    real = never(out, folders)
    try:
        empty = not any(real.iterdir())
    except OSError:  # absent, or not readable: nothing to lose, or refused below
        empty = not real.exists()
    if not empty and not is_report(real) and not overwrite:
        old = (real / "metrics.json").is_file() and (real / "summary.md").is_file()
        raise OutFolderError(
            f"--out {str(out)!r}: {real} holds files and is not a report verify wrote (it has no {MARKER} "
            "file), so verify will not replace it. Name another folder, or give --overwrite to put the report "
            f"there and keep the folder's present content beside it as {real.name}.kept-<date>-<time>"
            + (" (it looks like a report of a verify that wrote no marker: remove it yourself once)" if old else ""))
    return real


def replace(folder: Path, out: Path) -> Path | None:
    """Mark the complete report ``folder`` and rename it to ``out``. The folder it
    replaces is removed if it is a report or empty; anything else is kept, renamed beside
    ``out``: returns where (``None`` when nothing was kept)."""
    folder, out = Path(folder), Path(out)
    (folder / MARKER).write_text(marker_text())
    if not os.path.lexists(out):
        os.rename(folder, out)
        return None
    old = out.parent / f".{out.name}.old-{os.getpid()}"
    os.rename(out, old)
    try:
        os.rename(folder, out)
    except BaseException:  # the previous report goes back where it was
        os.rename(old, out)
        raise
    if is_report(old):
        shutil.rmtree(old, ignore_errors=True)
        return None
    try:
        os.rmdir(old)  # removes an empty folder only
        return None
    except OSError:
        pass
    stamp = time.strftime("%Y%m%d-%H%M%S")
    kept, n = out.parent / f"{out.name}.kept-{stamp}", 1
    while os.path.lexists(kept):
        n += 1
        kept = out.parent / f"{out.name}.kept-{stamp}-{n}"
    os.rename(old, kept)
    return kept
