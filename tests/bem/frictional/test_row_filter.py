"""bem.frictional.operators' row filter and its use in the line preconditioner: its symbol against the identity that
defines it, its transform against a translation, and what it is for (fewer GMRES
iterations on a converged frictional state)."""

from dataclasses import replace

import numpy as np
import pytest

from bem import Elastic, Grid, Layer, Loading, Paraboloid, Problem
from bem.frictional import Friction, SolverOptions, solve_friction
from bem.frictional import RollingOperators
from bem.frictional import active_set
from bem.frictional.preconditioner import LinePreconditioner
from bem.linear import fgmres
from bem.problem import compute_kernels
from bem.spectral import BLOCKS

# an elastic paraboloid on a thick layer (R = 20 mm, P = 100 N, mu = 0.2, creepage 0.01)
# on a 31 x 31 grid of 0.4 mm
G, H, R, P, MU, V, XI = 3.0e6, 0.2, 0.02, 100.0, 0.2, 1.0, 0.01
SPACING = 0.4e-3
GRID = Grid.centred((SPACING, SPACING), (0.6, 0.6), (750, 750), (6e-3, 6e-3))
PROBLEM = Problem(Layer(H, Elastic(G), 0.0), Paraboloid(R), GRID, Loading(V, load=P))
FRICTION = Friction(MU, "omega", omega=V * (1 - XI) / R, radius=R, dense_limit=0)
LONG = SolverOptions().filter_long  # the row filter's default power on the longest waves


@pytest.fixture(scope="module")
def kernels():
    return compute_kernels(PROBLEM, BLOCKS)[0]


def test_the_row_symbol_is_the_full_symbol_averaged_over_ky(kernels):
    """``row_filter(1) = C_row / C`` with ``C`` the symbol of the kernel wrapped onto the
    filter's period and ``C_row`` that of its row through the origin, which is ``C``
    averaged over ``k_y`` (a DFT identity, not how the code forms it): checked where
    ``|C|`` is above the filter's floor (every mode here), for ``ww, uu, vv``;
    ``row_filter(0.5) ** 2 = row_filter(1)``; the single-precision copy. The period is
    the transform-friendly length from 1.5 times the nodes a side on, within ``[K, 2 K -
    2]``."""
    ops = RollingOperators(GRID, kernels)
    assert ops.filter_size == (48, 48)  # 31 nodes: 47 -> 48, at most 60
    one, half = ops.row_filter(1.0), ops.row_filter(0.5)
    assert one.shape == (3, 48, 25)
    for c, name in enumerate(("ww", "uu", "vv")):
        table = kernels[name]
        # offsets within half the period at their true values (GRID is 31 x 31: centre 30)
        d = np.arange(48)
        d = np.where(d > 24, d - 48, d)
        cut = table[np.ix_(30 + d, 30 + d)].copy()
        cut[24, :] = 0.5 * (table[30 + 24, 30 + d] + table[30 - 24, 30 + d])
        cut[:, 24] = 0.5 * (table[30 + d, 30 + 24] + table[30 + d, 30 - 24])
        cut[24, 24] = 0.25 * (table[54, 54] + table[6, 54] + table[54, 6] + table[6, 6])
        full = np.fft.rfft2(cut)
        above = np.abs(full) >= 1e-3 * np.abs(full).max()
        row = np.broadcast_to(full.mean(axis=0), full.shape)
        np.testing.assert_allclose((one[c] * full)[above], row[above], rtol=1e-10,
                                   atol=1e-12 * np.abs(row).max())
        # wrapped, the symbols keep above the floor (1e-3 of the largest modulus; measured
        # 3.5e-3 and 3.7e-3 at their smallest): no mode is floored here
        assert above.all()
        assert np.abs(one[c] - 1).max() > 0.5  # the neighbouring rows matter
    np.testing.assert_allclose(half ** 2, one, rtol=1e-12)
    single = ops.row_filter(0.5, np.complex64)
    assert single.dtype == np.complex64 and ops.row_filter(0.5) is half
    np.testing.assert_allclose(single, half, rtol=1e-6)


