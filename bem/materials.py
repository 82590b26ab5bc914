"""Complex shear moduli ``G*(omega) = G'(omega) + i G''(omega)`` of linear viscoelastic solids.

Time dependence ``exp(+i omega t)`` (paper eqs. 23-26: mode ``m`` is felt at
``omega_m = -nu_x V``), so a passive material has ``G'' >= 0`` for ``omega > 0``, and a real
relaxation function gives ``G*(-omega) = conj G*(omega)``. Every ``modulus`` accepts any
real ``omega`` (rad/s), negative and zero included, vectorized; ``G*(0)`` is real.

Materials are frozen dataclasses; :func:`bem.case.material_from_config` builds one from the
``[material]`` table of a case file.
"""

from __future__ import annotations

import math
import numbers
import pathlib
from dataclasses import dataclass, field
from typing import Callable, Union

import numpy as np

from ._checks import NotANumber, real

__all__ = [
    "Elastic",
    "ThreeParameterSolid",
    "Prony",
    "MasterCurveTable",
    "Material",
]


def _real(name: str, value, unit: str, *, allow_zero: bool = False) -> float:
    """Return ``value`` as a float after checking it is a finite real number (not a bool;
    numpy scalars welcome) and > 0 (or >= 0)."""
    number = not isinstance(value, (bool, np.bool_)) and isinstance(value, numbers.Real)
    if not (number and math.isfinite(value)):
        raise (ValueError if number else NotANumber)(f"{name} must be a finite real number ({unit}), got {value!r}")
    return real(name, value, unit, ">=0" if allow_zero else ">0")


def _omega(omega) -> np.ndarray:
    return np.asarray(omega, dtype=float)


