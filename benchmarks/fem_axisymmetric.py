"""Timing of the axisymmetric fem_reference on the paper's thick case (section 10.1).

Prints, per indenter and element size, the wall time and the contact radius error against
the finest run (h = 5e-5 m, nested) and against Jaffar's 4.559 mm for the paraboloid. Run:
``python benchmarks/fem_axisymmetric.py [--markdown]``.
"""

import time

from _common import markdown_mode, markdown_table, reporter

from fem_reference import ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading, solve


def run(shape, h, refine=0):
    t0 = time.perf_counter()
    res = solve(ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter(shape, 0.02),
                               Loading(load=100.0), FemSettings(element_size=h, refine=refine)))
    return res, time.perf_counter() - t0


if __name__ == "__main__":
    markdown = markdown_mode()
    say = reporter(markdown)
    rows = []
    for shape in ("paraboloid", "sphere"):
        ref, t_ref = run(shape, 4e-4, refine=3)
        say(f"{shape}: reference h = 5e-5 m (nested), {ref.mesh.unknowns} unknowns, {t_ref:.1f} s, "
            f"radius {ref.contact_radius * 1e3:.4f} mm")
        for h in (4e-4, 2e-4, 1e-4, 5e-5):
            res, t = run(shape, h)
            jaffar = f"{res.contact_radius / 4.559e-3 - 1:+.3%}"
            say(f"  h = {h:.0e} m: {res.mesh.unknowns:6d} unknowns, {t:6.2f} s, radius "
                f"{res.contact_radius * 1e3:.4f} mm ({res.contact_radius / ref.contact_radius - 1:+.3%}"
                f" vs reference, {jaffar} vs Jaffar), "
                f"d {res.indentation:.5e} m, p_max {res.peak_pressure:.5e} Pa")
            rows.append([f"thick layer (H = 5 mm, P = 100 N), {shape} R = 20 mm, h = {h * 1e3:g} mm",
                         res.mesh.unknowns, f"{t:.2f}", f"{res.contact_radius * 1e3:.4f}",
                         f"{res.contact_radius / ref.contact_radius - 1:+.3%}",
                         jaffar if shape == "paraboloid" else ""])
    if markdown:
        print(markdown_table(["case", "unknowns", "wall (s)", "contact radius (mm)",
                              "vs h = 0.05 mm nested", "vs Jaffar's 4.559 mm"], rows))
