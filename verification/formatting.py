"""Small helpers the kinds and the report share: numbers for tables, bare figures."""

from __future__ import annotations

import math

__all__ = ["fmt", "new_figure"]


def fmt(v) -> str:
    """A number for a table: six significant digits, ``-`` for None, NaN or infinity."""
    return "-" if v is None or not math.isfinite(v) else f"{v:.6g}"


def new_figure(figsize):
    """A bare :class:`matplotlib.figure.Figure` with constrained layout: no pyplot and no
    ``matplotlib.use``, so writing a report never switches the caller's backend."""
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout="constrained")