def _reduced(wt) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split ``omega tau`` (-) for overflow-free rational functions of it.

    Returns ``(small, x, r)``: ``small = |wt| <= 1``, ``x = wt`` there (0 elsewhere) and
    ``r = 1 / wt`` elsewhere (0 there). A rational function written in ``x`` on the small
    side and in ``r`` on the other never forms ``wt**2``, so it stays finite for every
    ``wt``, infinite included (``r = 0``: the glassy limit).
    """
    wt = np.asarray(wt, dtype=float)
    small = np.abs(wt) <= 1.0
    x = np.where(small, wt, 0.0)
    r = 1.0 / np.where(small, 1.0, wt)
    return small, x, np.where(small, 0.0, r)


@dataclass(frozen=True)
class Elastic:
    """A purely elastic solid, ``G*(omega) = shear_modulus`` at every frequency.

    Parameters
    ----------
    shear_modulus : float
        Shear modulus ``G`` (Pa), > 0.
    """

    shear_modulus: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "shear_modulus", _real("shear_modulus", self.shear_modulus, "Pa"))

    def modulus(self, omega) -> np.ndarray:
        """``G*(omega)`` (Pa, complex, shape of ``omega``) at angular frequencies ``omega`` (rad/s)."""
        return np.full(np.shape(_omega(omega)), self.shear_modulus, dtype=complex)

    @property
    def relaxed_modulus(self) -> float:
        """``G(0)`` (Pa)."""
        return self.shear_modulus

    @property
    def glassy_modulus(self) -> float:
        """``G`` at infinite frequency (Pa)."""
        return self.shear_modulus


@dataclass(frozen=True)
class ThreeParameterSolid:
    """Spring ``G1`` in series with a Kelvin unit (spring ``G2``, dashpot ``eta``), paper eq. 71.

    ``G'(w) = G0 (1+f) ((1+f) + w^2 tau^2) / ((1+f)^2 + w^2 tau^2)`` and
    ``G''(w) = G0 (1+f) f w tau / ((1+f)^2 + w^2 tau^2)``. It equals the one-term
    :class:`Prony` series ``G_inf = G0``, ``G_1 = G0 f``, ``tau_1 = tau / (1 + f)``.
    For ``|omega tau| > 1`` the fractions are evaluated in ``1 / (omega tau)``, so the
    modulus is finite at every frequency (``G0 (1 + f)`` as ``|omega| -> inf``).

    Parameters
    ----------
    G0 : float
        Static (relaxed) shear modulus ``G'(0) = G1 G2 / (G1 + G2)`` (Pa), > 0.
    tau : float
        Creep time ``eta / G2`` (s), > 0.
    f : float
        ``G1 / G2`` (dimensionless), >= 0; the glassy modulus is ``G0 (1 + f)``.
    """

    G0: float
    tau: float
    f: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "G0", _real("G0", self.G0, "Pa"))
        object.__setattr__(self, "tau", _real("tau", self.tau, "s"))
        object.__setattr__(self, "f", _real("f", self.f, "(dimensionless)", allow_zero=True))

    def modulus(self, omega) -> np.ndarray:
        """``G*(omega)`` (Pa, complex, shape of ``omega``) at angular frequencies ``omega`` (rad/s)."""
        with np.errstate(over="ignore"):  # omega tau = inf is the glassy limit, r = 0
            small, x, r = _reduced(_omega(omega) * self.tau)
        g, f, c = self.G0 * (1 + self.f), self.f, 1 + self.f
        # (c + x^2) / (c^2 + x^2) = (c r^2 + 1) / (c^2 r^2 + 1), f x / (c^2 + x^2) = f r / (c^2 r^2 + 1)
        storage = np.where(small, (c + x * x) / (c * c + x * x), (c * r * r + 1) / (c * c * r * r + 1))
        loss = np.where(small, f * x / (c * c + x * x), f * r / (c * c * r * r + 1))
        return g * storage + 1j * (g * loss)

    @property
    def relaxation_time(self) -> float:
        """Relaxation time ``tau / (1 + f)`` (s) of the equivalent Maxwell branch."""
        return self.tau / (1 + self.f)

    @property
    def relaxed_modulus(self) -> float:
        """``G(0) = G0`` (Pa)."""
        return self.G0

    @property
    def glassy_modulus(self) -> float:
        """``G0 (1 + f)`` (Pa)."""
        return self.G0 * (1 + self.f)


def _sequence(name: str, value, unit: str) -> tuple[float, ...]:
    if isinstance(value, (str, bytes)) or np.ndim(value) != 1:
        raise ValueError(f"{name} must be a 1-D sequence of numbers ({unit}), got {value!r}")
    return tuple(_real(f"{name}[{i}]", v, unit) for i, v in enumerate(value))


@dataclass(frozen=True)
class Prony:
    """Generalized Maxwell solid: ``G*(w) = G_inf + sum_i G_i (i w tau_i) / (1 + i w tau_i)``.

    Each branch is evaluated in ``1 / (w tau_i)`` where ``|w tau_i| > 1``, so the modulus
    is finite at every frequency (``G_inf + sum G_i`` as ``|w| -> inf``).

    Parameters
    ----------
    G_inf : float
        Long-time (relaxed) shear modulus (Pa), > 0.
    G : sequence of float
        Moduli ``G_i`` of the Maxwell branches (Pa), each > 0.
    tau : sequence of float
        Relaxation times ``tau_i`` (s), each > 0, same length as ``G``.
    """

    G_inf: float
    G: tuple[float, ...]
    tau: tuple[float, ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "G_inf", _real("G_inf", self.G_inf, "Pa"))
        object.__setattr__(self, "G", _sequence("G", self.G, "Pa"))
        object.__setattr__(self, "tau", _sequence("tau", self.tau, "s"))
        if len(self.G) != len(self.tau):
            raise ValueError(f"G and tau must have the same length, got {len(self.G)} and {len(self.tau)}")

    def modulus(self, omega) -> np.ndarray:
        """``G*(omega)`` (Pa, complex, shape of ``omega``) at angular frequencies ``omega`` (rad/s)."""
        with np.errstate(over="ignore"):  # omega tau = inf is the glassy limit, r = 0
            small, x, r = _reduced(_omega(omega)[..., None] * np.asarray(self.tau))
        # i x / (1 + i x) = (x^2 + i x) / (1 + x^2) = (1 + i r) / (1 + r^2)
        d = np.where(small, 1 + x * x, 1 + r * r)
        storage = np.where(small, x * x, 1.0) / d
        loss = np.where(small, x, r) / d
        G = np.asarray(self.G)
        return self.G_inf + np.sum(G * storage, axis=-1) + 1j * np.sum(G * loss, axis=-1)

    @property
    def relaxed_modulus(self) -> float:
        """``G(0) = G_inf`` (Pa)."""
        return self.G_inf

    @property
    def glassy_modulus(self) -> float:
        """``G_inf + sum G_i`` (Pa)."""
        return self.G_inf + math.fsum(self.G)


def _check_table(omega, storage, loss, where: Callable[[int], str]) -> None:
    """Raise ``ValueError`` naming the row (``where(i)``) of the first bad entry."""
    if not len(omega) == len(storage) == len(loss):
        raise ValueError(
            f"omega, storage and loss must have the same length, got {len(omega)}, {len(storage)}, {len(loss)}"
        )
    if len(omega) < 2:
        raise ValueError(f"a master curve table needs at least 2 rows, got {len(omega)}")
    for i, row in enumerate(zip(omega, storage, loss)):
        for name, v in zip(("omega", "storage", "loss"), row):
            if not math.isfinite(v):
                raise ValueError(f"{name} must be finite, got {v!r} at {where(i)}")
        w, gs, gl = row
        if w <= 0:
            raise ValueError(f"omega must be > 0 rad/s, got {w!r} at {where(i)}")
        if gs <= 0:
            raise ValueError(f"storage must be > 0 Pa, got {gs!r} at {where(i)}")
        if gl < 0:
            raise ValueError(f"loss must be >= 0 Pa, got {gl!r} at {where(i)}")
        if i and w <= omega[i - 1]:
            raise ValueError(
                "omega must be strictly increasing (sorted, no duplicates), "
                f"got {w!r} after {omega[i - 1]!r} at {where(i)}"
            )


def _column(name: str, value, unit: str) -> tuple[float, ...]:
    if isinstance(value, (str, bytes)) or np.ndim(value) != 1:
        raise ValueError(f"{name} must be a 1-D sequence, got an array of shape {np.shape(value)}")
    return tuple(real(f"{name}[{i}]", v, unit, "any", finite=False) for i, v in enumerate(value))


@dataclass(frozen=True)
class MasterCurveTable:
    """A tabulated master curve ``(omega_k, G'_k, G''_k)``, interpolated in log-log.

    Inside the table, ``log G'`` is piecewise linear in ``log omega`` (a power law between
    nodes), and so is ``log G''`` when every loss entry is > 0; if any loss entry is 0
    (e.g. an elastic table), ``G''`` itself is piecewise linear in ``log omega``. Nodes are
    reproduced exactly. Piecewise linear rather than monotone cubic (PCHIP): its error has
    the proven bound ``h^2 / 8 max|d^2 log G / d(log omega)^2|`` (``h`` the node spacing in
    ``log omega``), it is exact on power-law segments, it never overshoots noisy data, and
    PCHIP's gain is small where it matters: it is third order for a monotone ``G'``, but
    its slope limiter at the loss peak keeps ``G''`` second order (measured on a
    three-term Prony model at 5-40 points per decade: PCHIP's ``G''`` error is 0.5-0.8
    times the linear one, its ``|G*|`` error at most 3 times smaller).

    Beyond the table (terminal solid behaviour at both ends, so ``G*(0)`` is real):
    below ``omega_min``, ``G' = G'(omega_min)`` and ``G'' = G''(omega_min) |omega| / omega_min``;
    above ``omega_max``, ``G' = G'(omega_max)`` and ``G'' = G''(omega_max) omega_max / |omega|``.
    Negative frequencies use ``G*(-omega) = conj G*(omega)``.

    Parameters
    ----------
    omega : sequence of float
        Angular frequencies (rad/s), > 0, strictly increasing; at least 2 rows.
    storage : sequence of float
        Storage modulus ``G'`` (Pa), > 0.
    loss : sequence of float
        Loss modulus ``G''`` (Pa), >= 0.
    """

    omega: tuple[float, ...]
    storage: tuple[float, ...]
    loss: tuple[float, ...]
    _log_loss: bool = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for name, unit in (("omega", "rad/s"), ("storage", "Pa"), ("loss", "Pa")):
            object.__setattr__(self, name, _column(name, getattr(self, name), unit))
        _check_table(self.omega, self.storage, self.loss, lambda i: f"row {i}")
        object.__setattr__(self, "_log_loss", min(self.loss) > 0)

    @classmethod
    def from_csv(cls, path) -> "MasterCurveTable":
        """Read a table from a CSV file.

        Three comma-separated columns per line: omega (rad/s), G' (Pa), G'' (Pa). Blank
        lines and ``#`` comments are ignored; the first non-comment line may be a header
        (it is skipped if it is not numeric). Errors name the file and line.
        """
        path = pathlib.Path(path)
        rows, lines, first = [], [], True
        for n, text in enumerate(path.read_text().splitlines(), start=1):
            text = text.split("#", 1)[0].strip()
            if not text:
                continue
            try:
                values = [float(c) for c in text.split(",")]
            except ValueError:
                if first:  # a header line
                    first = False
                    continue
                raise ValueError(f"{path} line {n}: could not parse numbers from {text!r}") from None
            first = False
            if len(values) != 3:
                raise ValueError(
                    f"{path} line {n}: expected 3 comma-separated columns (omega, G', G''), got {len(values)}"
                )
            rows.append(values)
            lines.append(n)
        omega, storage, loss = (list(c) for c in zip(*rows)) if rows else ([], [], [])
        _check_table(omega, storage, loss, lambda i: f"{path} line {lines[i]}")
        return cls(omega, storage, loss)

    def modulus(self, omega) -> np.ndarray:
        """``G*(omega)`` (Pa, complex, shape of ``omega``) at angular frequencies ``omega`` (rad/s)."""
        a = np.abs(_omega(omega))
        nodes, gs, gl = (np.asarray(c) for c in (self.omega, self.storage, self.loss))
        lo, hi = nodes[0], nodes[-1]
        c = np.clip(a, lo, hi)
        x = np.log(c)
        storage = np.exp(np.interp(x, np.log(nodes), np.log(gs)))
        if self._log_loss:
            loss = np.exp(np.interp(x, np.log(nodes), np.log(gl)))
        else:
            loss = np.interp(x, np.log(nodes), gl)
        k = np.clip(np.searchsorted(nodes, c), 0, len(nodes) - 1)  # reproduce nodes exactly
        at_node = nodes[k] == c
        storage = np.where(at_node, gs[k], storage)
        loss = np.where(at_node, gl[k], loss)
        loss = np.where(a < lo, gl[0] * (np.minimum(a, lo) / lo), loss)
        loss = np.where(a > hi, gl[-1] * (hi / np.maximum(a, hi)), loss)  # 0 at |omega| = inf
        return storage + 1j * np.where(_omega(omega) < 0, -loss, loss)

    @property
    def relaxed_modulus(self) -> float:
        """``G(0) = G'(omega_min)`` (Pa), by the low-frequency rule."""
        return self.storage[0]

    @property
    def glassy_modulus(self) -> float:
        """``G'(omega_max)`` (Pa), by the high-frequency rule."""
        return self.storage[-1]


Material = Union[Elastic, ThreeParameterSolid, Prony, MasterCurveTable]

