"""DMA isotherms: read a CSV of frequency sweeps at several temperatures.

A DMA frequency sweep at temperature ``T`` gives the storage and loss moduli at a few
frequencies. Here they are held as shear moduli ``G'``, ``G''`` (Pa) against angular
frequency ``omega`` (rad/s) and absolute temperature (K). Tensile data ``E'``, ``E''`` are
converted with ``G = E / 3``, exact for the incompressible solids of this package
(Poisson's ratio 1/2).

CSV format (comma separated, ``#`` comments and blank lines ignored, one header line)::

    # isotherm,temperature_degC,frequency_hz,E_storage_MPa,E_loss_MPa
    0,-49.96,0.1,8097.18,93.07
    0,-49.96,0.215,8576.84,118.19
    ...

Header names (case-insensitive):

- temperature: ``temperature_degC`` or ``temperature_K`` (or ``temperature`` with the
  ``temperature_unit`` argument);
- frequency: ``frequency_hz`` (cycles per second) or ``omega_rad_s`` (or ``frequency``
  with the ``frequency_unit`` argument);
- moduli: ``G_storage_<unit>`` and ``G_loss_<unit>`` (shear) or ``E_storage_<unit>`` and
  ``E_loss_<unit>`` (tensile, ``G = E / 3``), ``<unit>`` one of Pa, kPa, MPa, GPa (or no
  suffix with the ``modulus_unit`` argument);
- optional ``isotherm``: a label per row; a new isotherm starts where it changes.
  Without it, a new isotherm starts where the temperature jumps by more than
  ``temperature_tolerance`` (K) from the row before;
- optional ``density_kg_m3``: the density (kg/m^3) at each row's temperature, used by the
  vertical shift ``T rho / (T_ref rho_ref)``.

Other columns are ignored. Within an isotherm the frequencies must be strictly monotonic
(increasing or decreasing: both sweep directions are accepted); its temperature is the
mean of its rows.
"""

from __future__ import annotations

import csv
import math
import pathlib
import re
from dataclasses import dataclass
from typing import Callable, Optional, Sequence

import numpy as np

from .errors import DMAInputError

__all__ = ["Isotherm", "DMAData", "read_dma_csv"]

_MODULUS_UNITS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9}
_FREQUENCY_UNITS = {"hz": 2.0 * math.pi, "rad/s": 1.0, "rad_s": 1.0}
_TEMPERATURE_UNITS = {"degc": 273.15, "c": 273.15, "k": 0.0}
_MODULUS_RE = re.compile(r"^(g|e)_(storage|loss)(?:_(pa|kpa|mpa|gpa))?$")


def _frozen(a) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


def check_points(omega, storage, loss, where: Callable[[int], str], label: str = "",
                 monotonic: bool = True) -> None:
    """Raise :class:`DMAInputError` at the first point that breaks a rule.

    Rules: every value finite; ``omega > 0`` (rad/s); ``storage > 0`` and ``loss >= 0``
    (Pa); with ``monotonic``, ``omega`` strictly monotonic. ``where(i)`` names point ``i``
    in messages.
    """
    for i, (w, gs, gl) in enumerate(zip(omega, storage, loss)):
        for name, v, unit in (("frequency", w, "rad/s"), ("storage modulus", gs, "Pa"), ("loss modulus", gl, "Pa")):
            if not math.isfinite(v):
                raise DMAInputError(f"{where(i)}: {name} must be finite ({unit}), got {v!r}")
        if w <= 0:
            raise DMAInputError(f"{where(i)}: frequency must be > 0 rad/s, got {w!r}")
        if gs <= 0:
            raise DMAInputError(f"{where(i)}: storage modulus must be > 0 Pa, got {gs!r}")
        if gl < 0:
            raise DMAInputError(f"{where(i)}: loss modulus must be >= 0 Pa, got {gl!r}")
    d = np.diff(np.asarray(omega, dtype=float))
    if monotonic and len(d) and not (np.all(d > 0) or np.all(d < 0)):
        sign = 1.0 if d[0] > 0 else -1.0
        k = int(np.argmax(sign * d <= 0)) + 1 if d[0] != 0 else 1
        raise DMAInputError(
            f"{where(k)}: frequencies within an isotherm{label} must be strictly monotonic, "
            f"got {omega[k]!r} rad/s after {omega[k - 1]!r} rad/s"
        )


