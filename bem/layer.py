"""Fourier-space surface compliance of a bonded incompressible layer in a moving frame.

For one Fourier mode ``exp(i (nu_x x + nu_y y))`` the paper (eqs. 43-50) writes the
state ``q = (w, u, v, sigma_z, tau_xz, tau_yz)`` as ``q(z) = exp(A z) q(0)`` and, with the
displacements zero on the rigid base, relates the top displacements to the top tractions
by the 3x3 matrix ``C = T12(H) T22(H)^-1``:

    (w, u, v)(H) = C (sigma_z, tau_xz, tau_yz)(H)          [m/Pa]

Two independent evaluations:

* :func:`surface_compliance_expm`, the paper's route (matrix exponential of eq. 45), kept
  as the reference (in :mod:`bem.layer_reference`, with :func:`system_matrix`). For large
  ``kH`` the exponential overflows, so the layer is split into sublayers of ``k h <= 8``
  and the compliance is propagated upwards by the exact composition ``C <- (T11 C + T12)
  (T21 C + T22)^-1`` (which starts from ``C = 0`` at the bonded base and gives eq. 50
  after one sublayer).
* :func:`surface_compliance`, a closed form. In axes along and across the wave vector the
  mode splits into an antiplane part ``u_T = tanh(qH) / (G q) tau_T`` and an in-plane part
  ``(w, u_L)`` whose vertical displacement obeys ``(D^2 - k^2)(D^2 - q^2) w = 0``, with
  ``k^2 = nu_x^2 + nu_y^2`` and ``q^2 = k^2 - rho V^2 nu_x^2 / G*``. Its solutions that
  satisfy the base conditions are built from divided differences in ``lambda = k^2`` of
  the entire functions ``cosh(sqrt(lambda) z)`` and ``sinh(sqrt(lambda) z)/sqrt(lambda)``,
  so everything is analytic at ``k = 0`` and at ``q = k`` (no inertia); they are
  evaluated by power series for ``kH <= 1`` and with decaying exponentials otherwise
  (the common growth ``exp(kappa H)`` cancels in ``N M^-1``), so the result is finite
  and accurate from ``kH = 0`` to the half-space limit. Without inertia the compliances
  are real closed forms in ``kH`` (:func:`_static_parts`); with a little (``|k^2 - q^2| <=
  1e-6 k^2``) a mode that sees the base takes those and their terms of first and second
  order in ``k^2 - q^2`` (:func:`_expanded_parts`), exact to rounding in a third of the
  general route's time.

Transcription note (checked by ``tests/bem/test_layer_derivation.py``): eq. 27 of the
paper prints ``beta_y = (nu_x^2 + 4 nu_y^2) G* - rho V^2 nu_y^2``. The inertia term comes
from ``rho V^2 d^2/dx^2`` (eqs. 8, 35) and is ``- rho V^2 nu_x^2`` in every diagonal
entry; :func:`system_matrix` uses the corrected form.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ._checks import real
from .layer_reference import surface_compliance_expm, system_matrix

__all__ = [
    "Layer", "system_matrix", "surface_compliance", "surface_compliance_expm", "normal_compliance",
    "normal_compliance_outer", "compliance_blocks", "DEEP_KH", "SERIES_EPS",
]


#: the thickest layer (m): ``H^3`` and its products with the wavenumbers stay finite doubles
MAX_THICKNESS = 1e100


@dataclass(frozen=True)
class Layer:
    """An incompressible linear viscoelastic layer bonded to a rigid base.

    Parameters
    ----------
    thickness : float
        ``H`` (m), > 0.
    material : object
        Has ``modulus(omega) -> G*(omega)`` (Pa) for angular frequencies (rad/s); see
        :mod:`bem.materials`.
    density : float
        ``rho`` (kg/m^3), >= 0; 0 drops the inertia terms ``rho V^2``.
    """

    thickness: float
    material: object
    density: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "thickness", real("thickness", self.thickness, "m"))
        if self.thickness > MAX_THICKNESS:  # the series of the compliance hold H^3 (m^3), a double
            raise ValueError(f"thickness must be <= {MAX_THICKNESS:g} m (a layer thicker than its period "
                             f"is already a half-space to every mode of the grid), got {self.thickness!r}")
        object.__setattr__(self, "density", real("density", self.density, "kg/m^3", ">=0"))
        if not callable(getattr(self.material, "modulus", None)):
            raise TypeError(f"material must have a modulus(omega) method, got {self.material!r}")

    @property
    def relaxed_modulus(self) -> float:
        """``G(0)`` (Pa), the material's static shear modulus."""
        return float(np.real(self.material.modulus(0.0)))

    @property
    def shear_wave_speed(self) -> float:
        """Slowest shear-wave speed ``c_s = sqrt(G(0) / rho)`` (m/s); ``inf`` without inertia.

        ``G(0)`` because long waves are felt at low frequency, where a passive material is
        at its softest (relaxed) modulus. Steady motion of the unbounded layer is subsonic
        only below ``c_s``.
        """
        if self.density == 0:
            return math.inf
        return math.sqrt(self.relaxed_modulus / self.density)

    def inertia(self, speed: float) -> float:
        """``rho V^2`` (Pa) of the steady moving-frame inertia at ``speed`` (m/s); exactly 0
        without inertia, whatever the speed (no ``0 * inf``)."""
        return self.density * speed**2 if self.density > 0 else 0.0


