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
(the Prony fit), :mod:`~bem.dma.plots` (figures). Every error is a :class:`DMAError`, a
:class:`ValueError`.
"""

from .errors import DMAError, DMAInputError, PronyFitError, ShiftError
from .master import MasterCurve, build_master_curve
from .prony_fit import PronyFit, fit_prony
from .reader import DMAData, Isotherm, read_dma_csv
from .shift import Arrhenius, WLF, fit_arrhenius, fit_wlf, overlap_shifts

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
