"""The frictional tests' second setting: the section 11 layer at 0.05 m/s on the coarse
grid of a 0.2 m period (23 x 23 nodes, 0.5 mm), and a synthetic active-set state on its
frictionless contact of 150 N (random stick/slip split, slip directions and slopes)."""

import numpy as np

from bem import Layer, Sphere, ThreeParameterSolid
from bem.grid import Grid
from bem.kinematics import rolling_radius


LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
V = 0.05
GRID = Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (5.5e-3, 5.5e-3))


def synthetic_state(kernels, seed=0):
    """A synthetic active-set state on the frictionless contact of the coarse grid:
    random stick/slip split, slip directions and slip-law slopes."""
    from bem.contact import solve_normal
    from bem.frictional import RollingOperators

    ops = RollingOperators(GRID, kernels)
    X, Y = GRID.coordinates()
    s = Sphere(0.02).profile(X, Y)
    N0 = solve_normal(ops.op("ww"), s, load=150.0).force.ravel()
    rng = np.random.default_rng(seed)
    C = np.flatnonzero(N0 > 0)
    stick = np.zeros(N0.size, bool)
    stick[C] = rng.random(C.size) < 0.7
    ang = rng.uniform(0, 2 * np.pi, N0.size)
    e = np.stack([np.cos(ang), np.sin(ang)], 1)
    k = rng.uniform(0.1, 2.0, N0.size) * V / N0.max()
    ell = rolling_radius(Sphere(0.02), Y).ravel()
    arm = Sphere(0.02).rolling_arm(X, Y).ravel()
    return ops, s.ravel(), C, stick, e, k, ell, arm


def synthetic_row_system(kernels, load, indentation, omega, mode="pushed_at_top", contact=None):
    from bem.frictional import RollingSetup, SetState, SetSystem
    from bem.frictional.loading import constraint

    ops, s, C, stick, e, k, ell, arm = synthetic_state(kernels)
    if contact is not None:
        C = contact
    cons = None if omega is not None else constraint(mode, arm, ell, 0.02)
    setup = RollingSetup(ops=ops, profile=s, arm=arm, ell=ell, radius=0.02, speed=V, mu=0.2, load=load,
                         indentation=indentation, omega=omega, constraint=cons)
    inside = np.zeros(s.size, bool)
    inside[C] = True
    return SetSystem(setup, SetState(contact=inside, stick=stick & inside, direction=e, slope=k)), C
