"""Figures of a contact result (matplotlib, written to PNG).

The figures are :class:`matplotlib.figure.Figure` objects saved directly (no pyplot,
no ``matplotlib.use``): plotting never switches the backend of the caller's session
(a notebook keeps its own) and leaves no figure open in pyplot's registry.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["plot_normal_contact", "plot_frictional_contact", "plot_line_contact", "plot_line_friction"]


def _save(fig, path, dpi: int) -> Path:
    """Write ``fig`` to ``path`` (PNG), making its folder; return the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    return path


def plot_normal_contact(result, path: str | Path, title: str = "") -> Path:
    """Pressure map and its ``y = 0`` profile, side by side; returns the path."""
    from matplotlib.figure import Figure

    g = result.grid
    x_mm, y_mm = g.x * 1e3, g.y * 1e3
    p_mpa = result.pressure / 1e6
    fig = Figure(figsize=(11, 4.4), layout="constrained")
    ax0, ax1 = fig.subplots(1, 2)
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
    return _save(fig, path, 120)


def plot_frictional_contact(result, path: str | Path, title: str = "", max_arrows: int = 24) -> Path:
    """Pressure map, tangential traction vectors and stick/slip map of a
    :class:`bem.frictional.FrictionalContact`, side by side; returns the path.

    The vectors are the tractions ``(tau_xz, tau_yz)`` on the layer (Pa) at the contact
    nodes, subsampled to at most ``max_arrows`` per direction, over the contour of the
    contact; the map colours the nodes out of contact, in stick and in slip, with the slip
    velocity's direction drawn on the slip nodes.
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    g = result.grid
    x_mm, y_mm = g.x * 1e3, g.y * 1e3
    X, Y = np.meshgrid(x_mm, y_mm)
    contact = result.contact
    fig = Figure(figsize=(16, 4.8), layout="constrained")
    axes = fig.subplots(1, 3)
    ax0, ax1, ax2 = axes
    mesh = ax0.pcolormesh(x_mm, y_mm, result.pressure / 1e6, shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=ax0, label="contact pressure (MPa)")
    ax0.set_title("pressure")

    rows = np.flatnonzero(contact.any(axis=1))
    cols = np.flatnonzero(contact.any(axis=0))
    step = max(1, int(np.ceil(max(rows.size, cols.size, 1) / max_arrows)))
    sub = np.zeros_like(contact)
    sub[::step, ::step] = True
    sub &= contact
    tx, ty = result.traction_x / 1e6, result.traction_y / 1e6
    mag = np.hypot(tx, ty)
    mesh1 = ax1.pcolormesh(x_mm, y_mm, np.where(contact, mag, np.nan), shading="nearest", cmap="magma")
    fig.colorbar(mesh1, ax=ax1, label="|tangential traction| (MPa)")
    if sub.any():
        ax1.quiver(X[sub], Y[sub], tx[sub], ty[sub], color="c", angles="xy", pivot="middle")
    ax1.set_title("tangential traction on the layer")

    state = np.where(contact, np.where(result.stick, 1, 2), 0)
    ax2.pcolormesh(x_mm, y_mm, state, shading="nearest",
                   cmap=ListedColormap(["#eeeeee", "#4c72b0", "#dd8452"]), vmin=-0.5, vmax=2.5)
    slip = sub & result.slip
    if slip.any():
        ax2.quiver(X[slip], Y[slip], result.slip_x[slip], result.slip_y[slip], color="k",
                   angles="xy", pivot="middle")
    ax2.legend(handles=[Patch(color="#4c72b0", label=f"stick ({result.stick_fraction:.1%})"),
                        Patch(color="#dd8452", label="slip (arrows: slip velocity)")],
               loc="upper right", fontsize=8)
    ax2.set_title("stick / slip")
    for ax in axes:
        if contact.any():
            ax.contour(x_mm, y_mm, contact.astype(float), levels=[0.5], colors="w" if ax is ax0 else "k",
                       linewidths=0.8)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm), direction of motion ->")
        ax.set_ylabel("y (mm)")
    om = result.omega
    fig.suptitle(title or (
        f"P = {result.load:.4g} N, mu = {result.mu:g}, {result.mode}: R_r = {result.rolling_resistance:.5g} N "
        f"(friction {result.rolling_resistance_friction:.3g} N), Omega = {om:.5g} rad/s, "
        f"Q = {result.driving_force:.4g} N, T = {result.driving_torque:.4g} N m"
    ))
    return _save(fig, path, 110)


def plot_line_contact(result, path: str | Path, title: str = "") -> Path:
    """Pressure and surface deflection along ``x`` of a plane-strain line contact
    (:class:`bem.plane.LineContact`), one above the other, with the contact edges; returns
    the path."""
    from matplotlib.figure import Figure

    x_mm = result.grid.x * 1e3
    fig = Figure(figsize=(8, 6), layout="constrained")
    ax0, ax1 = fig.subplots(2, 1, sharex=True)
    ax0.plot(x_mm, result.pressure[0] / 1e6, "o-", ms=2)
    ax0.set_ylabel("pressure (MPa)")
    ax1.plot(x_mm, -result.deflection[0] * 1e6, "-", label="surface")
    ax1.plot(x_mm, (result.gap[0] - result.deflection[0]) * 1e6, "--", label="cylinder")  # s - d = h - u
    ax1.set_ylabel("height (um)")
    ax1.set_xlabel("x (mm), direction of motion ->")
    ax1.legend()
    for ax in (ax0, ax1):
        for edge in (result.trailing_edge, result.leading_edge):
            ax.axvline(edge * 1e3, color="0.6", lw=0.8)
        ax.grid(alpha=0.3)
    fig.suptitle(title or (
        f"plane strain: P = {result.load:.4g} N/m, b = {result.half_width * 1e3:.4g} mm, "
        f"R_r = {result.rolling_resistance:.5g} N/m"
    ))
    return _save(fig, path, 120)


def plot_line_friction(result, path: str | Path, title: str = "") -> Path:
    """A frictional plane-strain contact (:class:`bem.frictional.FrictionalContact` on a
    line grid) along ``x``: the pressure, the traction ``q = S_x / a`` on the layer with
    the Coulomb bounds ``+-mu p``, the stick nodes shaded; below, the slip velocity over
    ``V``. Returns the path."""
    from matplotlib.figure import Figure

    g = result.grid
    x_mm = g.x * 1e3
    p = result.pressure[0] / 1e6
    q = result.traction_x[0] / 1e6
    fig = Figure(figsize=(8, 6.4), layout="constrained")
    ax0, ax1 = fig.subplots(2, 1, sharex=True, height_ratios=(2, 1))
    ax0.plot(x_mm, p, "o-", ms=2, label="pressure p")
    ax0.plot(x_mm, q, "s-", ms=2, label="traction q on the layer")
    ax0.plot(x_mm, result.mu * p, ":", color="0.4", lw=1, label="+-mu p (Coulomb)")
    ax0.plot(x_mm, -result.mu * p, ":", color="0.4", lw=1)
    ax0.set_ylabel("MPa")
    ax1.plot(x_mm, result.slip_x[0] / result.speed, "-", color="C3")
    ax1.set_ylabel("slip velocity / V (-)")
    ax1.set_xlabel("x (mm), direction of motion ->")
    stick = result.stick[0]
    half = g.spacing * 1e3 / 2
    for ax in (ax0, ax1):
        for xs in x_mm[stick]:
            ax.axvspan(xs - half, xs + half, color="C2", alpha=0.12, lw=0)
        ax.grid(alpha=0.3)
    ax0.plot([], [], color="C2", alpha=0.3, lw=6, label="stick")
    ax0.legend(fontsize=8)
    fig.suptitle(title or (
        f"plane strain with friction (mu = {result.mu:g}, {result.mode}): P = {result.load:.4g} N/m\n"
        f"R_r = {result.rolling_resistance:.5g} N/m, of which friction {result.rolling_resistance_friction:.3g} N/m"
    ))
    return _save(fig, path, 120)
