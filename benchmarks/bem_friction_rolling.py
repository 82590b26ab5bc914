"""Frictional steady rolling of an elastic paraboloid against CONTACT's figures, and of the
paper's viscoelastic sphere (section 11) on grids up to 513 x 513.

The elastic paraboloid: a rigid paraboloid ``R = 20 mm`` on a thick elastic layer
(``H = 0.2 m``, ``G = 3 MPa``, ``rho = 0``), ``P = 100 N``, ``mu = 0.2``, ``V = 1 m/s``,
``Omega`` prescribed so that the creepage ``(V - Omega R) / V = 0.01`` on every row
(``l(y) = R`` through ``Friction.radius``, CONTACT's uniform longitudinal creepage), period
``L = 0.6 m`` (3 H, where the period stops mattering; ``--period``), ``Nt = L / 2a``,
half-width 6 mm; spacing 0.2 mm (61 x 61 nodes) and 0.1 mm (121 x 121); the case file
``examples/elastic-paraboloid-creepage.toml``. CONTACT's whole runs of it on the same
machine: BENCHMARKS.md, "External references".

The viscoelastic sphere: the section 11 friction example
(``examples/paper-section11-friction.toml``, 41 x 41) and the same problem on ``--nodes``
grids (``bem_friction.py``'s large-grid set-up: half-width 5.2 mm,
``a = 10.4 mm / (nodes - 1)``).

Printed per case: kernels (s), the frictionless solve of the same grid (s; the median of
``--repeat`` solves, each right before a frictional one; the ratio frictional / frictionless
is the median of those pairs' ratios), the frictional solve (s) and its parts (coarse-grid
start, fine active set), active-set and GMRES iterations, the result (creep force, stick
fraction, R_r) and the peak RSS.

``--old REV`` solves each case with the frictional solver of git revision ``REV`` as
well (the whole ``bem`` package of ``REV``, from ``git archive``, imported as ``bem_old``),
right after today's, and prints both and whether they end on the same state (contact and stick
sets, forces relative to the largest): a paired comparison on a shared machine.

Run (``OPENBLAS_NUM_THREADS=1``), one case a command so that the peak RSS is the case's own:
``python benchmarks/bem_friction_rolling.py --case contact --spacing 0.2e-3`` (and
``0.1e-3``), ``--case section11 --nodes 0`` (the example's 41 x 41), ``129``, ``257``,
``513``; add ``--repeat 3`` for a median, ``--old REV`` for a paired comparison,
``--old REV --pairs 9`` for nine more solves by each, alternated, and the median of the
pairs' ratios (on a machine whose speed drifts, the figure to quote). A summary table
(kernels, frictionless, frictional wall and CPU, ratio, whole run, iterations, peak RSS)
ends the output; with ``--markdown`` that table alone goes to stdout (Markdown), the
running report to stderr.
"""

import argparse
import importlib
import os
import re
import sys
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from _common import LAYER, machine, markdown_mode, markdown_table, peak_rss_mb, reporter

from bem import Elastic, Grid, Layer, Loading, Paraboloid, Problem, Sphere
from bem.frictional import solve_friction
from bem.contact import solve_normal
from bem.frictional import Friction
from bem.operator import ComplianceOperator
from bem.problem import compute_kernels
from bem.spectral import BLOCKS

G, H, R, P, MU, V, XI = 3.0e6, 0.2, 0.02, 100.0, 0.2, 1.0, 0.01
markdown = markdown_mode() if __name__ == "__main__" else False  # imported: the importer decides
say = reporter(markdown)


def contact_case(spacing: float, L: float = 0.6):
    nt = int(round(L / (2 * spacing)))
    grid = Grid.centred((spacing, spacing), (L, L), (nt, nt), (6e-3, 6e-3))
    problem = Problem(Layer(H, Elastic(G), 0.0), Paraboloid(R), grid, Loading(V, load=P))
    return problem, Friction(MU, "omega", omega=V * (1 - XI) / R, radius=R)


def section11_case(nodes: int | None):
    if nodes is None:
        grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (2000, 2000), (5e-3, 5e-3))
    else:
        half = 5.2e-3
        a = 2 * half / (nodes - 1)
        nt = int(0.2 / (2 * a)) + 1
        grid = Grid.centred((a, a), (0.2, 0.2), (nt, nt), (half, half))
    return Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0)), Friction(0.2)


