"""A deliberately simple "method" for the verification harness: Hertz's formulas.

It shows the plugin protocol: a function ``solve(problem, level) -> Run`` that takes a
case's ``[problem]`` (the checked dict of the case-file schema, SI units) and a refinement
level, and returns the harness's result type. Put it through every gate the BEM is held to::

    verify --case halfspace-hertz --method hertz=examples/hertz_method.py:solve

Hertz is exact for a half-space and wrong for a thin layer; the gates say so. To ship a
method in a package instead, register it under the entry-point group
``viscolayer.methods`` in that package's pyproject.toml::

    [project.entry-points."viscolayer.methods"]
    hertz = "mypackage.hertz_method:solve"
"""

import time

import numpy as np

from verification.results import Level, Run


def solve(problem: dict, level: Level) -> Run:
    """Hertz contact of the case's indenter on an incompressible half-space (E* = 4G)."""
    t0 = time.perf_counter()
    if problem["material"]["model"] != "elastic" or "load" not in problem["loading"]:
        raise ValueError("the Hertz 'method' solves elastic contact under a given load only")
    G, P, R = problem["material"]["shear_modulus"], problem["loading"]["load"], problem["indenter"]["radius"]
    a = (3 * P * R / (4 * 4 * G)) ** (1 / 3)
    p0 = 3 * P / (2 * np.pi * a**2)
    r = np.linspace(0.0, 1.5 * a, 301)
    pressure = p0 * np.sqrt(np.clip(1 - (r / a) ** 2, 0.0, None))
    scalars = {"contact_radius": a, "indentation": a**2 / R, "peak_pressure": p0, "load": P}
    return Run("hertz", level.size, scalars, r, pressure, time.perf_counter() - t0)
