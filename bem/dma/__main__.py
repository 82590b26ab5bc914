"""``bem dma FILE`` (or ``python -m bem.dma FILE``): master curve and Prony fit of a DMA CSV, with figures.

Prints the shift law, each isotherm's shift and the Prony fit's errors (with
``--print-material`` also the fitted series as a case file's ``[material]`` table); writes
``isotherms.png``, ``master-curve.png`` and ``shift-factors.png`` (after ``--prefix``)
into ``--out``, and,
with ``--table``, the master curve at ``--service-temperature`` as a
``MasterCurveTable`` CSV (omega rad/s, G' Pa, G'' Pa) for a case file's
``[material] model = "table"``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .errors import DMAError


def main(argv=None, prog: str = "python -m bem.dma") -> int:
    """Exit status 0, or 2 for bad input (the message names the file, line or option)."""
    p = argparse.ArgumentParser(prog=prog, description=__doc__.splitlines()[0],
                                epilog="exit status: 0 done; 2 bad input (the message names the file, line or "
                                       "option). Workflow: docs/materials.md")
    p.add_argument("file", type=Path, help="DMA CSV (format: docs/materials.md)")
    p.add_argument("--t-ref", type=float, required=True, help="reference temperature (degC)")
    p.add_argument("--law", choices=("wlf", "arrhenius"), default="wlf",
                   help="shift law fitted to the isotherms' overlap (default wlf)")
    p.add_argument("--quantity", choices=("modulus", "both", "tan_delta"), default=None,
                   help="curves overlapped (default modulus, or both with --vertical fit)")
    p.add_argument("--vertical", choices=("density", "fit"), default=None,
                   help="vertical shift b_T (default none)")
    p.add_argument("--terms-per-decade", type=float, default=2.0,
                   help="Prony relaxation times per decade (default 2, as [material] model = \"dma\")")
    p.add_argument("--out", type=Path, default=Path("."), help="folder for the PNG figures (default .)")
    p.add_argument("--prefix", default="", help="prefix of the figure file names (default none)")
    p.add_argument("--table", type=Path, default=None,
                   help="write the master curve table CSV here (default: not written)")
    p.add_argument("--print-material", action="store_true",
                   help="print the fitted Prony series as a case file's [material] table")
    p.add_argument("--service-temperature", type=float, default=None,
                   help="the table's temperature (degC; default --t-ref)")
    args = p.parse_args(argv)
    from .master import build_master_curve  # numpy, scipy and matplotlib after --help
    from .plots import plot_isotherms, plot_master_curve, plot_shift_factors
    from .reader import read_dma_csv

    try:
        data = read_dma_csv(args.file)
        master = build_master_curve(data, args.t_ref + 273.15, args.law, quantity=args.quantity,
                                    vertical=args.vertical)
        fit = master.fit_prony(terms_per_decade=args.terms_per_decade)
    except DMAError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(f"{data.source}: {len(data.isotherms)} isotherms, law {master.law}")
    for T, la, lb in zip(master.temperatures, master.log_aT, master.log_bT):
        print(f"  T = {T - 273.15:8.2f} degC   log10 a_T = {la:8.3f}   log10 b_T = {lb:7.3f}")
    print(f"Prony fit: {len(fit.material.G)} terms, G' error max {fit.max_error_storage:.3g} rms "
          f"{fit.rms_error_storage:.3g}, G'' error max {fit.max_error_loss:.3g} rms {fit.rms_error_loss:.3g}")
    if args.print_material:
        m = fit.material
        print("[material]  # Prony series at T_ref, shear moduli (Pa) and relaxation times (s)")
        print('model = "prony"')
        print(f"G_inf = {m.G_inf!r}")
        print(f"G = [{', '.join(repr(g) for g in m.G)}]")
        print(f"tau = [{', '.join(repr(t) for t in m.tau)}]")
    args.out.mkdir(parents=True, exist_ok=True)
    name = args.file.name
    figures = {
        "isotherms.png": plot_isotherms(data, f"{name}: isotherms"),
        "master-curve.png": plot_master_curve(master, fit, f"{name}: master curve"),
        "shift-factors.png": plot_shift_factors(master, f"{name}: shift factors"),
    }
    for fname, fig in figures.items():
        path = args.out / f"{args.prefix}{fname}"
        fig.savefig(path, dpi=110)
        print(f"wrote {path}")
    if args.table is not None:
        T = None if args.service_temperature is None else args.service_temperature + 273.15
        table = master.table(T)
        lines = ["omega_rad_s,G_storage_Pa,G_loss_Pa"] + [
            f"{w!r},{gs!r},{gl!r}" for w, gs, gl in zip(table.omega, table.storage, table.loss)]
        args.table.write_text("\n".join(lines) + "\n")
        print(f"wrote {args.table}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
