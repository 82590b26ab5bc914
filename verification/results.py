"""The harness's result types: what a method returns for one refinement level (:class:`Run`),
one compared quantity with its verdict (:class:`Gate`), a table for the report
(:class:`Table`) and everything one case produced (:class:`CaseResult`).

A method plugin returns a :class:`Run`; nothing else in the harness needs to be known to
put a new method through the cases and gates. What a method that is not built in returns
is read like user input (:func:`check_run`): anything the gates cannot compare is a
:class:`MethodError`, which fails that method's gates with the reason.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Level", "Run", "Gate", "Table", "CaseResult", "MethodError", "check_run", "check_scalar",
           "POSITIVE", "NON_NEGATIVE"]

#: scalars that are > 0 in any contact the cases pose: the load (N, or N/m for a line)
POSITIVE = ("load",)
#: scalars that cannot be negative: contact radius (m), contact area (m^2), peak pressure (Pa,
#: compressive positive)
NON_NEGATIVE = ("contact_radius", "contact_area", "peak_pressure")


@dataclass(frozen=True)
class Level:
    """One refinement level a method is asked to solve.

    Attributes
    ----------
    index : int
        Position in the case's list of levels, coarse (0) to fine.
    size : float or None
        The method's refinement parameter (m): node spacing, element size; ``None`` when
        the case gives none (a method with a single resolution).
    settings : dict
        The method's own section of the case file without its list of sizes (for example
        ``[bem] period`` and ``half_width``, ``[fem] model``).
    case : str
        The case's name (an external results file is looked up by it).
    sizes : tuple
        Every level's size, coarse to fine (a method may scale other settings with
        ``size / sizes[0]``).
    """

    index: int
    size: float | None
    settings: dict
    case: str = ""
    sizes: tuple = ()


@dataclass
class Run:
    """One method at one refinement level.

    Attributes
    ----------
    method : str
        The method's name.
    size : float or None
        The refinement parameter the run used (m).
    scalars : dict[str, float]
        Any of ``contact_radius`` (m), ``indentation`` (m), ``peak_pressure`` (Pa),
        ``load`` (N), ``rolling_resistance`` (N); a gate on a missing one fails and says so.
    r, pressure : ndarray
        Pressure samples (Pa, compressive positive) at distances ``r`` (m) from the
        indenter's axis; any layout (a radius, a grid flattened).
    seconds : float
        Wall time of the solve (s).
    grid, field : optional
        A BEM grid and its 2D pressure, for difference maps.
    """

    method: str
    size: float | None
    scalars: dict
    r: np.ndarray
    pressure: np.ndarray
    seconds: float = 0.0
    grid: object = None
    field: np.ndarray | None = None


@dataclass(frozen=True, kw_only=True)
class Gate:
    """One compared quantity with its verdict; built by keyword.

    ``error`` is in the units of ``tolerance`` (a relative difference, or a pressure
    difference in units of the reference peak, or an absolute difference where the case
    says so). A report-only gate is shown with its numbers and never fails.
    """

    case: str
    quantity: str
    method: str
    against: str
    level: str
    value: float
    reference: float
    error: float
    tolerance: float
    reason: str
    report_only: bool = False

    @property
    def within(self) -> bool:
        return bool(math.isfinite(self.error) and self.error <= self.tolerance)

    @property
    def passed(self) -> bool:
        return self.report_only or self.within

    @property
    def verdict(self) -> str:
        if self.report_only:
            return "REPORTED"
        return "PASS" if self.within else "FAIL"

    @property
    def margin(self) -> float:
        """``error / tolerance``: below 1 passes; infinite for a NaN error."""
        if not math.isfinite(self.error):
            return math.inf
        return self.error / self.tolerance if self.tolerance > 0 else math.inf

    @property
    def key(self) -> str:
        """A name that identifies the gate across runs (baseline comparison, JUnit)."""
        return f"{self.case}: {self.method} {self.quantity} vs {self.against} ({self.level})"


@dataclass(frozen=True)
class Table:
    """A table for the report: a title, column heads and rows of strings."""

    title: str
    head: tuple
    rows: tuple


@dataclass
class CaseResult:
    """Everything one case produced: runs per method (coarse to fine), convergence, the
    analytic reference, gates, the kind's own data (``extra``) and notes."""

    name: str
    title: str
    why: str
    kind: str
    runs: dict = field(default_factory=dict)
    convergence: dict = field(default_factory=dict)  # (method, quantity) -> metrics.Convergence
    reference: object = None
    gates: list = field(default_factory=list)
    extra: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    seconds: float = 0.0

    @property
    def passed(self) -> bool:
        return bool(self.gates) and all(g.passed for g in self.gates)

    @property
    def worst(self) -> Gate | None:
        """The gated (not report-only) comparison closest to, or furthest past, its tolerance."""
        gated = [g for g in self.gates if not g.report_only]
        return max(gated, key=lambda g: g.margin) if gated else None


