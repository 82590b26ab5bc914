"""Size and timing of the 3D (quarter cylinder) fem_reference, thick case.

For each element size prints unknowns, wall time, peak memory (RSS) and the
differences against the axisymmetric reference (h = 5e-5 m). Element sizes (m)
from the command line, default 6e-4 4e-4 3e-4:
``python benchmarks/fem_3d.py [6e-4 3e-4] [--markdown]``.
"""

import resource
import sys
import time

from _common import markdown_mode, markdown_table, reporter

from fem_reference import ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer, Loading, solve


def problem(**fem):
    return ContactProblem(Layer(5e-3), ElasticMaterial(3e6), Indenter("paraboloid", 0.02),
                          Loading(load=100.0), FemSettings(**fem))


if __name__ == "__main__":
    markdown = markdown_mode()
    say = reporter(markdown)
    sizes = [float(s) for s in sys.argv[1:]] or [6e-4, 4e-4, 3e-4]
    ref = solve(problem(element_size=5e-5))
    rows = []
    for h in sizes:
        t0 = time.perf_counter()
        zone = max(6e-3, 4.6e-3 + 3.6 * h)  # room for the edge fit, few candidate nodes
        res = solve(problem(model="3d", element_size=h, contact_zone=zone),
                    progress=lambda s: print("   ", s, file=sys.stderr, flush=True)
                    if "compliance" not in s else None)
        t = time.perf_counter() - t0
        rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024 ** 2
        diffs = {k: getattr(res, k) / getattr(ref, k) - 1 for k in ("contact_radius", "indentation", "peak_pressure")}
        times = ", ".join(f"{k} {v:.1f}" for k, v in res.solver.times.items())
        say(f"h = {h:.1e} m: {res.mesh.elements} tets, {res.mesh.unknowns} unknowns "
            f"({res.mesh.displacement_dofs} + {res.mesh.pressure_dofs} DOFs), "
            f"{res.mesh.contact_nodes} contact nodes, {t:.1f} s [{times}], "
            f"peak RSS {rss:.2f} GiB; vs axisymmetric: "
            + ", ".join(f"{k} {v:+.3%}" for k, v in diffs.items()))
        rows.append([f"thick layer, paraboloid, 3D quarter, h = {h * 1e3:g} mm", res.mesh.unknowns, f"{t:.1f}",
                     f"{rss:.2f}"] + [f"{v:+.2%}" for v in diffs.values()])
    if markdown:
        print(markdown_table(["case", "unknowns", "wall (s)", "peak RSS (GiB)", "contact radius vs axisymmetric",
                              "indentation vs axisymmetric", "peak pressure vs axisymmetric"], rows))
