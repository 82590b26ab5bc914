"""Case kinds: what a case runs. Each kind is a module with

- ``SECTIONS``: the case-file sections it reads besides the header, ``[problem]`` and
  ``[[gates]]`` (name -> :class:`verification.schema.Field` table, or a checker);
- ``check(case, path, methods)``: every kind-specific rule, raising
  :class:`verification.schema.CaseError` before anything is solved;
- ``run(case, context) -> CaseResult``: the solves and the gates;
- ``tables(result)`` and ``figures(result, folder)``: what the report shows.

The report knows kinds only through these four names.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from . import (friction_carter, friction_layer, friction_sphere, paper_sweeps, roller_3d, rolling_2d, rolling_3d,
               rolling_limits, stationary, sweep, table1)

__all__ = ["KINDS", "Context"]

KINDS = {
    "friction-carter": friction_carter,
    "friction-layer": friction_layer,
    "friction-sphere": friction_sphere,
    "stationary": stationary,
    "sweep": sweep,
    "table1": table1,
    "rolling-limits": rolling_limits,
    "rolling-2d": rolling_2d,
    "rolling-3d": rolling_3d,
    "roller-3d": roller_3d,
    "paper-sweeps": paper_sweeps,
}


@dataclass
class Context:
    """What a kind's ``run`` gets besides the case: progress lines, the quick flag, the
    methods by name, and the Dask client a kind that runs on Dask itself (``USES_DASK``)
    submits to (``None``: it starts its own local cluster)."""

    progress: Callable[[str], None] = print
    quick: bool = False
    methods: dict = field(default_factory=dict)
    client: object = None
