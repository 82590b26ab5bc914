"""Figures (matplotlib, PNG) and VTU export (meshio) of a :class:`ContactResult`."""

from __future__ import annotations

import numpy as np

from .result import ContactResult

__all__ = ["plot_result", "write_vtu"]


def plot_result(result: ContactResult, path) -> None:
    """Pressure profile (kPa against mm) and deformed surface u_z (um) to ``path`` (PNG).

    A bare :class:`matplotlib.figure.Figure` (no pyplot, no ``matplotlib.use``): the
    caller's backend is left as it is.
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 7))
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
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
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def write_vtu(result: ContactResult, path) -> None:
    """Vertex displacement (m) and pressure p (Pa) on the mesh, as VTU via meshio.

    Axisymmetric meshes are written in the (r, z) plane as (x, y, 0).
    """
    import meshio

    mesh = result.fields["mesh"]
    ub = result.fields["ubasis"]
    u, p = result.fields["u"], result.fields["p"]
    dim = mesh.p.shape[0]
    points = np.zeros((mesh.p.shape[1], 3))
    points[:, :dim] = mesh.p.T
    disp = np.zeros((mesh.p.shape[1], 3))
    for k in range(dim):
        disp[:, k] = u[ub.nodal_dofs[k]]
    cell_type = "triangle" if dim == 2 else "tetra"
    meshio.write(str(path), meshio.Mesh(points, [(cell_type, mesh.t.T)],
                                        point_data={"displacement": disp, "pressure": p}))
