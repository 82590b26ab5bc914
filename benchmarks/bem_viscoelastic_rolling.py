"""Frictionless steady rolling on a viscoelastic half-space against the elastic solve of the
same grid: GMRES iterations and solve time side by side.

The case: a rigid paraboloid ``R = 20 mm`` rolling at ``V = 0.05 m/s`` under ``P = 150 N``
on a layer thick enough to stand for the half-space (``H = 0.2 m``, ``rho = 0``, period
``L = 0.6 m``, ``Nt = L / 2a`` rounded up) of the standard linear solid of the paper
(``ThreeParameterSolid(G0=3 MPa, tau=0.25 s, f=1)``: the shear modulus rises from 3 MPa at
zero frequency to 6 MPa at high frequency, creep time 0.25 s, so ``V tau = 12.5 mm``,
about the contact's length). The elastic reference: the same grid, load and indenter on
``Elastic(3 MPa)``. Grids centred, half-width 7 mm (``--half-width``), spacing 0.09 mm
(155 x 155 nodes) and 0.18 mm (77 x 77; ``--spacing``).

Printed per grid: the kernels (s), then for each material the solve (:func:`bem.contact.
solve_normal` with its multilevel start; wall and CPU seconds, the median of ``--repeat``
solves, the two materials alternated), its active-set iterations, the GMRES iterations on
the fine grid and on all levels together, the contact nodes, the indentation and the
rolling resistance ``R_r = sum F x / R`` (N; > 0 with the contact shifted to the
leading edge, ``x > 0``; "all levels" counts every GMRES iteration of the solve, those of a
coarse level that the solver drops included: the elastic contact reaches the edge of the
20 x 20 level below 155 x 155, whose iterations are in no result's record); the ratios
viscoelastic / elastic of the
GMRES iterations (deterministic) and of the solve times (the median of the pairs' ratios,
each pair run back to back). CPU time counts every thread (:func:`bem.operator.fft_workers`
puts large transforms on every core; these grids' embeddings, up to 320 x 320, stay on one
thread while scipy.fft is not loaded).

Run with one BLAS thread: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bem_viscoelastic_rolling.py
--repeat 5``; ``--markdown`` prints the summary table alone on stdout (the running report on
stderr) for ``benchmarks/collect.py``.
"""

import argparse
import math
import os
import time

import numpy as np

from _common import machine, markdown_mode, markdown_table, peak_rss_mb, reporter

from bem import Elastic, Grid, Layer, Loading, Paraboloid, Problem, ThreeParameterSolid
from bem import linear
from bem.contact import solve_normal
from bem.linear import fgmres
from bem.operator import ComplianceOperator
from bem.problem import compute_kernels

H, L, R, P, V = 0.2, 0.6, 0.02, 150.0, 0.05
SLS = ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0)
ELASTIC = Elastic(3.0e6)
markdown = markdown_mode() if __name__ == "__main__" else False
say = reporter(markdown)


def problem(material, spacing: float, half_width: float) -> Problem:
    """The rolling paraboloid on ``material`` at ``spacing`` (m), half-width ``half_width`` (m)."""
    nt = int(math.ceil(L / (2 * spacing) - 1e-9))
    grid = Grid.centred((spacing, spacing), (L, L), (nt, nt), (half_width, half_width))
    return Problem(Layer(H, material, 0.0), Paraboloid(R), grid, Loading(V, load=P))


def levels(res) -> list:
    """``res`` and its coarse-grid starts, finest first."""
    out = []
    while res is not None:
        out.append(res)
        res = res.coarse
    return out


def prepared(material, spacing: float, half_width: float):
    """(operator, profile, rolling arm, kernel seconds) of one case."""
    p = problem(material, spacing, half_width)
    kernels, seconds = compute_kernels(p, ("ww",))
    X, Y = p.grid.coordinates()
    return ComplianceOperator(p.grid, kernels["ww"]), p.indenter.profile(X, Y), p.indenter.rolling_arm(X, Y), seconds


def timed_solve(op, profile, arm):
    t0, c0 = time.perf_counter(), time.process_time()
    res = solve_normal(op, profile, load=P, arm=arm)
    return res, time.perf_counter() - t0, time.process_time() - c0


def every_iteration(op, profile, arm) -> int:
    """GMRES iterations of one solve on every level, a dropped coarse level's included:
    :func:`bem.linear.fgmres` counted at each call (an untimed solve)."""
    counted = []

    def counting(*args, **kwargs):
        out = fgmres(*args, **kwargs)
        counted.append(out[2])
        return out

    linear.fgmres = counting
    try:
        solve_normal(op, profile, load=P, arm=arm)
    finally:
        linear.fgmres = fgmres
    return sum(counted)


