"""Figures of a contact result (matplotlib, written to PNG)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["plot_normal_contact"]


def plot_normal_contact(result, path: str | Path, title: str = "") -> Path:
    """Pressure map and its ``y = 0`` profile, side by side; returns the path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    g = result.grid
    x_mm, y_mm = g.x * 1e3, g.y * 1e3
    p_mpa = result.pressure / 1e6
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True)
    mesh = ax0.pcolormesh(x_mm, y_mm, p_mpa, shading="nearest", cmap="viridis")
    if result.contact.any():
        ax0.contour(x_mm, y_mm, result.contact.astype(float), levels=[0.5], colors="w", linewidths=0.8)
    ax0.set_aspect("equal")
    ax0.set_xlabel("x (mm), direction of motion ->")
    ax0.set_ylabel("y (mm)")
    fig.colorbar(mesh, ax=ax0, label="contact pressure (MPa)")
    row = np.argmin(np.abs(g.y))
    ax1.plot(x_mm, p_mpa[row], "o-", ms=3)
    ax1.set_xlabel("x (mm) at y = 0")
    ax1.set_ylabel("pressure (MPa)")
    ax1.grid(alpha=0.3)
    fig.suptitle(title or (
        f"P = {result.load:.4g} N, d = {result.indentation * 1e3:.4g} mm, "
        f"r_c = {result.contact_radius * 1e3:.4g} mm, R_r = {result.rolling_resistance:.5g} N"
    ))
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
