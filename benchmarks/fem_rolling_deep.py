"""fem_reference's plane-strain steady rolling on a deep layer against Hunter's (1961)
half-space solution.

The case is verification/cases/rolling-halfspace-2d.toml: a rigid cylinder R = 20 mm,
P = 1000 N/m, on the paper's three-parameter solid (G0 = 3 MPa, tau = 0.25 s, f = 1),
no inertia; b0 = sqrt(P R / (pi G0)) = 1.457 mm, speeds V tau / b0 = 0.01 .. 100.
Hunter's solution is verification.analytic.hunter_rolling_contact. Errors as the
harness measures them: R_r over Hunter's peak R_r of the sweep, the edges over Hunter's
contact length at that speed.

``.venv/bin/python benchmarks/fem_rolling_deep.py`` (= ``--hunter``): every speed of
the case at the recommended configuration, H = 1000 b0 (the case's layer), h = b0 / 30 and
grading 0.5 (``--H``, ``--size`` and ``--grading`` override them),
errors against Hunter (the
harness's interior pressure RMS included), time per speed and in all.
``... --counts``: unknowns against H / b0 for the tensor-product mesh
(every x line through the depth, band Z / 2) and the default (thinned x lines, shallow
band), without solving.
``... --depth [V tau / b0]``: R_r, D / V, edges and indentation for H / b0 = 10 .. 2560,
the observed order of the depth convergence and the Richardson limit.
``... --mesh``: the element size (b0 / 20 .. b0 / 60) at H = 1000 b0, V tau / b0 = 1.
``... --lengths``: the upstream and downstream lengths halved and doubled.
``... --inertia``: an elastic layer at 0.6 of the shear-wave speed against 2D Hertz with
the moving modulus, and the same-width contact at rest on the same mesh.
``--markdown``: the tables of ``--hunter`` and ``--counts`` alone on stdout (benchmarks/collect.py).
"""

import argparse
import math
import time

import numpy as np

import fem_reference as fr
from _common import markdown_table, reporter
from fem_reference.mesh import plane_strain_strip as mesh_plane

G0, TAU, F = 3.0e6, 0.25, 1.0
R, P = 0.02, 1000.0
B0 = math.sqrt(P * R / (math.pi * G0))
SCALED = (0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0)  # the case's V tau / b0
#: recommended configuration: H = DEPTH b0 (the case's layer), element size b0 / SIZE,
#: [fem] grading GRADING (default 0.3: R_r 0.148% of the peak instead of 0.334%, 2.8 times
#: the time), the other [fem] defaults
DEPTH, SIZE, GRADING = 1000.0, 30.0, 0.5
MATERIAL = fr.ThreeParameterMaterial(G0, TAU, F)
say = print  # the running report (stderr with --markdown)
TABLES = []  # the Markdown tables of the modes run


def hunter(scaled):
    from verification.analytic import hunter_rolling_contact

    return hunter_rolling_contact(P, R, G0, TAU, F, scaled * B0 / TAU)


def solve(scaled, depth=DEPTH, size=SIZE, material=MATERIAL, density=0.0, speed=None, load=P, **fem):
    V = scaled * B0 / TAU if speed is None else speed
    problem = fr.ContactProblem(fr.Layer(depth * B0, density), material, fr.Indenter("line", R),
                                fr.Loading(load=load, speed=V),
                                fr.FemSettings(element_size=B0 / size, **fem))
    t0 = time.perf_counter()
    res = fr.solve(problem)
    return res, time.perf_counter() - t0


def errors(res, ref, peak):
    length = ref.leading_edge - ref.trailing_edge
    return ((res.rolling_resistance - ref.rolling_resistance) / peak,
            (res.rolling_resistance_energy - ref.rolling_resistance) / peak,
            (res.leading_edge - ref.leading_edge) / length,
            (res.trailing_edge - ref.trailing_edge) / length)


def pressure_rms_interior(res, ref):
    """RMS of p - p_Hunter at the FEM's multiplier nodes in the inner 90% of Hunter's
    contact, over Hunter's peak pressure (the harness's pressure_rms_interior)."""
    centre, half = ref.centre, 0.9 * ref.half_width
    x = np.asarray(res.pressure_x)
    inside = np.abs(x - centre) < half
    diff = np.asarray(res.pressure)[inside] - ref.pressure(x[inside])
    return float(np.sqrt(np.mean(diff ** 2)) / ref.peak_pressure)