def old_module(rev: str, name: str = ""):
    """The ``bem`` package at git revision ``rev`` (or its module ``name``): its files
    (``git archive``) imported as the package ``bem_old`` (every ``bem`` import renamed), so
    that today's and the old code run in one process on the same inputs. One copy a
    process (the first ``rev`` asked for)."""
    if "bem_old" not in sys.modules:
        root = Path(__file__).resolve().parent.parent
        tmp = Path(tempfile.mkdtemp())
        archive = subprocess.run(["git", "archive", rev, "bem"], cwd=root, check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(tmp)], input=archive, check=True)
        (tmp / "bem").rename(tmp / "bem_old")
        for path in (tmp / "bem_old").rglob("*.py"):
            text = path.read_text()
            text = re.sub(r"\b(from|import) bem\b", r"\1 bem_old", text)
            path.write_text(text)
        sys.path.insert(0, str(tmp))
        importlib.import_module("bem_old")
        sys.path.remove(str(tmp))
    return importlib.import_module("bem_old" + (f".{name}" if name else ""))


def old_solver(rev: str):
    """``solve_friction`` of the ``bem`` package at git revision ``rev`` (:func:`old_module`);
    in revisions before the ``bem.frictional`` package, ``bem/rolling.py``'s."""
    try:
        return old_module(rev, "frictional").solve_friction
    except ModuleNotFoundError:
        return old_module(rev, "rolling").solve_friction


def compare(new, old) -> str:
    same = np.array_equal(new.contact, old.contact) and np.array_equal(new.stick, old.stick)
    scale = old.force.max()
    diff = max(float(np.abs(a - b).max()) for a, b in ((new.force, old.force), (new.force_x, old.force_x),
                                                         (new.force_y, old.force_y))) / scale
    return f"same contact and stick sets: {same}; forces differ by {diff:.1e} of the largest"


