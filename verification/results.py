"""The harness's result types: what a method returns for one refinement level (:class:`Run`),
one compared quantity with its verdict (:class:`Gate`), a table for the report
(:class:`Table`) and everything one case produced (:class:`CaseResult`).

A method plugin returns a :class:`Run`; nothing else in the harness needs to be known to
put a new method through the cases and gates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Level", "Run", "Gate", "Table", "CaseResult"]


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
