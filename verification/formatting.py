"""Small helpers the kinds and the report share: numbers for tables, the unit each
quantity is shown in, a gate's parameters, and bare figures.

One unit per quantity across the report and the progress lines: lengths in mm, pressures
in MPa, forces in N (N/m per unit length in plane strain); values are stored in SI (m, Pa,
N) and converted only for display.
"""

from __future__ import annotations

import math
import re

__all__ = ["fmt", "new_figure", "unit", "shown", "parameters", "plain_quantity", "scalars_line"]

LENGTHS = frozenset({"contact_radius", "indentation", "leading_edge", "trailing_edge", "pressure_centroid_x",
                     "half_width", "share_peak_thickness"})
FORCES = frozenset({"rolling_resistance", "rolling_resistance_energy", "rolling_resistance_slope", "load",
                    "table3", "table3_full_range"})
PRESSURE_METRICS = frozenset({"pressure_rms_interior", "pressure_max_interior", "pressure_rms_edge",
                              "pressure_max_edge"})
SYMBOLS = {"contact_radius": "r_c", "indentation": "d", "peak_pressure": "p_max", "rolling_resistance": "R_r",
           "load": "P", "leading_edge": "x_l", "trailing_edge": "x_t"}


def fmt(v) -> str:
    """A number for a table: six significant digits, ``-`` for None, NaN or infinity."""
    return "-" if v is None or not math.isfinite(v) else f"{v:.6g}"


def plain_quantity(quantity: str) -> str:
    """``rolling_resistance[a=1mm,Nt=500]`` -> ``rolling_resistance``."""
    return quantity.split("[", 1)[0]


def unit(quantity: str, kind: str = "", own: dict | None = None) -> tuple[str, float]:
    """(unit, factor from SI) in which a gate's value and reference are shown.

    Lengths (m) in mm, pressures (Pa) in MPa, forces in N (N/m for the plane-strain kind
    ``rolling-2d``, whose loads and rolling resistances are per unit length); the
    pressure metrics of the stationary kinds are differences in units of the reference's
    peak pressure (``of peak``); ``-`` for a dimensionless number. ``own``: the kind's own
    quantities' units (quantity -> (unit, factor)), which come first (a kind module's
    ``UNITS``, in its Runs tables' units; :mod:`verification.pages` passes them).
    """
    q = plain_quantity(quantity)
    own = own or {}
    if q in own:
        return own[q]
    if q in LENGTHS:
        return "mm", 1e3
    if kind == "rolling-2d" and q == "pressure_rms_interior":  # the kind compares the two peaks' run
        return "MPa (peaks)", 1e-6
    if q in PRESSURE_METRICS or q.endswith(tuple(f"_{m}" for m in PRESSURE_METRICS)):  # midplane_pressure_...
        return "of peak", 1.0
    if q in ("peak_pressure", "pressure_max"):
        return "MPa", 1e-6
    if q in FORCES:
        return ("N/m" if kind == "rolling-2d" else "N"), 1.0
    return "-", 1.0


def shown(value, quantity: str, kind: str = "", own: dict | None = None) -> str:
    """``value`` (SI) in the unit of :func:`unit`, six significant digits."""
    _, factor = unit(quantity, kind, own)
    return fmt(None if value is None else value * factor)


_PAIR = re.compile(r"^\s*([^=]+?)\s*=\s*(-?[0-9.eE+-]+)\s*([a-zA-Z/]*)\s*$")


def _pretty(text: str) -> str:
    """``H=0.5mm,Nt=500`` -> ``H = 0.5 mm, Nt = 500``."""
    out = []
    for part in text.split(","):
        m = _PAIR.match(part)
        out.append(f"{m[1]} = {m[2]}{' ' + m[3] if m[3] else ''}" if m else part.strip())
    return ", ".join(out)


def parameters(case_name: str, gate_case: str, quantity: str) -> str:
    """The parameters a gate is for, from the bracket of its case part
    (``thickness-sweep[H=0.5mm]``) and of its quantity (``rolling_resistance[a=1mm,Nt=500]``);
    empty when it has none."""
    found = []
    if gate_case != case_name and "[" in gate_case:
        found.append(gate_case.split("[", 1)[1].rstrip("]"))
    if "[" in quantity:
        found.append(quantity.split("[", 1)[1].rstrip("]"))
    return ", ".join(_pretty(f) for f in found)


def scalars_line(scalars: dict, names) -> str:
    """``r_c = 2.3185 mm, d = 0.253669 mm, p_max = 0.886706 MPa`` for a progress line:
    the scalars ``names`` that ``scalars`` holds, each in its report unit."""
    return ", ".join(f"{SYMBOLS.get(q, q)} = {shown(scalars[q], q)} {unit(q)[0]}" for q in names if q in scalars)


def new_figure(figsize):
    """A bare :class:`matplotlib.figure.Figure` with constrained layout: no pyplot and no
    ``matplotlib.use``, so writing a report never switches the caller's backend."""
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout="constrained")
