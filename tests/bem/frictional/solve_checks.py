"""The frictional solve tests' shared setting (the section 11 layer at 0.05 m/s on a 23 x 23
grid) and :func:`check_result`, which recomputes every field and figure of a result from its
forces and the definitions (eq. 51 by independent FFT products of the raw kernels, the gap,
the slip velocity, the Coulomb and stick conditions, the loading modes' equilibrium and the
record)."""

import numpy as np
import pytest

from bem import Grid, Layer, Loading, Problem, Sphere, ThreeParameterSolid
from bem.kinematics import rolling_radius, upwind_table
from bem.operator import ComplianceOperator


LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
R = 0.02
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.1, 0.1), (100, 100), (5.5e-3, 5.5e-3))  # 23 x 23, 529 nodes


def problem(indenter=Sphere(R), grid=GRID, **loading):
    return Problem(LAYER, indenter, grid, Loading(V, **(loading or {"load": 20.0})))


def _apply(grid, table, f):
    return ComplianceOperator(grid, table).apply(f)


def check_result(res, p, friction, kernels, coulomb=1e-6):
    """Every field and figure of ``res`` from its forces and the definitions; returns the
    recomputed slip velocity magnitude on the slip nodes (for further checks)."""
    g, V_ = p.grid, p.loading.speed
    X, Y = g.coordinates()
    ax = g.spacing_x
    N, Sx, Sy = res.force, res.force_x, res.force_y
    scale = np.abs(N).max()
    K = kernels
    delta = _apply(g, K["ww"], N) - _apply(g, K["wu"], Sx) - _apply(g, K["wv"], Sy)
    u = -_apply(g, K["uw"], N) + _apply(g, K["uu"], Sx) + _apply(g, K["uv"], Sy)
    v = -_apply(g, K["vw"], N) + _apply(g, K["vu"], Sx) + _apply(g, K["vv"], Sy)

    def d(b):
        return upwind_table(K[b], ax)

    dux = -_apply(g, d("uw"), N) + _apply(g, d("uu"), Sx) + _apply(g, d("uv"), Sy)
    dvx = -_apply(g, d("vw"), N) + _apply(g, d("vu"), Sx) + _apply(g, d("vv"), Sy)
    for got, want in ((res.deflection, delta), (res.displacement_x, u), (res.displacement_y, v)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * np.abs(want).max())
    s = p.indenter.profile(X, Y)
    h = s - res.indentation + delta
    reach = np.isfinite(s)
    np.testing.assert_allclose(res.gap[reach], h[reach], rtol=0, atol=1e-12 * abs(res.indentation))
    assert np.array_equal(np.isfinite(res.gap), reach)
    contact = N > 0
    np.testing.assert_array_equal(res.contact, contact)
    assert contact.sum() > 20 and not (res.stick & ~contact).any()
    assert (N >= 0).all() and not Sx[~contact].any() and not Sy[~contact].any()
    d_ = res.indentation
    gap_res = max(np.abs(h[contact]).max(), (-h[reach & ~contact]).max(initial=0.0)) / abs(d_)
    assert res.record.gap_residual == pytest.approx(gap_res, rel=1e-6, abs=1e-13)
    assert res.record.gap_residual < 1e-8
    ell = rolling_radius(p.indenter, Y, friction.radius)
    arm = p.indenter.rolling_arm(X, Y)
    om = res.omega
    wx = V_ * (1 + dux) - om * ell
    wy = V_ * dvx
    st, sl = res.stick, contact & ~res.stick
    # slip velocity: w on slip nodes, exactly 0 on stick nodes and off the contact
    np.testing.assert_allclose(res.slip_x[sl], wx[sl], rtol=0, atol=1e-12 * V_)
    np.testing.assert_allclose(res.slip_y[sl], wy[sl], rtol=0, atol=1e-12 * V_)
    assert not res.slip_x[~sl].any() and not res.slip_y[~sl].any()
    stick_res = float(np.hypot(wx, wy)[st].max(initial=0.0) / V_)
    assert res.record.stick_residual == pytest.approx(stick_res, abs=1e-13)
    assert stick_res < 1e-9
    mu = friction.mu
    smag, wmag = np.hypot(Sx, Sy), np.hypot(wx, wy)
    cone = np.maximum(smag[st] / (mu * N[st]) - 1, 0).max(initial=0.0)
    mag = np.abs(smag[sl] / (mu * N[sl]) - 1).max(initial=0.0)
    ang = (1 - (Sx * wx + Sy * wy)[sl] / (smag * wmag)[sl]).max(initial=0.0)
    assert res.record.coulomb_residual == pytest.approx(max(cone, mag, ang), abs=1e-12)
    assert res.record.coulomb_residual < coulomb
    # Q, T, R_r and its parts, eqs. 1-3 and 63
    Q = float((N * arm).sum() + Sx.sum())
    T = float(-(ell * Sx).sum())
    assert res.driving_torque == pytest.approx(T, rel=1e-12, abs=1e-15 * scale)
    if friction.mode == "torque" and mu > 0:
        assert res.driving_force == 0.0 and abs(Q) < 1e-10 * scale
    else:
        assert res.driving_force == pytest.approx(Q, rel=1e-12, abs=1e-15 * scale)
    if friction.mode == "pushed_at_top":
        assert T == pytest.approx(Q * (friction.radius or R), rel=1e-8)
    if friction.mode == "towed":
        assert abs(T) < 1e-12 * scale * R
    if friction.mode == "omega":
        assert om == friction.omega
    rr = res.driving_force + (T * om / V_)
    assert res.rolling_resistance == pytest.approx(rr, rel=1e-12, abs=1e-15 * scale)
    p_fric = float((Sx * res.slip_x + Sy * res.slip_y).sum())
    assert res.rolling_resistance_friction == pytest.approx(p_fric / V_, rel=1e-12, abs=1e-15 * scale)
    assert res.rolling_resistance_viscous == pytest.approx(rr - p_fric / V_, rel=1e-12, abs=1e-15 * scale)
    if p.loading.load is not None:
        assert res.load == pytest.approx(p.loading.load, rel=1e-12)
    else:
        assert res.indentation == p.loading.indentation
    assert res.load == pytest.approx(float(N.sum()), rel=1e-15)
    assert (res.speed, res.mu, res.mode, res.grid) == (V_, mu, friction.mode, g)
    for name in ("indentation", "load", "omega", "driving_force", "driving_torque", "rolling_resistance"):
        assert type(getattr(res, name)) is float, name
    r = res.record
    assert r.iterations == len(r.history) > 0
    last = r.history[-1]
    assert last[:2] == (int(contact.sum()), int(st.sum())) and last[3] == om
    assert last[2] <= max(friction.direction_tol, friction.set_tol if coulomb > 1e-6 else 0)
    return wmag[sl]