# ---------------------------------------------------------------------------------------
# closed form


def _exprel(z):
    """``(exp(z) - 1) / z`` for complex ``z`` with ``Re z <= 0``, accurate near 0."""
    z = np.asarray(z, dtype=complex)
    out = np.empty_like(z)
    small = np.abs(z) < 0.5
    zs = z[small]
    term = np.ones_like(zs)
    acc = np.ones_like(zs)
    for j in range(2, 20):
        term = term * zs / j
        acc = acc + term
    out[small] = acc
    zl = z[~small]
    out[~small] = np.expm1(zl) / zl
    return out


def _scaled_sinh_over(s, H, kappa):
    """``exp(-kappa H) sinh(s H) / s`` (m), accurate for small ``|s| H``."""
    out = np.empty(np.broadcast(s, kappa).shape, dtype=complex)
    s, kappa = np.broadcast_arrays(s, kappa)
    small = np.abs(s) * H < 1.0
    x = s[small] * H
    x2 = x * x
    term = np.ones_like(x)
    acc = np.ones_like(x)
    for j in range(1, 12):
        term = term * x2 / ((2 * j) * (2 * j + 1))
        acc = acc + term
    out[small] = H * acc * np.exp(-kappa[small] * H)
    sl, kl = s[~small], kappa[~small]
    out[~small] = (np.exp((sl - kl) * H) - np.exp(-(sl + kl) * H)) / (2 * sl)
    return out


def _scaled_cosh(s, H, kappa):
    """``exp(-kappa H) cosh(s H)`` (-)."""
    return 0.5 * (np.exp((s - kappa) * H) + np.exp(-(s + kappa) * H))


def _dd_series(a, b, H, odd):
    """Divided difference in ``lambda`` of ``cosh(sqrt(l) H)`` (odd=False, units m^2) or
    ``sinh(sqrt(l) H)/sqrt(l)`` (odd=True, units m^3) at ``a, b`` (1/m^2), by power series
    (for ``|a| H^2, |b| H^2 <= 1``)."""
    al, be = a * H * H, b * H * H
    h = np.ones_like(al)  # h_0
    bp = np.ones_like(al)  # be^j
    fact = 6.0 if odd else 2.0  # (2j+1)! or (2j)! for j = 1
    acc = h / fact
    for j in range(2, 16):
        bp = bp * be
        h = al * h + bp  # complete homogeneous symmetric polynomial h_{j-1}
        fact *= (2 * j) * (2 * j + 1) if odd else (2 * j - 1) * (2 * j)
        acc = acc + h / fact
    return acc * (H**3 if odd else H**2)


def _dd_exp(x, y, t):
    """``(exp(x t) - exp(y t)) / (x - y)`` (m), symmetric in ``x, y``, stable as ``x -> y``."""
    swap = y.real > x.real
    hi = np.where(swap, y, x)
    lo = np.where(swap, x, y)
    return t * np.exp(hi * t) * _exprel((lo - hi) * t)


def _divided_differences(k, q, H, kappa):
    """Scaled ``Gc[k^2, q^2]`` (m^2) and ``F[k^2, q^2]`` (m^3), see module docstring."""
    a, b = (k * k).astype(complex), q * q
    phi2 = np.empty(a.shape, dtype=complex)
    phi1 = np.empty(a.shape, dtype=complex)
    big = np.maximum(np.abs(a), np.abs(b))
    series = big * H * H <= 1.0
    close = ~series & (np.abs(a - b) <= 0.5 * big)
    direct = ~series & ~close

    i = series
    scale = np.exp(-kappa[i] * H)
    phi2[i] = _dd_series(a[i], b[i], H, odd=False) * scale
    phi1[i] = _dd_series(a[i], b[i], H, odd=True) * scale

    i = close
    kk, qq, kap = k[i].astype(complex), q[i], kappa[i]
    dp = _dd_exp(kk - kap, qq - kap, H)  # exp(-kappa H) (e^{kH} - e^{qH}) / (k - q)
    dm = _dd_exp(-kk - kap, -qq - kap, H)
    phi2[i] = (dp - dm) / (2 * (kk + qq))
    e_plus = (qq * dp - np.exp((qq - kap) * H)) / (kk * qq)
    e_minus = (-qq * dm - np.exp((-qq - kap) * H)) / (kk * qq)
    phi1[i] = (e_plus - e_minus) / (2 * (kk + qq))

    i = direct
    kk, qq, kap = k[i].astype(complex), q[i], kappa[i]
    da = a[i] - b[i]
    phi2[i] = (_scaled_cosh(kk, H, kap) - _scaled_cosh(qq, H, kap)) / da
    phi1[i] = (_scaled_sinh_over(kk, H, kap) - _scaled_sinh_over(qq, H, kap)) / da
    return phi2, phi1


