"""Timing and mesh convergence of fem_reference's plane-strain steady rolling.

The case: a rigid cylinder R = 20 mm, P = 500 N/m, on a layer H = 1 mm (H/b about 1.5)
of the paper's three-parameter solid (G0 = 3 MPa, tau = 0.25 s, f = 1), rolling at
V = 0.01 m/s (V tau_1 / b = 1.9, near the loss peak), no inertia.

``.venv/bin/python benchmarks/fem_rolling_2d.py``: one solve at the default
discretization, timed (stages from the solver record).
``... --convergence [h0]``: three nested meshes (h0 = 1e-4 m = b/6 by default, refined
once and twice),
the change of R_r, edges, indentation and energy balance between them, and the
Richardson estimate where the sequence is monotone (else the spread is the estimate).
``... --lengths``: R_r with the upstream and downstream lengths changed.
``--markdown`` (default and ``--convergence``): the results table alone on stdout.
"""

import sys
import time

import fem_reference as fr
from _common import markdown_mode, markdown_table, reporter

R, P, H, V = 0.02, 500.0, 1.0e-3, 0.01
MATERIAL = fr.ThreeParameterMaterial(3.0e6, 0.25, 1.0)


def solve(**fem):
    t0 = time.perf_counter()
    res = fr.solve(fr.ContactProblem(fr.Layer(H), MATERIAL, fr.Indenter("line", R),
                                     fr.Loading(load=P, speed=V), fr.FemSettings(**fem)))
    return res, time.perf_counter() - t0


HEAD = ["case", "unknowns", "wall (s)", "R_r (N/m)", "D/V (N/m)", "edges (mm)", "indentation (um)",
        "energy balance"]


def row(res, t, label):
    """One table row: the case by its mesh, then the figures in the units of ``HEAD``."""
    return [f"cylinder on H = 1 mm, V tau_1 / b = 1.9, {label}", res.mesh.unknowns, f"{t:.1f}",
            f"{res.rolling_resistance:.6f}", f"{res.rolling_resistance_energy:.6f}",
            f"{res.trailing_edge * 1e3:.5f} / {res.leading_edge * 1e3:.5f}", f"{res.indentation * 1e6:.5f}",
            f"{res.energy_balance:+.3%}"]


def line(res, t, label):
    return (f"{label:>22s}: {res.mesh.unknowns:7d} unknowns {t:7.1f} s  R_r {res.rolling_resistance:.6f} N/m  "
            f"edges [{res.trailing_edge * 1e3:.5f}, {res.leading_edge * 1e3:.5f}] mm  "
            f"d {res.indentation * 1e6:.5f} um  energy balance {res.energy_balance:+.3%}  "
            f"D/V {res.rolling_resistance_energy:.6f} N/m")


def richardson(values, ratio=2.0):
    """(estimate, observed order) from three values on meshes h, h/2, h/4, or (None, None)
    when the differences change sign (no asymptotic range)."""
    d1, d2 = values[1] - values[0], values[2] - values[1]
    if d1 == 0 or d2 == 0 or d1 * d2 < 0 or abs(d2) >= abs(d1):
        return None, None
    import math

    order = math.log(abs(d1 / d2)) / math.log(ratio)
    return values[2] + d2 / (ratio ** order - 1.0), order


if __name__ == "__main__":
    markdown = markdown_mode()
    say = reporter(markdown)
    if "--convergence" in sys.argv:
        h0 = float(sys.argv[sys.argv.index("--convergence") + 1]) if len(sys.argv) > 2 else 1e-4
        runs = [solve(element_size=h0, refine=k) for k in range(3)]
        rows = []
        for (res, t), k in zip(runs, range(3)):
            say(line(res, t, f"h = {h0 / 2 ** k:.2e} m"))
            rows.append(row(res, t, f"h = {h0 / 2 ** k:.2e} m (nested)"))
        limits = {}
        for name in ("rolling_resistance", "rolling_resistance_energy", "leading_edge", "trailing_edge", "indentation",
                     "contact_length"):
            vals = [getattr(r, name) for r, _ in runs]
            est, order = richardson(vals)
            scale = {"leading_edge": 1e3, "trailing_edge": 1e3, "indentation": 1e6}.get(name, 1.0)  # mm, um
            limits[name] = f"{est * scale:.6g} (order {order:.2f})" if est is not None else "not monotone"
            tail = (f"Richardson {est:.6g} (order {order:.2f}); finest vs it {vals[2] / est - 1:+.3%}"
                    if est is not None else
                    f"not monotone: spread of the two finest {abs(vals[2] / vals[1] - 1):.3%}")
            say(f"{name:>18s}: {vals[0]:.6g} {vals[1]:.6g} {vals[2]:.6g}; changes "
                  f"{vals[1] / vals[0] - 1:+.3%}, {vals[2] / vals[1] - 1:+.3%}; {tail}")
        rows.append(["Richardson", "", "", limits["rolling_resistance"], limits["rolling_resistance_energy"],
                     f"{limits['trailing_edge']} / {limits['leading_edge']}", limits["indentation"], ""])
        if markdown:
            print(markdown_table(HEAD, rows))
    elif "--lengths" in sys.argv:
        base, t = solve(element_size=5e-5)
        say(line(base, t, "default lengths"))
        for up, down in ((0.0047, None), (0.017, None), (None, 0.012), (None, 0.043),
                         (0.032, 0.086)):
            res, t = solve(element_size=5e-5, upstream=up, downstream=down)
            say(line(res, t, f"up {up} down {down}") +
                  f"  R_r {res.rolling_resistance / base.rolling_resistance - 1:+.4%}")
    else:
        res, t = solve()
        say(line(res, t, "default"))
        say({k: round(v, 2) for k, v in res.solver.times.items()})
        if markdown:
            print(markdown_table(HEAD, [row(res, t, f"default mesh (h = {res.mesh.element_size:.2e} m)")]))
