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

from . import analytic
from .results import CaseResult, Gate, Level, Run, Table

__all__ = ["analytic", "CaseResult", "Gate", "Level", "Run", "Table"]