def test_the_long_wave_power_blends_into_the_short_wave_power(kernels):
    """``row_filter(p, long=L, waves=w)``: ``(C_row / C) ** L`` on the zero wave, and in
    the limits of ``w`` the one-power filters, ``** p`` (``w -> 0``, but for the zero
    wave) and ``** L`` (``w -> inf``); in between each entry's exponent lies between ``p`` and ``L``,
    nearer ``L`` on longer waves."""
    ops = RollingOperators(GRID, kernels)
    one, short, long = ops.row_filter(1.0), ops.row_filter(0.5), ops.row_filter(0.8)
    tiny = ops.row_filter(0.5, long=0.8, waves=1e-9).copy()
    np.testing.assert_allclose(tiny[:, 0, 0], long[:, 0, 0], rtol=1e-12)  # the zero wave keeps L
    tiny[:, 0, 0] = short[:, 0, 0]
    np.testing.assert_allclose(tiny, short, rtol=1e-12)
    np.testing.assert_allclose(ops.row_filter(0.5, long=0.8, waves=1e12), long, rtol=1e-12)
    mid = ops.row_filter(0.5, long=0.8, waves=3.0)
    np.testing.assert_allclose(mid[:, 0, 0], long[:, 0, 0], rtol=1e-12)
    real = np.abs(one.imag) < 1e-12 * np.abs(one) + 1e-300
    pos = real & (one.real > 0) & (np.abs(np.log(np.abs(one))) > 1e-3)
    q = np.log(np.abs(mid[pos])) / np.log(np.abs(one[pos]))
    assert q.min() >= 0.5 - 1e-9 and q.max() <= 0.8 + 1e-9 and q.max() - q.min() > 0.25
    # along the first row of the embedding (k_y = 0) the exponent falls as k_x grows
    row = np.log(np.abs(mid[0, 0, 1:])) / np.log(np.abs(one[0, 0, 1:]))
    assert np.all(np.diff(row[np.abs(np.log(np.abs(one[0, 0, 1:]))) > 1e-3]) <= 1e-9)
    assert ops.row_filter(0.5, long=0.8, waves=3.0) is mid  # kept
    # the Gaussian's width: on the k_y = 0 row, one wave-width from zero the exponent has
    # come 1 - 1/e of the way to p, two widths 1 - e^-4
    Ey, width = ops.filter_size
    n1 = 3 * GRID.nodes_x / width  # the waves across the grid at k_x index 3
    at = ops.row_filter(0.5, long=0.8, waves=n1)
    for i, want in ((3, 0.5 + 0.3 / np.e), (6, 0.5 + 0.3 * np.exp(-4))):
        got = np.log(np.abs(at[:, 0, i])) / np.log(np.abs(one[:, 0, i]))
        np.testing.assert_allclose(got, want, rtol=1e-9)
    # the default width is the solver's
    assert ops.row_filter(0.5, long=0.8) is ops.row_filter(0.5, long=0.8, waves=SolverOptions().filter_waves)


def test_filter_on_is_a_convolution_on_the_nodes(kernels):
    """With the spectrum of a shift by one node along ``x`` and two along ``y``,
    ``filter_on`` moves each value to its neighbour (0 entering), per row of values,
    read back on a node subset."""
    ops = RollingOperators(GRID, kernels)
    Ey, Ex = ops.filter_size
    ky = np.fft.fftfreq(Ey)[:, None]
    kx = np.fft.rfftfreq(Ex)[None, :]
    shift = np.exp(-2j * np.pi * (2 * ky + 1 * kx))
    Ky, Kx = GRID.shape
    rng = np.random.default_rng(3)
    values = rng.normal(size=(3, Ky, Kx))
    # two node sets in turn (the read-back positions are kept for the last one), in double
    # and in single precision (measured 4e-7 of the largest value)
    for nodes in (np.flatnonzero(rng.random(Ky * Kx) < 0.5), np.flatnonzero(rng.random(Ky * Kx) < 0.3)):
        held = np.zeros((3, Ky * Kx))
        held[:, nodes] = values.reshape(3, -1)[:, nodes]
        held = held.reshape(3, Ky, Kx)
        want = np.zeros_like(held)
        want[:, 2:, 1:] = held[:, :-2, :-1]
        want = want.reshape(3, -1)[:, nodes]
        for spectra, tol in ((np.stack([shift] * 3), 1e-12), (np.stack([shift] * 3).astype(np.complex64), 2e-6)):
            got = ops.filter_on(nodes, values.reshape(3, -1)[:, nodes], spectra)
            assert got.dtype == (np.float32 if tol > 1e-9 else np.float64)
            np.testing.assert_allclose(got, want, rtol=0, atol=tol * np.abs(values).max())


