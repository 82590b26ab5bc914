"""Mode sums over ``n`` of the half-space's real symbols (``1 / k``, ``nu_x^a / k^p``).

Without inertia a deep mode's compliance is ``1 / G(omega_m)`` times a real function of
``nu`` built from ``1 / k`` and ``nu_x^a nu_y^b / k^3`` (:func:`halfspace_symbols`);
with a little inertia every block is a short series in ``eps = rho V^2 nu_x^2 / (G k^2)``
(:data:`INERTIA_SERIES`) of real arrays ``nu_x^a nu_y^b / k^p`` times factors of the row
``m``. So every deep-mode kernel is a sum over ``m`` of row factors times the sums over
``n`` of a few real arrays, weighted by functions of ``n`` alone, and no complex symbol of
every mode is formed. Those arrays separate: ``k^-p`` is a sum of about 170 Gaussians
``exp(-alpha k^2) = exp(-alpha nu_x^2) exp(-alpha nu_y^2)`` to rounding
(:func:`inverse_power_gaussians`), so the sums over ``n`` are taken once, of the
Gaussians (:func:`column_sums`: matrix products, DCT-I / DST-I on a lattice, or chirp-z),
and every row's are a product with its own Gaussians (:func:`gaussian_sums`): ``O(N_x Q
K)`` for ``Q`` Gaussians and ``K`` offsets instead of ``O(N_x N_y K)``. On a square grid
with one real modulus :func:`square_sums` separates the sums over ``m`` as well.
(``docs/derivations.md``, section 14.)
"""

from __future__ import annotations

import math

import numpy as np

from .mode_sums import cos_sums, lattice_half, over_n, sin_sums, trig_table

__all__ = ["HALFSPACE_KH", "INERTIA_SERIES", "halfspace_symbols", "inverse_power_gaussians", "GAUSSIAN_STEP",
           "gaussian_sums",
           "series_arrays", "series_factor", "column_sums", "square_sums"]

#: ``k H`` beyond which a mode does not see the base: the layer's compliance is the
#: half-space's to ``exp(-k H) = 9e-27`` (:mod:`bem.layer` switches at 50)
HALFSPACE_KH = 60.0


def halfspace_symbols(nu_x: np.ndarray, nu_y: np.ndarray) -> dict:
    """``G C_PQ`` (m) of an incompressible half-space without inertia, on the outer grid
    ``nu_x[:, None], nu_y[None, :]`` (rad/m): real, ``0`` at ``k = 0``.

    With ``q = k`` the Rayleigh function is ``4 k^3``, so ``G c_zz = G c_LL = 1 / (2 k)``,
    ``G c_TT = 1 / k`` and the normal-tangential entries vanish: ``ww = 1 / (2 k)``,
    ``uu = (nu_x^2 / 2 + nu_y^2) / k^3``, ``vv = (nu_x^2 + nu_y^2 / 2) / k^3 = 3 ww - uu``,
    ``uv = vu = -nu_x nu_y / (2 k^3)`` (:func:`bem.layer.compliance_blocks` at ``k H > 50``).
    Returned: ``ww, uu, uv``.
    """
    nx, ny = np.asarray(nu_x, float)[:, None], np.asarray(nu_y, float)[None, :]
    k = np.hypot(nx, ny)
    with np.errstate(divide="ignore"):
        inv_k = np.where(k > 0, 1.0 / k, 0.0)
    inv_k3 = inv_k * inv_k * inv_k
    return {"ww": 0.5 * inv_k, "uu": (0.5 * nx * nx + ny * ny) * inv_k3, "uv": (-0.5 * nx) * ny * inv_k3}