def _wave_frame_small(k, q, H):
    """In-plane compliances for ``kH <= 2``: bases analytic in ``k^2`` (divided differences).

    Returns ``c_zz, c_zL/k, c_Lz/k, c_LL`` times ``G``.
    """
    kappa = np.maximum(k, q.real)
    phi2, phi1 = _divided_differences(k, q, H, kappa)
    ch = _scaled_cosh(k, H, kappa)
    sh = 0.5 * (np.exp((k - kappa) * H) - np.exp(-(k + kappa) * H))
    shk = _scaled_sinh_over(k, H, kappa)
    q2 = q * q
    dphi2 = shk + q2 * phi1  # (lambda F)[k^2, q^2]
    ddphi2 = ch + q2 * phi2  # (lambda Gc)[k^2, q^2]
    k2 = k * k
    s1 = -ch + 2 * k2 * phi2  # sigma_z / G of the two basis solutions
    s2 = -sh + 2 * k * dphi2
    t1 = k * (dphi2 + k2 * phi1)  # tau_L / (i G)
    t2 = ddphi2 + k2 * phi2
    det = s1 * t2 - s2 * t1
    c_zz = (k2 * phi1 * t2 - k * phi2 * t1) / det
    c_zL_k = -1j * (phi2 * s1 - k * phi1 * s2) / det
    c_Lz_k = 1j * (phi2 * t2 - dphi2 * (dphi2 + k2 * phi1)) / det
    c_LL = (dphi2 * s1 - k * phi2 * s2) / det
    return c_zz, c_zL_k, c_Lz_k, c_LL


def _wave_frame_large(k, q, H):
    """In-plane compliances for ``kH > 2``, times ``G``.

    Basis of ``(D^2 - k^2)(D^2 - q^2) w = 0`` anchored at the boundary each function decays
    from: ``a1 = e^{-k(H-z)}``, ``a2 = (e^{-q(H-z)} - e^{-k(H-z)})/(k - q)``,
    ``b1 = e^{-kz}``, ``b2 = (e^{-qz} - e^{-kz})/(k - q)``; all bounded, independent as
    ``q -> k``. Pressure from ``p = G (D^3 - q^2 D) w / k^2``. The base conditions
    ``w = w' = 0`` fix the ``b`` coefficients; the top tractions fix ``a``.
    """
    E = np.exp(-k * H)
    A0 = _dd_exp(-q, -k.astype(complex), H)  # a2(0) = b2(H)
    A0p = q * A0 - E  # a2'(0)
    # b coefficients (c3, c4) in terms of the a coefficients (c1, c2)
    c3 = (-E, -A0)
    c4 = (-2 * k * E, -(A0p + k * A0))
    kq = k + q
    # top values of w, w', w'', p/G for each basis function: (a1, a2, b1, b2)
    w = (1.0, 0.0, E, A0)
    dw = (k, -1.0, -k * E, -q * A0 + E)
    ddw = (k * k, -kq, k * k * E, q * q * A0 - kq * E)
    p = ((k - q) * kq / k, -kq / k, -(k - q) * kq * E / k, kq * E / k)

    def top(f):
        return tuple(f[j] + c3[j] * f[2] + c4[j] * f[3] for j in (0, 1))

    W, DW, DDW, P = top(w), top(dw), top(ddw), top(p)
    S = tuple(-P[j] + 2 * DW[j] for j in (0, 1))  # sigma_z / G
    T = tuple((DDW[j] + k * k * W[j]) / k for j in (0, 1))  # tau_L / (i G)
    U = tuple(DW[j] / k for j in (0, 1))  # u_L / i
    det = S[0] * T[1] - S[1] * T[0]
    c_zz = (W[0] * T[1] - W[1] * T[0]) / det
    c_zL_k = -1j * (W[1] * S[0] - W[0] * S[1]) / det / k
    c_Lz_k = 1j * (U[0] * T[1] - U[1] * T[0]) / det / k
    c_LL = (U[1] * S[0] - U[0] * S[1]) / det
    return c_zz, c_zL_k, c_Lz_k, c_LL


