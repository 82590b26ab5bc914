"""``python -m bem.dma FILE``: master curve and Prony fit of a DMA CSV, with figures.

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
from .master import build_master_curve
from .plots import plot_isotherms, plot_master_curve, plot_shift_factors
from .reader import read_dma_csv


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m bem.dma", description=__doc__.splitlines()[0])
    p.add_argument("file", type=Path, help="DMA CSV (format: bem.dma.reader)")
    p.add_argument("--t-ref", type=float, required=True, help="reference temperature (degC)")
    p.add_argument("--law", choices=("wlf", "arrhenius"), default="wlf")
    p.add_argument("--quantity", choices=("modulus", "both", "tan_delta"), default=None)
    p.add_argument("--vertical", choices=("density", "fit"), default=None)
    p.add_argument("--terms-per-decade", type=float, default=1.0)
    p.add_argument("--out", type=Path, default=Path("."), help="folder for the PNG figures")
    p.add_argument("--prefix", default="", help="prefix of the figure file names")
    p.add_argument("--table", type=Path, default=None, help="write the master curve table CSV here")
    p.add_argument("--print-material", action="store_true",
                   help="print the fitted Prony series as a case file's [material] table")
    p.add_argument("--service-temperature", type=float, default=None, help="table temperature (degC)")
    args = p.parse_args(argv)
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
