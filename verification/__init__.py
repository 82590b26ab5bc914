"""Verification of the layer-contact models.

The flow, one module each, imports one way (top to bottom):

- :mod:`.results`: the result types (``Level``, ``Run``, ``Gate``, ``Table``, ``CaseResult``);
- :mod:`.schema`: the typed schema of a case file, checked before any solve;
- :mod:`.analytic` and :mod:`.metrics`: analytic references (a subpackage, one module per
  reference: Hertz, the bonded layer's compliance, Jaffar's thick and thin layers,
  Hunter's rolling cylinder), comparison metrics;
- :mod:`.methods`: what is put through the cases (``bem``, ``fem``, plugins, results files);
- :mod:`.kinds`: what a case runs, its tables and figures;
- :mod:`.runner`: load and check the cases, run them;
- :mod:`.report`: the atomic report, JUnit, drift against a baseline;
- :mod:`.cli`: ``verify``.
"""

import importlib

# Imported on first use (PEP 562), so that ``verify --help`` answers without loading scipy.
_RESULTS = ("CaseResult", "Gate", "Level", "Run", "Table")


def __getattr__(name: str):
    if name in _RESULTS:
        value = getattr(importlib.import_module(".results", __name__), name)
        globals()[name] = value
        return value
    try:  # a submodule, as ``verification.analytic`` after ``import verification``
        return importlib.import_module(f".{name}", __name__)
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["analytic", "CaseResult", "Gate", "Level", "Run", "Table"]
