"""``sweep FILE.toml``: run a parametric study of BEM cases on Dask.

Writes, in ``--out`` (default ``out/sweeps/<name>``): ``results.csv`` (one row per point,
as they arrive), ``summary.json`` (counts and times), ``sweep.json`` (whose folder it is),
``plot-<result>.png``, ``fits.csv`` / ``fits.json``, and ``grid-error.csv`` when an axis
halves the node spacing (each figure's Richardson limit and grid error,
:mod:`sweeps.grid_error`). Exit status: 0 every point
solved, 1 some point failed (its row says why), 2 bad input (the sweep file, a point's
case, more points than ``MAX_POINTS``, an unreachable scheduler, another sweep's folder
without ``--overwrite``, a damaged table with ``--no-cache``), 130 interrupted (the
finished rows are kept; run again to compute the rest).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

__all__ = ["main"]


def _check(sweep, points) -> None:
    from bem.case import problem_from_config

    from .kernels import kernel_key

    keys = {}
    for p in points:
        try:
            problem, _ = problem_from_config(p.config)
            plane = getattr(problem, "plane_strain", False)  # a line contact forms its own 1D kernels
            keys.setdefault(f"plane-{p.index}" if plane else kernel_key(p.config, problem), []).append(p.index)
        except ValueError as exc:
            print(f"  point {p.index} {p.values}: {exc}")
    axes = ", ".join(f"{a.key} ({len(a.values)})" for a in sweep.axes)
    print(f"sweep {sweep.name}: {len(points)} points over {axes}, combined as {sweep.combine}; "
          f"{len(keys)} kernel set(s)")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="sweep", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", type=Path, help="the sweep file (TOML; see docs/sweeps.md)")
    parser.add_argument("--out", type=Path, help="output folder (default out/sweeps/NAME)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="an existing Dask scheduler (tcp://host:8786, or its scheduler file *.json); "
                             "default: a local cluster")
    parser.add_argument("--timeout", type=float, default=10.0, metavar="SECONDS",
                        help="how long to wait for --scheduler to answer (default 10)")
    parser.add_argument("--workers", type=int, metavar="N",
                        help="workers of the local cluster (default: the machine's cores)")
    parser.add_argument("--cache", type=Path, help="cache folder: kernel sets and finished points (default out/sweeps/kernel-cache)")
    parser.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
    parser.add_argument("--keep-failed", action="store_true",
                        help="keep the points an earlier run recorded as failed (default: compute them again)")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace what --out holds (another sweep's table, or this sweep's earlier run) "
                             "instead of refusing or resuming")
    parser.add_argument("--no-plots", action="store_true", help="no PNG plots")
    parser.add_argument("--check", action="store_true",
                        help="check the sweep file and every point, count the kernel sets, run nothing")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    if args.workers is not None and args.workers < 1:
        parser.error(f"--workers must be >= 1, got {args.workers}")

    from .engine import run_sweep
    from .report import write_report
    from .spec import SweepError, expand, read_sweep

    try:
        sweep = read_sweep(args.file)
        points = expand(sweep)
    except SweepError as exc:
        print(f"sweep: error: {exc}", file=sys.stderr)
        return 2
    if args.check:
        _check(sweep, points)
        return 0
    out = args.out or Path("out") / "sweeps" / sweep.name
    cache = None if args.no_cache else (args.cache or Path("out") / "sweeps" / "kernel-cache")
    try:
        report = run_sweep(sweep, out, scheduler=args.scheduler, workers=args.workers, cache=cache,
                           timeout=args.timeout, keep_failed=args.keep_failed, overwrite=args.overwrite,
                           stream=None if args.quiet else sys.stderr)
    except SweepError as exc:
        print(f"sweep: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130
    written = write_report(sweep, report.rows, out, plots=not args.no_plots)
    for f in written["fits"]:
        if "error" in f:
            print(f"sweep: fit {f['law']} of {f['y']} failed: {f['error']}", file=sys.stderr)
    if not args.quiet:
        for p in written["plots"]:
            print(f"wrote {p}", file=sys.stderr)
    return 1 if report.failed else 0


if __name__ == "__main__":
    sys.exit(main())