@dataclass(frozen=True, eq=False)
class Isotherm:
    """One frequency sweep at one temperature (shear moduli, SI units).

    Parameters
    ----------
    temperature : float
        Absolute temperature (K), > 0.
    omega : array of float
        Angular frequencies (rad/s), > 0, strictly monotonic; stored increasing.
    storage, loss : array of float
        Shear storage ``G'`` (Pa, > 0) and loss ``G''`` (Pa, >= 0) moduli.
    density : float, optional
        Density at ``temperature`` (kg/m^3), > 0; ``None`` if not measured.
    """

    temperature: float
    omega: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    density: Optional[float] = None

    def __post_init__(self) -> None:
        T = self.temperature
        if not (isinstance(T, (int, float)) and math.isfinite(T) and T > 0):
            raise DMAInputError(f"isotherm temperature must be a finite number > 0 K, got {T!r}")
        if not len(self.omega) == len(self.storage) == len(self.loss):
            raise DMAInputError(
                f"isotherm at {T} K: omega, storage and loss must have the same length, "
                f"got {len(self.omega)}, {len(self.storage)}, {len(self.loss)}"
            )
        if len(self.omega) < 2:
            raise DMAInputError(f"isotherm at {T} K needs at least 2 frequencies, got {len(self.omega)}")
        check_points(self.omega, self.storage, self.loss, lambda i: f"isotherm at {T} K, point {i}")
        order = np.argsort(self.omega)
        for name in ("omega", "storage", "loss"):
            object.__setattr__(self, name, _frozen(np.asarray(getattr(self, name), dtype=float)[order]))
        if self.density is not None and not (math.isfinite(self.density) and self.density > 0):
            raise DMAInputError(f"isotherm at {T} K: density must be > 0 kg/m^3, got {self.density!r}")


@dataclass(frozen=True, eq=False)
class DMAData:
    """Isotherms of one material, sorted by temperature.

    Parameters
    ----------
    isotherms : sequence of Isotherm
        At least one; stored sorted by temperature (K).
    source : str
        Where the data came from (a file name), used in messages.
    """

    isotherms: tuple
    source: str = "<arrays>"

    def __post_init__(self) -> None:
        iso = tuple(self.isotherms)
        if not iso:
            raise DMAInputError(f"{self.source}: no isotherm found")
        object.__setattr__(self, "isotherms", tuple(sorted(iso, key=lambda s: s.temperature)))

    @property
    def temperatures(self) -> np.ndarray:
        """Isotherm temperatures (K), increasing."""
        return np.array([s.temperature for s in self.isotherms])

    @classmethod
    def from_arrays(cls, temperature, omega, storage, loss, density=None, source: str = "<arrays>") -> "DMAData":
        """Build from one array per isotherm: ``temperature[k]`` (K) and ``omega[k]``
        (rad/s), ``storage[k]``, ``loss[k]`` (shear moduli, Pa); ``density[k]`` (kg/m^3)
        optional."""
        dens = [None] * len(temperature) if density is None else list(density)
        return cls(
            tuple(Isotherm(float(T), w, gs, gl, d) for T, w, gs, gl, d in zip(temperature, omega, storage, loss, dens)),
            source,
        )


def _unit(kind: str, header_unit: Optional[str], argument: Optional[str], table: dict, path, column: str) -> str:
    """The unit of a column from its header or the argument; they must agree if both."""
    arg = argument.lower() if argument is not None else None
    if arg is not None and arg not in table:
        raise DMAInputError(f"{path}: {kind}_unit must be one of {', '.join(table)}, got {argument!r}")
    if header_unit is not None and arg is not None and table[header_unit] != table[arg]:
        raise DMAInputError(
            f"{path}: column {column!r} says {header_unit!r} but {kind}_unit={argument!r}; remove one"
        )
    unit = header_unit if header_unit is not None else arg
    if unit is None:
        raise DMAInputError(
            f"{path}: column {column!r} has no unit; name it with one ({_HINTS[kind]}) "
            f"or pass {kind}_unit"
        )
    return unit


_HINTS = {
    "temperature": "temperature_degC or temperature_K",
    "frequency": "frequency_hz or omega_rad_s",
    "modulus": "e.g. G_storage_Pa, E_loss_MPa",
}


def _columns(header: Sequence[str], path, temperature_unit, frequency_unit, modulus_unit) -> dict:
    """Map the header to column indices and conversion factors to SI."""
    names = [h.strip().lower() for h in header]
    found = f"(columns found: {', '.join(h.strip() for h in header)})"
    out: dict = {}
    for i, n in enumerate(names):
        if n in ("temperature_degc", "temperature_c", "temperature_k", "temperature"):
            unit = n.split("_", 1)[1] if "_" in n else None
            unit = _unit("temperature", unit, temperature_unit, _TEMPERATURE_UNITS, path, header[i].strip())
            out["T"] = (i, _TEMPERATURE_UNITS[unit])
        elif n in ("frequency_hz", "omega_rad_s", "frequency"):
            unit = {"frequency_hz": "hz", "omega_rad_s": "rad/s"}.get(n)
            unit = _unit("frequency", unit, frequency_unit, _FREQUENCY_UNITS, path, header[i].strip())
            out["w"] = (i, _FREQUENCY_UNITS[unit])
        elif m := _MODULUS_RE.match(n):
            kind, part, unit = m.groups()
            scale = _MODULUS_UNITS[_unit("modulus", unit, modulus_unit, _MODULUS_UNITS, path, header[i].strip())]
            out.setdefault("kind", set()).add(kind)
            out[part] = (i, scale / 3.0 if kind == "e" else scale)
        elif n == "isotherm":
            out["iso"] = (i, None)
        elif n == "density_kg_m3":
            out["rho"] = (i, 1.0)
    if len(out.get("kind", ())) > 1:
        raise DMAInputError(f"{path}: give shear (G_...) or tensile (E_...) moduli, not both {found}")
    for key, what in (("T", _HINTS["temperature"]), ("w", _HINTS["frequency"]),
                      ("storage", "G_storage_<unit> or E_storage_<unit>"), ("loss", "G_loss_<unit> or E_loss_<unit>")):
        if key not in out:
            raise DMAInputError(f"{path}: missing column {what} {found}")
    return out


