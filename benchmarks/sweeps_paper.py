"""The paper's parametric studies on Dask (issue 12): figures 7-10 with friction, and the
speed-up from one to two workers.

    ../.venv/bin/python sweeps_paper.py all [--workers 2]      # every figure and table, fresh cache
    ../.venv/bin/python sweeps_paper.py speedup FILE [--points N]

``all`` runs examples/sweeps/fig7a ... fig10b and the two tables in one fresh cache
folder (the tables' and figure 9's points shared with figures 7 and 8 come from the
cache) and prints, per sweep and in total: wall time, points computed, kernel sets formed,
and the worker time in kernels, solves (with the energy figure) and overhead.
``speedup`` runs one sweep file without a cache on one worker, then on two, and prints
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


def run_all(workers: int) -> None:
    from sweeps import connect

    cache = OUT / "cache"
    shutil.rmtree(cache, ignore_errors=True)
    totals = {"wall": 0.0, "kernel": 0.0, "solve": 0.0, "energy": 0.0, "points": 0, "kernels": 0}
    results = {}
    t0 = time.perf_counter()
    client = connect(workers=workers)
    startup = time.perf_counter() - t0
    print(f"local cluster of {workers} workers up in {startup:.1f} s", flush=True)
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
            print(_line(name, r, wall), flush=True)
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
    print(f"TOTAL {totals['wall']:.1f} s wall on {workers} workers (+{startup:.1f} s cluster start), "
          f"{totals['points']} points solved, {totals['kernels']} kernel sets; worker time: kernels "
          f"{100 * totals['kernel'] / work:.1f} %, solves {100 * totals['solve'] / work:.1f} %, energy "
          f"{100 * totals['energy'] / work:.1f} %, overhead and idle {100 * other / work:.1f} %")
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="what", required=True)
    a = sub.add_parser("all")
    a.add_argument("--workers", type=int, default=2)
    s = sub.add_parser("speedup")
    s.add_argument("file")
    args = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    if args.what == "all":
        run_all(args.workers)
    else:
        speedup(args.file)


if __name__ == "__main__":
    main()
