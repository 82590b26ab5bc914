"""``bem solve CASE.toml``: one contact problem from a case file.

Exit status: 0 done; 1 the solve failed or an output file could not be written (the
result is printed first); 2 bad input or usage."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import casefile

# numpy and the solver are imported in main(), after the arguments are parsed: --help
# answers without loading them.


def _strict(value):
    """``value`` with NaN and infinities as ``None``: strict JSON."""
    if isinstance(value, dict):
        return {k: _strict(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_strict(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


PLOT_SUFFIXES = (".png", ".pdf", ".svg")
EXIT_CODES = ("exit status: 0 done; 1 the solve failed or --plot/--fields could not be written (the result is "
              "printed first); 2 bad input or usage.")


def _write_outputs(args, friction, result, summary) -> list[str]:
    """Write ``--fields`` and ``--plot``; returns the messages of those that failed."""
    import numpy as np

    from .plane import LineContact

    failed = []
    if args.fields:
        extra = {} if friction is None else {
            "force_x": result.force_x, "force_y": result.force_y, "stick": result.stick,
            "slip_x": result.slip_x, "slip_y": result.slip_y,
            "displacement_x": result.displacement_x, "displacement_y": result.displacement_y}
        try:
            np.savez_compressed(
                args.fields, x=result.grid.x, y=result.grid.y, force=result.force,
                pressure=result.pressure, deflection=result.deflection, gap=result.gap,
                contact=result.contact, summary=json.dumps(summary), **extra,
            )
        except OSError as exc:
            failed.append(f"--fields {args.fields} was not written: {exc}")
    if args.plot:
        from .plots import plot_frictional_contact, plot_line_contact, plot_normal_contact

        plot = plot_normal_contact if friction is None else plot_frictional_contact
        if isinstance(result, LineContact):
            plot = plot_line_contact
        try:
            plot(result, args.plot)
        except (OSError, ValueError) as exc:
            failed.append(f"--plot {args.plot} was not written: {exc}")
    return failed


def main(argv: list[str] | None = None) -> int:
    """Exit status: 0 done, 1 the solve failed or an output could not be written (the
    result is printed first), 2 bad input or usage."""
    parser = argparse.ArgumentParser(prog="bem", description=__doc__.replace("``", ""))
    sub = parser.add_subparsers(dest="command", required=True)
    s = sub.add_parser("solve", help="solve a case file",
                       description="Solve one contact problem with the BEM: stationary or rolling, with or without "
                                   "friction (a [friction] section). Progress lines go to stderr, the result to stdout.",
                       epilog=EXIT_CODES)
    s.add_argument("case", type=Path, help="the case file (TOML, SI units; docs/case-files.md)")
    s.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override an entry of the case file (value parsed as TOML; a bare word for a "
                        "string key); repeatable; default: the file as written")
    s.add_argument("--json", action="store_true", help="print one JSON object (SI units) on stdout; default: text")
    s.add_argument("--plot", type=Path, metavar="FILE.png", help="write the pressure map and y = 0 profile, or with friction the pressure "
                   "map, tangential traction vectors and stick/slip map (PNG, PDF or SVG); default: no plot")
    s.add_argument("--fields", type=Path, metavar="FILE.npz",
                   help="save nodal coordinates and fields (NPZ); default: not saved")
    s.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    sub.add_parser("dma", add_help=False, help="DMA CSV to master curve, Prony fit and figures "
                   "(bem dma --help; docs/materials.md)")
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["dma"]:  # its own parser, options included; matplotlib and the fit only when asked
        from .dma.__main__ import main as dma_main

        return dma_main(argv[1:], prog="bem dma")
    args = parser.parse_args(argv)

    from .case import friction_from_config, problem_from_config, read_case
    from .contact import ContactError
    from .driver import solve
    from .plane import LineContact

    def progress(line: str) -> None:
        if not args.quiet:
            print(line, file=sys.stderr, flush=True)

    try:
        casefile.check_output(args.plot, PLOT_SUFFIXES, "--plot")
        casefile.check_output(args.fields, (".npz",), "--fields")
        config = read_case(args.case, args.set)
        problem, auto = problem_from_config(config)
        friction = friction_from_config(config)
    except ValueError as exc:  # casefile.CaseFileError, and the rules of bem's own inputs
        print(f"bem: error: {exc}", file=sys.stderr)
        return 2
    try:
        result = solve(problem, friction, progress=progress, grow=auto and friction is None)
    except ValueError as exc:
        print(f"bem: error: {exc}", file=sys.stderr)
        return 2
    except ContactError as exc:
        print(f"bem: error: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    summary = _strict({**result.summary(), "timings_s": result.record.times})
    if args.json:
        print(json.dumps(summary, indent=2, allow_nan=False))
    elif isinstance(result, LineContact):
        print("plane strain (line contact), per unit length along the cylinder's axis")
        print(f"rolling resistance  {result.rolling_resistance:.6g} N/m")
        if problem.loading.speed > 0:
            print(f"energy figure       {result.rolling_resistance_energy:.6g} N/m (P_visc / V)")
        print(f"indentation         {result.indentation:.6g} m")
        print(f"half-width          {result.half_width:.6g} m ((leading - trailing edge) / 2)")
        print(f"trailing edge       {result.trailing_edge:.6g} m")
        print(f"leading edge        {result.leading_edge:.6g} m")
        print(f"load                {result.load:.6g} N/m")
        print(f"peak pressure       {result.peak_pressure:.6g} Pa")
    else:
        print(f"rolling resistance  {result.rolling_resistance:.6g} N")
        if friction is None and problem.loading.speed > 0:
            print(f"energy figure       {result.rolling_resistance_energy:.6g} N (P_visc / V)")
        print(f"indentation         {result.indentation:.6g} m")
        print(f"contact radius      {result.contact_radius:.6g} m (equivalent, sqrt(area/pi))")
        print(f"load                {result.load:.6g} N")
        print(f"peak pressure       {result.peak_pressure:.6g} Pa")
        if friction is not None:
            print(f"  friction part     {result.rolling_resistance_friction:.6g} N")
            print(f"  viscous part      {result.rolling_resistance_viscous:.6g} N")
            print(f"energy figure       {result.rolling_resistance_energy:.6g} N ((P_visc + P_fric) / V)")
            print(f"omega               {result.omega:.6g} rad/s")
            print(f"driving force       {result.driving_force:.6g} N")
            print(f"driving torque      {result.driving_torque:.6g} N m")
            print(f"stick fraction      {result.stick_fraction:.4g}")
    sys.stdout.flush()
    failed = _write_outputs(args, friction, result, summary)
    for message in failed:
        print(f"bem: error: the result above was computed, but {message}", file=sys.stderr)
    for path in (args.fields, args.plot):
        if path and not any(str(path) in m for m in failed):
            progress(f"wrote {path}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
