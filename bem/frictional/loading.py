"""The loading modes: the equilibrium row each adds, and the check that friction can
carry what the mode asks for (see :mod:`bem.frictional` for the equations)."""

from __future__ import annotations

import numpy as np

from .model import LoadingUnreachable

__all__ = ["constraint", "check_reachable"]


def constraint(mode: str, arm: np.ndarray, ell: np.ndarray, radius: float):
    """Coefficients ``(c_N, c_x)`` of the loading mode's row ``c_N . N + c_x . S_x = 0``
    (``arm`` -, ``ell`` m, ``radius`` m), or ``None`` for mode ``omega``.

    ``pushed_at_top``: ``Q R = -sum l S_x`` with ``Q = sum N arm + sum S_x``;
    ``towed``: ``T = -sum l S_x = 0``; ``torque``: ``Q = 0``.
    """
    if mode == "pushed_at_top":
        return radius * arm, radius + ell
    if mode == "towed":
        return np.zeros_like(arm), ell
    if mode == "torque":
        return arm, np.ones_like(arm)
    return None


def check_reachable(mode: str, mu: float, cons, N0: np.ndarray) -> None:
    """Raise :class:`LoadingUnreachable` when even full slip (``|S| = mu N`` everywhere,
    with the frictionless normal forces ``N0``, N) cannot meet the mode's row."""
    if cons is None or mode == "towed":
        return
    need = abs(float(cons[0] @ N0))
    can = mu * float(np.abs(cons[1]) @ N0)
    if can < need:
        raise LoadingUnreachable(
            f"mode {mode!r} needs tangential forces beyond the friction limit: mu = {mu} "
            f"can give a moment/force of {can:.4g}, the rolling resistance asks for {need:.4g} "
            f"(in units of N{' m' if mode == 'pushed_at_top' else ''}); raise mu or use mode "
            "'towed' or 'omega'")
