"""A progress bar on stderr: points done of the total, failures, elapsed time and ETA."""

from __future__ import annotations

import sys
import time

__all__ = ["Progress", "duration"]


def duration(seconds: float) -> str:
    """``seconds`` as ``"1 h 02 min"``, ``"3 min 05 s"`` or ``"12 s"``."""
    s = int(round(seconds))
    if s >= 3600:
        return f"{s // 3600} h {s % 3600 // 60:02d} min"
    if s >= 60:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s} s"


class Progress:
    """Points done, total, failures and the ETA (from the pace of the points computed in
    this run), redrawn in place on a terminal and at most once a second otherwise.

    Parameters
    ----------
    name : str
        The sweep's name.
    total : int
        Points in the sweep.
    done : int
        Points already finished (resumed from an earlier run).
    stream : file, optional
        Where to draw (stderr); ``None`` draws nothing.
    """

    width = 30

    def __init__(self, name: str, total: int, done: int = 0, stream=sys.stderr):
        self.name, self.total, self.done, self.resumed = name, total, done, done
        self.failed = 0
        self.stream = stream
        self.start = time.perf_counter()
        self._last = 0.0
        self._tty = bool(stream is not None and getattr(stream, "isatty", lambda: False)())

    def line(self) -> str:
        elapsed = time.perf_counter() - self.start
        fresh = self.done - self.resumed
        left = self.total - self.done
        eta = duration(elapsed / fresh * left) if fresh and left else ("0 s" if not left else "?")
        filled = int(self.width * self.done / self.total) if self.total else self.width
        bar = "#" * filled + "." * (self.width - filled)
        failed = f", {self.failed} failed" if self.failed else ""
        return (f"sweep {self.name}: [{bar}] {self.done}/{self.total} points{failed}, "
                f"{duration(elapsed)} elapsed, ETA {eta}")

    def update(self, failed: bool = False) -> None:
        """One more point finished."""
        self.done += 1
        self.failed += bool(failed)
        self.draw(force=self.done == self.total)

    def draw(self, force: bool = False) -> None:
        if self.stream is None:
            return
        now = time.perf_counter()
        if self._tty:
            self.stream.write("\r" + self.line())
            if self.done == self.total:
                self.stream.write("\n")
        elif force or now - self._last >= 1.0:
            self.stream.write(self.line() + "\n")
            self._last = now
        self.stream.flush()

    def say(self, text: str) -> None:
        """A message line (kept clear of the bar)."""
        if self.stream is None:
            return
        self.stream.write(("\r\033[K" if self._tty else "") + text + "\n")
        self.stream.flush()