def run(label: str, problem: Problem, friction: Friction, repeat: int, verbose: bool, solver=solve_friction,
        kernels=None) -> dict:
    if kernels is None:
        kernels, kernel_s = compute_kernels(problem, BLOCKS)
    else:
        kernels, kernel_s = kernels
    X, Y = problem.grid.coordinates()
    profile = problem.indenter.profile(X, Y)
    op = ComplianceOperator(problem.grid, kernels["ww"])
    normal_times, times, cpus, lines = [], [], [], []
    for i in range(repeat):
        # the frictionless solve right before each frictional one: the ratio is taken pair
        # by pair, so that it holds while the machine's speed drifts
        t0 = time.perf_counter()
        normal = solve_normal(op, profile, load=problem.loading.load)
        normal_times.append(time.perf_counter() - t0)
        stamp = time.perf_counter()
        lines.clear()

        def progress(msg, stamp=stamp):
            lines.append(f"{time.perf_counter() - stamp:7.2f} s  {msg}")
            if verbose:
                say("   ", lines[-1])

        t0, c0 = time.perf_counter(), time.process_time()
        res, _ = solver(problem, friction, kernels=kernels, energy=False, progress=progress)
        times.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    ratio = float(np.median(np.array(times) / np.array(normal_times)))
    normal_s = float(np.median(normal_times))
    times.sort()
    cpus.sort()
    solve_s, solve_cpu = times[len(times) // 2], cpus[len(cpus) // 2]
    r = res.record
    g = problem.grid
    say(f"{label}: {g.nodes_x} x {g.nodes_y} nodes, a = {g.spacing_x * 1e3:.4g} mm, Nt = {g.truncation_x}, "
          f"{int(res.contact.sum())} contact nodes")
    say(f"  kernels {kernel_s:.2f} s, frictionless solve {normal_s:.3f} s "
          f"({normal.record.iterations} it, {normal.record.linear_iterations} GMRES)")
    say(f"  frictional solve {solve_s:.3f} s (median of {repeat}; {ratio:.1f} x frictionless, the median of the pairs), "
          f"CPU {solve_cpu:.3f} s, whole run {kernel_s + solve_s:.2f} s; {r.iterations} active-set iterations, "
          f"{r.linear_solver} {r.linear_iterations} iterations")
    say(f"  creep force -sum S_x = {-res.force_x.sum():.6g} N ({-res.force_x.sum() / (MU * res.load):.5f} mu P), "
          f"stick fraction {res.stick_fraction:.4f}, R_r = {res.rolling_resistance:.6g} N, Omega = {res.omega:.8g}")
    say(f"  residuals gap {r.gap_residual:.1e} stick {r.stick_residual:.1e} Coulomb {r.coulomb_residual:.1e}; "
          f"peak RSS {peak_rss_mb():.0f} MB")
    coarse = [ln for ln in lines if "coarse" in ln]
    if coarse:
        say(f"  coarse start done at {coarse[-1].split(' s')[0].strip()} s")
    SUMMARY.append((f"{label}, {g.nodes_x} x {g.nodes_y}", int(res.contact.sum()), kernel_s, normal_s,
                    solve_s, solve_cpu, ratio, kernel_s + solve_s, r.iterations, r.linear_iterations,
                    peak_rss_mb()))
    return {"kernel_s": kernel_s, "normal_s": normal_s, "solve_s": solve_s, "solve_cpu": solve_cpu, "result": res,
            "kernels": (kernels, kernel_s)}


SUMMARY: list = []


def print_summary() -> None:
    """One row per case: time against CONTACT and against the frictionless solve, iterations
    and memory (a Markdown table on stdout with ``--markdown``)."""
    if not SUMMARY:
        return
    head = ("case", "contact nodes", "kernels (s)", "frictionless (s)", "frictional (s)", "frictional CPU (s)",
            "frictional / frictionless", "whole run (s)", "active-set iterations", "GMRES iterations",
            "peak RSS (MB)")
    rows = [[case, nc, f"{ks:.2f}", f"{ns:.3f}", f"{fs:.3f}", f"{fc:.3f}", f"{ratio:.2f}", f"{whole:.2f}", it, lin,
             f"{rss:.0f}"] for case, nc, ks, ns, fs, fc, ratio, whole, it, lin, rss in SUMMARY]
    if markdown:
        print(markdown_table(head, rows))
        return
    print("\nsummary (peak RSS of the process so far, kernels included)")
    print(" | ".join(head))
    for row in rows:
        print(" | ".join(str(c) for c in row))


def paired(label, problem, friction, args):
    new = run(label, problem, friction, args.repeat, args.verbose)
    if args.old:
        t0 = time.perf_counter()
        try:
            old = run(label + f" [solver of {args.old}]", problem, friction, args.repeat, args.verbose,
                      solver=old_solver(args.old), kernels=new["kernels"])
        except Exception as exc:  # noqa: BLE001 - the old solver's failure is a result here
            say(f"  the solver of {args.old} failed after {time.perf_counter() - t0:.1f} s: "
                  f"{type(exc).__name__}: {exc}")
            return
        say(f"  new against {args.old}: {compare(new['result'], old['result'])}; "
              f"solve {old['solve_s']:.2f} s -> {new['solve_s']:.2f} s ({old['solve_s'] / new['solve_s']:.1f}x), CPU "
              f"{old['solve_cpu']:.2f} s -> {new['solve_cpu']:.2f} s ({old['solve_cpu'] / new['solve_cpu']:.1f}x)",
              flush=True)
        if args.pairs:
            alternate(problem, friction, old_solver(args.old), new["kernels"][0], args.pairs, args.old)


def alternate(problem, friction, old, kernels, pairs: int, rev: str) -> None:
    """``pairs`` solves by today's solver and by ``old``, in turn (which goes first
    alternating), and the median of the pairs' ratios old / new with their range: a ratio
    that holds while the machine's speed drifts, which the medians of two blocks of runs
    do not."""
    times: dict = {"new": [], "old": []}
    for i in range(pairs):
        order = (("new", solve_friction), ("old", old))
        for name, solver in (order if i % 2 == 0 else order[::-1]):
            t0 = time.perf_counter()
            solver(problem, friction, kernels=kernels, energy=False)
            times[name].append(time.perf_counter() - t0)
    ratio = np.array(times["old"]) / np.array(times["new"])
    say(f"  {pairs} alternated pairs: today {np.median(times['new']):.3f} s, {rev} {np.median(times['old']):.3f} s "
          f"(medians); ratio {rev} / today {np.median(ratio):.3f} (median; {ratio.min():.2f}-{ratio.max():.2f})",
          flush=True)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", choices=("contact", "section11", "all"), default="all")
    ap.add_argument("--spacing", type=float, nargs="*", default=[0.2e-3, 0.1e-3])
    ap.add_argument("--nodes", type=int, nargs="*", default=[0, 129, 257],
                    help="section 11 grids (nodes a side; 0: the example's own 41 x 41)")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--verbose", action="store_true")
    ap.add_argument("--period", type=float, default=0.6, help="period L (m) of the elastic paraboloid's layer")
    ap.add_argument("--old", metavar="REV", help="also solve with the frictional solver of this git revision")
    ap.add_argument("--pairs", type=int, default=0,
                    help="with --old: this many more solves by each, alternated, and their paired ratio")
    args = ap.parse_args()
    say(machine(), "| load average", " ".join(f"{x:.2f}" for x in os.getloadavg()))
    if args.case in ("contact", "all"):
        for a in args.spacing:
            paired(f"elastic paraboloid, creepage {XI:g}, spacing {a * 1e3:g} mm, L = {args.period:g} m",
                   *contact_case(a, args.period), args)
    if args.case in ("section11", "all"):
        for n in args.nodes:
            paired(f"viscoelastic sphere (section 11), mu = {MU:g}", *section11_case(n or None), args)
    print_summary()
    say("load average at the end", " ".join(f"{x:.2f}" for x in os.getloadavg()))
