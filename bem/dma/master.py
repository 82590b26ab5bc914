"""Master curve by time-temperature superposition of DMA isotherms.

:func:`build_master_curve` shifts every isotherm to the reference temperature ``T_ref``
(K): horizontally by ``a_T`` (reduced frequency ``a_T omega``) and, if asked, vertically
by ``b_T`` (moduli divided by ``b_T``); conventions in :mod:`bem.dma.shift`. The shift
law is either given (:class:`~bem.dma.shift.WLF`, :class:`~bem.dma.shift.Arrhenius`:
every isotherm is shifted by the law) or named (``"wlf"``, ``"arrhenius"``): then each
isotherm's shift is fitted from its overlap with its neighbour, the law's constants are
fitted to those shifts, and the law fixes their common constant (``a_T(T_ref) = 1`` on
the law). The result, a :class:`MasterCurve`, gives a
:class:`bem.materials.MasterCurveTable` or a fitted :class:`bem.materials.Prony` at
any service temperature.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Optional, Union

import numpy as np

from ..materials import MasterCurveTable
from .errors import ShiftError
from .reader import DMAData
from .shift import WLF, Arrhenius, ShiftLaw, fit_arrhenius, fit_wlf, overlap_shifts

__all__ = ["MasterCurve", "build_master_curve"]

Density = Union[float, Callable[[float], float]]


@dataclass(frozen=True, eq=False)
class MasterCurve:
    """Shifted DMA points at the reference temperature and the shift law.

    Attributes
    ----------
    law : WLF or Arrhenius
        Horizontal shift law; ``law.T_ref`` is the reference temperature (K).
    temperatures : ndarray
        Isotherm temperatures (K), increasing.
    log_aT, log_bT : ndarray
        Horizontal and vertical shifts ``log10 a_T``, ``log10 b_T`` applied to each isotherm.
    omega : ndarray
        Reduced angular frequencies ``a_T omega`` (rad/s) of every point, increasing.
    storage, loss : ndarray
        Reduced shear moduli ``G' / b_T``, ``G'' / b_T`` (Pa) of every point.
    isotherm : ndarray of int
        Index (into ``temperatures``) of each point's isotherm.
    vertical : {None, "density", "fit"}
        How ``b_T`` was found: none (``b_T = 1``), ``T rho / (T_ref rho_ref)``, or fitted
        by overlap (then ``log10 b_T = vertical_slope (T - T_ref)`` at other temperatures).
    vertical_slope : float
        Slope (1/K) of the straight line fitted to the fitted ``log10 b_T``; 0 otherwise.
    density : float or callable, optional
        Density (kg/m^3), constant or a function of temperature (K), for ``"density"``.
    source : str
        Where the data came from.
    """

    law: ShiftLaw
    temperatures: np.ndarray
    log_aT: np.ndarray
    log_bT: np.ndarray
    omega: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    isotherm: np.ndarray
    vertical: Optional[str] = None
    vertical_slope: float = 0.0
    density: Optional[Density] = None
    source: str = "<arrays>"

    @property
    def T_ref(self) -> float:
        """Reference temperature (K)."""
        return self.law.T_ref

    def log_shift(self, temperature) -> np.ndarray:
        """``log10 a_T`` (law) at ``temperature`` (K); raises :class:`ShiftError` below a WLF singularity."""
        return self.law.log_aT(temperature)

    def log_vertical(self, temperature) -> np.ndarray:
        """``log10 b_T`` at ``temperature`` (K) by the vertical rule (0 without one)."""
        T = np.asarray(temperature, dtype=float)
        if self.vertical == "density":
            rho = self.density if callable(self.density) else (lambda t: self.density)
            return np.log10(T * np.vectorize(rho)(T) / (self.T_ref * rho(self.T_ref)))
        return self.vertical_slope * (T - self.T_ref)

    def points_at(self, temperature: Optional[float] = None):
        """The master curve's points moved to ``temperature`` (K; default ``T_ref``).

        Returns ``(omega, storage, loss)``: ``omega / a_T`` (rad/s) and moduli times
        ``b_T`` (Pa), sorted by frequency.
        """
        if temperature is None:
            return self.omega.copy(), self.storage.copy(), self.loss.copy()
        a = 10.0 ** float(self.log_shift(temperature))
        b = 10.0 ** float(self.log_vertical(temperature))
        return self.omega / a, self.storage * b, self.loss * b

    def table(self, temperature: Optional[float] = None, points_per_decade: float = 10.0) -> MasterCurveTable:
        """A :class:`bem.materials.MasterCurveTable` at ``temperature`` (K; default ``T_ref``).

        The shifted points are averaged in bins ``1 / points_per_decade`` decades wide in
        frequency (geometric means of ``omega`` and ``G'``; of ``G''`` too, or the
        arithmetic mean where a bin holds a zero loss), which merges overlapping isotherms
        into one strictly increasing table.
        """
        if not (math.isfinite(points_per_decade) and points_per_decade > 0):
            raise ShiftError(f"points_per_decade must be > 0, got {points_per_decade!r}")
        w, gs, gl = self.points_at(temperature)
        x = np.log10(w)
        bins = np.floor((x - x[0]) * points_per_decade + 1e-9).astype(int)
        rows = []
        for k in np.unique(bins):
            m = bins == k
            loss = 10 ** np.mean(np.log10(gl[m])) if np.all(gl[m] > 0) else float(np.mean(gl[m]))
            rows.append((10 ** np.mean(x[m]), 10 ** np.mean(np.log10(gs[m])), loss))
        omega, storage, loss = zip(*rows)
        return MasterCurveTable(omega, storage, loss)

    def fit_prony(self, temperature: Optional[float] = None, **options):
        """Fit a :class:`bem.materials.Prony` to the points at ``temperature`` (K).

        ``options`` go to :func:`bem.dma.prony_fit.fit_prony`; returns its
        :class:`~bem.dma.prony_fit.PronyFit`.
        """
        from .prony_fit import fit_prony

        return fit_prony(*self.points_at(temperature), **options)


def _law(law, T_ref: float):
    if isinstance(law, (WLF, Arrhenius)):
        if T_ref is not None and not math.isclose(law.T_ref, T_ref):
            raise ShiftError(f"T_ref = {T_ref} K differs from the given law's T_ref = {law.T_ref} K")
        return law, None
    name = str(law).lower()
    if name not in ("wlf", "arrhenius"):
        raise ShiftError(f"law must be 'wlf', 'arrhenius', a WLF or an Arrhenius, got {law!r}")
    if T_ref is None or not (math.isfinite(T_ref) and T_ref > 0):
        raise ShiftError(f"T_ref must be given as a temperature > 0 K to fit a {name} law, got {T_ref!r}")
    return None, name


def build_master_curve(
    data: DMAData,
    T_ref: Optional[float] = None,
    law: Union[str, WLF, Arrhenius] = "wlf",
    *,
    vertical: Optional[str] = None,
    density: Optional[Density] = None,
    quantity: Optional[str] = None,
    min_overlap: float = 0.5,
) -> MasterCurve:
    """Build the master curve of ``data`` at ``T_ref`` by time-temperature superposition.

    Parameters
    ----------
    data : DMAData
        The isotherms (shear moduli, Pa; ``G = E / 3`` for tensile data, incompressible).
    T_ref : float, optional
        Reference temperature (K); may be omitted when ``law`` is given as an object.
    law : "wlf", "arrhenius", WLF or Arrhenius
        A name: shifts fitted from the overlap of neighbouring isotherms (at least 2),
        then the law's constants fitted to them (WLF needs 3 isotherms or more). An
        object: the shifts are the law's.
    vertical : {None, "density", "fit"}
        No vertical shift; ``b_T = T rho(T) / (T_ref rho(T_ref))`` with ``density``; or
        ``log10 b_T`` fitted by overlap (needs a named ``law``).
    density : float or callable, optional
        Density (kg/m^3), constant or a function of temperature (K), for
        ``vertical="density"``; by default the data's ``density_kg_m3`` column,
        interpolated linearly in temperature (constant beyond the isotherms).
    quantity : {"modulus", "both", "tan_delta"}, optional
        Curves overlapped when fitting shifts (see :func:`~bem.dma.shift.overlap_shifts`).
        Default ``"modulus"`` (``log10 |G*|``, monotonic in frequency, so its overlap
        has one best shift outside flat plateaus), or ``"both"`` with ``vertical="fit"``
        (the loss tangent, blind to vertical shifts, then pins the horizontal one).
    min_overlap : float
        Least overlap of neighbouring isotherms (decades of frequency).

    Raises
    ------
    ShiftError
        A single isotherm where shifts are fitted, an isotherm at or below the WLF
        singularity, an unknown law or vertical rule, missing density.
    """
    given, name = _law(law, T_ref)
    T = data.temperatures
    if vertical not in (None, "density", "fit"):
        raise ShiftError(f"vertical must be None, 'density' or 'fit', got {vertical!r}")
    if vertical == "fit" and given is not None:
        raise ShiftError("vertical='fit' fits shifts from the data: give the law by name ('wlf' or 'arrhenius')")
    if vertical == "density" and density is None:
        rho = [s.density for s in data.isotherms]
        if any(r is None for r in rho):
            raise ShiftError(f"{data.source}: vertical='density' needs the density argument or a density_kg_m3 column")
        density = (lambda Tk, rho=np.array(rho): float(np.interp(Tk, T, rho))) if len(rho) > 1 else float(rho[0])
    if isinstance(density, (int, float)) and not (math.isfinite(density) and density > 0):
        raise ShiftError(f"density must be a finite number > 0 kg/m^3, got {density!r}")
    slope = 0.0
    if given is not None:
        law_obj = given
        log_a = np.asarray(law_obj.log_aT(T), dtype=float)
        log_b = np.zeros_like(log_a)
    else:
        if quantity is None:
            quantity = "both" if vertical == "fit" else "modulus"
        rel_a, rel_b = overlap_shifts(data, quantity=quantity, vertical=vertical == "fit", min_overlap=min_overlap)
        fit = fit_wlf if name == "wlf" else fit_arrhenius
        law_obj, c = fit(T, rel_a, T_ref, offset=True)
        log_a = rel_a - c
        log_b = np.zeros_like(log_a)
        if vertical == "fit":
            A = np.column_stack([T - T_ref, np.ones_like(T)])
            (slope, c_b), *_ = np.linalg.lstsq(A, rel_b, rcond=None)
            log_b, slope = rel_b - c_b, float(slope)
    curve = MasterCurve(law_obj, T, log_a, log_b, np.empty(0), np.empty(0), np.empty(0), np.empty(0, int),
                        vertical, slope, density, data.source)
    if vertical == "density":
        log_b = np.asarray(curve.log_vertical(T), dtype=float)
    w, gs, gl, idx = [], [], [], []
    for k, s in enumerate(data.isotherms):
        w.append(s.omega * 10.0 ** log_a[k])
        gs.append(s.storage / 10.0 ** log_b[k])
        gl.append(s.loss / 10.0 ** log_b[k])
        idx.append(np.full(len(s.omega), k))
    w, gs, gl, idx = (np.concatenate(c) for c in (w, gs, gl, idx))
    order = np.argsort(w, kind="stable")
    arrays = [T, log_a, log_b, w[order], gs[order], gl[order], idx[order]]
    for a in arrays:
        a.setflags(write=False)
    return MasterCurve(law_obj, *arrays, vertical, slope, density, data.source)