def test_the_row_filter_cuts_gmres_iterations_on_a_converged_state(kernels, monkeypatch):
    """On the converged fine system of the 31 x 31 case, GMRES from zero to 1e-10 |b|
    with the lines alone and with the row filter (``filter_power``, one power, and the default
    blend into ``filter_long``): measured 40, 22 and 21 iterations; asserted at least a third
    fewer, all on the same solution (measured within 5e-8 of the largest entry; the
    residual, 1e-10 |b|, allows no better; 1e-6 asserted). The blend's own gain shows on
    longer runs (test below)."""
    systems = []
    solve = active_set.LinearSolves.__call__
    monkeypatch.setattr(active_set.LinearSolves, "__call__",
                        lambda self, system, *a, **k: systems.append(system) or solve(self, system, *a, **k))
    solve_friction(PROBLEM, FRICTION, kernels=kernels, energy=False)
    system = [s for s in systems if s.ops.grid.shape == GRID.shape][-1]
    assert system.nC > 400 and system.A.size and system.B.size
    out = {}
    for power, long in ((0, None), (0.5, None), (0.5, LONG)):
        LinePreconditioner(dtype=np.float64, options=SolverOptions(filter_power=power, filter_long=long)).attach(system)
        x, ok, its = fgmres(system.matvec, system.b, system.precondition,
                            tol=1e-10 * np.linalg.norm(system.b), restart=300, maxiter=2)
        assert ok
        out[long if power else 0] = x, its
    for key in (None, LONG):
        assert out[key][1] <= 0.65 * out[0][1], (out[0][1], out[key][1])
        np.testing.assert_allclose(out[key][0], out[0][0], rtol=0, atol=1e-6 * np.abs(out[0][0]).max())


def test_the_long_wave_blend_cuts_gmres_iterations_on_longer_runs(monkeypatch):
    """The elastic paraboloid at creepage 0.01 on a 61 x 61 grid (0.2 mm, runs of up to 52
    nodes), the converged fine system, GMRES from zero to 1e-10 |b|: the row filter at one
    power against the default blend into ``filter_long`` over ``filter_waves``: measured 27 against 24
    iterations (single precision, as in the solver); asserted at least 2 fewer (a count
    that may move by one with the machine's rounding)."""
    grid = Grid.centred((0.2e-3, 0.2e-3), (0.6, 0.6), (1500, 1500), (6e-3, 6e-3))
    problem = Problem(Layer(H, Elastic(G), 0.0), Paraboloid(R), grid, Loading(V, load=P))
    friction = Friction(MU, "omega", omega=V * (1 - XI) / R, radius=R)
    systems = []
    solve = active_set.LinearSolves.__call__
    monkeypatch.setattr(active_set.LinearSolves, "__call__",
                        lambda self, system, *a, **k: systems.append(system) or solve(self, system, *a, **k))
    solve_friction(problem, friction, energy=False)
    system = [s for s in systems if s.ops.grid.shape == grid.shape][-1]
    its = {}
    for long in (None, LONG):
        LinePreconditioner(options=SolverOptions(filter_long=long)).attach(system)
        x, ok, its[long] = fgmres(system.matvec, system.b, system.precondition,
                                  tol=1e-10 * np.linalg.norm(system.b), restart=300, maxiter=2)
        assert ok
    assert its[LONG] <= its[None] - 2, its


def test_a_filtered_solve_ends_on_the_lines_alone_state(kernels):
    """The filter changes the path, not the answer: the same contact and stick sets and
    forces within 1e-9 of the largest with ``filter_power = 0``, both runs converged to a
    slip misfit of 1e-9 (``direction_tol``; with the default 1e-7 a run may end at any
    misfit below it: measured, the lines alone ended at 8.1e-8, forces 5.4e-9 of the
    largest from the run that went on to 3e-11)."""
    friction = replace(FRICTION, direction_tol=1e-9)
    a, _ = solve_friction(PROBLEM, friction, kernels=kernels, energy=False)
    b, _ = solve_friction(PROBLEM, friction, kernels=kernels, energy=False, options=SolverOptions(filter_power=0))
    assert max(a.record.history[-1][2], b.record.history[-1][2]) <= 1e-9
    assert b.record.linear_iterations > a.record.linear_iterations
    assert np.array_equal(a.stick, b.stick) and np.array_equal(a.contact, b.contact)
    scale = a.force.max()
    for u, w in ((a.force, b.force), (a.force_x, b.force_x), (a.force_y, b.force_y)):
        np.testing.assert_allclose(u, w, rtol=0, atol=1e-9 * scale)
