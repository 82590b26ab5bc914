"""The conveyor idler sweep's results per roll, per metre of roll face and as a coefficient.

    sweep examples/sweeps/conveyor-idler-dma.toml --out out/conveyor-idler
    python examples/conveyor_idler_table.py out/conveyor-idler/results.csv --roll-length 0.465

The sweep solves the 3D contact of a roll of finite length, so its ``rolling_resistance``
R is the resistance of one roll (N) under the load P on it (N). The belt lies across the
roll's whole face length L (m), so R / L is the resistance per metre of belt width on that
roll (N/m), and R / P the rolling-resistance coefficient (-). Prints a Markdown table:
temperature (degC), belt speed (m/s), R per roll (N), R / L (N/m), R / P (-), the energy
figure's departure from R (D / V over R, minus 1: a measure of the grid's error) and the
mean contact width, contact area over L (mm).
"""

from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("results", type=Path, help="the sweep's results.csv")
    p.add_argument("--roll-length", type=float, default=0.465, help="roll face length L (m), default 0.465")
    p.add_argument("--plot", type=Path, help="also draw R against V per temperature (PNG)")
    args = p.parse_args(argv)
    if not args.roll_length > 0:
        p.error(f"--roll-length must be > 0 m, got {args.roll_length}")
    if not args.results.is_file():
        p.error(f"{args.results}: not found; run the sweep first")
    with args.results.open(newline="", encoding="utf-8") as fh:
        rows = [r for r in csv.DictReader(fh)]
    L = args.roll_length
    print(f"| T (degC) | V (m/s) | R per roll (N) | R / L, L = {L:g} m (N/m) | R / P (-) | D / (V R) - 1 | "
          "mean contact width (mm) |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for r in sorted(rows, key=lambda r: (float(r["material.temperature"]), float(r["loading.speed"]))):
        T, V = float(r["material.temperature"]) - 273.15, float(r["loading.speed"])
        if r["status"] != "ok":
            print(f"| {T:.0f} | {V:g} | failed: {r['error']} | | | | |")
            continue
        R, P = float(r["rolling_resistance"]), float(r["load"])
        energy = float(r["rolling_resistance_energy"]) / R - 1.0
        width = float(r["contact_area"]) / L * 1e3
        print(f"| {T:.0f} | {V:g} | {R:.4g} | {R / L:.4g} | {R / P:.3g} | {energy:+.1%} | {width:.2f} |")
    if args.plot:
        _plot([r for r in rows if r["status"] == "ok"], L, args.plot)
    return 0


def _plot(rows, L: float, path: Path) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 4.2), layout="constrained")
    ax = fig.subplots()
    for T in sorted({float(r["material.temperature"]) for r in rows}):
        pts = sorted((float(r["loading.speed"]), float(r["rolling_resistance"]))
                     for r in rows if float(r["material.temperature"]) == T)
        ax.plot(*zip(*pts), "o-", label=f"{T - 273.15:.0f} degC")
    ax.set_xlabel("belt speed V (m/s)")
    ax.set_ylabel("rolling resistance per roll R (N)")
    right = ax.secondary_yaxis("right", functions=(lambda r: r / L, lambda r: r * L))
    right.set_ylabel(f"per metre of roll face, L = {L:g} m (N/m)")
    ax.set_ylim(0, 1.3 * max(float(r["rolling_resistance"]) for r in rows))
    ax.grid(True, alpha=0.3)
    ax.legend(title="service temperature", fontsize=8, ncol=3, loc="upper left")
    fig.savefig(path, dpi=110)
    print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
