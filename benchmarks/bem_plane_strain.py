"""Plane-strain BEM (bem.plane) against 2D Hertz and Hunter (1961), with timings.

Usage: ``python benchmarks/bem_plane_strain.py [--per-b0 N] [--depth H_OVER_B0 ...] [--speeds K]
[--markdown]`` (default depths 3000 and 10000 b0; the table: one row per depth).

* 2D Hertz: elastic layer of the same depth, cylinder with b / R = 1e-3 (the exact circle
  is a parabola to 1e-7), half-width and peak pressure.
* Hunter: the paper's three-parameter solid with f = 2 (G0 = 1 MPa, tau = 1 s) on a thick
  layer, over ``K`` speeds log-spaced in ``V tau / b0`` from 0.01 to 100 (``b0`` the relaxed
  Hertz half-width, 1 mm): rolling resistance, its energy figure, both edges and the
  pressure RMS, against :func:`verification.analytic.hunter_rolling_contact`; the grid is
  ``a = b0 / N`` (default N = 100.37, not commensurate with the contact), period 3 H,
  ``N_t = L / (2 a)``.

Dense contact solves of a few hundred nodes are BLAS-bound: on a loaded 2-core machine a
multi-threaded BLAS spins (a 300-node solve took 0.16 s instead of 7 ms); run with
``OPENBLAS_NUM_THREADS=1`` for stable figures (the first line says which).
"""

import argparse
import math
import os
import time

import numpy as np
from _common import machine, markdown_table, reporter

from bem import Elastic, Layer, Loading, Problem, ThreeParameterSolid, solve
from bem.indenters import LineCylinder
from bem.plane import LineGrid
from verification.analytic import hertz_line_contact, hunter_rolling_contact

ap = argparse.ArgumentParser()
ap.add_argument("--per-b0", type=float, default=100.37)
ap.add_argument("--depth", type=float, nargs="+", default=[3000.0, 10000.0], help="H / b0")
ap.add_argument("--speeds", type=int, default=13)
ap.add_argument("--markdown", action="store_true", help="print the results table alone, in Markdown")
args = ap.parse_args()
say = reporter(args.markdown)

G0, TAU, F, R, B0 = 1e6, 1.0, 2.0, 1.0, 1e-3
P = math.pi * G0 * B0**2 / R
say(machine(), "| OPENBLAS_NUM_THREADS =", os.environ.get("OPENBLAS_NUM_THREADS", "unset"),
    "| load average", " ".join(f"{v:.1f}" for v in os.getloadavg()))


def grid(H):
    a = B0 / args.per_b0
    L = 3 * H
    return LineGrid.centred(a, L, math.ceil(L / (2 * a)), 1.5 * B0)


rows = []
for depth in args.depth:
    H = depth * B0
    g = grid(H)
    t = time.perf_counter()
    res = solve(Problem(Layer(H, Elastic(G0)), LineCylinder(R), g, Loading(0.0, load=P)))
    tm = res.record.times
    wall = time.perf_counter() - t
    hz = hertz_line_contact(P, R, G0)
    hertz = (res.half_width / hz.half_width - 1, res.peak_pressure / hz.peak_pressure - 1)
    say(f"grid: a = b0/{args.per_b0:g}, H = {depth:g} b0, L = 3 H, Nt = {g.truncation}, {g.nodes} nodes")
    say(f"2D Hertz: half-width {hertz[0]:+.2e}, peak pressure {hertz[1]:+.2e}, centre "
        f"{res.contact_centre / B0:+.1e} b0; kernel {tm['kernel_s']:.2f} s, solve {tm['solve_s']:.3f} s, "
        f"wall {wall:.2f} s")

    say(f"{'V tau/b0':>9} {'R_r/P':>10} {'BEM':>9} {'energy':>9} {'lead':>9} {'trail':>9} {'p RMS':>8} {'s':>6}")
    worst = {"R_r": 0.0, "energy": 0.0, "edge": 0.0, "rms": 0.0}
    walls = []
    total = time.perf_counter()
    layer = Layer(H, ThreeParameterSolid(G0, TAU, F))
    for s in np.logspace(-2, 2, args.speeds):
        V = s * B0 / TAU
        hu = hunter_rolling_contact(P, R, G0, TAU, F, V)
        t = time.perf_counter()
        res = solve(Problem(layer, LineCylinder(R), g, Loading(V, load=P)))
        tm = res.record.times
        walls.append(time.perf_counter() - t)
        L2 = 2 * hu.half_width
        e_rr = res.rolling_resistance / hu.rolling_resistance - 1
        e_en = res.rolling_resistance_energy / hu.rolling_resistance - 1
        e_l = (res.leading_edge - hu.leading_edge) / L2
        e_t = (res.trailing_edge - hu.trailing_edge) / L2
        x = res.x
        inside = (x > hu.trailing_edge + g.spacing) & (x < hu.leading_edge - g.spacing)
        rms = float(np.sqrt(np.mean((res.pressure_profile - hu.pressure(x))[inside] ** 2)) / hu.peak_pressure)
        worst.update(R_r=max(worst["R_r"], abs(e_rr)), energy=max(worst["energy"], abs(e_en)),
                     edge=max(worst["edge"], abs(e_l), abs(e_t)), rms=max(worst["rms"], rms))
        say(f"{s:9.3g} {hu.rolling_resistance_coefficient:10.4e} {e_rr:+9.2e} {e_en:+9.2e} {e_l:+9.2e} "
            f"{e_t:+9.2e} {rms:8.1e} {walls[-1]:6.2f}")
    sweep = time.perf_counter() - total
    say(f"worst: R_r {worst['R_r']:.2e}, energy figure {worst['energy']:.2e}, edges {worst['edge']:.2e} of the "
        f"contact length, pressure RMS (interior) {worst['rms']:.2e} of the peak; sweep {sweep:.1f} s")
    rows.append([f"three-parameter solid (f = 2), H = {depth:g} b0, a = b0 / {args.per_b0:g}", g.truncation,
                 f"{hertz[0]:+.1e} / {hertz[1]:+.1e}", f"{worst['R_r']:.1e}", f"{worst['energy']:.1e}",
                 f"{worst['edge']:.1e}", f"{worst['rms']:.1e}", f"{min(walls):.2f}-{max(walls):.2f}", f"{sweep:.1f}"])
if args.markdown:
    print(markdown_table(
        ["layer and grid", "N_t", "elastic vs 2D Hertz: half-width / peak pressure",
         f"worst over {args.speeds} speeds V tau / b0 = 0.01..100 vs Hunter: R_r", "energy figure",
         "edges (of 2 b)", "pressure RMS (of the peak)", "per speed (s)", "sweep (s)"], rows))