class MethodError(RuntimeError):
    """A method gave no usable result: it raised, exited, could not be imported, or returned
    something the gates cannot compare. The kinds record it and fail the method's gates
    with this message; the run goes on."""


def _show(value) -> str:
    if isinstance(value, float) and not math.isfinite(value):
        return "NaN" if math.isnan(value) else ("Infinity" if value > 0 else "-Infinity")
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def check_scalar(name: str, value, what: str = "") -> float:
    """One scalar of a result: a finite real number (not a bool) that keeps its physical
    sign (:data:`POSITIVE`, :data:`NON_NEGATIVE`); returned as a float (SI units).

    ``what`` names it in the messages (default ``scalar 'NAME'``).

    Raises
    ------
    MethodError
        Naming the scalar, the value and the rule.
    """
    hint = "" if what else " (leave out a quantity the method does not compute)"
    what = what or f"scalar {name!r}"
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise MethodError(f"{what} must be a real number, got {type(value).__name__} {_show(value)}")
    v = float(value)
    if not math.isfinite(v):
        raise MethodError(f"{what} must be a finite number, got {_show(v)}{hint}")
    if name in POSITIVE and not v > 0:
        raise MethodError(f"{what} must be > 0, got {v!r}")
    if name in NON_NEGATIVE and v < 0:
        raise MethodError(f"{what} cannot be negative, got {v!r}")
    return v


def _samples(value, what: str) -> np.ndarray:
    try:
        a = np.asarray(value)
    except (TypeError, ValueError) as exc:
        raise MethodError(f"{what} must be an array of real numbers: {exc}") from None
    if a.dtype.kind not in "iuf":
        raise MethodError(f"{what} must be an array of real numbers, got {a.dtype} values")
    a = a.astype(float)
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        raise MethodError(f"{what} holds {bad.size} non-finite value(s) of {a.size} (the first at flat index "
                          f"{bad[0]}: {_show(float(a.ravel()[bad[0]]))})")
    return a


def check_run(run) -> Run:
    """``run`` read like user input; a clean copy (float scalars, flat float arrays).

    A :class:`Run` whose ``method`` is a string; ``size`` ``None`` or a finite number > 0
    (m); ``seconds`` finite and >= 0 (s); every scalar as :func:`check_scalar` says, and a
    ``leading_edge`` (m) not behind the ``trailing_edge``; ``r`` (m) and ``pressure`` (Pa)
    arrays of finite real numbers of one shape; ``field`` (Pa), when given, finite.

    Raises
    ------
    MethodError
        The first rule broken, naming the field and the value.
    """
    if not isinstance(run, Run):
        raise MethodError(f"{type(run).__name__} {_show(run)} is not a verification.results.Run")
    if not isinstance(run.method, str):
        raise MethodError(f"Run.method must be a string, got {_show(run.method)}")
    if not isinstance(run.scalars, dict):
        raise MethodError(f"Run.scalars must be a dict of name -> number, got {type(run.scalars).__name__}")
    scalars = {}
    for name, value in run.scalars.items():
        if not isinstance(name, str):
            raise MethodError(f"Run.scalars: a name must be a string, got {_show(name)}")
        scalars[name] = check_scalar(name, value)
    if scalars.get("leading_edge", math.inf) < scalars.get("trailing_edge", -math.inf):
        raise MethodError(f"scalar 'leading_edge' = {scalars['leading_edge']!r} m is behind 'trailing_edge' = "
                          f"{scalars['trailing_edge']!r} m")
    size = None
    if run.size is not None:
        size = check_scalar("size", run.size, "Run.size (m)")
        if not size > 0:
            raise MethodError(f"Run.size must be None or a number > 0 (m), got {size!r}")
    seconds = check_scalar("seconds", run.seconds, "Run.seconds")
    if seconds < 0:
        raise MethodError(f"Run.seconds cannot be negative, got {seconds!r}")
    r, pressure = _samples(run.r, "Run.r (m)"), _samples(run.pressure, "Run.pressure (Pa)")
    if r.shape != pressure.shape:
        raise MethodError(f"Run.r and Run.pressure must have one shape, got {r.shape} and {pressure.shape}")
    field_ = None if run.field is None else _samples(run.field, "Run.field (Pa)")
    return Run(run.method, size, scalars, r.ravel(), pressure.ravel(), seconds, run.grid, field_)