def run_hunter(depth, size, grading):
    refs = [hunter(s) for s in SCALED]
    peak = max(abs(r.rolling_resistance) for r in refs)
    fem = {"grading": grading}
    say(f"H = {depth:g} b0, h = b0/{size:g}, grading {grading:g}; Hunter's peak R_r {peak:.5f} N/m")
    say(f"{'V tau/b0':>8s} {'unknowns':>8s} {'fill':>6s} {'s':>6s} {'R_r':>9s} {'Hunter':>9s} "
          f"{'dR_r/pk':>8s} {'dD/V/pk':>8s} {'lead/L':>8s} {'trail/L':>8s} {'p rms':>7s} {'e.bal.':>7s}")
    worst = np.zeros(5)
    total = 0.0
    rows = []
    for s, ref in zip(SCALED, refs):
        res, t = solve(s, depth, size, **fem)
        total += t
        e = errors(res, ref, peak) + (pressure_rms_interior(res, ref),)
        worst = np.maximum(worst, np.abs(e))
        rows.append([f"V tau / b0 = {s:g}", res.mesh.unknowns, f"{t:.1f}", f"{e[0]:+.3%}", f"{e[1]:+.3%}",
                     f"{e[2]:+.3%} / {e[3]:+.3%}", f"{e[4]:.3%}", f"{res.energy_balance:+.2%}"])
        say(f"{s:8g} {res.mesh.unknowns:8d} {res.solver.factor_nonzeros / 1e6:5.1f}M {t:6.1f} "
              f"{res.rolling_resistance:9.5f} {ref.rolling_resistance:9.5f} {e[0]:+8.3%} {e[1]:+8.3%} "
              f"{e[2]:+8.3%} {e[3]:+8.3%} {e[4]:7.3%} {res.energy_balance:+7.2%}", flush=True)
    say(f"worst: R_r {worst[0]:.3%} of the peak (D/V {worst[1]:.3%}), leading edge {worst[2]:.3%}, "
          f"trailing {worst[3]:.3%} of the contact length, interior pressure RMS {worst[4]:.3%} of the "
          f"peak; {total:.0f} s in all "
          f"({total / len(SCALED):.1f} s per speed)")
    rows.append(["**worst**, all nine speeds", "", f"{total:.0f} (all)", f"{worst[0]:.3%}", f"{worst[1]:.3%}",
                 f"{worst[2]:.3%} / {worst[3]:.3%}", f"{worst[4]:.3%}", ""])
    TABLES.append(markdown_table(
        [f"rolling-halfspace-2d, H = {depth:g} b0, h = b0 / {size:g}, grading {grading:g}", "unknowns", "wall (s)",
         "R_r - Hunter (of the peak)", "D/V - Hunter (of the peak)", "leading / trailing edge (of L)",
         "interior pressure RMS (of the peak)", "energy balance"], rows))


def run_counts():
    from fem_reference.rolling.plane_strain.discretization import resolve_plane
    from fem_reference.rolling.plane_strain.system import build_rolling_system
    import dataclasses

    say(f"{'H/b0':>6s} {'tensor unknowns':>16s} {'default unknowns':>17s} {'ratio':>6s}")
    rows = []
    for depth in (1, 4, 10, 40, 160, 640, 2560):
        problem = fr.ContactProblem(fr.Layer(depth * B0), MATERIAL, fr.Indenter("line", R),
                                    fr.Loading(load=P, speed=B0 / TAU),
                                    fr.FemSettings(element_size=B0 / SIZE))
        disc = resolve_plane(problem)
        new = build_rolling_system(problem, disc).n_unknowns
        saved = mesh_plane.ASPECT
        mesh_plane.ASPECT = None
        try:
            old = build_rolling_system(problem, dataclasses.replace(
                disc, band=min(0.5 * disc.contact_zone, depth * B0))).n_unknowns
        finally:
            mesh_plane.ASPECT = saved
        say(f"{depth:6g} {old:16d} {new:17d} {new / old:6.2f}", flush=True)
        rows.append([f"H = {depth:g} b0, h = b0 / {SIZE:g}", old, new, f"{new / old:.2f}"])
    TABLES.append(markdown_table(["layer (no solve)", "unknowns, tensor mesh (band Z/2)", "unknowns, default mesh",
                                  "ratio"], rows))


def richardson(h_values, values):
    """Order and limit from the last three values on a geometric sequence of H (ratio 2)."""
    d1, d2 = values[-2] - values[-3], values[-1] - values[-2]
    if d1 * d2 <= 0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log(abs(d1 / d2)) / math.log(2.0)
    return p, values[-1] + d2 / (2.0 ** p - 1.0)


