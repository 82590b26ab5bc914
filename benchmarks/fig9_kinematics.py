"""Figure 9 under each rolling kinematics, with its grid error: the friction share
P_fric / (P_visc + P_fric), R_r^F and friction's effect on R_r against the layer
thickness H (P = 50 and 125 N; kinematics paper, small_slope, exact) on the grids
a = 0.5, 0.25, 0.125 and 0.0625 mm (Nt = 1600 on each).

    ../.venv/bin/python fig9_kinematics.py run [--workers 1] [--out DIR] [--cache DIR]
    ../.venv/bin/python fig9_kinematics.py report [--out DIR] [--figure PNG]

``run`` solves the sweep files of examples/sweeps/fig9-kinematics/ one after the other
on one local cluster with one kernel cache, printing each sweep's wall time. ``report``
reads their tables and prints, per load, kinematics and thickness, the figure on each
grid with its Richardson limit and the grid error of the finest grid from the finest
three (:func:`sweeps.paper.grid_estimate`; the order from the coarsest three beside it), the
share's rise towards thin layers (:func:`sweeps.paper.share_rise`) on every grid, and
draws the share against H (``--figure``, e.g. docs/images/fig9-kinematics.png).
Outputs under ../out/fig9-kinematics/ by default (docs/sweeps.md, "Figure 9").
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

FOLDER = ROOT / "examples" / "sweeps" / "fig9-kinematics"
OUT = ROOT / "out" / "fig9-kinematics"
#: the grids, coarse to fine (name suffix, spacing in m)
GRIDS = (("a0p5", 0.5e-3), ("a0p25", 0.25e-3), ("a0p125", 0.125e-3), ("a0p0625", 0.0625e-3))
FILES = [f"{kind}-{g}" for g, _ in GRIDS for kind in ("share", "frictionless")]
KINEMATICS = ("paper", "small_slope", "exact")
LOADS = (50.0, 125.0)


def run(workers: int, out: Path, cache: Path) -> None:
    from sweeps import connect, read_sweep, run_sweep

    t0 = time.perf_counter()
    client = connect(workers=workers)
    print(f"local cluster of {workers} worker(s) up in {time.perf_counter() - t0:.1f} s", flush=True)
    try:
        for name in FILES:
            sweep = read_sweep(FOLDER / f"{name}.toml")
            t = time.perf_counter()
            r = run_sweep(sweep, out / name, cache=cache, client=client, stream=None)
            print(f"{name:22s} {time.perf_counter() - t:7.1f} s wall  {r.computed:3d} points solved "
                  f"({r.resumed} cached, {r.failed} failed)  {r.kernels_formed:2d} kernel sets formed", flush=True)
    finally:
        cluster = getattr(client, "cluster", None)
        client.close()
        if cluster is not None:
            cluster.close()


def _series(out: Path, y: str, load: float, kinematics: str, grids=GRIDS):
    """``H, [values per grid]`` of ``y`` (``effect``: friction's effect on R_r, the
    equilibrium figure, :func:`sweeps.paper.friction_effect`)."""
    import numpy as np

    from sweeps.paper import curve, read_table

    H0, per_grid = None, []
    for g, _ in grids:
        rows = read_table(out / f"share-{g}" / "results.csv")
        fixed = {"loading.load": load, "friction.kinematics": kinematics}
        col = "rolling_resistance" if y == "effect" else y
        H, v = curve(rows, "layer.thickness", col, **fixed)
        if y == "effect":
            Hn, v0 = curve(read_table(out / f"frictionless-{g}" / "results.csv"), "layer.thickness", col,
                           **{"loading.load": load})
            assert np.allclose(H, Hn), (g, H, Hn)
            v = v / v0 - 1
        assert H0 is None or np.allclose(H, H0), (g, H, H0)
        H0 = H
        per_grid.append(v)
    return H0, per_grid


def estimates(out: Path, y: str, load: float, kinematics: str):
    """``[(H, values coarse to fine, Convergence)]`` of ``y`` on the grids (the estimate
    from the finest three)."""
    from sweeps.paper import grid_estimate

    H, per_grid = _series(out, y, load, kinematics)
    return [(h, [v[i] for v in per_grid], grid_estimate([v[i] for v in per_grid])) for i, h in enumerate(H)]


def report(out: Path, figure: Path | None) -> None:
    from sweeps.paper import grid_estimate, read_table, share_rise

    scale = {"friction_share": (100, "%"), "rolling_resistance_friction": (1e3, "mN"), "effect": (100, "%")}
    for y in ("friction_share", "rolling_resistance_friction", "effect"):
        k, unit = scale[y]
        print(f"\n{y} ({unit}): values at a = 0.5 / 0.25 / 0.125 / 0.0625 mm, Richardson limit +/- grid error "
              "of the finest (observed order of the finest three, of the coarsest three; '3x' = not asymptotic, "
              "error = three times the last change)")
        for load in LOADS:
            for kin in KINEMATICS:
                print(f"  P = {load:g} N, {kin}")
                for h, vals, c in estimates(out, y, load, kin):
                    order = f"p = {c.order:.2f}" if c.asymptotic else "3x"
                    order += f", coarse p = {grid_estimate(vals[:3]).order:.2f}"
                    print(f"    H = {h * 1e3:4g} mm  " + " / ".join(f"{k * v:8.4f}" for v in vals)
                          + f"   -> {k * c.extrapolated:8.4f} +/- {k * c.error_finest:.4f}  ({order})")
    print("\nrise towards thin layers, share(5 mm) / share(1 mm), a = 0.5 / 0.25 / 0.125 / 0.0625 mm, "
          "Richardson limit +/- grid error:")
    tables = [read_table(out / f"share-{g}" / "results.csv") for g, _ in GRIDS]
    for load in LOADS:
        for kin in KINEMATICS:
            rise = [share_rise(t, **{"loading.load": load, "friction.kinematics": kin}) for t in tables]
            c = grid_estimate(rise)
            order = f"p = {c.order:.2f}" if c.asymptotic else "3x"
            print(f"  P = {load:g} N, {kin:11s} " + " / ".join(f"{v:.4f}" for v in rise)
                  + f"   -> {c.extrapolated:.4f} +/- {c.error_finest:.4f} ({order})")
    if figure is not None:
        draw(out, figure)


def draw(out: Path, path: Path) -> None:
    """The share against H, one panel per load, one curve per kinematics: the finest
    grid's values with bars of their grid error, the 0.5 mm grid as faint markers."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True, constrained_layout=True)
    colours = {"paper": "C0", "small_slope": "C2", "exact": "C3"}
    for ax, load in zip(axes, LOADS):
        for kin in KINEMATICS:
            est = estimates(out, "friction_share", load, kin)
            H = np.array([e[0] for e in est]) * 1e3
            fine = np.array([e[1][-1] for e in est]) * 100
            err = np.array([e[2].error_finest for e in est]) * 100
            lower = np.minimum(err, 0.9 * fine)  # a log axis: the bar stops above zero
            ax.errorbar(H, fine, yerr=[lower, err], fmt="o-", ms=4, lw=1.4, capsize=3, color=colours[kin],
                        label=f"{kin} (a = 0.0625 mm, bar: grid error)")
            ax.plot(H, [100 * e[1][0] for e in est], "x", ms=5, color=colours[kin], alpha=0.6)
        ax.axvspan(6, 8, color="0.85", zorder=0, label="paper's maximum, H = 6-8 mm")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks([1, 2, 3, 5, 7, 10, 15, 30])
        ax.set_xticklabels(["1", "2", "3", "5", "7", "10", "15", "30"])
        ax.set_xlabel("layer thickness H (mm)")
        ax.set_title(f"P = {load:g} N (x: a = 0.5 mm)", fontsize=10)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("friction share P_fric / (P_visc + P_fric) (%)")
    axes[1].legend(fontsize=8, loc="upper right")
    fig.savefig(path, dpi=110)
    print(f"\nwrote {path}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="what", required=True)
    a = sub.add_parser("run")
    a.add_argument("--workers", type=int, default=1)
    a.add_argument("--out", type=Path, default=OUT)
    a.add_argument("--cache", type=Path, default=OUT / "cache")
    b = sub.add_parser("report")
    b.add_argument("--out", type=Path, default=OUT)
    b.add_argument("--figure", type=Path, default=None)
    args = ap.parse_args()
    if args.what == "run":
        run(args.workers, args.out, args.cache)
    else:
        report(args.out, args.figure)


if __name__ == "__main__":
    main()