SUMMARY: list = []


def run(spacing: float, half_width: float, repeat: int) -> None:
    cases = {"viscoelastic": prepared(SLS, spacing, half_width), "elastic": prepared(ELASTIC, spacing, half_width)}
    times = {name: ([], []) for name in cases}
    results = {}
    for i in range(repeat):
        order = list(cases) if i % 2 == 0 else list(cases)[::-1]
        for name in order:
            op, profile, arm, _ = cases[name]
            results[name], wall, cpu = timed_solve(op, profile, arm)
            times[name][0].append(wall)
            times[name][1].append(cpu)
    grid = cases["elastic"][0].grid
    say(f"spacing {spacing * 1e3:g} mm: {grid.nodes_x} x {grid.nodes_y} nodes, Nt = {grid.truncation_x}")
    row = {}
    for name, (_, _, _, kernel_s) in cases.items():
        res = results[name]
        lv = levels(res)
        fine, total = res.record.linear_iterations, every_iteration(*cases[name][:3])
        wall, cpu = float(np.median(times[name][0])), float(np.median(times[name][1]))
        rr = res.rolling_resistance
        say(f"  {name}: kernels {kernel_s:.2f} s; solve {wall:.3f} s wall, {cpu:.3f} s CPU (median of {repeat}); "
            f"{res.record.iterations} active-set iterations, GMRES {fine} fine, {total} on all levels "
            f"({' / '.join(str(r.record.linear_iterations) for r in lv)} from "
            f"{' / '.join(str(r.grid.nodes_x) for r in lv)} nodes a side in the records, "
            f"{total - sum(r.record.linear_iterations for r in lv)} on dropped levels); {int(res.contact.sum())} contact nodes, "
            f"d = {res.indentation:.6e} m, R_r = {rr:.6g} N")
        row[name] = (int(res.contact.sum()), kernel_s, wall, cpu, res.record.iterations, fine, total, rr)
    pairs = np.array(times["viscoelastic"][0]) / np.array(times["elastic"][0])
    v, e = row["viscoelastic"], row["elastic"]
    say(f"  viscoelastic / elastic: GMRES {v[5] / e[5]:.2f} fine, {v[6] / e[6]:.2f} all levels; "
        f"solve time {np.median(pairs):.2f} (median of the pairs; {pairs.min():.2f}-{pairs.max():.2f}); "
        f"peak RSS {peak_rss_mb():.0f} MB")
    SUMMARY.append((f"{spacing * 1e3:g} mm, {grid.nodes_x} x {grid.nodes_y}", v, e, v[5] / e[5], v[6] / e[6],
                    float(np.median(pairs))))


def print_summary() -> None:
    head = ("grid", "contact nodes visco / elastic", "kernels visco / elastic (s)", "visco solve (s)",
            "visco solve CPU (s)", "visco active-set / GMRES fine / all levels", "elastic solve (s)",
            "elastic solve CPU (s)", "elastic active-set / GMRES fine / all levels",
            "GMRES visco / elastic, fine / all", "solve time visco / elastic", "visco R_r (N)")
    rows = [[g, f"{v[0]} / {e[0]}", f"{v[1]:.2f} / {e[1]:.2f}", f"{v[2]:.3f}", f"{v[3]:.3f}",
             f"{v[4]} / {v[5]} / {v[6]}", f"{e[2]:.3f}", f"{e[3]:.3f}", f"{e[4]} / {e[5]} / {e[6]}",
             f"{rf:.2f} / {ra:.2f}", f"{rt:.2f}", f"{v[7]:.6g}"] for g, v, e, rf, ra, rt in SUMMARY]
    table = markdown_table(head, rows)
    print(table if markdown else "\nsummary\n" + table)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, nargs="*", default=[0.09e-3, 0.18e-3], help="node spacings (m)")
    ap.add_argument("--half-width", type=float, default=7e-3, help="half-width of the grid (m)")
    ap.add_argument("--repeat", type=int, default=3, help="solves of each material, alternated")
    args = ap.parse_args()
    say(machine(), "| load average", " ".join(f"{x:.2f}" for x in os.getloadavg()))
    for a in args.spacing:
        run(a, args.half_width, args.repeat)
    print_summary()
    say("load average at the end", " ".join(f"{x:.2f}" for x in os.getloadavg()))
