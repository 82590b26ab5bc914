"""Timing of the axisymmetric fem_reference on the paper's thick case (section 10.1).

Prints, per element size, the wall time and the contact radius error against the
finest run (and against Jaffar's 4.559 mm for the paraboloid). Run:
``.venv/bin/python benchmarks/fem_axisymmetric.py``.
"""

import time

from fem_reference import ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading, solve


def run(shape, h, refine=0):
    t0 = time.perf_counter()
    res = solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter(shape, 0.02),
                               Loading(load=100.0), FemSettings(element_size=h, refine=refine)))
    return res, time.perf_counter() - t0


if __name__ == "__main__":
    for shape in ("paraboloid", "sphere"):
        ref, t_ref = run(shape, 4e-4, refine=3)
        print(f"{shape}: reference h = 5e-5 m (nested), {ref.mesh.unknowns} unknowns, {t_ref:.1f} s, "
              f"radius {ref.contact_radius * 1e3:.4f} mm")
        for h in (4e-4, 2e-4, 1e-4, 5e-5):
            res, t = run(shape, h)
            print(f"  h = {h:.0e} m: {res.mesh.unknowns:6d} unknowns, {t:6.2f} s, radius "
                  f"{res.contact_radius * 1e3:.4f} mm ({res.contact_radius / ref.contact_radius - 1:+.3%}"
                  f" vs reference, {res.contact_radius / 4.559e-3 - 1:+.3%} vs Jaffar), "
                  f"d {res.indentation:.5e} m, p_max {res.peak_pressure:.5e} Pa")