def synthetic_system(kernels, load=None, indentation=1e-4, omega=2.4, seed=0, flip=None, hole=None, turn=0.0, ops=None):
    """A synthetic set state on the frictionless contact of 20 N: random stick/slip
    split, slip directions (turned by ``turn`` rad) and slopes; ``hole``: a node left out
    of the contact (splitting its grid row's run in two); ``ops``: the operators of
    another such system (new ones otherwise)."""
    from bem.contact import solve_normal
    from bem.frictional import RollingOperators, RollingSetup, SetState, SetSystem
    from bem.kinematics import rolling_radius

    ops = RollingOperators(GRID, kernels) if ops is None else ops
    X, Y = GRID.coordinates()
    s = Sphere(0.02).profile(X, Y).ravel()
    N0 = solve_normal(ops.op("ww"), s.reshape(GRID.shape), load=20.0).force.ravel()
    rng = np.random.default_rng(seed)
    contact = N0 > 0
    if hole is not None:
        contact[hole] = False
    stick = contact & (rng.random(N0.size) < 0.6)
    if flip is not None:
        stick[flip] = ~stick[flip]
    ang = rng.uniform(0, 2 * np.pi, N0.size) + turn
    e = np.stack([np.cos(ang), np.sin(ang)], 1)
    k = rng.uniform(0.1, 2.0, N0.size) * V / N0.max()
    ell = rolling_radius(Sphere(0.02), Y).ravel()
    arm = Sphere(0.02).rolling_arm(X, Y).ravel()
    cons = None
    if omega is None:
        from bem.frictional.loading import constraint
        cons = constraint("pushed_at_top", arm, ell, 0.02)
    setup = RollingSetup(ops=ops, profile=s, arm=arm, ell=ell, radius=0.02, speed=V, mu=0.3, load=load,
                         indentation=indentation, omega=omega, constraint=cons)
    return SetSystem(setup, SetState(contact=contact, stick=stick & contact, direction=e, slope=k))
