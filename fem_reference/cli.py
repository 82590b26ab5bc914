"""Command line: ``fem-reference solve CASE.toml [--json] [--set s.k=v] [--plot F.png] [--vtu F.vtu]``.

Progress (a line per stage and per active-set iteration) goes to stderr; the
result goes to stdout, as one JSON object with ``--json`` (``contact_radius``
m, ``indentation`` m, ``load`` N, ``peak_pressure`` Pa, ``mesh`` and
``solver``; for a line indenter, steady rolling in plane strain: ``speed`` m/s,
``load`` N/m, ``indentation`` m, ``rolling_resistance`` N/m,
``pressure_centroid_x``, ``leading_edge``, ``trailing_edge``, ``contact_length`` m,
``peak_pressure`` Pa, ``dissipation`` and ``pressure_power`` W/m,
``energy_balance``; for a sphere rolling in the 3d model the same in N and W, with
``lateral_edge`` m and ``peak_memory`` bytes), before any file is written: ``--plot`` a
figure (:func:`~.output.plot_result`), ``--vtu`` the fields (:func:`~.output.write_vtu`).
Output paths are checked before the solve. Exit status 0 on success, 2 for bad input, 1 when the solve fails or an
output could not be written, 130 when interrupted (SIGINT or SIGTERM: nothing written).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import sys
import threading
from pathlib import Path
from typing import List, Optional

import casefile

from .errors import FemReferenceError, InputError  # light; the model is imported in main(), after parsing

__all__ = ["main"]

DEFAULTS_3D = """\
3d rolling (fem.model = "3d", loading.speed > 0) at its default mesh (element size
min(a_est / 10, H / 5), grading 0.3, far size H), measured on the paper's section 11
sphere (examples/paper-section11-frictionless.toml): 46k unknowns, 21 s and 1.5 GB with
MKL Pardiso on a loaded machine, R_r 0.08% and D/V 0.12% below the BEM's 3.0256 N and
3.0751 N (indentation within 0.005%). The rolling-sphere-3d cases refine the whole
mesh: 89k unknowns, R_r -0.26%, 2.8 GB; 172k, -0.09%, 6.4 GB (docs/derivations.md
section 9)."""


EXIT_CODES = """\
exit status: 0 done; 1 the solve failed or --plot/--vtu could not be written (the
result is printed first); 2 bad input or usage."""


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="fem-reference", description=__doc__.splitlines()[0].replace("``", ""),
                                 epilog=EXIT_CODES)
    sub = ap.add_subparsers(dest="command", required=True)
    s = sub.add_parser("solve", help="solve a case file (frictionless: stationary elastic, or "
                       "steady rolling of a line indenter in plane strain or of a sphere in 3d)",
                       epilog=f"{EXIT_CODES}\n\n{DEFAULTS_3D}", formatter_class=argparse.RawDescriptionHelpFormatter)
    s.add_argument("case", help="TOML case file (docs/case-files.md)")
    s.add_argument("--json", action="store_true", help="print the result as one JSON object (SI units); "
                   "default: text")
    s.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override an entry; the value is parsed as TOML; repeatable; default: the file "
                        "as written")
    s.add_argument("--plot", metavar="FILE.png", help="pressure profile and deformed surface (a "
                   "rolling sphere: also the pressure map; profiles on y = 0); default: no plot")
    s.add_argument("--vtu", metavar="FILE.vtu", help="export the mesh with displacement, pressure "
                   "and viscous strains (meshio; a rolling sphere: the half layer y >= 0); default: none")
    s.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    return ap


def _interrupt(signum, frame):
    raise KeyboardInterrupt(signal.Signals(signum).name)


def main(argv: Optional[List[str]] = None) -> int:
    """Exit status: 0 done, 1 the solve failed or an output could not be written (the result
    is printed first), 2 bad input or usage, 130 interrupted (SIGINT or SIGTERM: nothing
    written, a half-written output removed)."""
    args = _parser().parse_args(argv)
    previous = {}
    if threading.current_thread() is threading.main_thread():  # handlers live in the main thread only
        previous = {s: signal.signal(s, _interrupt) for s in (signal.SIGINT, signal.SIGTERM)}
    outputs = [p for p in (args.plot, args.vtu) if p is not None]
    existed = {p: Path(p).exists() for p in outputs}
    try:
        return _run(args)
    except KeyboardInterrupt as exc:
        for path in outputs:  # an output this run began writing, not one that was there before
            if not existed[path]:
                with contextlib.suppress(OSError):
                    os.remove(path)
        print(f"fem-reference: interrupted ({exc or 'SIGINT'}): nothing written", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader of stdout went away: a quiet end
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)


def _run(args) -> int:
    """The ``solve`` command on parsed ``args``; its exit status."""
    from .case import load_case
    from .output import plot_result, write_vtu
    from .rolling.result import RollingResult
    from .driver import solve

    def progress(line: str) -> None:
        print(f"fem-reference: {line}", file=sys.stderr, flush=True)

    try:
        plot = casefile.check_output(args.plot, (".png", ".pdf", ".svg"), "--plot")
        vtu = casefile.check_output(args.vtu, (".vtu",), "--vtu")
        problem = load_case(args.case, args.set)
    except (InputError, casefile.InputError) as exc:
        print(f"fem-reference: error: {exc}", file=sys.stderr)
        return 2
    try:
        result = solve(problem, progress=None if args.quiet else progress)
    except InputError as exc:
        print(f"fem-reference: error: {exc}", file=sys.stderr)
        return 2
    except FemReferenceError as exc:
        print(f"fem-reference: error: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    summary = result.summary()
    if args.json:
        print(json.dumps(summary, indent=2, allow_nan=False))
    elif isinstance(result, RollingResult):
        eb = summary["energy_balance"]
        per = "" if result.mesh.model == "3d" else "/m"
        where = " (y = 0)" if result.mesh.model == "3d" else ""
        print(f"speed              {result.speed:.6e} m/s\nload               {result.load:.6e} N{per}\n"
              f"indentation        {result.indentation:.6e} m\n"
              f"rolling resistance {result.rolling_resistance:.6e} N{per} (D/V "
              f"{result.rolling_resistance_energy:.6e} N{per})\n"
              f"contact edges{where} {result.trailing_edge:.6e} .. {result.leading_edge:.6e} m\n"
              f"peak pressure      {result.peak_pressure:.6e} Pa\n"
              f"dissipation        {result.dissipation:.6e} W{per} (energy balance "
              f"{'n/a' if eb is None else f'{eb:+.2e}'})\n"
              f"{result.mesh.model}: {result.mesh.unknowns} unknowns, "
              f"{result.solver.iterations} active-set iterations")
    else:
        print(f"contact radius {result.contact_radius:.6e} m\nindentation    "
              f"{result.indentation:.6e} m\nload           {result.load:.6e} N\n"
              f"peak pressure  {result.peak_pressure:.6e} Pa\n"
              f"{result.mesh.model}: {result.mesh.unknowns} unknowns, "
              f"{result.solver.iterations} active-set iterations")
    sys.stdout.flush()
    failed = 0
    for option, path, write in (("--plot", plot, plot_result), ("--vtu", vtu, write_vtu)):
        if path is None:
            continue
        try:
            write(result, path)
        except (OSError, ValueError) as exc:
            print(f"fem-reference: error: the result above was computed, but {option} {path} was not "
                  f"written: {exc}", file=sys.stderr)
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