def run_depth(scaled):
    ref = hunter(scaled)
    peak = max(abs(hunter(s).rolling_resistance) for s in SCALED)
    depths = (10, 20, 40, 80, 160, 320, 640, 1280, 2560)
    rows = []
    for depth in depths:
        res, t = solve(scaled, depth)
        rows.append((res.rolling_resistance, res.rolling_resistance_energy, res.leading_edge,
                     res.trailing_edge, res.indentation))
        e = errors(res, ref, peak)
        say(f"H = {depth:4g} b0: {res.mesh.unknowns:6d} unknowns {t:6.1f} s  R_r {rows[-1][0]:.5f}  "
              f"D/V {rows[-1][1]:.5f} N/m (Hunter {ref.rolling_resistance:.5f}: {e[0]:+.3%}, {e[1]:+.3%} of "
              f"the peak)  edges {e[3]:+.3%} / {e[2]:+.3%} of L  indentation {rows[-1][4] * 1e6:.3f} um",
              flush=True)
    for k, name in enumerate(("R_r", "D/V", "leading edge", "trailing edge")):
        vals = [r[k] for r in rows]
        diffs = np.diff(vals)
        p, lim = richardson(depths, vals)
        tail = f"order {p:.2f}, limit {lim:.6g}" if p is not None else "not monotone"
        say(f"{name}: successive changes {', '.join(f'{d:+.3g}' for d in diffs)}; {tail}")


def run_mesh():
    ref = hunter(1.0)
    peak = max(abs(hunter(s).rolling_resistance) for s in SCALED)
    for size in (20, 30, 45, 60):
        res, t = solve(1.0, DEPTH, size)
        e = errors(res, ref, peak)
        say(f"h = b0/{size}: {res.mesh.unknowns} unknowns {t:.1f} s  R_r {e[0]:+.3%} D/V {e[1]:+.3%} of the "
              f"peak, edges {e[3]:+.3%} / {e[2]:+.3%} of L, energy balance {res.energy_balance:+.3%}",
              flush=True)


def run_lengths():
    """R_r and edges at the recommended configuration with the upstream and downstream
    lengths (default Z + 8 H each) halved and doubled."""
    peak = max(abs(hunter(s).rolling_resistance) for s in SCALED)
    H = DEPTH * B0
    for scaled in (1.0, 100.0):
        base, _ = solve(scaled, grading=GRADING)
        for k in (0.5, 2.0):
            res, t = solve(scaled, grading=GRADING, upstream=k * base.mesh.upstream,
                           downstream=k * base.mesh.downstream)
            L = base.contact_length
            say(f"V tau/b0 = {scaled:g}, lengths x {k:g} ({res.mesh.upstream / H:.1f} H, "
                  f"{res.mesh.downstream / H:.1f} H): R_r {(res.rolling_resistance - base.rolling_resistance) / peak:+.2e} "
                  f"of the peak, edges {(res.trailing_edge - base.trailing_edge) / L:+.1e} / "
                  f"{(res.leading_edge - base.leading_edge) / L:+.1e} of L, {res.mesh.unknowns} unknowns "
                  f"({base.mesh.unknowns} at the defaults)", flush=True)


def run_inertia():
    rho, M = 1000.0, 0.6
    beta = math.sqrt(1 - M * M)
    g = (beta ** 3 + beta ** 2 + 3 * beta - 1) / (2 * (1 + beta))
    b = math.sqrt(P * R / (math.pi * G0 * g))
    elastic = fr.ElasticMaterial(G0)
    for size in (30, 60):
        for depth in (40, 160):
            fem = dict(contact_zone=1.5 * B0)
            moving, _ = solve(0, depth, size, elastic, rho, speed=M * math.sqrt(G0 / rho), **fem)
            rest, _ = solve(0, depth, size, fr.ElasticMaterial(G0 * g), **fem)
            say(f"h = b0/{size}, H = {depth} b0: half-width at 0.6 c_s {moving.contact_length / 2 / b - 1:+.3%} "
                  f"from Hertz with G_eff = {g:.4f} G; at rest with G_eff on the same mesh "
                  f"{rest.contact_length / 2 / b - 1:+.3%}; peak pressures {moving.peak_pressure / rest.peak_pressure - 1:+.2e} "
                  f"apart", flush=True)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--hunter", action="store_true")
    ap.add_argument("--counts", action="store_true")
    ap.add_argument("--depth", nargs="?", const=1.0, type=float, default=None, metavar="V_TAU_OVER_B0")
    ap.add_argument("--mesh", action="store_true")
    ap.add_argument("--inertia", action="store_true")
    ap.add_argument("--lengths", action="store_true")
    ap.add_argument("--H", type=float, default=DEPTH, help="H / b0 of --hunter")
    ap.add_argument("--size", type=float, default=SIZE, help="b0 / h of --hunter")
    ap.add_argument("--grading", type=float, default=GRADING, help="[fem] grading of --hunter")
    ap.add_argument("--markdown", action="store_true",
                    help="print the tables of --hunter and --counts alone, in Markdown")
    a = ap.parse_args()
    say = reporter(a.markdown)
    if a.counts:
        run_counts()
    if a.depth is not None:
        run_depth(a.depth)
    if a.mesh:
        run_mesh()
    if a.inertia:
        run_inertia()
    if a.lengths:
        run_lengths()
    if a.hunter or not (a.counts or a.depth is not None or a.mesh or a.inertia or a.lengths):
        run_hunter(a.H, a.size, a.grading)
    if a.markdown:
        print("\n\n".join(TABLES))