def read_dma_csv(
    path,
    *,
    temperature_unit: Optional[str] = None,
    frequency_unit: Optional[str] = None,
    modulus_unit: Optional[str] = None,
    temperature_tolerance: float = 1.0,
) -> DMAData:
    """Read DMA isotherms from a CSV file (format in the module docstring).

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.
    temperature_unit : {"degC", "K"}, optional
        Unit of a column named plain ``temperature``.
    frequency_unit : {"Hz", "rad/s"}, optional
        Unit of a column named plain ``frequency`` (Hz: cycles per second, ``omega = 2 pi f``).
    modulus_unit : {"Pa", "kPa", "MPa", "GPa"}, optional
        Unit of modulus columns without a unit suffix.
    temperature_tolerance : float
        Without an ``isotherm`` column, a temperature step larger than this (K) between
        consecutive rows starts a new isotherm.

    Returns
    -------
    DMAData
        Shear moduli (Pa; ``G = E / 3`` for tensile data, incompressible), angular
        frequencies (rad/s), temperatures (K).

    Raises
    ------
    DMAInputError
        Naming the file, the line or column, the value and the rule: a missing column,
        a value that is not a number, a non-finite or negative modulus, a temperature
        at or below 0 K, frequencies not strictly monotonic within an isotherm.
    """
    path = pathlib.Path(path)
    rows: list[tuple[int, list[str]]] = []
    with path.open(newline="", encoding="utf-8-sig") as fh:  # a byte-order mark is not a column name
        for n, line in enumerate(fh, start=1):
            text = line.split("#", 1)[0].strip()
            if text:
                rows.append((n, next(csv.reader([text]))))
    if not rows:
        raise DMAInputError(f"{path}: no header line and no data")
    cols = _columns(rows[0][1], path, temperature_unit, frequency_unit, modulus_unit)
    header = [h.strip() for h in rows[0][1]]
    groups: list[dict] = []
    prev = None
    for n, cells in rows[1:]:
        if len(cells) != len(header):
            raise DMAInputError(f"{path} line {n}: expected {len(header)} columns, got {len(cells)}")
        values = {}
        for key in ("T", "w", "storage", "loss", "rho"):
            if key not in cols:
                continue
            i, scale = cols[key]
            try:
                v = float(cells[i])
            except ValueError:
                raise DMAInputError(f"{path} line {n}, column {header[i]!r}: not a number: {cells[i]!r}") from None
            if not math.isfinite(v):
                raise DMAInputError(f"{path} line {n}, column {header[i]!r}: must be finite, got {cells[i]!r}")
            if key in ("storage", "loss") and (v < 0 or (key == "storage" and v == 0)):
                rule = "> 0" if key == "storage" else ">= 0"
                raise DMAInputError(
                    f"{path} line {n}, column {header[i]!r}: {key} modulus must be {rule}, got {cells[i]!r}"
                )
            values[key] = v + scale if key == "T" else v * scale
        if values["T"] <= 0:
            raise DMAInputError(f"{path} line {n}: temperature must be > 0 K, got {values['T']!r} K")
        label = cells[cols["iso"][0]].strip() if "iso" in cols else None
        new = prev is None or (label != prev["label"] if label is not None
                               else abs(values["T"] - prev["T"][-1]) > temperature_tolerance)
        if new:
            prev = {"label": label, "T": [], "w": [], "storage": [], "loss": [], "rho": [], "lines": []}
            groups.append(prev)
        for key in ("T", "w", "storage", "loss"):
            prev[key].append(values[key])
        if "rho" in values:
            prev["rho"].append(values["rho"])
        prev["lines"].append(n)
    isotherms = []
    for g in groups:
        T = float(np.mean(g["T"]))
        where = (lambda lines: lambda i: f"{path} line {lines[i]}")(g["lines"])
        if len(g["w"]) < 2:
            raise DMAInputError(
                f"{where(0)}: the isotherm at {T:.2f} K has 1 row; an isotherm needs at least 2 frequencies"
            )
        check_points(g["w"], g["storage"], g["loss"], where, f" (isotherm at {T:.2f} K)")
        rho = float(np.mean(g["rho"])) if g["rho"] else None
        isotherms.append(Isotherm(T, g["w"], g["storage"], g["loss"], rho))
    return DMAData(tuple(isotherms), str(path))
