"""Influence kernels: the paper's truncated double Fourier sums (eqs. 52-62).

The displacement in direction ``P`` at node ``M`` due to a unit force in direction ``Q``
spread uniformly over the patch of node ``N`` (eq. 52) is, with ``nu = (2 pi m / L_x,
2 pi n / L_y)`` and ``|m| <= N_tx``, ``|n| <= N_ty``,

    C_PQ(M, N) = sum_mn  sinc(m a_x / L_x) sinc(n a_y / L_y) / (L_x L_y)
                         * C_PQ(nu; G*(omega_m)) exp(i nu . (x_M - x_N))      (eqs. 56-62)

which depends on the node offset only (the "configurational similarity" of section 8).
When ``2 N_t a / L`` is an odd integer the two end modes ``+-N_t`` fall on the same
lattice frequency, the grid's Nyquist ``pi / a``, and each takes half its term
(:func:`end_weights`; ``docs/derivations.md``, section 8, "End modes").
:func:`influence_kernels` evaluates it for every offset of the grid at once: the mode
symbols on the quarter ``m, n >= 0`` (reality ``g(-m, -n) = conj g(m, n)`` and parity in
``n``), summed over ``n`` then ``m`` (:mod:`bem.mode_sums`): by matrix products up to
:data:`_MATMUL_NODES` nodes a side, above by chirp-z (Bluestein) transforms, exact for any
``a / L`` at a cost of ``O(N_t^2 log N_t)``, or by DCT-I / DST-I when ``L = 2 Q a`` with
``Q >= N_t``. The deep modes of a layer without inertia, or with a little (``rho V^2 /
|G| <= 1e-6``), need no complex symbol: their sums are of real arrays, ``1 / k`` and ``1 /
k^3`` without inertia, ``nu_x^a nu_y^b / k^p`` with it, and those separate into sums of
Gaussians in ``nu_x`` and ``nu_y`` (:mod:`bem.halfspace_sums`): ``O(N_t Q K)`` for ``Q``
(about 170) Gaussians and ``K`` nodes a side; on a layer so thin that every mode sees the
base (``nu H <= 50``) there is no deep part, and every mode's own symbol is summed
(:func:`_every_mode_sees_the_base`). ``vu = uv`` is computed once.
:func:`influence_kernels_direct` is the paper's route, summing every term for two source
nodes, kept as the slow reference.

A kernel table ``K`` has shape ``(2 K_y - 1, 2 K_x - 1)``; ``K[dy + K_y - 1, dx + K_x - 1]``
is the displacement (m) at offset ``(dx a_x, dy a_y)`` from a unit force (N), with the
traction sign of the paper (``sigma_z`` positive in tension, displacements positive along
``+z, +x, +y``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .batches import CHUNK, ROWS, in_batches
from .grid import Grid
from .halfspace_sums import (HALFSPACE_KH, INERTIA_SERIES, gaussian_sums, halfspace_symbols, series_arrays,
                             series_factor, square_sums)
from .layer import DEEP_KH, SERIES_EPS, Layer, compliance_blocks, normal_compliance_outer, surface_compliance
from .mode_sums import chirp_sum, over_m_mirrored, over_n

__all__ = ["BLOCKS", "chirp_sum", "end_weights", "influence_kernels", "influence_kernels_direct", "kernels_with_power",
           "mode_symbols"]

#: block name -> (row, column) in the 3x3 compliance, rows/cols ordered (w, u, v)
BLOCKS = {p + q: (i, j) for i, p in enumerate("wuv") for j, q in enumerate("wuv")}
_ODD_IN_NY = {"wv", "vw", "uv", "vu"}
_PARITY = {b: -1.0 if b in _ODD_IN_NY else 1.0 for b in BLOCKS}  # of a table in dy
#: blocks that are another's times a sign at every mode (``docs/derivations.md`` section 13):
#: every route computes ``vu = uv`` once; the closed form's ``uw`` and ``-wu`` round apart where
#: exponentially small (a thick layer's base coupling), so only the series' deep modes share them
_MIRRORED = {"uw": ("wu", -1.0), "vw": ("wv", -1.0), "vu": ("uv", 1.0)}


def _check_blocks(blocks) -> tuple[str, ...]:
    blocks = tuple(blocks)
    bad = [b for b in blocks if b not in BLOCKS]
    if bad or not blocks:
        raise ValueError(f"blocks must be among {sorted(BLOCKS)}, got {blocks!r}")
    return blocks


def end_weights(truncation: int, spacing: float, period: float) -> np.ndarray:
    """Weights of the modes ``m = 0 .. N_t`` of a truncated sum ``|m| <= N_t`` sampled on
    nodes ``spacing`` (m) apart, ``period`` (m) the period: 1, except ``1/2`` for the end
    modes when ``k = 2 N_t a / L`` is an odd integer. Then ``exp(+-i 2 pi N_t x_j / L) =
    (-1)^j`` up to a common factor: both end modes fall on the lattice's Nyquist frequency
    ``pi / a``, whose alias class would hold ``k + 1`` kept modes where every other lattice
    frequency's holds ``k`` (``L`` a multiple of ``a``). (An even ``k`` makes ``sinc(N_t a /
    L) = 0`` at the end modes; otherwise no two kept modes alias exactly.) Shape
    ``(N_t + 1,)``."""
    w = np.ones(truncation + 1)
    k = 2 * truncation * spacing / period
    if round(k) % 2 == 1 and abs(k - round(k)) <= 1e-9 * k:
        w[-1] = 0.5
    return w


@dataclass(frozen=True, eq=False, repr=False)
class _Modes:
    """The truncated Fourier modes ``0 <= m <= N_tx``, ``0 <= n <= N_ty`` of a grid: wave
    numbers ``nu_x, nu_y`` (rad/m), moduli ``G`` (Pa, complex) at ``omega_m = -nu_x V``,
    sinc weights over the periods ``sx, sy`` (1/m: a unit force's traction coefficients),
    the kernels' weights ``wx, wy`` (1/m: the same times :func:`end_weights`), spacing over
    period ``rx, ry`` (-)."""

    m: np.ndarray
    n: np.ndarray
    nu_x: np.ndarray
    nu_y: np.ndarray
    G: np.ndarray
    sx: np.ndarray
    sy: np.ndarray
    wx: np.ndarray
    wy: np.ndarray
    rx: float
    ry: float


def _modes(grid: Grid, layer: Layer, speed: float) -> _Modes:
    g = grid
    rx, ry = g.spacing_x / g.period_x, g.spacing_y / g.period_y
    m, n = np.arange(g.truncation_x + 1), np.arange(g.truncation_y + 1)
    nu_x = 2 * np.pi * m / g.period_x
    sx, sy = np.sinc(m * rx) / g.period_x, np.sinc(n * ry) / g.period_y
    return _Modes(m=m, n=n, nu_x=nu_x, nu_y=2 * np.pi * n / g.period_y, G=_moduli(layer, nu_x, speed), sx=sx, sy=sy,
                  wx=sx * end_weights(g.truncation_x, g.spacing_x, g.period_x),
                  wy=sy * end_weights(g.truncation_y, g.spacing_y, g.period_y), rx=rx, ry=ry)


def mode_symbols(grid: Grid, layer: Layer, speed: float, blocks=("ww",)) -> dict:
    """Fourier weights ``g_PQ(m, n)`` for ``0 <= m <= N_tx``, ``0 <= n <= N_ty``.

    ``g = sinc_x sinc_y C_PQ / (L_x L_y)`` (m/N) times the :func:`end_weights` of both
    directions, complex, shape ``(N_tx + 1, N_ty + 1)``.
    ``speed`` is ``V`` (m/s).
    """
    blocks = _check_blocks(blocks)
    md = _modes(grid, layer, speed)
    weight = np.outer(md.wx, md.wy)
    rho_V2 = layer.inertia(speed)
    out = {b: np.empty((md.m.size, md.n.size), dtype=complex) for b in blocks}

    def work(start: int) -> None:
        s = slice(start, min(start + CHUNK, md.m.size))
        for b, sym in _symbol_rows(layer, md.nu_x[s], md.nu_y, md.G[s], rho_V2, weight[s], blocks).items():
            out[b][s] = sym

    in_batches(md.m.size, work)
    return out


def _symbol_rows(layer: Layer, nu_x, nu_y, G, rho_V2: float, weight, blocks) -> dict:
    """The symbols ``g_PQ`` (m/N) of the modes ``nu_x[:, None], nu_y[None, :]`` (rad/m),
    ``G`` (Pa) per ``nu_x``, ``weight`` the sinc weights over ``L_x L_y`` (1/m^2)."""
    if blocks == ("ww",):
        return {"ww": normal_compliance_outer(nu_x, nu_y, G, rho_V2, layer.thickness) * weight}
    parts = compliance_blocks(nu_x[:, None], nu_y[None, :], G[:, None], rho_V2, layer.thickness, blocks)
    return {b: parts[b] * weight for b in blocks}


def _kernels_streamed(grid: Grid, layer: Layer, speed: float, blocks: tuple, power: bool = False):
    """The kernels of :func:`mode_symbols` summed a batch of ``m`` at a time: each batch's
    symbols are summed over ``n`` at once (:func:`bem.mode_sums.over_n`), so only
    ``(N_tx + 1) x (2 K_y - 1)``
    partial sums a block are kept, not every mode's symbol (at 513 x 513 nodes, ``N_t =
    4924``, 9 x 0.39 GB of symbols). The same sums, in the same order. With ``power`` the
    :func:`kernels_with_power` tables from the same symbols as well (``{}`` without)."""
    Kx, Ky = grid.nodes_x, grid.nodes_y
    chirp = max(Kx, Ky) > _MATMUL_NODES
    md = _modes(grid, layer, speed)
    rho_V2 = layer.inertia(speed)
    H = {b: np.empty((md.m.size, 2 * Ky - 1), dtype=complex) for b in blocks}
    Hp = {b: np.empty((md.m.size, 2 * Ky - 1), dtype=complex) for b in blocks} if power else {}

    def work(start: int) -> None:
        s = slice(start, min(start + CHUNK, md.m.size))
        weight = np.outer(md.wx[s], md.wy)
        for b, sym in _symbol_rows(layer, md.nu_x[s], md.nu_y, md.G[s], rho_V2, weight, blocks).items():
            H[b][s] = over_n(sym, b in _ODD_IN_NY, md.ry, Ky, chirp)
            if power:
                Hp[b][s] = over_n(sym, b in _ODD_IN_NY, md.ry, Ky, chirp, md.sy) * _power_rows(grid, md, s)

    in_batches(md.m.size, work)
    return ({b: over_m_mirrored(H.pop(b)[:, Ky - 1 :], md.rx, Kx, chirp, _PARITY[b]) for b in blocks},
            {b: over_m_mirrored(Hp.pop(b)[:, Ky - 1 :], md.rx, Kx, chirp, _PARITY[b]) for b in blocks} if power else {})



def _power_rows(grid: Grid, md: "_Modes", s: slice) -> np.ndarray:
    """With the sinc weight ``sy(n)`` inside the sum over ``n``, what turns a kernel's
    partial sums into a :func:`kernels_with_power` table's: ``i nu_x L_x L_y sx(m)``
    (rows ``s`` of ``m``, a column; the end weights stay once, from the kernel's symbol)."""
    return ((1j * grid.period_x * grid.period_y) * md.nu_x[s] * md.sx[s])[:, None]


def _moduli(layer: Layer, nu_x: np.ndarray, speed: float) -> np.ndarray:
    """``G*(omega_m)`` (Pa, complex) of the modes ``nu_x`` (rad/m), ``omega_m = -nu_x V``."""
    with np.errstate(over="ignore"):  # |omega| = inf is the glassy limit, finite in every material
        return np.asarray(layer.material.modulus(-nu_x * speed), dtype=complex)


_MATMUL_NODES = 128  # up to this many nodes a side, trigonometric matrix products win


def _kernels_halfspace_split(grid: Grid, layer: Layer, speed: float, blocks: tuple, power: bool = False):
    """The kernels without inertia (``rho V^2 = 0``), split into the half-space modes'
    sum and a correction on the few modes that see the base (``k H <= HALFSPACE_KH``).

    Without inertia a half-space mode's symbol is ``sinc_x sinc_y / (L_x L_y G(omega_m))``
    times a real function of ``nu`` (:func:`halfspace_symbols`) made of ``1 / k`` and ``1 /
    k^3``: their sums over ``n`` are those of Gaussians times each row's own
    (:func:`bem.halfspace_sums.gaussian_sums`), before the factors of the row (``1 / G``,
    ``nu_x``); on a square grid with one real ``G`` the sums over ``m`` too
    (:func:`bem.halfspace_sums.square_sums`). The
    normal-tangential blocks have no half-space part, ``vu = uv`` and ``vv = 3 ww - uu``. The modes near the origin take the
    exact symbols (:func:`bem.layer.compliance_blocks`) less the half-space ones. The same
    truncated sum as :func:`_kernels_streamed`, to rounding. With ``power`` the
    :func:`kernels_with_power` tables from the same symbols as well (``{}`` without).
    """
    g = grid
    Kx, Ky = g.nodes_x, g.nodes_y
    chirp = max(Kx, Ky) > _MATMUL_NODES
    md = _modes(grid, layer, speed)
    m, n, nu_x, nu_y, G, wx, wy, sy, rx, ry = md.m, md.n, md.nu_x, md.nu_y, md.G, md.wx, md.wy, md.sy, md.rx, md.ry
    inv_G = 1.0 / G
    need = {"ww": ("ww", "vv"), "uu": ("uu", "vv"), "uv": ("uv", "vu")}
    parts = [b for b in ("ww", "uu", "uv") if any(t in blocks for t in need[b])]
    kinds = ("kernel", "power") if power else ("kernel",)
    square = (not power and Kx == Ky and np.array_equal(nu_x, nu_y) and np.array_equal(wx, wy)
              and rx == ry and np.all(G == G[0]) and G[0].imag == 0)
    H = {} if square else {(k, b): np.empty((m.size, Ky), dtype=complex) for k in kinds for b in parts}
    # ww = 1 / (2 k), uu = (nu_x^2 / 2 + nu_y^2) / k^3 = 1 / k - nu_x^2 / (2 k^3),
    # uv = -nu_x nu_y / (2 k^3) (halfspace_symbols): the sums over n of 1 / k, nu_x^2 / k^3
    # and sign(n) nu_y / k^3, by Gaussians
    keys = [key for key, part in (((0, 1, False), "ww" in parts or "uu" in parts), ((2, 3, False), "uu" in parts),
                                  ((0, 3, True), "uv" in parts)) if part]
    weights = [wy * sy if k == "power" else wy for k in kinds]
    sums = None if square or not keys else gaussian_sums(nu_x, nu_y, weights, ry, Ky, chirp, keys)

    def work(start: int) -> None:
        s = slice(start, min(start + ROWS, m.size))
        got = sums(s)
        for ik, k in enumerate(kinds):
            rows = (wx[s] * inv_G[s])[:, None] * (_power_rows(g, md, s) if k == "power" else 1.0)
            if "ww" in parts:
                H[k, "ww"][s] = (0.5 * got[0, 1, False, ik]) * rows
            if "uu" in parts:
                H[k, "uu"][s] = (got[0, 1, False, ik] - 0.5 * got[2, 3, False, ik]) * rows
            if "uv" in parts:
                H[k, "uv"][s] = (-0.5j * got[0, 3, True, ik]) * (nu_x[s, None] * rows)

    if square:
        half = {("kernel", b): t / G[0].real
                for b, t in square_sums(nu_x, wx, rx, Kx, parts, chirp).items()}
    else:
        if keys:
            in_batches(m.size, work, ROWS)
        half = {key: over_m_mirrored(H.pop(key), rx, Kx, chirp, _PARITY[key[1]]) for key in list(H)}
    for k in kinds:
        if "vv" in blocks:
            half[k, "vv"] = 3 * half[k, "ww"] - half[k, "uu"]
        if "vu" in blocks:
            half[k, "vu"] = half[k, "uv"]
    # the modes that see the base: exact less half-space symbols, summed by products, a batch
    # of rows at a time (on a thin layer every mode sees the base: whole tables of them would
    # hold N_t^2 symbols a block)
    Mx = min(m.size, int(HALFSPACE_KH * g.period_x / (2 * np.pi * layer.thickness)) + 1)
    My = min(n.size, int(HALFSPACE_KH * g.period_y / (2 * np.pi * layer.thickness)) + 1)
    near = {(k, b): np.empty((Mx, 2 * Ky - 1), dtype=complex) for k in kinds for b in blocks}

    def correction(start: int) -> None:
        s = slice(start, min(start + ROWS, Mx))
        exact = compliance_blocks(nu_x[s, None], nu_y[None, :My], G[s, None], 0.0, layer.thickness, blocks)
        hs = halfspace_symbols(nu_x[s], nu_y[:My])
        hs["vv"], hs["vu"] = 3 * hs["ww"] - hs["uu"], hs["uv"]
        weight = np.outer(wx[s], wy[:My])
        for k, b in near:
            corr = exact[b] - hs[b] * inv_G[s, None] if b in hs else exact[b]
            h = over_n(corr * weight, b in _ODD_IN_NY, ry, Ky, False, sy[:My] if k == "power" else None)
            near[k, b][s] = h * _power_rows(g, md, s) if k == "power" else h

    in_batches(Mx, correction, ROWS)
    out = {k: {} for k in ("kernel", "power")}
    for k, b in list(near):
        K = over_m_mirrored(near.pop((k, b))[:, Ky - 1 :], rx, Kx, False, _PARITY[b])
        out[k][b] = K + half[k, b] if (k, b) in half else K
    return out["kernel"], out["power"]


def _every_mode_sees_the_base(grid: Grid, layer: Layer) -> bool:
    """Whether every mode has ``nu_x H`` and ``nu_y H`` at most ``DEEP_KH`` (50): the
    half-space split and the series would then take all their deep sums off again on the
    modes near the base, and every mode's own symbol, summed directly
    (:func:`_kernels_streamed`), costs less. Measured, the paper's sphere on a 1 mm layer
    (61 x 61 nodes, ``N_t = 500``; kernels and power tables, one thread): with a little
    inertia 93 against 124 ms by the series, without 61 against 78 ms by the split; at 3
    mm 107 against 138 ms; at 5 mm (nearly half the rows deep) the series 72 against 91 ms."""
    g, H = grid, layer.thickness
    return max(g.truncation_x / g.period_x, g.truncation_y / g.period_y) * 2 * np.pi * H <= DEEP_KH


def _series_holds(grid: Grid, layer: Layer, speed: float) -> bool:
    """Whether every mode beyond ``k H = DEEP_KH`` (50) takes the series in ``eps = rho V^2
    nu_x^2 / (G k^2)`` (:data:`bem.halfspace_sums.INERTIA_SERIES`): ``eps <= rho V^2 /
    |G(omega_m)|`` below :data:`bem.layer.SERIES_EPS` on every row ``m``, with a margin of
    1e-3."""
    md = _modes(grid, layer, speed)
    return bool(layer.inertia(speed) * np.max(1.0 / np.abs(md.G)) <= (1 - 1e-3) * SERIES_EPS)


def _kernels_series(grid: Grid, layer: Layer, speed: float, blocks: tuple, power: bool = False):
    """The kernels with a little inertia (:func:`_series_holds`): a deep mode's symbol is a
    sum of real arrays ``nu_x^a nu_y^b / k^p`` times factors of the row
    (:data:`bem.halfspace_sums.INERTIA_SERIES`), summed over ``n`` once an array for all the
    blocks (kernels' and power tables' weights side by side), as sums of Gaussians
    (:func:`bem.halfspace_sums.gaussian_sums`), before the factors of the row;
    the modes ``k H <= 50`` (a box of rows and columns) add their exact less series symbols.
    The same truncated sum as :func:`_kernels_streamed`, to rounding and the series' next
    terms (``3/8 eps^2`` of a block of order one, ``1.5 eps^3`` of a normal-tangential one).
    With ``power`` the :func:`kernels_with_power` tables as well (``{}`` without)."""
    g, H = grid, layer.thickness
    Kx, Ky = g.nodes_x, g.nodes_y
    chirp = max(Kx, Ky) > _MATMUL_NODES
    md = _modes(grid, layer, speed)
    rho_V2 = layer.inertia(speed)
    kinds = ("kernel", "power") if power else ("kernel",)
    weights = [md.wy * md.sy if k == "power" else md.wy for k in kinds]
    source = {b: _MIRRORED.get(b, (b, 1.0)) for b in blocks}  # a deep part shared: uw = -wu ...
    terms = {src: INERTIA_SERIES[src] for src, _ in source.values()}
    keys = sorted({t[:3] for ts in terms.values() for t in ts}, key=lambda t: (t[2], t))  # even, then odd
    column = {key: i for i, key in enumerate(keys)}
    factor = {(b, i): series_factor(t[3], md.G, rho_V2) for b, ts in terms.items() for i, t in enumerate(ts)}
    far = {(k, b): np.empty((md.m.size, Ky), dtype=complex) for k in kinds for b in blocks}  # dy >= 0
    # the modes k H <= DEEP_KH (a row and a column more) add their exact less series symbols
    Mx = min(md.m.size, int(DEEP_KH * g.period_x / (2 * np.pi * H)) + 2)
    My = min(md.n.size, int(DEEP_KH * g.period_y / (2 * np.pi * H)) + 2)
    sums_of = gaussian_sums(md.nu_x, md.nu_y, weights, md.ry, Ky, chirp, keys)  # the series' sums over n

    def rows(k: str, s: slice) -> np.ndarray:
        return md.wx[s, None] * (_power_rows(g, md, s) if k == "power" else 1.0)

    def work(start: int) -> None:
        s = slice(start, min(start + ROWS, md.m.size))
        sums = sums_of(s)
        deep = {(src, ik): sum(factor[src, i][s, None] * (1j if odd else 1.0) * sums[a, p, odd, ik]
                               for i, (a, p, odd, _) in enumerate(ts))
                for src, ts in terms.items() for ik in range(len(kinds))}
        near = start < Mx
        if near:  # the box's exact and series symbols
            t = slice(start, min(start + ROWS, Mx))
            exact = compliance_blocks(md.nu_x[t, None], md.nu_y[None, :My], md.G[t, None], rho_V2, H, blocks)
            arrays = series_arrays(md.nu_x[t], md.nu_y[:My], keys)
            series = {src: sum(factor[src, i][t, None] * (arrays[column[a, p, odd]] * (md.nu_y[:My] if odd else 1.0))
                               for i, (a, p, odd, _) in enumerate(ts))
                      for src, ts in terms.items()}
        for b, (src, sign) in source.items():
            for ik, k in enumerate(kinds):
                far[k, b][s] = sign * deep[src, ik]
                if near:
                    corr = exact[b] - sign * series[src]
                    far[k, b][t] += over_n(corr, b in _ODD_IN_NY, md.ry, Ky, False, weights[ik][:My])[:, Ky - 1 :]
                far[k, b][s] *= rows(k, s)

    in_batches(md.m.size, work, ROWS)
    out = {k: {} for k in ("kernel", "power")}
    for k, b in list(far):
        out[k][b] = over_m_mirrored(far.pop((k, b)), md.rx, Kx, chirp, _PARITY[b])
    return out["kernel"], out["power"]


def influence_kernels(grid: Grid, layer: Layer, speed: float, blocks=("ww",)) -> dict:
    """Kernel tables of the requested blocks, by fast transforms.

    Parameters
    ----------
    grid : Grid
    layer : Layer
    speed : float
        Rolling/sliding speed ``V`` (m/s), ``>= 0``.
    blocks : iterable of str
        Among ``ww, wu, wv, uw, uu, uv, vw, vu, vv`` (displacement then force direction).

    Returns
    -------
    dict of str -> ndarray, shape ``(2 K_y - 1, 2 K_x - 1)``, float (m/N)

    Raises
    ------
    ValueError
        If ``speed`` is negative or not finite, or a kernel is not finite (naming the
        speed and the grid): a solve never proceeds on NaN compliances.
    """
    return _tables(grid, layer, speed, blocks, power=False)[0]


def kernels_with_power(grid: Grid, layer: Layer, speed: float, blocks=("ww",)) -> tuple[dict, dict]:
    """:func:`influence_kernels` and, from the same mode symbols, the power tables of the
    same blocks: the steady power the layer absorbs from nodal forces spread on their
    patches is a quadratic form of the forces,

        P_visc = -V sum_PQ sum_MN F_P(M) W_PQ(x_M - x_N) F_Q(N),
        W_PQ(d) = L_x L_y sum_mn e_m e_n i nu_x (sinc_x sinc_y / (L_x L_y))^2 C_PQ(nu; G*(omega_m)) exp(i nu . d)

    (the mode sum of :func:`bem.energy.viscous_dissipation` with the force transforms
    written out; ``e_m e_n`` the :func:`end_weights`, once, as in the kernels), tables like
    the kernels' (``(2 K_y - 1, 2 K_x - 1)``, real, 1/m).
    Computing them costs one more transform of each batch of symbols, not another
    evaluation of the layer's compliance at every mode: the power of any forces is then
    a few FFTs (:func:`bem.energy.dissipation_from_tables`).
    """
    return _tables(grid, layer, speed, blocks, power=True)


def _tables(grid: Grid, layer: Layer, speed: float, blocks, power: bool) -> tuple[dict, dict]:
    if not (np.isfinite(speed) and speed >= 0):
        raise ValueError(f"speed must be finite and >= 0 m/s, got {speed!r}")
    blocks = _check_blocks(blocks)
    if _every_mode_sees_the_base(grid, layer):
        split = _kernels_streamed
    elif layer.inertia(speed) == 0:
        split = _kernels_halfspace_split
    elif _series_holds(grid, layer, speed):
        split = _kernels_series
    else:
        split = _kernels_streamed
    own = tuple(dict.fromkeys("uv" if b == "vu" else b for b in blocks))  # vu = uv, the same sums
    out, pw = split(grid, layer, speed, own, power)
    for tables in (out, pw):
        if "vu" in blocks and tables:
            tables["vu"] = tables["uv"].copy() if "uv" in blocks else tables.pop("uv")
    bad = [b for b, k in (*out.items(), *pw.items()) if not np.isfinite(k).all()]
    if bad:
        g = grid
        raise ValueError(
            f"the influence kernels {', '.join(bad)} are not finite at speed = {speed:g} m/s on the grid "
            f"of {g.nodes_x} x {g.nodes_y} nodes (a = {g.spacing_x:g} x {g.spacing_y:g} m, "
            f"L = {g.period_x:g} x {g.period_y:g} m, N_t = {g.truncation_x} x {g.truncation_y}): "
            "the material's modulus or the layer's compliance is not finite at some of the modes' "
            f"frequencies |omega_m| = 2 pi m V / L_x <= {2 * np.pi * g.truncation_x * speed / g.period_x:.3g} "
            "rad/s; use a lower loading.speed or check the material model"
        )
    return out, pw


def influence_kernels_direct(grid: Grid, layer: Layer, speed: float, blocks=("ww",)) -> dict:
    """The paper's direct summation (eqs. 56-62) for unit forces at nodes 1 and ``K_x``.

    Every term ``|m| <= N_tx, |n| <= N_ty`` is added explicitly, times its
    :func:`end_weights`; the other columns follow by configurational similarity (sec. 8)
    with the ``y``-parity of each block.
    Cost ``O(N_T N_t^2)``: a reference for small grids only.
    """
    blocks = _check_blocks(blocks)
    g = grid
    m = np.arange(-g.truncation_x, g.truncation_x + 1)
    n = np.arange(-g.truncation_y, g.truncation_y + 1)
    nu_x, nu_y = 2 * np.pi * m / g.period_x, 2 * np.pi * n / g.period_y
    with np.errstate(over="ignore"):
        G = np.asarray(layer.material.modulus(-nu_x * speed), dtype=complex)
    C = surface_compliance(nu_x[:, None], nu_y[None, :], G[:, None], layer.inertia(speed), layer.thickness)
    # eqs. 56-59: Fourier coefficients of a unit force on a patch, without its phase
    with np.errstate(invalid="ignore", divide="ignore"):
        fx = np.where(m == 0, g.spacing_x / g.period_x, np.sin(np.pi * m * g.spacing_x / g.period_x) / (np.pi * m))
        fy = np.where(n == 0, g.spacing_y / g.period_y, np.sin(np.pi * n * g.spacing_y / g.period_y) / (np.pi * n))
    fx = fx * end_weights(g.truncation_x, g.spacing_x, g.period_x)[np.abs(m)]
    fy = fy * end_weights(g.truncation_y, g.spacing_y, g.period_y)[np.abs(n)]
    coef = np.outer(fx, fy) / g.cell_area
    x, y = g.x, g.y
    ex = np.exp(1j * np.outer(x, nu_x))  # (K_x, modes)
    ey = np.exp(1j * np.outer(y, nu_y))
    out = {}
    Kx, Ky = g.nodes_x, g.nodes_y
    for b in blocks:
        sym = coef * C[..., BLOCKS[b][0], BLOCKS[b][1]]
        table = np.zeros((2 * Ky - 1, 2 * Kx - 1))
        for src in (0, Kx - 1):  # nodes 1 and K_x (first row of the grid)
            phase = sym * np.exp(-1j * np.add.outer(nu_x * x[src], nu_y * y[0]))
            disp = (ey @ (ex @ phase).T).real  # eq. 62 at every node, (K_y, K_x)
            dx = np.arange(Kx) - src
            table[Ky - 1 :, dx + Kx - 1] = disp  # dy >= 0
        sign = -1.0 if b in _ODD_IN_NY else 1.0
        table[: Ky - 1] = sign * table[Ky:][::-1]  # dy < 0 by the y-parity of the block
        out[b] = table
    return out
