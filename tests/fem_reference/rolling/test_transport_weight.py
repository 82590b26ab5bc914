"""The streamline weight of the viscous-strain transport and what the 3D rolling model
keeps in memory.

- :func:`~fem_reference.rolling.assembly.supg_weight`: Galerkin where an element is shorter
  than two memory lengths V tau, the L2 projection as V -> 0, continuous between.
- Why Galerkin there: P1 Galerkin on the 1D transport -l w' + w = 0 carries the exponential
  memory exp(x / l) node to node with a growth factor exact to (h / l)^4 / 180, against
  (h / l)^3 for the full streamline weight (the discrete growth factor, from the stencil).
- The 3D volume forms are polynomials of degree <= 2: the 4-point rule assembles the same
  system as the 11-point one.
- Pardiso's factors are released when the solve ends.
"""

from __future__ import annotations

import numpy as np
import pytest

from fem_reference import (ContactProblem, FemSettings, Indenter, Layer, Loading,
                           ThreeParameterMaterial, solve)
from fem_reference.rolling.assembly import supg_weight
from fem_reference.rolling.three_d import system as box
from fem_reference.rolling.three_d.discretization import resolve_box

H, R, P = 5e-3, 0.02, 150.0
COARSE = dict(model="3d", element_size=1.5e-3, contact_zone=9.5e-3, grading=0.5, fit_nodes=2,
              upstream=0.03, downstream=0.03, domain_radius=0.022)


def _problem(speed=0.01):
    return ContactProblem(Layer(H, 1000.0), ThreeParameterMaterial(G0=3e6, tau=0.25, f=1.0),
                          Indenter("sphere", R), Loading(load=P, speed=speed), FemSettings(**COARSE))


def test_weight_is_off_below_two_memory_lengths_and_one_at_rest():
    ell = 1e-3
    h = np.array([0.1, 1.0, 2.0, 2.0 + 1e-9, 3.0, 1e3]) * ell
    d = supg_weight(h, ell)
    assert np.all(d[:3] == 0.0) and d[3] == pytest.approx(0.0, abs=1e-9)  # continuous at h = 2 l
    assert d[4] == pytest.approx(0.2, rel=1e-14)  # (3 - 2) / (3 + 2)
    assert np.all(np.diff(d) >= 0) and d[-1] == pytest.approx(1.0, abs=5e-3)
    assert supg_weight(np.array([1e-3]), 0.0)[0] == 1.0  # V = 0: the L2 projection w = E(u)


def _growth(s, delta):
    """Discrete growth factor per element of P1 Petrov-Galerkin on -l w' + w = 0, h = s l,
    test function phi - delta l phi' (the stencil's root nearest exp(s))."""
    k = 1.0 / s
    a = k / 2 + 1 / 6 - delta * (k * k + k / 2)
    b = 2 / 3 + 2 * delta * k * k
    c = -k / 2 + 1 / 6 - delta * (k * k - k / 2)
    roots = np.roots([c, b, a])
    return roots[np.argmin(np.abs(roots - np.exp(s)))].real


@pytest.mark.parametrize("s", [0.05, 0.1, 0.2])
def test_galerkin_carries_the_memory_to_fourth_order(s):
    galerkin = np.log(_growth(s, 0.0)) / s - 1.0
    streamline = np.log(_growth(s, s / (s + 2.0))) / s - 1.0  # the full weight h / (2 l + h)
    assert galerkin == pytest.approx(s ** 4 / 180.0, rel=0.05)
    assert abs(streamline) > 10.0 * abs(galerkin)


def test_four_point_rule_assembles_the_same_3d_system(monkeypatch):
    problem = _problem()
    disc = resolve_box(problem)
    low = box.build_box_system(problem, disc)
    monkeypatch.setattr(box, "INTORDER", 4)
    high = box.build_box_system(problem, disc)
    assert low.S.shape == high.S.shape
    diff = abs(low.S - high.S).max()
    assert diff <= 1e-11 * abs(high.S).max()
    assert low.scale == pytest.approx(high.scale, rel=1e-11)


def test_pardiso_factors_are_released_after_the_solve(monkeypatch):
    pytest.importorskip("pypardiso")
    from fem_reference.linsolve import PardisoSolver

    freed = []
    original = PardisoSolver.free
    monkeypatch.setattr(PardisoSolver, "free", lambda self: (freed.append(self), original(self)))
    r = solve(_problem())
    assert r.solver.linear_solver == "pardiso" and len(freed) == 1
