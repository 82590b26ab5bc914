"""The paper's parametric studies on Dask: figures 7-10 with friction, and the
speed-up from one to two workers.

    ../.venv/bin/python sweeps_paper.py all [--workers 2] [--markdown]   # every figure and table, fresh cache
    ../.venv/bin/python sweeps_paper.py compare                # the paper's findings against them
    ../.venv/bin/python sweeps_paper.py speedup FILE

``all`` runs examples/sweeps/fig7a ... fig10b and the two tables in one fresh cache
folder (the tables' and figure 9's points shared with figures 7 and 8 come from the
cache) and prints, per sweep and in total: wall time, points computed, kernel sets formed,
and the worker time in kernels, solves (with the energy figure) and overhead.
``compare`` prints the paper's findings against those tables (Tables 2-3, the friction
share, the peaks of figures 9 and 10). ``speedup`` runs one sweep file without a cache on one worker, then on two, and prints
the ratio of wall times. Outputs under ../out/bench-sweeps/.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

from sweeps import read_sweep, run_sweep, write_report  # noqa: E402

sys.path.insert(0, str(HERE))
from _common import markdown_table, reporter  # noqa: E402

OUT = ROOT / "out" / "bench-sweeps"
FILES = ["fig7a-load-H5", "fig7b-load-H30", "fig8a-thickness-P50", "fig8b-thickness-P125",
         "fig9a-friction-share-P50", "fig9b-friction-share-P125", "fig10a-speed-H1", "fig10b-speed-H30",
         "table2-power-law", "table3-two-exponential"]


def _line(name, r, wall):
    work = r.workers * wall
    share = (lambda v: f"{100 * v / work:5.1f} %") if work else (lambda v: "-")
    return (f"{name:30s} {wall:8.1f} s  {r.computed:4d} pts ({r.resumed} cached)  {r.kernels_formed:3d} kernels  "
            f"kernels {share(r.kernel_seconds)}  solves {share(r.solve_seconds + r.energy_seconds)}  "
            f"(energy {share(r.energy_seconds)})  overhead {share(max(0.0, work - r.kernel_seconds - r.solve_seconds - r.energy_seconds))}")


def _shares(r, wall, workers) -> list:
    work = workers * wall
    if not work:
        return ["-"] * 4
    other = max(0.0, work - r["kernel"] - r["solve"] - r["energy"])
    return [f"{100 * v / work:.1f}" for v in (r["kernel"], r["solve"], r["energy"], other)]


def run_all(workers: int, markdown: bool = False) -> None:
    """Every sweep file in one fresh cache; with ``markdown`` the table alone on stdout."""
    from sweeps import connect

    say = reporter(markdown)
    rows = []
    cache = OUT / "cache"
    shutil.rmtree(cache, ignore_errors=True)
    totals = {"wall": 0.0, "kernel": 0.0, "solve": 0.0, "energy": 0.0, "points": 0, "kernels": 0}
    results = {}
    t0 = time.perf_counter()
    client = connect(workers=workers)
    startup = time.perf_counter() - t0
    say(f"local cluster of {workers} workers up in {startup:.1f} s")
    try:
        for name in FILES:
            sweep = read_sweep(ROOT / "examples" / "sweeps" / f"{name}.toml")
            out = OUT / name
            shutil.rmtree(out, ignore_errors=True)
            t = time.perf_counter()
            r = run_sweep(sweep, out, cache=cache, client=client, stream=None)
            r.workers = workers
            wall = time.perf_counter() - t
            write_report(sweep, r.rows, out)
            say(_line(name, r, wall))
            rows.append([name, f"{r.computed} ({r.resumed} cached)", r.kernels_formed, f"{wall:.1f}"]
                        + _shares({"kernel": r.kernel_seconds, "solve": r.solve_seconds,
                                   "energy": r.energy_seconds}, wall, workers))
            totals["wall"] += wall
            totals["kernel"] += r.kernel_seconds
            totals["solve"] += r.solve_seconds
            totals["energy"] += r.energy_seconds
            totals["points"] += r.computed
            totals["kernels"] += r.kernels_formed
            results[name] = {"wall": wall, "computed": r.computed, "cached": r.resumed, "failed": r.failed,
                             "kernels": r.kernels_formed, "kernel_s": r.kernel_seconds, "solve_s": r.solve_seconds,
                             "energy_s": r.energy_seconds, "point_s": r.point_seconds}
    finally:
        client.close()
        client.cluster.close() if getattr(client, "cluster", None) else None
    work = workers * totals["wall"]
    other = work - totals["kernel"] - totals["solve"] - totals["energy"]
    say(f"TOTAL {totals['wall']:.1f} s wall on {workers} workers (+{startup:.1f} s cluster start), "
          f"{totals['points']} points solved, {totals['kernels']} kernel sets; worker time: kernels "
          f"{100 * totals['kernel'] / work:.1f} %, solves {100 * totals['solve'] / work:.1f} %, energy "
          f"{100 * totals['energy'] / work:.1f} %, overhead and idle {100 * other / work:.1f} %")
    if markdown:
        rows.append([f"**all** (+{startup:.1f} s cluster start)", totals["points"], totals["kernels"],
                     f"{totals['wall']:.1f}"] + _shares(totals, totals["wall"], workers))
        print(markdown_table([f"sweep (examples/sweeps/, {workers} workers)", "points solved", "kernel sets",
                              "wall (s)", "kernels (% of worker time)", "solves (%)", "energy figures (%)",
                              "overhead and idle (%)"], rows))
    (OUT / "all.json").write_text(json.dumps({"workers": workers, "startup_s": startup, "totals": totals,
                                              "sweeps": results}, indent=2))


def speedup(file: str) -> None:
    from sweeps import connect

    sweep = read_sweep(file)
    walls = {}
    for n in (1, 2):
        client = connect(workers=n)
        try:
            out = OUT / f"speedup-{n}"
            shutil.rmtree(out, ignore_errors=True)
            t = time.perf_counter()
            r = run_sweep(sweep, out, cache=None, client=client, stream=None)
            walls[n] = time.perf_counter() - t
            r.workers = n
            print(f"{n} worker(s): " + _line(sweep.name, r, walls[n]), flush=True)
        finally:
            client.close()
            client.cluster.close()
    print(f"speed-up 1 -> 2 workers: {walls[1] / walls[2]:.2f} ({walls[1]:.1f} s -> {walls[2]:.1f} s)")


def compare() -> None:
    """The paper's findings against the tables that ``all`` wrote."""
    import numpy as np

    from sweeps import fit_law
    from sweeps.paper import (FRICTION_SHARE_LIMIT, SHARE_PEAK_RANGE, TABLE2, TABLE3, curve, friction_share_max,
                              law_gap, paper_fit, peak_position, read_table)

    def rows(name):
        return read_table(OUT / name / "results.csv")

    print("Table 2 (R_r = a P^b, with friction), ours against the paper's midpoints, P = 10-150 N:")
    for H, name in ((5e-3, "fig7a-load-H5"), (30e-3, "fig7b-load-H30")):
        r = rows(name)
        for y in ("rolling_resistance", "rolling_resistance_energy"):
            P, R = curve(r, "loading.load", y, case="base-friction")
            f = fit_law("power", P, R)
            gap = law_gap(f, paper_fit(TABLE2, H, (10, 150)), 10, 150)
            print(f"  H = {H * 1e3:g} mm {y:27s} a = {f.values[0]:.4e} [{f.lower[0]:.4e}, {f.upper[0]:.4e}]  "
                  f"b = {f.values[1]:.4f} [{f.lower[1]:.4f}, {f.upper[1]:.4f}]  r2 = {f.r2:.6f}  "
                  f"largest gap to the paper's law {100 * gap:.2f} %")
    print("Table 3 (R_r = a exp(b H) + c exp(d H), with friction), H = 1-30 mm:")
    for P, name in ((50.0, "fig8a-thickness-P50"), (125.0, "fig8b-thickness-P125")):
        r = rows(name)
        for y in ("rolling_resistance", "rolling_resistance_energy"):
            H, R = curve(r, "layer.thickness", y, case="base-friction")
            f = fit_law("two_exponential", H, R)
            text = "  ".join(f"{n} = {v:.4g} [{lo:.4g}, {hi:.4g}]" for n, v, lo, hi in
                             zip(f.names, f.values, f.lower, f.upper))
            for lo in (1e-3, 2e-3):
                gap = law_gap(f, paper_fit(TABLE3, P, (lo, 30e-3)), lo, 30e-3)
                text += f"  gap {lo * 1e3:g}-30 mm {100 * gap:.2f} %"
            print(f"  P = {P:g} N {y:27s} {text}  r2 = {f.r2:.6f}")
    print("Friction against no friction at the same point (figures 7, 8):")
    for name, x in (("fig7a-load-H5", "loading.load"), ("fig7b-load-H30", "loading.load"),
                    ("fig8a-thickness-P50", "layer.thickness"), ("fig8b-thickness-P125", "layer.thickness")):
        r = rows(name)
        for y in ("rolling_resistance", "rolling_resistance_energy"):
            _, a = curve(r, x, y, case="base-friction")
            _, b = curve(r, x, y, case="base-frictionless")
            print(f"  {name:22s} {y:27s} R_r(friction) / R_r(none) - 1: min {100 * (a / b - 1).min():+.2f} %, "
                  f"max {100 * (a / b - 1).max():+.2f} %")
    share = max(friction_share_max(rows(n)) for n in ("fig7a-load-H5", "fig7b-load-H30"))
    print(f"Friction share, figures 7 (P <= 150 N): largest {100 * share:.2f} % (paper: below "
          f"{100 * FRICTION_SHARE_LIMIT:.2f} %)")
    for name in ("fig9a-friction-share-P50", "fig9b-friction-share-P125"):
        H, s = curve(rows(name), "layer.thickness", "friction_share")
        k = int(np.argmax(s))
        print(f"  {name}: share {100 * s.min():.2f}-{100 * s.max():.2f} %, largest at H = {H[k] * 1e3:g} mm, "
              f"parabola vertex {peak_position(H, s) * 1e3:.2f} mm (paper: {SHARE_PEAK_RANGE[0] * 1e3:g}-"
              f"{SHARE_PEAK_RANGE[1] * 1e3:g} mm)")
    print("Figure 10, speed of the rolling-resistance peak:")
    for name in ("fig10a-speed-H1", "fig10b-speed-H30"):
        r = rows(name)
        for P in (10.0, 50.0, 100.0, 150.0):
            out = []
            for y in ("rolling_resistance", "rolling_resistance_energy"):
                V, R = curve(r, "loading.speed", y, **{"loading.load": P})
                out.append(f"{y.split('_')[-1]} {peak_position(V, R, log=True):.4g} m/s (R_r max {R.max():.4g} N)")
            print(f"  {name} P = {P:g} N: " + "; ".join(out))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="what", required=True)
    a = sub.add_parser("all")
    a.add_argument("--workers", type=int, default=2)
    a.add_argument("--markdown", action="store_true", help="print the table alone, in Markdown")
    s = sub.add_parser("speedup")
    s.add_argument("file")
    sub.add_parser("compare")
    args = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    if args.what == "all":
        run_all(args.workers, args.markdown)
    elif args.what == "compare":
        compare()
    else:
        speedup(args.file)


if __name__ == "__main__":
    main()