def _wave_frame_halfspace(k, q, d):
    """In-plane compliances of a half-space (``kH, Re(q) H > 50``: the base terms of
    :func:`_wave_frame_large` are below ``exp(-50)``), times ``G``. ``R`` is the
    incompressible Rayleigh function ``q^3 + k q^2 + 3 k^2 q - k^3`` (``4 k^3`` at rest);
    ``k - q = d / (k + q)`` from ``d = k^2 - q^2 = rho V^2 nu_x^2 / G`` (the difference
    itself would keep ``1e-16 k`` of a coupling of order ``eps k``)."""
    R = q * (q * (q + k) + 3 * k * k) - k**3
    k_q = d / (k + q)
    return k * (k + q) / R, 1j * k_q / R, -1j * k_q / R, q * (q + k) / R


#: ``k H`` beyond which (with ``Re(q) H``) a mode takes the half-space compliance
DEEP_KH = 50.0


def _static_parts(k, H):
    """``G`` times the wave frame's compliances without inertia (``q = k``), real: ``c_zz``,
    ``i c_zL/k = -i c_Lz/k``, ``c_LL``, ``c_TT`` (m, m^2, m, m) of ``k`` (1/m), from
    ``kH = 0`` to the half-space. With ``y = 2 k H`` and ``D = cosh y + y^2 / 2 + 1``:
    ``c_zz = H (sinh y - y) / (y D)``, ``c_LL = H (sinh y + y) / (y D)``, ``c_zL/k = -i H^2 /
    D``, ``c_TT = tanh(kH) / k`` (``docs/derivations.md`` section 2, "No inertia"), written
    with ``E = exp(-y)``: ``D = e^y (1 + E^2 + (y^2 + 2) E) / 2``; ``(sinh y - y) / y`` by its
    series below ``y = 1``, where the difference would cancel."""
    shape = np.shape(k)
    y = 2.0 * H * np.ravel(k)
    E = np.exp(-y)
    den = 1.0 + E * (E + 2.0) + (E * y) * y  # 2 D e^-y; E y first: no inf * 0 at huge k H
    with np.errstate(divide="ignore", invalid="ignore"):  # k = 0: the limits, below
        zz = H * (1.0 - E * (E + 2.0 * y)) / (y * den)
        ll = H * (2.0 * y * E - np.expm1(-2.0 * y)) / (y * den)
        tt = -H * np.expm1(-y) / ((1.0 + E) * (0.5 * y))
    small = y < 1.0
    if small.any():
        ys = y[small]
        y2 = ys * ys
        term = y2 / 6.0  # (sinh y - y) / y = sum_{j >= 1} y^(2j) / (2j + 1)!
        acc = term.copy()
        for j in range(2, 13):
            term = term * y2 / ((2 * j) * (2 * j + 1))
            acc += term
        zz[small] = H * acc / (np.cosh(ys) + 0.5 * y2 + 1.0)
        zero = y == 0
        ll[zero] = tt[zero] = H
    return tuple(a.reshape(shape) for a in (zz, 2.0 * H * H * E / den, ll, tt))


