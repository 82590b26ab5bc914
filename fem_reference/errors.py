"""Exceptions raised by :mod:`fem_reference`.

Every failure of a solve ends in one of these; a solve never returns a wrong
answer quietly.
"""

__all__ = [
    "FemReferenceError",
    "InputError",
    "MissingDependencyError",
    "MeshError",
    "LinearSolverError",
    "ContactNotConvergedError",
    "ContactZoneError",
]


class FemReferenceError(Exception):
    """Base class of every error raised by :mod:`fem_reference`."""


class InputError(FemReferenceError, ValueError):
    """An input value breaks its rule (the message names field, value and rule)."""


class MissingDependencyError(InputError):
    """A setting needs an optional package that is not installed (``fem.solver =
    "minres"`` needs pyamg); the message says what to install or which setting to use
    instead. An :class:`InputError`: the command line exits with status 2."""


class MeshError(FemReferenceError):
    """gmsh failed to make a mesh, or the mesh lacks a named boundary."""


class LinearSolverError(FemReferenceError):
    """The sparse factorization or the Krylov iteration failed."""


class ContactNotConvergedError(FemReferenceError):
    """The active-set iteration cycled or reached its iteration limit."""


class ContactZoneError(FemReferenceError):
    """The contact reached the edge of the refined candidate zone (or the domain).

    The candidate zone, refined and carrying the contact multiplier, must hold the
    whole contact area with room to spare: raise ``fem.contact_zone`` (m) or lower
    the load.
    """
