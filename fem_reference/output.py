"""Figures (matplotlib, PNG/PDF/SVG) and VTU export (meshio) of a solve's result: a
stationary :class:`~.stationary.result.ContactResult`, a plane-strain
:class:`~.rolling.plane_strain.result.CylinderRollingResult` or a 3D
:class:`~.rolling.three_d.result.SphereRollingResult`.

Figures are bare :class:`matplotlib.figure.Figure` objects (no pyplot, no
``matplotlib.use``): the caller's backend is left as it is.
"""

from __future__ import annotations

import numpy as np

from .rolling.result import RollingResult
from .rolling.three_d.result import SphereRollingResult
from .stationary.result import ContactResult

__all__ = ["plot_result", "write_vtu"]


def plot_result(result, path) -> None:
    """Draw ``result`` to ``path``: the contact pressure (kPa) and the deformed surface
    u_z (um) against r or x (mm); for a rolling sphere also the map of the contact
    pressure over the candidate disk (both halves: the solution is even in y), with the
    pressure and the surface on the line y = 0 below it."""
    from matplotlib.figure import Figure

    if isinstance(result, SphereRollingResult):
        fig = Figure(figsize=(7, 10))
        ax0, ax1, ax2 = fig.subplots(3, 1, gridspec_kw=dict(height_ratios=(1.3, 1, 1)))
        _pressure_map(fig, ax0, result)
    else:
        fig = Figure(figsize=(7, 7))
        ax1, ax2 = fig.subplots(2, 1, sharex=True)
    if isinstance(result, RollingResult):
        _rolling_line(ax1, ax2, result)
    else:
        _stationary(ax1, ax2, result)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def _stationary(ax1, ax2, result: ContactResult) -> None:
    style = dict(marker="o", ms=2, lw=0.8) if result.mesh.model == "axisymmetric" \
        else dict(marker=".", ms=2, lw=0)
    order = np.argsort(result.radius)
    ax1.plot(result.radius[order] * 1e3, result.pressure[order] / 1e3, **style)
    ax1.axvline(result.contact_radius * 1e3, color="k", ls="--", lw=0.8,
                label=f"contact radius {result.contact_radius * 1e3:.4f} mm")
    ax1.set_ylabel("contact pressure -sigma_zz (kPa)")
    ax1.set_title(f"{result.mesh.model}: P = {result.load:.4g} N, d = "
                  f"{result.indentation * 1e6:.4g} um, p_max = {result.peak_pressure / 1e3:.4g} kPa")
    ax1.legend()
    ax2.plot(result.surface_radius * 1e3, result.surface_uz * 1e6, lw=1)
    ax2.set_xlabel("r (mm)")
    ax2.set_ylabel("surface displacement u_z (um)")
    ax2.set_xlim(0, min(result.surface_radius.max(), 3 * result.contact_radius) * 1e3)


def _rolling_line(ax1, ax2, result: RollingResult) -> None:
    """Pressure and surface u_z along x (on y = 0 for the sphere), with the fitted edges."""
    sphere = isinstance(result, SphereRollingResult)
    unit = "N" if sphere else "N/m"
    on = " on y = 0" if sphere else ""
    ax1.plot(result.pressure_x * 1e3, result.pressure / 1e3, marker="o", ms=2, lw=0.8)
    for edge, name in ((result.trailing_edge, "trailing"), (result.leading_edge, "leading")):
        ax1.axvline(edge * 1e3, color="k", ls="--", lw=0.8,
                    label=f"{name} edge {edge * 1e3:.4f} mm")
    ax1.set_ylabel(f"contact pressure{on} (kPa)")
    ax1.set_title(f"{result.mesh.model} rolling at V = {result.speed:g} m/s: P = {result.load:.4g} {unit}, "
                  f"R_r = {result.rolling_resistance:.4g} {unit}, d = {result.indentation * 1e6:.4g} um",
                  fontsize=9)
    ax1.legend(fontsize=8)
    ax2.plot(result.surface_x * 1e3, result.surface_uz * 1e6, lw=1)
    ax2.set_xlabel("x (mm; the indenter moves towards +x)")
    ax2.set_ylabel(f"surface displacement u_z{on} (um)")
    reach = 3.0 * max(result.leading_edge, -result.trailing_edge)
    ax2.set_xlim(-reach * 1e3, reach * 1e3)
    ax1.set_xlim(-reach * 1e3, reach * 1e3)


def _pressure_map(fig, ax, result: SphereRollingResult) -> None:
    """Filled contours of the nodal contact pressure (kPa) over the candidate disk."""
    from matplotlib.tri import Triangulation

    xy, lam = result.zone_xy, result.zone_pressure
    off = xy[:, 1] > 1e-9 * result.mesh.contact_zone  # the nodes off y = 0, mirrored
    x = np.concatenate([xy[:, 0], xy[off, 0]]) * 1e3
    y = np.concatenate([xy[:, 1], -xy[off, 1]]) * 1e3
    p = np.concatenate([lam, lam[off]]) / 1e3
    levels = np.linspace(0.0, max(p.max(), 1e-12), 21)
    cs = ax.tricontourf(Triangulation(x, y), p, levels=levels, cmap="viridis")
    fig.colorbar(cs, ax=ax, label="contact pressure (kPa)")
    ax.plot([result.trailing_edge * 1e3, result.leading_edge * 1e3], [0.0, 0.0], "w|-", lw=0.8,
            label="fitted edges on y = 0")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("contact pressure over the candidate disk (the half y >= 0 solved, mirrored)",
                 fontsize=9)
    ax.legend(fontsize=8, loc="upper right")


def write_vtu(result, path) -> None:
    """The mesh with the vertex displacement (m) and the hydrostatic pressure p (Pa) as
    VTU via meshio; for a rolling result also, per Maxwell branch i (from 1), the
    viscous-strain components at the vertices as ``viscous_strain_<i>`` (-): (a, c) in
    plane strain (eps_v = [[a, c], [c, -a]] in the x-z plane), (w_0 .. w_4) in 3D
    (eps_v = [[w_0, w_2, w_3], [w_2, w_1, w_4], [w_3, w_4, -w_0 - w_1]]).

    Two-dimensional meshes (the axisymmetric (r, z) and plane-strain (x, z) sections)
    are written in their plane as (x, y, 0); the 3D rolling mesh is the half layer
    y >= 0 that was solved.
    """
    import meshio

    mesh = result.fields["mesh"]
    ub = result.fields["ubasis"]
    u, p = result.fields["u"], result.fields["p"]
    dim, n = mesh.p.shape
    points = np.zeros((n, 3))
    points[:, :dim] = mesh.p.T
    disp = np.zeros((n, 3))
    for k in range(dim):
        disp[:, k] = u[ub.nodal_dofs[k]]
    data = {"displacement": disp, "pressure": p[result.fields["pbasis"].nodal_dofs[0]]}
    wb = result.fields.get("wbasis")
    for i, comps in enumerate(result.fields.get("w") or (), start=1):
        data[f"viscous_strain_{i}"] = np.column_stack([c[wb.nodal_dofs[0]] for c in comps])
    cell_type = "triangle" if dim == 2 else "tetra"
    meshio.write(str(path), meshio.Mesh(points, [(cell_type, mesh.t.T)], point_data=data))