# A little inertia: with d = rho V^2 nu_x^2 / G = k^2 - q^2 each of _static_parts' compliances
# (times G) is P0 + d P1 + d^2 P2 + O(d^3) (docs/derivations.md section 2, "A little
# inertia"). Each P is H^a num(y) / (c y^p B^n), y = 2 k H, B = D = cosh y + y^2/2 + 1 or
# C = 1 + cosh y, num a sum of terms f y^e sinh(j y) ("s") or cosh(j y) ("c") (j <= n):
# (a, c, p, B, n, terms); the couplings in _static_parts' convention, G c_zL/k = -G c_Lz/k =
# -i (zl + d zl1 + d^2 zl2) (reciprocity keeps them opposite at every order).
_INERTIA_TERMS = {
    1: {"zz": (3, 2, 3, "D", 2, ((3, 0, 2, "s"), (6, 0, 1, "s"), (1, 2, 1, "s"), (-6, 1, 1, "c"), (-6, 1, 0, "c"),
                                 (-1, 3, 1, "c"), (-2, 3, 0, "c"))),
        "zl": (4, 2, 4, "D", 2, ((-2, 0, 2, "c"), (2, 0, 0, "c"), (4, 2, 0, "c"), (2, 3, 1, "s"), (1, 4, 0, "c"))),
        "ll": (3, 2, 3, "D", 2, ((2, 0, 1, "s"), (-2, 1, 0, "c"), (1, 0, 2, "s"), (-2, 1, 1, "c"), (3, 2, 1, "s"),
                                 (-1, 3, 1, "c"))),
        "tt": (3, 0.25, 3, "C", 1, ((1, 0, 1, "s"), (-1, 1, 0, "c")))},
    2: {"zz": (5, 48, 5, "D", 3, ((132, 0, 3, "s"), (-64, 3, 2, "c"), (-264, 1, 2, "c"), (-7, 4, 2, "s"),
                                  (144, 2, 2, "s"), (480, 0, 2, "s"), (-42, 5, 1, "c"), (-448, 3, 1, "c"),
                                  (-960, 1, 1, "c"), (5, 6, 1, "s"), (46, 4, 1, "s"), (240, 2, 1, "s"), (564, 0, 1, "s"),
                                  (-1, 7, 0, "c"), (-54, 5, 0, "c"), (-336, 3, 0, "c"), (-696, 1, 0, "c"))),
        "zl": (6, 24, 6, "D", 3, ((-60, 0, 3, "c"), (7, 4, 2, "c"), (-72, 2, 2, "c"), (-120, 0, 2, "c"), (36, 3, 2, "s"),
                                  (48, 1, 2, "s"), (-5, 6, 1, "c"), (-8, 4, 1, "c"), (144, 2, 1, "c"), (60, 0, 1, "c"),
                                  (36, 5, 1, "s"), (120, 3, 1, "s"), (96, 1, 1, "s"), (7, 6, 0, "c"), (81, 4, 0, "c"),
                                  (216, 2, 0, "c"), (120, 0, 0, "c"))),
        "ll": (5, 48, 5, "D", 3, ((36, 0, 3, "s"), (-8, 3, 2, "c"), (-24, 1, 2, "c"), (-7, 4, 2, "s"), (48, 2, 2, "s"),
                                  (96, 0, 2, "s"), (-30, 5, 1, "c"), (-128, 3, 1, "c"), (-192, 1, 1, "c"), (5, 6, 1, "s"),
                                  (46, 4, 1, "s"), (48, 2, 1, "s"), (84, 0, 1, "s"), (1, 7, 0, "c"), (-18, 5, 0, "c"),
                                  (-168, 3, 0, "c"), (-168, 1, 0, "c"))),
        "tt": (5, 0.25, 5, "C", 2, ((3, 0, 1, "s"), (-3, 1, 0, "c"), (1.5, 0, 2, "s"), (-3, 1, 1, "c"), (-1, 2, 1, "s")))},
}
#: below this ``y = 2 k H`` the numerators are summed as Taylor series (their closed forms
#: cancel: the first-order c_zz by 1e-13 at ``y = 1``, 2e-15 at ``y = 2``)
INERTIA_SERIES_Y = 2.5
_SERIES_TERMS = 22  # of the series in y^2: at INERTIA_SERIES_Y the next is below 1e-22 of the sum


_INERTIA_NAMES = [(order, name) for order in (1, 2) for name in ("zz", "zl", "ll", "tt")]


