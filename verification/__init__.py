"""Verification of the layer-contact models: analytic references (:mod:`verification.analytic`).

The harness that runs ``bem`` and ``fem_reference`` on the same cases and compares them
with these references lives here as well (added later).
"""

from . import analytic

__all__ = ["analytic"]
