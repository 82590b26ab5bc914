"""The paper's route to a bonded incompressible layer's surface compliance, kept as the
reference of :func:`bem.layer.surface_compliance` (the closed form): the 6x6 system matrix
of eq. 45 (``beta_y`` corrected, see :mod:`bem.layer`) and the compliance ``T12 T22^-1``
(eq. 50) from its matrix exponential, composed over sublayers. Both are re-exported by
:mod:`bem.layer`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["system_matrix", "surface_compliance_expm"]


def system_matrix(nu_x, nu_y, G, rho_V2):
    """The 6x6 matrix ``A`` of eq. 45 (with ``beta_y`` corrected, see :mod:`bem.layer`).

    Parameters
    ----------
    nu_x, nu_y : float
        Wavenumbers (rad/m).
    G : complex
        Complex shear modulus ``G*(omega_m)`` (Pa).
    rho_V2 : float
        ``rho V^2`` (Pa): density (kg/m^3) times the squared speed (m/s)^2.

    Returns
    -------
    ndarray, shape (6, 6), complex
        ``dq/dz = A q`` for ``q = (w, u, v, sigma_z, tau_xz, tau_yz)`` (eq. 43).
    """
    G = complex(G)
    inertia = rho_V2 * nu_x**2
    bx = (4 * nu_x**2 + nu_y**2) * G - inertia
    by = (nu_x**2 + 4 * nu_y**2) * G - inertia
    bxy = 3 * nu_x * nu_y * G
    ix, iy = 1j * nu_x, 1j * nu_y
    return np.array(
        [
            [0, -ix, -iy, 0, 0, 0],
            [-ix, 0, 0, 0, 1 / G, 0],
            [-iy, 0, 0, 0, 0, 1 / G],
            [-inertia, 0, 0, 0, -ix, -iy],
            [0, bx, bxy, -ix, 0, 0],
            [0, bxy, by, -iy, 0, 0],
        ],
        dtype=complex,
    )


def surface_compliance_expm(nu_x, nu_y, G, rho_V2, H, max_kh=8.0):
    """Reference compliance ``T12 T22^-1`` (eq. 50) from the matrix exponential.

    Parameters as in :func:`bem.layer.surface_compliance` but scalars only; ``max_kh`` is the largest
    ``k h`` of one sublayer (the composition is exact, so it only guards overflow).

    Returns
    -------
    ndarray, shape (3, 3), complex
        Maps ``(sigma_z, tau_xz, tau_yz)`` (Pa) to ``(w, u, v)`` (m).
    """
    from scipy.linalg import expm  # the reference route only: its import costs the solvers 0.17 s

    k = float(np.hypot(nu_x, nu_y))
    scale = max(k, abs(np.sqrt(complex(k * k - rho_V2 * nu_x**2 / complex(G)))))
    n_sub = max(1, int(np.ceil(scale * H / max_kh)))
    T = expm(system_matrix(nu_x, nu_y, G, rho_V2) * (H / n_sub))
    T11, T12, T21, T22 = T[:3, :3], T[:3, 3:], T[3:, :3], T[3:, 3:]
    C = np.zeros((3, 3), dtype=complex)
    for _ in range(n_sub):
        C = np.linalg.solve((T21 @ C + T22).T, (T11 @ C + T12).T).T
    return C
