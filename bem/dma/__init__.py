"""DMA data to materials: master curves by time-temperature superposition and passive
Prony series fitted to them. SI units: K, rad/s, Pa, J/mol.

Workflow (see ``docs/materials.md``)::

    from bem.dma import read_dma_csv, build_master_curve

    data = read_dma_csv("examples/data/dma-pyvisco-freq-raw.csv")   # G = E / 3
    master = build_master_curve(data, T_ref=273.15 + 20, law="wlf")
    fit = master.fit_prony(tolerance=0.1)                            # PronyFit
    material = fit.material                                          # bem.materials.Prony
    table = master.table(temperature=273.15 + 40)                    # MasterCurveTable

Modules: :mod:`~bem.dma.reader` (CSV and arrays), :mod:`~bem.dma.shift` (WLF, Arrhenius,
overlap shifts), :mod:`~bem.dma.master` (the master curve), :mod:`~bem.dma.prony_fit`
(the Prony fit), :mod:`~bem.dma.plots` (figures), :mod:`~bem.dma.case` (a case file's
``[material] model = "dma"`` at its service temperature, and the check of the case's
frequency band against the data). Every error is a :class:`DMAError`, a
:class:`ValueError`.
"""

import importlib

from .errors import DMAError, DMAInputError, PronyFitError, ShiftError

# The numerical names are imported on first use (PEP 562), so that ``bem dma --help``
# answers without loading numpy and scipy; ``from bem.dma import fit_prony`` works as usual.
_EXPORTS = {
    "master": ("MasterCurve", "build_master_curve"),
    "prony_fit": ("PronyFit", "fit_prony"),
    "reader": ("DMAData", "Isotherm", "read_dma_csv"),
    "shift": ("Arrhenius", "WLF", "fit_arrhenius", "fit_wlf", "overlap_shifts"),
}
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "read_dma_csv",
    "DMAData",
    "Isotherm",
    "WLF",
    "Arrhenius",
    "fit_wlf",
    "fit_arrhenius",
    "overlap_shifts",
    "build_master_curve",
    "MasterCurve",
    "fit_prony",
    "PronyFit",
    "DMAError",
    "DMAInputError",
    "ShiftError",
    "PronyFitError",
]