@functools.cache
def _inertia_tables():
    """The eight terms of :data:`_INERTIA_TERMS` as two matrices: the closed forms'
    numerators ``num e^{-n y}`` (``E = e^{-y}``: ``sinh(j y) e^{-n y} = (E^{n-j} - E^{n+j}) /
    2``) on the products ``E^e y^p`` that occur (listed), and the series: the coefficients
    of ``num / y^m`` in ``y^2`` (``num`` starts at ``y^m``), exact (integers over a common
    factorial) then rounded; with each term's ``a - 2 order, c, p, B, n, m``."""
    closed = {}
    series = np.zeros((len(_INERTIA_NAMES), _SERIES_TERMS))
    meta = []
    top = 2 * _SERIES_TERMS + 12
    scale = math.factorial(top)
    for row, (order, name) in enumerate(_INERTIA_NAMES):
        a, c, p, B, n, terms = _INERTIA_TERMS[order][name]
        for f, e, j, kind in terms:
            for power, sign in ((n - j, 0.5), (n + j, 0.5 if kind == "c" else -0.5)):
                closed.setdefault((power, e), np.zeros(len(_INERTIA_NAMES)))[row] += sign * f
        num = [0] * (top + 1)  # num's Taylor coefficients times 2 top! (f may be a half)
        for f, e, j, kind in terms:
            assert 2 * f == round(2 * f), f
            for i in range(0 if kind == "c" else 1, top + 1 - e, 2):
                num[i + e] += round(2 * f) * j**i * (scale // math.factorial(i))
        m = next(i for i, v in enumerate(num) if v)
        assert not any(num[m + 1::2]), (order, name)  # num / y^m is even in y
        series[row] = [v / (2 * scale) for v in num[m::2][:_SERIES_TERMS]]
        meta.append((a - 2 * order, c, p, B, n, m))
    keys = sorted(closed)
    return keys, np.array([closed[key] for key in keys]).T, series, meta


def _powers(x: np.ndarray, top: int) -> list:
    """``[x^0, x^1, ..., x^top]`` by products (an integer power of an array is a ``pow``
    call an element; ``np.vander``'s columns, strided, took 95 against 50 ms in
    :func:`_expanded_parts` on 250 000 modes)."""
    out = [np.ones_like(x), x]
    while len(out) <= top:
        out.append(out[-1] * x)
    return out


def _inertia_parts(k, H):
    """The first- and second-order terms in inertia of :func:`_static_parts`' ``zz, zl, ll,
    tt``: two tuples of real arrays (m^3, m^4, m^3, m^3 and m^5, m^6, m^5, m^5), ``G c = P0 +
    d P1 + d^2 P2 + O(d^3)`` with ``d = rho V^2 nu_x^2 / G`` (:data:`_INERTIA_TERMS`): every
    numerator at once, as a matrix product of its coefficients with the powers of ``E`` and
    ``y`` (or of ``y^2`` in the series), a block of modes at a time."""
    shape = np.shape(k)
    y = 2.0 * H * np.ravel(np.asarray(k, dtype=float))
    out = np.empty((8, y.size))
    for start in range(0, y.size, _INERTIA_BLOCK):
        _inertia_block(y[start:start + _INERTIA_BLOCK], H, out[:, start:start + _INERTIA_BLOCK])
    first, second = (tuple(r.reshape(shape) * H ** (2 * order) for r in out[4 * order - 4:4 * order])
                     for order in (1, 2))
    return first, second


def _expanded_parts(k, d, H):
    """The wave frame's compliances times ``G`` (``c_zz, c_zL/k, c_Lz/k, c_LL, c_TT``) to
    second order in a little inertia ``d = k^2 - q^2`` (:func:`_inertia_parts`), a block
    of modes at a time."""
    shape = np.shape(k)
    k, d = np.ravel(k), np.ravel(d) * (H * H)  # d H^2: P1 / H^2 and P2 / H^4 hold no H^6
    zz, zl, ll, tt = (np.empty(k.size, dtype=complex) for _ in range(4))
    P = np.empty((8, min(k.size, _INERTIA_BLOCK)))
    for start in range(0, k.size, _INERTIA_BLOCK):
        s = slice(start, start + _INERTIA_BLOCK)
        kb, db = k[s], d[s]
        Pb = P[:, :kb.size]
        _inertia_block(2.0 * H * kb, H, Pb)
        for out, p0, p1, p2 in zip((zz, zl, ll, tt), _static_parts(kb, H), Pb[:4], Pb[4:]):
            out[s] = p0 + db * (p1 + db * p2)
    zl = zl.reshape(shape)
    return zz.reshape(shape), -1j * zl, 1j * zl, ll.reshape(shape), tt.reshape(shape)


#: modes a block of :func:`_inertia_block` (in :func:`_expanded_parts`, the solver's route, and
#: :func:`_inertia_parts`): its dozens of arrays then stay in cache (250 000
#: modes in blocks of 32 768 took 89 ms, in blocks of 4096 25-33 ms; 8192: 59 ms)
_INERTIA_BLOCK = 4096


def _inertia_block(y, H, out):
    """:func:`_inertia_parts` over ``H^2`` (first order) and ``H^4`` (second) on one block
    of ``y = 2 k H``, into ``out`` (8 rows): no power of ``H`` above the second, finite up
    to :data:`MAX_THICKNESS`."""
    keys, closed, series, meta = _inertia_tables()
    scale = np.array([H**a / c for a, c, *_ in meta])  # a: the power of H less twice the order (1 or 2)
    big = np.flatnonzero(y >= INERTIA_SERIES_Y)
    if big.size:
        yb = y[big]
        E = np.exp(-yb)
        yc = np.minimum(yb, 800.0)  # past y = 745 E = 0: every power of y there meets E^(>= 1)
        Ep, Yp = _powers(E, max(e for e, _ in keys)), _powers(yc, max(p for _, p in keys))
        basis = np.empty((len(keys), yb.size))
        for row, (e, p) in zip(basis, keys):
            np.multiply(Ep[e], Yp[p], out=row)
        num = (closed * scale[:, None]) @ basis
        C = 0.5 * (1.0 + E) ** 2  # (1 + cosh y) e^{-y}
        B = {"C": _powers(1.0 / C, 3), "D": _powers(1.0 / (C + 0.5 * E * yc * yc), 3)}  # (B e^{-y})^-n
        inv_y = _powers(1.0 / yb, max(p for _, _, p, *_ in meta))
        for row, (_, _, p, b, n, _) in enumerate(meta):
            out[row, big] = num[row] * inv_y[p] * B[b][n]
    small = np.flatnonzero(y < INERTIA_SERIES_Y)
    if small.size:
        ys = y[small]
        t = ys * ys
        num = (series * scale[:, None]) @ np.array(_powers(t, _SERIES_TERMS - 1))
        ch = np.cosh(ys)
        B = {"C": _powers(1.0 / (ch + 1.0), 3), "D": _powers(1.0 / (ch + 0.5 * t + 1.0), 3)}
        for row, (_, _, p, b, n, m) in enumerate(meta):  # m - p: 0 or 2
            out[row, small] = num[row] * B[b][n] * (t if m > p else 1.0)


def _antiplane(q, H):
    """``tanh(qH) / q`` (m), even in ``q``."""
    tq = np.empty_like(q)
    sq = np.abs(q) * H < 1.0
    tq[sq] = _scaled_sinh_over(q[sq], H, np.zeros(sq.sum())) / np.cosh(q[sq] * H)
    qb = q[~sq]
    e2 = np.exp(-2 * qb * H)
    tq[~sq] = (1 - e2) / ((1 + e2) * qb)
    return tq


def _mode_parts(nu_x, nu_y, G, rho_V2, H):
    """Compliances in the wave frame: ``k``, ``c_zz``, ``c_zL/k``, ``c_Lz/k``, ``c_LL``,
    ``c_TT`` (m/Pa, or m^2/Pa for the ``/k`` ones). Without inertia (``rho_V2 = 0``) each is
    a real function of ``k`` over ``G`` (:func:`_static_parts`). A mode that sees the base
    (``kH <= DEEP_KH``) with a little inertia, ``|d| = |rho V^2 nu_x^2 / G| <= SERIES_EPS
    k^2``, takes those plus their terms of first and second order in ``d``
    (:func:`_expanded_parts`): the next term is below 0.7 ``eps^3`` of each compliance,
    rounding, and where ``kH > 3`` the couplings, themselves of order ``eps`` there, are
    nearer the truth than the general route's difference of near-equal terms (3.1e-13
    against up to 1.7e-9 of the coupling at ``eps = 4.6e-7``, against a 40-digit matrix
    exponential). The other modes take the general route, deep ones the half-space."""
    nu_x, nu_y, G = np.broadcast_arrays(
        np.asarray(nu_x, float), np.asarray(nu_y, float), np.asarray(G, complex)
    )
    k = np.hypot(nu_x, nu_y)
    if rho_V2 == 0:
        zz, zl, ll, tt = _static_parts(k, H)
        inv_G = 1.0 / G
        coupling = zl * inv_G
        return k, zz * inv_G, -1j * coupling, 1j * coupling, ll * inv_G, tt * inv_G
    d = rho_V2 * nu_x**2 / G  # k^2 - q^2
    expand = (k * H <= DEEP_KH) & (np.abs(d) <= SERIES_EPS * k * k)
    if expand.all():  # the modes near the base of a slow roll: no masking
        inv_G = 1.0 / G
        return (k, *(v * inv_G for v in _expanded_parts(k, d, H)))
    q = np.sqrt(k * k - d)  # principal root, Re q >= 0
    half = ~expand & (np.minimum(k, q.real) * H > DEEP_KH)
    if half.all():  # the common case for the high modes: no masking
        parts = [v / G for v in _wave_frame_halfspace(k, q, d)]
        return (k, *parts, 1 / (G * q))
    parts = [np.empty(k.shape, dtype=complex) for _ in range(5)]
    small = k * H <= 2.0
    regimes = (
        (expand, lambda k, q, d: _expanded_parts(k, d, H)),
        (small & ~expand, lambda k, q, d: (*_wave_frame_small(k, q, H), _antiplane(q, H))),
        (~small & ~half & ~expand, lambda k, q, d: (*_wave_frame_large(k, q, H), _antiplane(q, H))),
        (half, lambda k, q, d: (*_wave_frame_halfspace(k, q, d), 1 / q)),
    )
    for mask, fn in regimes:
        if mask.any():
            for out, val in zip(parts, fn(k[mask], q[mask], d[mask])):
                out[mask] = val / G[mask]
    return (k, *parts)


_ENTRY = {"ww": (0, 0), "wu": (0, 1), "wv": (0, 2), "uw": (1, 0), "uu": (1, 1), "uv": (1, 2),
          "vw": (2, 0), "vu": (2, 1), "vv": (2, 2)}


def compliance_blocks(nu_x, nu_y, G, rho_V2, H, blocks=tuple(_ENTRY)):
    """Entries of :func:`surface_compliance` by name (``"ww"``, ``"wu"``, ... displacement
    then traction direction), each an array of the broadcast shape (m/Pa); only the
    requested ones are formed."""
    nu_x, nu_y = np.broadcast_arrays(np.asarray(nu_x, float), np.asarray(nu_y, float))
    k, c_zz, c_zL_k, c_Lz_k, c_LL, c_TT = _mode_parts(nu_x, nu_y, G, rho_V2, H)
    nu_x, nu_y = np.broadcast_to(nu_x, k.shape), np.broadcast_to(nu_y, k.shape)
    zero = k == 0
    ks = np.where(zero, 1.0, k)
    cx = np.where(zero, 1.0, nu_x / ks)  # at k = 0, c_LL = c_TT = H/G: any unit direction
    sy = np.where(zero, 0.0, nu_y / ks)
    make = {
        "ww": lambda: c_zz,
        "wu": lambda: c_zL_k * nu_x,
        "wv": lambda: c_zL_k * nu_y,
        "uw": lambda: c_Lz_k * nu_x,
        "vw": lambda: c_Lz_k * nu_y,
        "uu": lambda: cx * cx * c_LL + sy * sy * c_TT,
        "vv": lambda: sy * sy * c_LL + cx * cx * c_TT,
        "uv": lambda: cx * sy * (c_LL - c_TT),
        "vu": lambda: cx * sy * (c_LL - c_TT),
    }
    return {b: make[b]() for b in blocks}


def surface_compliance(nu_x, nu_y, G, rho_V2, H):
    """Closed-form surface compliance ``T12 T22^-1`` of eq. 50, all nine entries.

    Parameters
    ----------
    nu_x, nu_y : array_like
        Wavenumbers (rad/m), broadcastable.
    G : array_like of complex
        Complex shear modulus at the mode's frequency ``omega = -nu_x V`` (Pa).
    rho_V2 : float
        Density (kg/m^3) times squared speed (m^2/s^2), in Pa. 0 for no inertia.
    H : float
        Layer thickness (m).

    Returns
    -------
    ndarray, shape (..., 3, 3), complex
        ``(w, u, v) = C (sigma_z, tau_xz, tau_yz)``, in m/Pa; ``sigma_z`` positive in
        tension, ``w`` positive upwards (away from the base).
    """
    parts = compliance_blocks(nu_x, nu_y, G, rho_V2, H)
    C = np.empty(parts["ww"].shape + (3, 3), dtype=complex)
    for name, (i, j) in _ENTRY.items():
        C[..., i, j] = parts[name]
    return C


#: below this ``eps = rho V^2 nu_x^2 / (G k^2)`` a deep mode's normal compliance is a series
#: (:func:`normal_compliance_outer`)
SERIES_EPS = 1e-6


def normal_compliance_outer(nu_x, nu_y, G, rho_V2, H):
    """:func:`normal_compliance` on the outer grid ``nu_x[:, None], nu_y[None, :]`` with
    one modulus ``G[i]`` per ``nu_x[i]``, fast for the many half-space modes.

    Where ``kH > 50`` and ``eps = rho V^2 nu_x^2 / (G k^2)`` is below 1e-6, the half-space
    value ``k (k + q) / (G R)`` is replaced by its expansion
    ``(1 + 3/4 eps) / (2 G k) + O(eps^2)`` (relative error ~1e-12), which needs complex
    arithmetic only along ``nu_x``; every other mode takes the exact path.
    """
    nu_x, nu_y, G = (np.asarray(a) for a in (nu_x, nu_y, G))
    k = np.hypot(nu_x[:, None], nu_y[None, :])
    b = 0.75 * rho_V2 * nu_x**2 / G
    with np.errstate(divide="ignore", invalid="ignore"):  # k = 0 is redone exactly below
        inv_k = 1.0 / k
        out = (inv_k * inv_k) * b[:, None]
        out += 1.0
        out *= inv_k
        out *= (0.5 / G)[:, None]
        exact = (k * H <= DEEP_KH) | (np.abs(b)[:, None] * inv_k**2 > 0.75 * SERIES_EPS)
    if exact.any():
        i, j = np.nonzero(exact)
        out[i, j] = normal_compliance(nu_x[i], nu_y[j], G[i], rho_V2, H)
    return out


def normal_compliance(nu_x, nu_y, G, rho_V2, H):
    """The ``w / sigma_z`` entry of :func:`surface_compliance` alone (m/Pa), cheaper."""
    return _mode_parts(nu_x, nu_y, G, rho_V2, H)[1]