def _powers_of_k2(k2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``1 / k`` and ``1 / k^3`` of ``k2 = k^2`` (1/m^2; overwritten), 0 at ``k = 0``."""
    zero = k2 == 0
    k2[zero] = 1.0
    inv_k = np.sqrt(k2)
    np.divide(1.0, inv_k, out=inv_k)
    inv_k[zero] = 0.0
    inv_k3 = np.divide(inv_k, k2, out=k2)
    return inv_k, inv_k3


#: ``G C_PQ`` of a deep mode with a little inertia, ``eps = c nu_x^2 / k^2``, ``c = rho V^2 /
#: G(omega_m)`` (-): block -> terms ``(a, p, odd, (c0, c1, ...))``, each the real array ``X^a /
#: k^p`` (times ``Y`` when ``odd``; ``X = nu_x``, ``Y = nu_y``, all of the scale of ``1 / k``)
#: times ``c0 + c1 c + c2 c^2 + ...``. The blocks of order one to first order in ``eps``
#: (the next term below ``3/8 eps^2`` of ``1 / k``: 3.7e-13 at ``eps = 1e-6``); the
#: normal-tangential ones, ``i nu_x (eps / 8 + 5 eps^2 / 32 + 11 eps^3 / 64) / k^2`` (or
#: ``nu_y``), to third, the next term ``95/512 eps^4`` (``1.5 eps^3`` of the block's own
#: size) (``docs/derivations.md``, "Deep modes with a little inertia").
INERTIA_SERIES = {
    "ww": ((0, 1, False, (0.5,)), (2, 3, False, (0, 0.375))),
    "uu": ((0, 1, False, (1,)), (2, 3, False, (-0.5, 0.5)), (4, 5, False, (0, -0.375))),
    "vv": ((0, 1, False, (0.5,)), (2, 3, False, (0.5, 0.125)), (4, 5, False, (0, 0.375))),
    "uv": ((1, 3, True, (-0.5,)), (3, 5, True, (0, -0.375))),
    "wu": ((3, 4, False, (0, 0.125j)), (5, 6, False, (0, 0, 0.15625j)), (7, 8, False, (0, 0, 0, 0.171875j))),
    "wv": ((2, 4, True, (0, 0.125j)), (4, 6, True, (0, 0, 0.15625j)), (6, 8, True, (0, 0, 0, 0.171875j))),
}
INERTIA_SERIES["vu"] = INERTIA_SERIES["uv"]
INERTIA_SERIES["uw"] = tuple((a, p, o, tuple(-x for x in cs)) for a, p, o, cs in INERTIA_SERIES["wu"])
INERTIA_SERIES["vw"] = tuple((a, p, o, tuple(-x for x in cs)) for a, p, o, cs in INERTIA_SERIES["wv"])


def series_arrays(nu_x: np.ndarray, nu_y: np.ndarray, keys) -> np.ndarray:
    """The real arrays ``X^a / k^p`` (m^(p - a)) of the :data:`INERTIA_SERIES` terms' ``keys``
    ``(a, p, odd)`` on the outer grid ``nu_x[:, None], nu_y[None, :]`` (rad/m), stacked in the
    order of ``keys``: ``(len(keys), rows, columns)``; 0 at ``k = 0`` (the factor ``Y`` of the
    odd terms goes into the sums' weight). Every ``p - a`` is 1 or 2: ``(X / k)^a / k^(p -
    a)``, no power of ``k`` that could overflow."""
    inv_k, inv_k2 = _powers_of_k2(np.add.outer(nu_x * nu_x, nu_y * nu_y))  # 1 / k, 1 / k^3
    np.multiply(inv_k, inv_k, out=inv_k2)  # 1 / k^2
    out = np.empty((len(keys), *inv_k.shape))
    cos = {1: nu_x[:, None] * inv_k}  # X / k
    for i, (a, p, _) in enumerate(keys):
        tail = inv_k if p - a == 1 else inv_k2
        for j in range(2, a + 1):
            if j not in cos:
                cos[j] = cos[j - 1] * cos[1]
        if a:
            np.multiply(cos[a], tail, out=out[i])
        else:
            out[i] = tail
    return out


def series_factor(coefs, G: np.ndarray, rho_V2: float) -> np.ndarray:
    """``(c0 + c1 c + c2 c^2 + ...) / G`` (1/Pa, complex) of the rows' moduli ``G`` (Pa), ``c =
    rho V^2 / G``, ``rho V^2 = rho_V2`` (Pa)."""
    c = rho_V2 / np.asarray(G, complex)
    acc = np.zeros_like(c)
    for a in reversed(coefs):
        acc = acc * c + a
    return acc / G


def column_sums(E: np.ndarray, odd: bool, weights, nu_y: np.ndarray, ratio: float, count: int,
                chirp: bool) -> list:
    """``sum_{|n| <= N_t} E(r, |n|) w(n) exp(2 pi i ratio n dy)``, ``0 <= dy < count``, of the
    real rows ``E`` (columns ``n >= 0``) for every ``w`` of ``weights`` (functions of ``n``,
    1/m), with the odd extension ``sign(n) Y`` for ``odd`` (``Y = nu_y``, rad/m): a real
    ``(rows, count)`` table for each weight (``i`` times it for ``odd``; even, or odd, in
    ``dy``). By one matrix product (the weights side by side in the table), DCT-I / DST-I on
    a lattice, or chirp-z."""
    N = E.shape[1]
    ws = [w * nu_y if odd else w for w in weights]
    if not chirp:
        T = trig_table(ratio, N, count, odd)
        h = E @ np.concatenate([w[:, None] * T for w in ws], axis=1)
        return [h[:, i * count : (i + 1) * count] for i in range(len(ws))]
    Q = lattice_half(ratio, N, count)
    if Q:
        return [sin_sums(E * w, Q, count) if odd else cos_sums(E, Q, count, weight=w) for w in ws]
    return [(h.imag if odd else h.real) for h in (over_n(E, odd, ratio, count, True, w)[:, count - 1 :] for w in ws)]


def gaussian_sums(nu_x: np.ndarray, nu_y: np.ndarray, weights, ratio: float, count: int, chirp: bool, keys):
    """The sums over ``n`` of the deep modes' real arrays: a function of a slice of the rows
    ``nu_x`` (rad/m, ``m >= 0``) that returns, for every ``key = (a, p, odd)`` and every
    ``w`` of ``weights`` (functions of ``n``, 1/m), ``sum_{|n| <= N_t} X^a / k^p w(n)
    exp(2 pi i ratio n dy)`` (``sign(n) Y`` more for ``odd``; 0 at ``k = 0``), ``0 <= dy <
    count``: real ``(rows, count)`` under ``(a, p, odd, index of w)``, ``i`` times them for
    the odd ones.

    With ``k^-p = sum_q c_q exp(-alpha_q X^2) exp(-alpha_q Y^2)``
    (:func:`inverse_power_gaussians`) a row's sum is ``X^a sum_q c_q exp(-alpha_q X^2)
    T_q(dy)``, ``T_q`` the sums over ``n`` of ``exp(-alpha_q Y^2)`` (:func:`column_sums`, once
    for all rows): a product ``(rows x Q) (Q x count)`` for every power, parity and weight,
    ``O(N_x Q count)`` instead of ``O(N_x N_y count)``, and no array over every mode. The
    Gaussians' value at ``k = 0`` (``sum c_q``, for ``a = 0``) leaves the row ``m = 0``."""
    keys = list(keys)
    nw = len(weights)
    alpha, c = inverse_power_gaussians(min(nu_x[1], nu_y[1]), math.hypot(nu_x[-1], nu_y[-1]),
                                       sorted({p for _, p, _ in keys}))
    E = np.multiply.outer(-alpha, nu_y * nu_y)
    np.exp(E, out=E)
    T = {odd: column_sums(E, odd, weights, nu_y, ratio, count, chirp) for odd in {odd for *_, odd in keys}}
    combos = sorted({(p, odd) for _, p, odd in keys})
    place = {combo: j * count for j, combo in enumerate(combos)}
    # a product for each weight: a kernel's sums do not depend on whether power tables are
    # asked as well (the same numbers, bit for bit)
    stacks = [np.concatenate([c[p][:, None] * T[odd][ik] for p, odd in combos], axis=1) for ik in range(nw)]

    def rows(s: slice) -> dict:
        X = nu_x[s]
        R = np.multiply.outer(X * X, -alpha)  # the rows' Gaussians
        np.exp(R, out=R)
        H = [R @ stack for stack in stacks]
        out = {}
        for a, p, odd in keys:
            for ik in range(nw):
                j = place[p, odd]
                h = X[:, None] ** a * H[ik][:, j : j + count] if a else H[ik][:, j : j + count].copy()
                if not a and not odd and X.size and X[0] == 0:
                    h[0] -= c[p].sum() * weights[ik][0]
                out[a, p, odd, ik] = h
        return out

    return rows


def _mirror(h: np.ndarray, sign: float) -> np.ndarray:
    """``(rows, 2 count - 1)`` over ``dy = -(count - 1) .. count - 1`` from ``dy >= 0``, even
    (``sign = 1``) or odd (-1) in ``dy``."""
    return np.concatenate([sign * h[:, :0:-1], h], axis=1)


def inverse_power_gaussians(k_min: float, k_max: float, powers=(1, 3)) -> tuple[np.ndarray, dict]:
    """Exponents ``alpha`` (m^2), shared, and for each ``p > 0`` of ``powers`` weights ``c[p]``
    (m^p) with ``k^-p = sum_q c[p]_q exp(-alpha_q k^2)`` to 2e-15 relative for ``k_min <= k <=
    k_max`` (1/m), ``p`` up to 8: about 170 terms at ``k_max / k_min = 2000``, 210 at 10^5.

    From ``k^-p = 2 / Gamma(p / 2) int exp(-k^2 e^(2 s) + p s) ds`` over the real line (``t =
    e^s`` in ``int_0^inf t^(p - 1) exp(-k^2 t^2) dt = Gamma(p / 2) / (2 k^p)``) by the
    trapezoidal rule in ``s``, step :data:`GAUSSIAN_STEP`, on nodes that every ``p`` shares:
    the integrand is analytic in the strip ``|Im s| < pi / 4``, so the error falls as
    ``exp(-pi^2 / (2 h))``. The nodes run from where ``exp(-k_min^2 e^(2 s)) e^(p s)`` is
    below 1e-17 down to where the tail ``e^(p s)`` is 1e-17 of ``k_max^-p``; the nodes with
    ``alpha k_max^2 < 1e-6`` are one term for each ``p``, of its summed weight and mean
    exponent (what is left is second order in ``alpha k^2``). ``docs/derivations.md``,
    section 14."""
    top = 0.5 * math.log(40.0 + 3 * max(powers))
    bottom = min(math.log(1e-17) / p for p in powers) - math.log(k_max / k_min)
    s = top - GAUSSIAN_STEP * np.arange(int((top - bottom) / GAUSSIAN_STEP) + 1)
    alpha = np.exp(2 * s) / k_min**2
    weights = {p: (2 / math.gamma(p / 2) * GAUSSIAN_STEP / k_min**p) * np.exp(p * s) for p in powers}
    flat = alpha * k_max**2 < 1e-6
    if not flat.any():
        return alpha, weights
    kept = alpha.size - flat.sum()
    tails = [(w[flat].sum(), (w[flat] * alpha[flat]).sum()) for w in weights.values()]
    c = {p: np.concatenate([w[~flat], np.zeros(len(powers))]) for p, w in weights.items()}
    for i, p in enumerate(powers):
        c[p][kept + i] = tails[i][0]
    return np.concatenate([alpha[~flat], [t / w for w, t in tails]]), c


#: the trapezoidal step of :func:`inverse_power_gaussians` in ``s = log t``: at 0.1 the error
#: is rounding's for every power to 8 (0.6-1.8e-15); at 0.12 it is for p <= 4 (5e-15 at p =
#: 5, 1.1e-13 at p = 8), at 0.15 1.5e-14 (p = 1) to 2.5e-12 (p = 4)
GAUSSIAN_STEP = 0.1


def square_sums(nu: np.ndarray, weight: np.ndarray, ratio: float, count: int, parts, chirp: bool = False) -> dict:
    """``G`` times the half-space kernels ``ww, uu, uv`` (m/N times Pa) of a square lattice
    of modes (the same ``nu`` (rad/m), ``weight`` (1/m) and ``ratio = a / L`` along ``x`` and
    ``y``) and a constant real ``G``, as sums of separable Gaussians: real tables ``(2 count -
    1, 2 count - 1)`` of the parts asked.

    With ``k^-p = sum_q c_q exp(-alpha_q nu_x^2) exp(-alpha_q nu_y^2)``
    (:func:`inverse_power_gaussians`) and ``F = 1 / k`` (0 at ``k = 0``), the sums over ``m,
    n >= 0`` are ``2 G ww = sum_q c_q A_q' A_q``, ``G uu = 2 G ww - sum_q c_q X_q' A_q / 2`` and
    ``2 G uv = sum_q c_q B_q' B_q`` (:func:`halfspace_symbols`), of the single sums over ``n``
    (:func:`column_sums`: products, DCT-I / DST-I or chirp-z, as ``chirp`` says) of ``E =
    exp(-alpha nu^2)`` against ``w``, ``nu^2 w`` and ``nu w`` (odd): ``O(Q N count)`` or
    ``O(Q N log N)``, not ``O(N^2 count)``. The mode ``k = 0`` that the Gaussians give ``F``
    (``sum c_q w_0^2``) is taken off. The sums are indexed ``[dx, dy]``, the tables ``[dy, dx]``."""
    nu2 = nu * nu
    alpha, c = inverse_power_gaussians(nu[1], math.sqrt(2.0) * nu[-1])
    E = np.multiply.outer(-alpha, nu2)
    np.exp(E, out=E)
    out = {}
    if "ww" in parts or "uu" in parts:
        A, *X = column_sums(E, False, [weight] + ([nu2 * weight] if "uu" in parts else []), nu, ratio, count, chirp)
        F = (A.T * c[1]) @ A - c[1].sum() * weight[0] ** 2
        if "ww" in parts:
            out["ww"] = _unfold(0.5 * F, 1.0)
        if "uu" in parts:
            out["uu"] = _unfold((F - 0.5 * (X[0].T * c[3]) @ A).T, 1.0)  # nu_x^2 / k^3
    if "uv" in parts:
        (B,) = column_sums(E, True, [weight], nu, ratio, count, chirp)
        out["uv"] = _unfold(0.5 * (B.T * c[3]) @ B, -1.0)
    return out


def _unfold(T: np.ndarray, sign: float) -> np.ndarray:
    """The table over ``|dy|, |dx| < count`` from ``T[dy, dx]`` on ``dy, dx >= 0``, even
    (``sign = 1``) or odd (-1) in each offset."""
    T = _mirror(T, sign)
    return np.concatenate([sign * T[:0:-1], T])
