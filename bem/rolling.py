"""Former home of the frictional solver, now the package :mod:`bem.frictional`; these
names stay importable from here."""

from .frictional import RollingOperators, solve_friction, solve_rolling

__all__ = ["RollingOperators", "solve_rolling", "solve_friction"]
