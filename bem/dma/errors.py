"""Errors of the DMA workflow; each is a :class:`ValueError` whose message names the
file, row or key, the value and the rule it breaks."""

from __future__ import annotations

__all__ = ["DMAError", "DMAInputError", "ShiftError", "PronyFitError"]


class DMAError(ValueError):
    """Base class of every error raised by :mod:`bem.dma`."""


class DMAInputError(DMAError):
    """A DMA file or array breaks a rule: missing column, bad unit, non-monotonic
    frequencies within an isotherm, negative or non-finite moduli."""


class ShiftError(DMAError):
    """Time-temperature shifting cannot be done as asked: a single isotherm, isotherms
    that do not overlap, a temperature at or below the WLF singularity ``T_ref - C2``,
    or invalid shift-law constants."""


class PronyFitError(DMAError):
    """A Prony series fit cannot reach the requested tolerance, or its relaxed modulus
    comes out zero (the data show no rubbery plateau)."""
