"""Unit tests of bem.materials: exact identities, limits, interpolation error bounds, validation."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from bem.case import material_from_config
from bem.materials import (
    Elastic,
    MasterCurveTable,
    Prony,
    ThreeParameterSolid,
)

OMEGA = np.concatenate([[0.0], np.logspace(-6, 6, 241)])
OMEGA = np.concatenate([-OMEGA[::-1], OMEGA])  # symmetric, with +0.0 and -0.0

PAPER = ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0)  # section 11.1
PRONY3 = Prony(G_inf=1.0e6, G=(2.0e6, 1.0e6, 5.0e5), tau=(1.0e-3, 0.1, 10.0))


def _table_from(model, per_decade, lo=-5, hi=5):
    w = np.logspace(lo, hi, (hi - lo) * per_decade + 1)
    g = model.modulus(w)
    return MasterCurveTable(w, g.real, g.imag)


def _models():
    return [Elastic(3.0e6), PAPER, PRONY3, _table_from(PRONY3, 10)]


# ---------------------------------------------------------------- identities and limits


@pytest.mark.parametrize("G0, tau, f", [(3.0e6, 0.25, 1.0), (1.0e5, 1.0e-3, 9.0), (7.0e6, 40.0, 0.01)])
def test_three_parameter_equals_its_prony_equivalent(G0, tau, f):
    # Spring G1 in series with Kelvin (G2, eta): G0 = G1 G2/(G1+G2), f = G1/G2, tau = eta/G2.
    # Its relaxation function is G0 + G0 f exp(-t (1+f)/tau): a one-term Prony series.
    three = ThreeParameterSolid(G0, tau, f)
    prony = Prony(G_inf=G0, G=(G0 * f,), tau=(tau / (1 + f),))
    a, b = three.modulus(OMEGA), prony.modulus(OMEGA)
    assert np.max(np.abs(a - b) / np.abs(b)) < 1e-14
    assert three.relaxation_time == tau / (1 + f)


@pytest.mark.parametrize("model", _models(), ids=lambda m: type(m).__name__)
def test_limits_passivity_symmetry_and_shape(model):
    g0 = model.modulus(0.0)
    assert g0.shape == () and g0.imag == 0 and g0.real == model.relaxed_modulus
    g_high = model.modulus(1e40)
    assert abs(g_high.real - model.glassy_modulus) <= 1e-13 * model.glassy_modulus
    assert abs(g_high.imag) <= 1e-13 * model.glassy_modulus
    g = model.modulus(OMEGA)
    assert g.dtype == complex and g.shape == OMEGA.shape
    assert np.all(g[OMEGA > 0].imag >= 0)  # passivity (time dependence exp(+i omega t))
    assert np.all(g.real > 0)
    assert np.array_equal(model.modulus(-OMEGA), np.conj(g))  # G*(-w) = conj G*(w), exactly
    grid = OMEGA[:6].reshape(2, 3)
    assert np.array_equal(model.modulus(grid), g[:6].reshape(2, 3))


def test_closed_form_limits():
    assert PAPER.relaxed_modulus == 3.0e6 and PAPER.glassy_modulus == 6.0e6
    assert PRONY3.relaxed_modulus == 1.0e6 and PRONY3.glassy_modulus == 4.5e6
    # eq. 71 at omega tau = 1 + f: G' = G0 (1+f) (1 + (1+f)) / (2 (1+f)), G'' = G0 f / 2
    g = PAPER.modulus(2.0 / 0.25)
    assert g == pytest.approx(3.0e6 * 2 * 3 / 4 + 1j * 3.0e6 / 2, rel=1e-15)
    # a single Maxwell branch peaks at omega tau = 1 with G'' = G_1 / 2
    one = Prony(1.0, (2.0,), (0.5,))
    assert one.modulus(2.0) == pytest.approx(1.0 + 2.0 * (0.5 + 0.5j), rel=1e-15)
    assert np.all(Elastic(2.5).modulus(OMEGA) == 2.5)


# ---------------------------------------------------------------- the table


def test_table_reproduces_its_nodes_exactly():
    w = np.logspace(-3, 3, 13) * np.pi
    g = PRONY3.modulus(w)
    table = MasterCurveTable(w, g.real, g.imag)
    assert np.array_equal(table.modulus(w), g)
    assert np.array_equal(table.modulus(-w), np.conj(g))


def _log_second_derivatives(model: Prony, w):
    """d^2 log G' / d(log w)^2 and d^2 log G'' / d(log w)^2 of a Prony model, in closed form.

    With s = (w tau)^2 and r = w tau: s/(1+s) has x-derivatives 2s/(1+s)^2 and
    4s(1-s)/(1+s)^3; r/(1+r^2) has r(1-r^2)/(1+r^2)^2 and r(1-6r^2+r^4)/(1+r^2)^3.
    """
    G, tau = np.asarray(model.G), np.asarray(model.tau)
    s, r = (w[:, None] * tau) ** 2, w[:, None] * tau
    p0 = model.G_inf + (G * s / (1 + s)).sum(1)
    p1 = (G * 2 * s / (1 + s) ** 2).sum(1)
    p2 = (G * 4 * s * (1 - s) / (1 + s) ** 3).sum(1)
    l0 = (G * r / (1 + r**2)).sum(1)
    l1 = (G * r * (1 - r**2) / (1 + r**2) ** 2).sum(1)
    l2 = (G * r * (1 - 6 * r**2 + r**4) / (1 + r**2) ** 3).sum(1)
    return p2 / p0 - (p1 / p0) ** 2, l2 / l0 - (l1 / l0) ** 2


def test_log_second_derivatives_match_finite_differences():
    x, dx = np.linspace(-8, 8, 41), 1e-4
    for part, d2 in zip((np.real, np.imag), _log_second_derivatives(PRONY3, np.exp(x))):
        logg = lambda x: np.log(part(PRONY3.modulus(np.exp(x))))  # noqa: E731
        fd = (logg(x + dx) - 2 * logg(x) + logg(x - dx)) / dx**2
        assert np.allclose(d2, fd, atol=1e-5)


def _interpolation_errors(per_decade):
    """Relative errors of G', G'' between nodes and their proven bounds, interval by interval.

    Linear interpolation of a C^2 function f on an interval of width h errs by at most
    h^2/8 max|f''|; here f = log G(log w), so |G_interp / G - 1| <= exp(h^2/8 max|f''|) - 1.
    """
    table = _table_from(PRONY3, per_decade)
    nodes = np.log(np.asarray(table.omega))
    h = nodes[1] - nodes[0]
    t = np.linspace(0, 1, 65)[1:-1]
    x = nodes[:-1, None] + h * t  # (intervals, points)
    w = np.exp(x)
    exact, approx = PRONY3.modulus(w), table.modulus(w)
    d2p, d2l = (d.reshape(w.shape) for d in _log_second_derivatives(PRONY3, w.ravel()))
    result = []
    for part, d2 in ((np.real, d2p), (np.imag, d2l)):
        err = np.abs(part(approx) / part(exact) - 1)
        bound = np.expm1(h**2 / 8 * np.abs(d2).max(axis=1, keepdims=True) * 1.01)
        result.append((err, bound))
    return result


def test_table_interpolation_error_is_within_the_second_order_bound():
    # 10 points per decade: h = ln(10)/10 = 0.23, the bound is h^2/8 max|f''|.
    for err, bound in _interpolation_errors(10):
        assert np.all(err <= bound)
        assert np.max(err / bound) > 0.9  # the bound is attained: linear interpolation, nothing better
    (ep, _), (el, _) = _interpolation_errors(10)
    assert ep.max() < 2e-3 and el.max() < 7e-3  # measured 1.5e-3 (G') and 6.4e-3 (G'')


def test_table_interpolation_converges_at_second_order():
    coarse, fine = _interpolation_errors(10), _interpolation_errors(20)
    for (ec, _), (ef, _) in zip(coarse, fine):
        assert 3.8 < ec.max() / ef.max() < 4.2


def test_table_outside_its_range_and_zero_loss():
    table = MasterCurveTable((1.0, 100.0), (1.0e6, 4.0e6), (2.0e5, 1.0e5))
    assert table.modulus(10.0) == pytest.approx(2.0e6 + 1j * math.sqrt(2.0e10), rel=1e-15)  # power law
    assert table.modulus(0.25) == pytest.approx(1.0e6 + 0.5e5j, rel=1e-15)  # G'' ~ omega below
    assert table.modulus(400.0) == pytest.approx(4.0e6 + 0.25e5j, rel=1e-15)  # G'' ~ 1/omega above
    assert table.modulus(-400.0) == pytest.approx(4.0e6 - 0.25e5j, rel=1e-15)
    assert table.relaxed_modulus == 1.0e6 and table.glassy_modulus == 4.0e6
    elastic = MasterCurveTable((1.0, 100.0), (1.0e6, 4.0e6), (0.0, 0.0))
    assert np.all(elastic.modulus(OMEGA).imag == 0)
    mixed = MasterCurveTable((1.0, 100.0), (1.0e6, 1.0e6), (0.0, 2.0e5))
    assert mixed.modulus(10.0) == pytest.approx(1.0e6 + 1.0e5j, rel=1e-15)  # G'' linear in log w


# ---------------------------------------------------------------- validation


@pytest.mark.parametrize(
    "build, message",
    [
        (lambda: Elastic(-3.0), "shear_modulus must be > 0 Pa, got -3.0"),
        (lambda: Elastic(0), "shear_modulus must be > 0 Pa, got 0.0"),
        (lambda: Elastic(float("nan")), "shear_modulus must be a finite real number (Pa), got nan"),
        (lambda: Elastic("3e6"), "shear_modulus must be a finite real number (Pa), got '3e6'"),
        (lambda: Elastic(True), "shear_modulus must be a finite real number (Pa), got True"),
        (lambda: ThreeParameterSolid(0.0, 0.25, 1.0), "G0 must be > 0 Pa, got 0.0"),
        (lambda: ThreeParameterSolid(3e6, -0.25, 1.0), "tau must be > 0 s, got -0.25"),
        (lambda: ThreeParameterSolid(3e6, 0.25, -1.0), "f must be >= 0 (dimensionless), got -1.0"),
        (lambda: ThreeParameterSolid(3e6, math.inf, 1.0), "tau must be a finite real number (s), got inf"),
        (lambda: Prony(-1.0, (1.0,), (1.0,)), "G_inf must be > 0 Pa, got -1.0"),
        (lambda: Prony(1.0, (1.0, -2.0), (1.0, 1.0)), "G[1] must be > 0 Pa, got -2.0"),
        (lambda: Prony(1.0, (1.0,), (0.0,)), "tau[0] must be > 0 s, got 0.0"),
        (lambda: Prony(1.0, (1.0, 2.0), (1.0,)), "G and tau must have the same length, got 2 and 1"),
        (lambda: Prony(1.0, 2.0, (1.0,)), "G must be a 1-D sequence of numbers (Pa), got 2.0"),
        (lambda: MasterCurveTable((1.0,), (1.0,), (0.0,)), "a master curve table needs at least 2 rows, got 1"),
        (
            lambda: MasterCurveTable((1.0, 2.0), (1.0, 1.0), (0.0,)),
            "omega, storage and loss must have the same length, got 2, 2, 1",
        ),
        (lambda: MasterCurveTable((1.0, 2.0), (1.0, -1.0), (0.0, 0.0)), "storage must be > 0 Pa, got -1.0 at row 1"),
        (lambda: MasterCurveTable((1.0, 2.0), (1.0, 0.0), (0.0, 0.0)), "storage must be > 0 Pa, got 0.0 at row 1"),
        (lambda: MasterCurveTable((1.0, 2.0), (1.0, 1.0), (-5.0, 0.0)), "loss must be >= 0 Pa, got -5.0 at row 0"),
        (lambda: MasterCurveTable((0.0, 2.0), (1.0, 1.0), (0.0, 0.0)), "omega must be > 0 rad/s, got 0.0 at row 0"),
        (lambda: MasterCurveTable((-1.0, 2.0), (1.0, 1.0), (0.0, 0.0)), "omega must be > 0 rad/s, got -1.0 at row 0"),
        (
            lambda: MasterCurveTable((1.0, 3.0, 2.0), (1.0,) * 3, (0.0,) * 3),
            "omega must be strictly increasing (sorted, no duplicates), got 2.0 after 3.0 at row 2",
        ),
        (
            lambda: MasterCurveTable((1.0, 2.0, 2.0), (1.0,) * 3, (0.0,) * 3),
            "omega must be strictly increasing (sorted, no duplicates), got 2.0 after 2.0 at row 2",
        ),
        (lambda: MasterCurveTable((1.0, 2.0), (1.0, math.nan), (0.0, 0.0)), "storage must be finite, got nan at row 1"),
        (lambda: MasterCurveTable((1.0, math.inf), (1.0, 1.0), (0.0, 0.0)), "omega must be finite, got inf at row 1"),
        (lambda: MasterCurveTable((1.0, 2.0), (1.0, 1.0), (0.0, -math.inf)), "loss must be finite, got -inf at row 1"),
        (
            lambda: MasterCurveTable([[1.0, 2.0]], (1.0, 1.0), (0.0, 0.0)),
            "omega must be a 1-D sequence, got an array of shape (1, 2)",
        ),
    ],
)
def test_validation_messages(build, message):
    with pytest.raises(ValueError, match=re.escape(message) + "$"):
        build()


def test_fields_are_normalized_and_frozen():
    p = Prony(1, [2, 3], np.array([0.1, 1.0]))
    assert p == Prony(1.0, (2.0, 3.0), (0.1, 1.0)) and isinstance(p.G, tuple)
    with pytest.raises(AttributeError):
        p.G_inf = 2.0


# ---------------------------------------------------------------- CSV


def test_from_csv_round_trip(tmp_path):
    table = _table_from(PRONY3, 3, lo=-2, hi=2)
    lines = ["# master curve of a three-term Prony model", "omega, G', G''  # header"]
    lines += [f"{w!r}, {gs!r},{gl!r}" for w, gs, gl in zip(table.omega, table.storage, table.loss)]
    lines.insert(5, "   # a comment in the middle")
    lines.insert(7, "")
    path = tmp_path / "curve.csv"
    path.write_text("\n".join(lines) + "\n")
    assert MasterCurveTable.from_csv(path) == table
    assert MasterCurveTable.from_csv(str(path)) == table
    (tmp_path / "bare.csv").write_text("1, 2e6, 0\n10, 3e6, 1e5\n")  # no header
    assert MasterCurveTable.from_csv(tmp_path / "bare.csv") == MasterCurveTable((1, 10), (2e6, 3e6), (0, 1e5))


@pytest.mark.parametrize(
    "text, message",
    [
        ("omega,G',G''\n1,2,3\n10,2\n", "{path} line 3: expected 3 comma-separated columns (omega, G', G''), got 2"),
        ("1,2,3\n10,2,3,4\n", "{path} line 2: expected 3 comma-separated columns (omega, G', G''), got 4"),
        ("omega,G',G''\n1,2,3\nten,2,3\n", "{path} line 3: could not parse numbers from 'ten,2,3'"),
        ("# c\nomega,G',G''\n1,2,3\n# c\n10,-2,3\n", "storage must be > 0 Pa, got -2.0 at {path} line 5"),
        (
            "1,2,3\n1,2,3\n",
            "omega must be strictly increasing (sorted, no duplicates), got 1.0 after 1.0 at {path} line 2",
        ),
        ("1,2,3\n10,2,nan\n", "loss must be finite, got nan at {path} line 2"),
        ("omega,G',G''\n1,2,3\n", "a master curve table needs at least 2 rows, got 1"),
        ("# only a comment\n", "a master curve table needs at least 2 rows, got 0"),
    ],
)
def test_from_csv_errors_name_the_line(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=re.escape(message.format(path=path)) + "$"):
        MasterCurveTable.from_csv(path)


# ---------------------------------------------------------------- case files


def test_material_from_config_each_model(tmp_path):
    assert material_from_config({"model": "elastic", "shear_modulus": 3.0e6}, tmp_path) == Elastic(3.0e6)
    three = {"model": "three_parameter", "G0": 3.0e6, "tau": 0.25, "f": 1}
    assert material_from_config(three, tmp_path) == PAPER
    prony = {"model": "prony", "G_inf": 1.0e6, "G": [2.0e6, 1.0e6], "tau": [0.1, 1.0]}
    assert material_from_config(prony, tmp_path) == Prony(1.0e6, (2.0e6, 1.0e6), (0.1, 1.0))
    (tmp_path / "curves").mkdir()
    (tmp_path / "curves" / "m.csv").write_text("omega,G',G''\n1,2e6,1e5\n10,3e6,2e5\n")
    table = material_from_config({"model": "table", "file": "curves/m.csv"}, tmp_path)
    assert table == MasterCurveTable((1.0, 10.0), (2e6, 3e6), (1e5, 2e5))


@pytest.mark.parametrize(
    "section, message",
    [
        ({"shear_modulus": 1.0}, "material.model is missing (allowed: elastic, three_parameter, prony, table, dma)"),
        (
            {"model": "maxwell"},
            "material.model must be one of elastic, three_parameter, prony, table, dma, got 'maxwell'",
        ),
        (
            {"model": "elastic", "shear_modulus": 1.0, "G0": 1.0},
            "unknown key material.G0 for model 'elastic' (allowed keys: model, shear_modulus)",
        ),
        (
            {"model": "three_parameter", "G0": 1.0, "tau": 1.0},
            "material.f is missing for model 'three_parameter' (required keys: G0, tau, f)",
        ),
        (
            {"model": "prony", "G_inf": 1.0, "G": [1.0]},
            "material.tau is missing for model 'prony' (required keys: G_inf, G, tau)",
        ),
        ({"model": "table"}, "material.file is missing for model 'table' (required keys: file)"),
        ({"model": "table", "file": 3}, "material.file must be a path string, got 3"),
        ({"model": "elastic", "shear_modulus": -3.0}, "shear_modulus must be > 0 Pa, got -3.0"),
    ],
)
def test_material_from_config_errors(tmp_path, section, message):
    with pytest.raises(ValueError, match=re.escape(message) + "$"):
        material_from_config(section, tmp_path)


# ---------------------------------------------------------------- DMA data in a case


def _dma_csv(path, law, temperatures=(273.15, 293.15, 313.15)) -> None:
    """Isotherms of PRONY3 under ``law`` at 0.1-100 Hz (K, rad/s, shear Pa)."""
    w = 2 * np.pi * np.logspace(-1, 2, 10)
    rows = ["temperature_K,omega_rad_s,G_storage_Pa,G_loss_Pa"]
    for T in temperatures:
        g = PRONY3.modulus(w * 10.0 ** float(law.log_aT(T)))
        rows += [f"{T!r},{float(x)!r},{float(a)!r},{float(b)!r}" for x, a, b in zip(w, g.real, g.imag)]
    path.write_text("\n".join(rows) + "\n")


def test_shifted_prony_is_the_time_temperature_identity():
    """b_T G*_ref(a_T omega) equals the series with moduli times b_T and times times a_T."""
    from bem.dma.case import shifted_prony

    for log_a, log_b in ((2.5, 0.0), (-3.0, 0.02)):
        moved = shifted_prony(PRONY3, log_a, log_b)
        np.testing.assert_allclose(moved.modulus(OMEGA), 10 ** log_b * PRONY3.modulus(10 ** log_a * OMEGA),
                                   rtol=1e-13, atol=0)


def test_material_from_config_dma_at_a_service_temperature(tmp_path):
    from bem.dma import WLF

    law = WLF(8.86, 101.6, 293.15)
    (tmp_path / "data").mkdir()
    _dma_csv(tmp_path / "data" / "dma.csv", law)
    sec = {"model": "dma", "file": "data/dma.csv", "reference_temperature": 293.15, "C1": 8.86, "C2": 101.6,
           "terms_per_decade": 3.0}
    at_ref = material_from_config(sec, tmp_path)
    assert isinstance(at_ref, Prony)
    hot = material_from_config({**sec, "temperature": 313.15}, tmp_path)
    a_T = 10.0 ** (-8.86 * 20.0 / 121.6)
    np.testing.assert_allclose(hot.modulus(OMEGA), at_ref.modulus(a_T * OMEGA), rtol=1e-12)
    w = np.logspace(-0.5, 2.5, 31) / a_T  # the data's range at 313.15 K, away from its ends
    assert np.max(np.abs(hot.modulus(w) / PRONY3.modulus(a_T * w) - 1)) < 0.01  # the fit of exact data
    table = material_from_config({k: v for k, v in sec.items() if k != "terms_per_decade"} | {"form": "table"},
                                 tmp_path)
    assert isinstance(table, MasterCurveTable) and table.omega[0] < 1.0 < table.omega[-1]


@pytest.mark.parametrize("extra, message", [
    ({"temperatur": 300.0}, "[material]: unknown key 'temperatur' for model = \"dma\""),
    ({"temperature": 0.0}, "[material] temperature must be > 0 K, got 0.0"),
    ({"C1": 8.86}, "C1 = 8.86 is given without C2"),
])
def test_material_from_config_dma_errors(tmp_path, extra, message):
    from bem.dma import WLF

    _dma_csv(tmp_path / "dma.csv", WLF(8.86, 101.6, 293.15))
    with pytest.raises(ValueError, match=re.escape(message)):
        material_from_config({"model": "dma", "file": "dma.csv", "reference_temperature": 293.15, **extra}, tmp_path)
