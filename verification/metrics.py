"""Comparison metrics, the same for every method: contact radius from the gap, pressure
differences relative to the peak, and grid convergence (observed order, Richardson)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from bem.convergence import Convergence, richardson  # one Richardson for the harness and bem's error bars

__all__ = ["fit_contact_radius", "PressureDifference", "pressure_difference", "Convergence", "richardson"]


def fit_contact_radius(r, gap, contact, spacing: float, band: float = 3.0) -> float:
    """Contact radius (m) from the gap just outside the contact, for a smooth indenter.

    Near the edge the gap opens like ``(r - r_c)^(3/2)`` (Hertz, and any smooth
    frictionless contact), so ``g^(2/3)`` is linear in ``r``; the radius is the zero of
    the least-squares line through the open samples within ``band * spacing`` of the
    first open one. It moves smoothly with the load instead of by whole node spacings,
    and reads the same from a BEM grid (samples in every direction) as from a FEM radius
    (samples along one line).

    Parameters
    ----------
    r, gap : ndarray
        Sample distances from the axis (m) and gaps there (m, ``>= 0``).
    contact : ndarray of bool
        Samples in contact.
    spacing : float
        Typical sample spacing near the edge (m).
    band : float
        Width of the fitting band in spacings.
    """
    r, gap, contact = (np.asarray(a).ravel() for a in (r, gap, contact))
    if not contact.any() or contact.all():
        raise ValueError("the contact radius needs samples both in and out of contact")
    open_ = ~contact & (r > r[contact].max()) & np.isfinite(gap)
    if not open_.any():
        raise ValueError("no open sample outside the contact")
    sel = open_ & (r <= r[open_].min() + band * spacing)
    if np.unique(r[sel]).size < 2:
        raise ValueError("fewer than two distinct open radii in the fitting band")
    beta, alpha = np.polyfit(r[sel], np.maximum(gap[sel], 0.0) ** (2.0 / 3.0), 1)
    if not beta > 0:
        raise ValueError("the gap does not open outward near the contact edge")
    return float(-alpha / beta)


@dataclass(frozen=True)
class PressureDifference:
    """Differences between two pressure fields, relative to the reference's peak (-).

    ``interior``: ``r < edge_fraction r_c``; ``edge``: the band from there to ``r_c``.
    """

    max_interior: float
    rms_interior: float
    max_edge: float
    rms_edge: float
    peak_reference: float


def pressure_difference(r, pressure, reference, contact_radius: float, edge_fraction: float = 0.9) -> PressureDifference:
    """Compare sampled pressures ``pressure`` (Pa) at radii ``r`` (m) with a reference
    profile ``reference(r)`` (Pa), inside a contact of radius ``contact_radius`` (m)."""
    r = np.asarray(r, float).ravel()
    p = np.asarray(pressure, float).ravel()
    ref = np.asarray(reference(r), float).ravel()
    peak = float(np.max(reference(np.linspace(0.0, contact_radius, 401))))
    inner = r < edge_fraction * contact_radius
    edge = (r >= edge_fraction * contact_radius) & (r < contact_radius)
    d = (p - ref) / peak

    def stats(mask):
        if not mask.any():
            return math.nan, math.nan
        return float(np.abs(d[mask]).max()), float(np.sqrt(np.mean(d[mask] ** 2)))

    mi, ri = stats(inner)
    me, re = stats(edge)
    return PressureDifference(mi, ri, me, re, peak)

