"""Fit a passive Prony series (generalized Maxwell solid) to a master curve.

The model ``G*(w) = G_inf + sum_i G_i (i w tau_i) / (1 + i w tau_i)`` is linear in the
moduli once the relaxation times are fixed. The times are log-spaced over the data's
range, ``1 / omega_max`` to ``1 / omega_min``, ``terms_per_decade`` per decade, and the
moduli ``G_inf, G_i >= 0`` solve one non-negative least-squares problem
(:func:`scipy.optimize.nnls`) on ``G'`` and ``G''`` jointly, each row divided by its
data value so the fit minimizes relative errors. Terms whose modulus comes out 0 are
dropped (:class:`bem.materials.Prony` takes positive moduli only); the others are then
polished by nonlinear least squares with moduli and times free, in logarithms (so the
moduli stay > 0): on a grid a single Maxwell branch between two grid times is only
approximated (max G'' error 9 % at 3 terms per decade for the paper's three-parameter
solid), polished it is recovered to round-off. Non-negative moduli make the material
passive by construction (``G''(omega) >= 0`` at every ``omega > 0``), and a Prony series
satisfies the Kramers-Kronig relations exactly.

Why not pyvisco (NREL, BSD-3-Clause, the well-kept package for this job): its frequency
fit is by default a collocation at one relaxation time per decade with fixed heuristic
"stiffness" matrices (Kraus and Niederwald 2017), not a least-squares fit over every
data point, and its optional least-squares mode weighs absolute errors scaled by the
glassy modulus, so the rubbery end's relative error is left free; its
API passes pandas DataFrames with ad-hoc attributes, prints its progress and draws on
pyplot's global state; and it requires Jupyter, voila, ipywidgets and spreadsheet
readers. The fit here is about 80 lines on SciPy, which the package already depends
on, fits every data point, reports its errors and returns the project's own
:class:`bem.materials.Prony`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np
from scipy.optimize import least_squares, nnls

from ..materials import Prony
from .errors import PronyFitError
from .reader import check_points

__all__ = ["PronyFit", "fit_prony"]


@dataclass(frozen=True)
class PronyFit:
    """A Prony series fitted to ``(omega, G', G'')`` data, with its errors.

    Attributes
    ----------
    material : bem.materials.Prony
        The fitted series (Pa, s): use it as a layer's material.
    max_error_storage, rms_error_storage : float
        Max and RMS of ``|G'_fit - G'| / G'`` over the data (dimensionless).
    max_error_loss, rms_error_loss : float
        Max and RMS of ``|G''_fit - G''| / G''`` over the data points with ``G'' > 0``
        (dimensionless; 0 if there are none).
    omega_min, omega_max : float
        Frequency range of the data (rad/s); outside it the series is an extrapolation.
    """

    material: Prony
    max_error_storage: float
    rms_error_storage: float
    max_error_loss: float
    rms_error_loss: float
    omega_min: float
    omega_max: float

    @property
    def max_error(self) -> float:
        """The larger of the two max relative errors (dimensionless)."""
        return max(self.max_error_storage, self.max_error_loss)


def _errors(fit: np.ndarray, data: np.ndarray) -> tuple[float, float]:
    m = data > 0
    if not m.any():
        return 0.0, 0.0
    e = np.abs(fit[m] - data[m]) / data[m]
    return float(e.max()), float(np.sqrt(np.mean(e * e)))


def _refine(w, gs, gl, wl, g_inf, G, tau):
    """Polish the non-zero terms: moduli and times free, in logarithms (so > 0).

    Nonlinear least squares (:func:`scipy.optimize.least_squares`) of the same relative
    residuals from the NNLS solution; each ``log10 tau_i`` stays within a decade of the
    data's range. Returns the polished ``(G_inf, G, tau)``, or the start if it is worse.
    """
    n = len(G)
    lo_t, hi_t = np.log(1.0 / w[-1]) - np.log(10.0), np.log(1.0 / w[0]) + np.log(10.0)

    def parts(p):
        x = w[:, None] * np.exp(p[1 + n:])[None, :]
        Gi = np.exp(p[1:1 + n])
        d = 1 + x * x
        return x, Gi, d

    def residual(p):
        x, Gi, d = parts(p)
        return np.concatenate([(np.exp(p[0]) + (x * x / d) @ Gi) / gs - 1.0, ((x / d) @ Gi - gl) / wl])

    def jacobian(p):  # derivatives in log G_inf, log G_i, log tau_i (d/d log tau = x d/dx)
        x, Gi, d = parts(p)
        J_s = np.hstack([np.full((len(w), 1), np.exp(p[0])), Gi * x * x / d, Gi * 2 * x * x / d ** 2]) / gs[:, None]
        J_l = np.hstack([np.zeros((len(w), 1)), Gi * x / d, Gi * x * (1 - x * x) / d ** 2]) / wl[:, None]
        return np.vstack([J_s, J_l])

    p0 = np.concatenate([[np.log(g_inf)], np.log(G), np.clip(np.log(tau), lo_t + 1e-9, hi_t - 1e-9)])
    lower = np.concatenate([np.full(1 + n, -np.inf), np.full(n, lo_t)])
    upper = np.concatenate([np.full(1 + n, np.inf), np.full(n, hi_t)])
    res = least_squares(residual, p0, jac=jacobian, bounds=(lower, upper), max_nfev=200)
    if np.sum(res.fun ** 2) >= np.sum(residual(p0) ** 2):
        return g_inf, G, tau
    return float(np.exp(res.x[0])), np.exp(res.x[1:1 + n]), np.exp(res.x[1 + n:])


def fit_prony(omega, storage, loss, *, terms_per_decade: float = 3.0,
              tolerance: Optional[float] = None, refine: bool = True,
              loss_weight: float = 1.0) -> PronyFit:
    """Fit a passive :class:`bem.materials.Prony` to a master curve.

    Parameters
    ----------
    omega : array of float
        Angular frequencies (rad/s), > 0, any order.
    storage, loss : array of float
        Shear storage ``G'`` (Pa, > 0) and loss ``G''`` (Pa, >= 0) moduli at ``omega``.
    terms_per_decade : float
        Relaxation times per decade of the data's frequency range (> 0).
    tolerance : float, optional
        If given, the largest relative error of ``G'`` or ``G''`` that is accepted.
    loss_weight : float
        Weight (> 0) of the ``G''`` residuals against the ``G'`` ones; below 1 where the
        loss data are noisier than the storage data.
    refine : bool
        Polish the moduli and relaxation times of the non-zero NNLS terms by nonlinear
        least squares (moduli kept > 0, so the result stays passive).

    Returns
    -------
    PronyFit

    Raises
    ------
    PronyFitError
        The max relative error exceeds ``tolerance`` (the message gives both and what
        to try), or the relaxed modulus ``G_inf`` comes out 0 (no rubbery plateau in
        the data).
    """
    w, gs, gl = (np.asarray(a, dtype=float).ravel() for a in (omega, storage, loss))
    order = np.argsort(w)
    w, gs, gl = w[order], gs[order], gl[order]
    check_points(w, gs, gl, lambda i: f"master curve point {i}", monotonic=False)
    if not (math.isfinite(terms_per_decade) and terms_per_decade > 0):
        raise PronyFitError(f"terms_per_decade must be > 0, got {terms_per_decade!r}")
    if not (math.isfinite(loss_weight) and loss_weight > 0):
        raise PronyFitError(f"loss_weight must be > 0, got {loss_weight!r}")
    decades = math.log10(w[-1] / w[0])
    n = max(int(math.ceil(decades * terms_per_decade)) + 1, 1)
    tau = np.geomspace(1.0 / w[-1], 1.0 / w[0], n)
    x = w[:, None] * tau[None, :]
    scale = float(np.median(np.hypot(gs, gl)))
    # rows: G' / G'_data = 1 and G'' / G''_data = 1; columns: G_inf, G_1..G_n (units of scale)
    wl = np.where(gl > 0, gl, np.hypot(gs, gl)) / loss_weight
    A_s = np.hstack([np.ones((len(w), 1)), x * x / (1 + x * x)]) / gs[:, None]
    A_l = np.hstack([np.zeros((len(w), 1)), x / (1 + x * x)]) / wl[:, None]
    b = np.concatenate([np.ones(len(w)), gl / wl])
    coef, _ = nnls(np.vstack([A_s, A_l]) * scale, b, maxiter=50 * (n + 1))
    coef = coef * scale
    if coef[0] <= 0:
        raise PronyFitError(
            "the fitted relaxed modulus G_inf is 0: the master curve shows no rubbery plateau "
            f"down to {w[0]:.3g} rad/s; add data at lower reduced frequency"
        )
    keep = coef[1:] > 0
    g_inf, G, tau = float(coef[0]), coef[1:][keep], tau[keep]
    if refine and len(G):
        g_inf, G, tau = _refine(w, gs, gl, wl, g_inf, G, tau)
        keep = G > 1e-12 * (g_inf + G.sum())  # a term polished down to nothing
        G, tau = G[keep], tau[keep]
    order = np.argsort(tau)
    material = Prony(g_inf, tuple(G[order].tolist()), tuple(tau[order].tolist()))
    g = material.modulus(w)
    es, rs = _errors(g.real, gs)
    el, rl = _errors(g.imag, gl)
    result = PronyFit(material, es, rs, el, rl, float(w[0]), float(w[-1]))
    if tolerance is not None and result.max_error > tolerance:
        raise PronyFitError(
            f"the Prony fit cannot reach tolerance = {tolerance:g}: max relative error of G' is "
            f"{es:.3g} and of G'' is {el:.3g} with {terms_per_decade:g} terms per decade over "
            f"{w[0]:.3g}-{w[-1]:.3g} rad/s; try more terms per decade, or smoother (less noisy) data"
        )
    return result
