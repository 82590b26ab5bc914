"""The conveyor idler sweep's results per unit belt width and per idler.

    sweep examples/sweeps/conveyor-idler-dma.toml --out out/conveyor-idler
    python examples/conveyor_idler_table.py out/conveyor-idler/results.csv --belt-width 1.2

The sweep solves a line contact (plane strain), so its ``rolling_resistance`` is per
metre of belt width (N/m); on a flat idler carrying the belt's whole width ``B`` (m) the
resistance per idler is ``B`` times that (the roller's ends neglected). Prints a Markdown
table: temperature (degC), belt speed (m/s), rolling resistance per unit width (N/m) and
per idler (N), the coefficient R / q (-, q the load per unit width) and the contact's
half-width (mm).
"""

from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("results", type=Path, help="the sweep's results.csv")
    p.add_argument("--belt-width", type=float, default=1.2, help="belt width B (m), default 1.2")
    p.add_argument("--plot", type=Path, help="also draw R against V per temperature (PNG)")
    args = p.parse_args(argv)
    if not args.belt_width > 0:
        p.error(f"--belt-width must be > 0 m, got {args.belt_width}")
    if not args.results.is_file():
        p.error(f"{args.results}: not found; run the sweep first")
    with args.results.open(newline="", encoding="utf-8") as fh:
        rows = [r for r in csv.DictReader(fh)]
    B = args.belt_width
    print(f"| T (degC) | V (m/s) | R per unit width (N/m) | R per idler, B = {B:g} m (N) | R / q (-) | "
          "half-width (mm) |")
    print("|---:|---:|---:|---:|---:|---:|")
    for r in sorted(rows, key=lambda r: (float(r["material.temperature"]), float(r["loading.speed"]))):
        T, V = float(r["material.temperature"]) - 273.15, float(r["loading.speed"])
        if r["status"] != "ok":
            print(f"| {T:.0f} | {V:g} | failed: {r['error']} | | | |")
            continue
        R, q = float(r["rolling_resistance"]), float(r["load"])
        half = float(r["contact_radius"]) * 1e3  # a line contact's half-width
        print(f"| {T:.0f} | {V:g} | {R:.4g} | {R * B:.4g} | {R / q:.3g} | {half:.4f} |")
    if args.plot:
        _plot([r for r in rows if r["status"] == "ok"], B, args.plot)
    return 0


def _plot(rows, B: float, path: Path) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 4.2), layout="constrained")
    ax = fig.subplots()
    for T in sorted({float(r["material.temperature"]) for r in rows}):
        pts = sorted((float(r["loading.speed"]), float(r["rolling_resistance"]))
                     for r in rows if float(r["material.temperature"]) == T)
        ax.plot(*zip(*pts), "o-", label=f"{T - 273.15:.0f} degC")
    ax.set_xlabel("belt speed V (m/s)")
    ax.set_ylabel("rolling resistance per unit width (N/m)")
    right = ax.secondary_yaxis("right", functions=(lambda r: r * B, lambda r: r / B))
    right.set_ylabel(f"per idler, belt width {B:g} m (N)")
    ax.grid(True, alpha=0.3)
    ax.legend(title="service temperature", fontsize=8)
    fig.savefig(path, dpi=110)
    print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
