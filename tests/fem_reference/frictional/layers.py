"""Shared layers of the frictional FEM tests: the problems and their condensed
compliances, made once per test process (each factorization costs seconds)."""

from __future__ import annotations

import functools

import numpy as np

from fem_reference import (ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading,
                           ThreeParameterMaterial)
from fem_reference.frictional import surface_compliance

#: the Carter layer: R = 5 cm, P' = 250 N/m, G = 1 MPa (a = 1.995 mm), V = 1 cm/s
RADIUS, LOAD, MODULUS, SPEED, ZONE = 0.05, 250.0, 1.0e6, 0.01, 3.0e-3


def elastic_problem(thickness: float, h: float, speed: float = SPEED) -> ContactProblem:
    """The cylinder on an incompressible elastic layer ``thickness`` (m) thick, element
    size ``h`` (m) on the zone |x| <= 3 mm."""
    return ContactProblem(Layer(thickness), ElasticMaterial(MODULUS), Indenter("line", RADIUS),
                          Loading(load=LOAD, speed=speed), FemSettings(element_size=h, contact_zone=ZONE))


def viscous_problem(h: float) -> ContactProblem:
    """The cylinder on a 5 mm three-parameter layer (G0 = 1 MPa, tau = 0.2 s, f = 10: V tau
    = 2 mm, about the contact's half-width), element size ``h`` (m)."""
    return ContactProblem(Layer(0.005), ThreeParameterMaterial(MODULUS, 0.2, 10.0), Indenter("line", RADIUS),
                          Loading(load=LOAD, speed=SPEED), FemSettings(element_size=h, contact_zone=ZONE))


@functools.lru_cache(maxsize=None)
def elastic(thickness: float, h: float, speed: float = SPEED):
    problem = elastic_problem(thickness, h, speed)
    return problem, surface_compliance(problem)


@functools.lru_cache(maxsize=None)
def viscous(h: float):
    problem = viscous_problem(h)
    return problem, surface_compliance(problem)


def assert_coulomb(r, tol: float = 1e-9) -> None:
    """The discrete conditions the result must satisfy, recomputed from its arrays: N >= 0,
    zero gap-side forces off contact, |S| <= mu N, |S| = mu N and S w >= 0 on slip, w = 0
    on stick (to ``tol`` of the scales)."""
    N, S, w = r.normal, r.tangential, r.slip_velocity
    scale = N.max()
    assert np.all(N >= -tol * scale)
    assert np.all(np.abs(N[~r.contact]) <= tol * scale) and np.all(np.abs(S[~r.contact]) <= tol * scale)
    assert np.all(np.abs(S) <= r.mu * N * (1 + tol) + tol * scale)
    assert np.allclose(np.abs(S[r.slip]), r.mu * N[r.slip], rtol=1e-9, atol=tol * scale)
    assert np.all(S[r.slip] * w[r.slip] >= -tol * scale * r.speed)
    assert np.all(np.abs(w[r.stick]) <= 1e-9 * r.speed)
