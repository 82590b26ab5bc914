"""Figures of the DMA workflow: isotherms, master curve, shift factors.

Each function returns a :class:`matplotlib.figure.Figure` built without pyplot (no
global figure registry, no backend switch); save it with ``fig.savefig(path)``.
Frequencies are angular (rad/s), moduli shear (Pa, shown in MPa), temperatures in
degrees Celsius on the colour scale.
"""

from __future__ import annotations

from typing import Optional

import numpy as np

__all__ = ["plot_isotherms", "plot_master_curve", "plot_shift_factors"]


def _colours(temperatures):
    from matplotlib import cm, colors

    t = np.asarray(temperatures) - 273.15
    norm = colors.Normalize(vmin=t.min(), vmax=t.max() if t.max() > t.min() else t.min() + 1)
    return cm.ScalarMappable(norm=norm, cmap="coolwarm"), t


def _two_panels(title: str):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 4.2), layout="constrained")
    axes = fig.subplots(1, 2)
    for ax, name in zip(axes, ("storage modulus G' (MPa)", "loss modulus G'' (MPa)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel(name)
        ax.grid(True, which="major", alpha=0.3)
    if title:
        fig.suptitle(title)
    return fig, axes


def plot_isotherms(data, title: str = ""):
    """The measured isotherms of a :class:`~bem.dma.reader.DMAData`, ``G'`` and ``G''``
    against ``omega`` (rad/s), coloured by temperature."""
    fig, axes = _two_panels(title)
    sm, t = _colours(data.temperatures)
    for s, tc in zip(data.isotherms, t):
        for ax, g in zip(axes, (s.storage, s.loss)):
            ax.plot(s.omega, g / 1e6, "o-", ms=3, lw=0.8, color=sm.to_rgba(tc))
    for ax in axes:
        ax.set_xlabel("angular frequency omega (rad/s)")
    fig.colorbar(sm, ax=axes, label="temperature (degC)")
    return fig


def plot_master_curve(master, fit=None, title: str = ""):
    """The shifted points of a :class:`~bem.dma.master.MasterCurve` (coloured by their
    isotherm's temperature) against reduced frequency ``a_T omega`` (rad/s) at ``T_ref``,
    and the fitted Prony series if a :class:`~bem.dma.prony_fit.PronyFit` is given."""
    fig, axes = _two_panels(title)
    sm, t = _colours(master.temperatures)
    colours = sm.to_rgba(t[master.isotherm])
    for ax, g in zip(axes, (master.storage, master.loss)):
        ax.scatter(master.omega, g / 1e6, s=9, c=colours, label="shifted data")
    if fit is not None:
        w = np.geomspace(master.omega[0], master.omega[-1], 400)
        g = fit.material.modulus(w)
        n = len(fit.material.G)
        for ax, part in zip(axes, (g.real, g.imag)):
            ax.plot(w, part / 1e6, "k-", lw=1.2, label=f"Prony fit ({n} terms)")
    for ax in axes:
        ax.set_xlabel(f"reduced frequency a_T omega (rad/s) at T_ref = {master.T_ref - 273.15:.1f} degC")
        ax.legend(loc="best", fontsize=8)
    fig.colorbar(sm, ax=axes, label="isotherm temperature (degC)")
    return fig


def plot_shift_factors(master, title: str = "", temperatures: Optional[np.ndarray] = None):
    """``log10 a_T`` against temperature: each isotherm's shift and the law's curve
    (and ``log10 b_T`` in a second panel when a vertical shift was applied)."""
    from matplotlib.figure import Figure

    vertical = master.vertical is not None
    fig = Figure(figsize=(11 if vertical else 6, 4.2), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, 2 if vertical else 1))
    T = master.temperatures
    if temperatures is None:
        lo = T.min() - 5.0
        if hasattr(master.law, "singular_temperature"):
            lo = max(lo, master.law.singular_temperature + 1.0)
        temperatures = np.linspace(lo, T.max() + 5.0, 200)
    ax = axes[0]
    ax.plot(T - 273.15, master.log_aT, "o", label="isotherms")
    ax.plot(np.asarray(temperatures) - 273.15, master.log_shift(temperatures), "-", label=_law_label(master.law))
    ax.axvline(master.T_ref - 273.15, color="0.6", lw=0.8, ls="--")
    ax.set_xlabel("temperature (degC)")
    ax.set_ylabel("log10 a_T")
    ax.legend(loc="best", fontsize=8)
    ax.grid(True, alpha=0.3)
    if vertical:
        ax = axes[1]
        ax.plot(T - 273.15, master.log_bT, "o", label="isotherms")
        ax.plot(np.asarray(temperatures) - 273.15, master.log_vertical(temperatures), "-", label=master.vertical)
        ax.set_xlabel("temperature (degC)")
        ax.set_ylabel("log10 b_T")
        ax.legend(loc="best", fontsize=8)
        ax.grid(True, alpha=0.3)
    if title:
        fig.suptitle(title)
    return fig


def _law_label(law) -> str:
    if hasattr(law, "C1"):
        return f"WLF: C1 = {law.C1:.3g}, C2 = {law.C2:.3g} K"
    return f"Arrhenius: E_a = {law.activation_energy / 1e3:.4g} kJ/mol"
