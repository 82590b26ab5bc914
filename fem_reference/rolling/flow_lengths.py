"""The flow lengths of a truncated rolling layer, both models: the material enters at x =
upstream undeformed and relaxed, and leaves at x = -downstream after it has relaxed.

The influence of the clamped ends decays over about the thickness H (and the contact
size), and behind the indenter the material recovers over the creep length V t_r, with
t_r the longest creep time (m).
"""

from __future__ import annotations

from ..errors import InputError
from ..materials import PronyMaterial, as_prony
from ..problem import ContactProblem

__all__ = ["check_flow_lengths", "creep_length"]


def creep_length(problem: ContactProblem) -> float:
    """V t_r (m): the distance the material travels in its longest creep time (0 for an
    elastic layer or at rest)."""
    mat = as_prony(problem.material)
    if not isinstance(mat, PronyMaterial):
        return 0.0
    return problem.loading.speed * mat.retardation_time


def check_flow_lengths(problem: ContactProblem, zone: float, near: float, upstream: float,
                       downstream: float, size: str, defaults: str) -> None:
    """Raise :class:`InputError` unless the material enters undeformed and relaxed and
    relaxes before it leaves (both rolling models): upstream >= Z + 2 near and
    downstream >= Z + 2 near + 3 V t_r, with ``near`` = max(H, ``size``) (m), ``size`` the
    name of the contact-size estimate in the message, ``defaults`` "(up, down)" the
    model's default multipliers "a H, b size[, c V t_r]" as text."""
    lv = creep_length(problem)
    up_default, down_default = defaults
    need_up = zone + 2.0 * near
    if upstream < need_up:
        raise InputError(
            f"fem.upstream = {upstream:.4g} m is too short: the material must enter undeformed and "
            f"relaxed, which needs the inflow at least contact_zone + 2 max(H, {size}) = {need_up:.4g} m "
            f"ahead of the indenter; raise fem.upstream (default contact_zone + max({up_default}))")
    need_down = need_up + 3.0 * lv
    if downstream < need_down:
        raise InputError(
            f"fem.downstream = {downstream:.4g} m is too short for the material to relax before it "
            f"leaves: it needs at least contact_zone + 2 max(H, {size}) + 3 V t_r = {need_down:.4g} m "
            f"(V t_r = {lv:.4g} m, the creep length at {problem.loading.speed:g} m/s); raise "
            f"fem.downstream (default contact_zone + max({down_default}))")
