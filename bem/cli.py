"""``bem solve CASE.toml``: one contact problem from a case file.

Exit status: 0 done; 1 the solve failed or an output file could not be written (the
result is printed first); 2 bad input or usage; 130 interrupted (SIGINT or SIGTERM).

All or nothing: ``--fields`` and ``--plot`` are written under temporary names and
renamed, together with printing the result, once everything is computed; an interrupt
before that point leaves no file and prints no result, one during it (milliseconds) is
honoured after it. A closed standard output (``bem solve CASE --json | head``) ends the
command quietly."""

from __future__ import annotations

import argparse
import contextlib
import gc
import io
import math
import os
import signal
import sys
import threading
from pathlib import Path

import casefile

from .threads import one_blas_thread_from_start

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
              "printed first); 2 bad input or usage; 130 interrupted (SIGINT, SIGTERM: no output written).")


def _partial(path: Path) -> Path:
    """The temporary name ``path`` is written under before it is renamed (same folder and
    suffix: the writers choose the format from it)."""
    return path.with_name(f".{path.stem}.{os.getpid()}.partial{path.suffix}")


def _write_outputs(args, friction, result, summary) -> list[str]:
    """Write ``--fields`` and ``--plot`` under their :func:`_partial` names; returns the
    messages of those that failed."""
    import numpy as np

    from .plane import LineContact

    failed = []
    fields, plot_path = args.fields, args.plot
    if args.fields:
        extra = {} if friction is None else {
            "force_x": result.force_x, "force_y": result.force_y, "stick": result.stick,
            "slip_x": result.slip_x, "slip_y": result.slip_y,
            "displacement_x": result.displacement_x, "displacement_y": result.displacement_y}
        import json

        try:
            np.savez_compressed(
                _partial(fields), x=result.grid.x, y=result.grid.y, force=result.force,
                pressure=result.pressure, deflection=result.deflection, gap=result.gap,
                contact=result.contact, summary=json.dumps(summary), **extra,
            )
        except OSError as exc:
            failed.append(f"--fields {fields} was not written: {exc}")
    if args.plot:
        from .plots import plot_frictional_contact, plot_line_contact, plot_line_friction, plot_normal_contact

        plot = plot_normal_contact if friction is None else plot_frictional_contact
        if isinstance(result, LineContact):
            plot = plot_line_contact
        elif friction is not None and getattr(result, "plane_strain", False):
            plot = plot_line_friction
        try:
            plot(result, _partial(plot_path))
        except (OSError, ValueError) as exc:
            failed.append(f"--plot {plot_path} was not written: {exc}")
    return failed


class _Signals:
    """SIGINT and SIGTERM as :class:`KeyboardInterrupt` while the work runs; recorded,
    not raised, while the outputs are committed (:meth:`committing`)."""

    def __init__(self) -> None:
        self.deferred = None
        self.commit = False
        self.previous = {}
        if threading.current_thread() is threading.main_thread():  # handlers live in the main thread only
            self.previous = {s: signal.signal(s, self._handle) for s in (signal.SIGINT, signal.SIGTERM)}

    def _handle(self, signum, frame) -> None:
        if self.commit:
            self.deferred = signum
            return
        raise KeyboardInterrupt(signal.Signals(signum).name)

    @contextlib.contextmanager
    def committing(self):
        self.commit = True
        try:
            yield
        finally:
            self.commit = False

    def restore(self) -> None:
        for s, handler in self.previous.items():
            signal.signal(s, handler)


def _commit(text: str, paths, failed: list[str], progress) -> int:
    """Print ``text`` and rename the partial files of ``paths`` (those not in ``failed``)
    to their names; the exit status (1 if an output failed)."""
    try:
        sys.stdout.write(text)
        sys.stdout.flush()
    except BrokenPipeError:  # the reader went away: quiet, and no second error at exit
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    for path in paths:
        if path and not any(str(path) in m for m in failed):
            try:
                os.replace(_partial(path), path)
            except OSError as exc:
                failed.append(f"{path} was not written: {exc}")
                continue
            progress(f"wrote {path}")
    _discard([p for p in paths if p and any(str(p) in m for m in failed)])  # a half-written file
    for message in failed:
        print(f"bem: error: the result above was computed, but {message}", file=sys.stderr)
    return 1 if failed else 0


def _discard(paths) -> None:
    for path in paths:
        if path:
            with contextlib.suppress(OSError):
                os.remove(_partial(path))


class _Formatter(argparse.HelpFormatter):
    """argparse's help formatter at the terminal's width (``COLUMNS``, else the terminal of
    standard output, else 80), found without argparse's import of shutil: argparse builds
    a formatter for every argument it adds, and shutil's import (with zlib, bz2 and lzma)
    took 2.8 ms of every start."""

    def __init__(self, prog, **kwargs):
        if kwargs.get("width") is None:
            try:
                columns = int(os.environ["COLUMNS"])
            except (KeyError, ValueError):
                try:
                    columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
                except (AttributeError, ValueError, OSError):
                    columns = 80
            kwargs["width"] = columns - 2
        super().__init__(prog, **kwargs)


def main(argv: list[str] | None = None) -> int:
    """Exit status: 0 done, 1 the solve failed or an output could not be written (the
    result is printed first), 2 bad input or usage, 130 interrupted (module docstring)."""
    parser = argparse.ArgumentParser(prog="bem", description=__doc__.replace("``", ""), formatter_class=_Formatter)
    sub = parser.add_subparsers(dest="command", required=True)
    s = sub.add_parser("solve", help="solve a case file", formatter_class=_Formatter,
                       description="Solve one contact problem with the BEM: stationary or rolling, with or without "
                                   "friction (a [friction] section). Progress lines go to stderr, the result to stdout.",
                       epilog=EXIT_CODES)
    s.add_argument("case", type=Path, help="the case file (TOML, SI units; docs/case-files.md)")
    s.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override an entry of the case file (value parsed as TOML; a bare word for a "
                        "string key); repeatable; default: the file as written")
    s.add_argument("--json", action="store_true", help="print one JSON object (SI units) on stdout; default: text")
    s.add_argument("--plot", type=Path, metavar="FILE.png",
                   help="write the pressure map and y = 0 profile, or with friction the pressure map, tangential "
                        "traction vectors and stick/slip map; a line contact: the profiles along x (with friction: "
                        "pressure, traction, +-mu p, stick zone, slip velocity); PNG, PDF or SVG; default: no plot")
    s.add_argument("--fields", type=Path, metavar="FILE.npz",
                   help="save nodal coordinates and fields (NPZ); default: not saved")
    s.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    s.add_argument("--error-estimate", action=argparse.BooleanOptionalAction, default=None,
                   help="with friction: solve again on the grid coarsened by 2 and 4 and give each frictional "
                        "figure's Richardson limit and grid error (the frictional figures converge at first "
                        "order: one grid's value is no better than its error; 1.1-1.4 times the time of the solve alone); "
                        "default: on with [friction], --no-error-estimate to skip it")
    sub.add_parser("dma", add_help=False, help="DMA CSV to master curve, Prony fit and figures "
                   "(bem dma --help; docs/materials.md)")
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["dma"]:  # its own parser, options included; matplotlib and the fit only when asked
        _modules_loaded()
        from .dma.__main__ import main as dma_main

        return dma_main(argv[1:], prog="bem dma")
    args = parser.parse_args(argv)
    signals = _Signals()
    try:
        return _run(args, signals)
    except KeyboardInterrupt as exc:
        _discard((args.fields, args.plot))
        print(f"bem: interrupted ({exc or 'SIGINT'}): nothing written", file=sys.stderr)
        return 130
    finally:
        signals.restore()


def _run(args, signals: _Signals) -> int:
    """The ``solve`` command on parsed ``args``; its exit status."""
    from .case import friction_from_config, problem_from_config, read_case
    from .contact import ContactError
    from .driver import solve
    from .plane import LineContact

    _modules_loaded()

    def progress(line: str) -> None:
        if not args.quiet:
            print(line, file=sys.stderr, flush=True)

    try:
        casefile.check_output(args.plot, PLOT_SUFFIXES, "--plot")
        casefile.check_output(args.fields, (".npz",), "--fields")
        config = read_case(args.case, args.set)
        problem, auto = problem_from_config(config)
        _keep_freed_memory(problem.grid.nodes_x * problem.grid.nodes_y)
        friction = friction_from_config(config)
        if args.error_estimate is None:
            args.error_estimate = friction is not None
        if args.error_estimate and friction is None:
            raise ValueError("--error-estimate estimates the grid error of the frictional figures: "
                             "the case needs a [friction] section")
    except ValueError as exc:  # casefile.CaseFileError, and the rules of bem's own inputs
        print(f"bem: error: {exc}", file=sys.stderr)
        return 2
    estimate = None
    try:
        result = solve(problem, friction, progress=progress, grow=auto and friction is None)
    except ValueError as exc:
        print(f"bem: error: {exc}", file=sys.stderr)
        return 2
    except ContactError as exc:
        print(f"bem: error: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    if args.error_estimate:
        estimate = _grid_error(problem, friction, result, progress)
    summary = _strict({**result.summary(), "timings_s": result.record.times,
                       **({"grid_error": estimate if isinstance(estimate, dict) else estimate.summary()}
                          if estimate else {})})
    failed = _write_outputs(args, friction, result, summary)
    text = io.StringIO()
    with contextlib.redirect_stdout(text):
        _print_result(args, problem, friction, result, summary, LineContact)
        if estimate is not None and not args.json:
            print("\n".join(estimate.lines()) if not isinstance(estimate, dict) else
                  f"grid error: not estimated ({estimate['not_estimated']})")
    with signals.committing():
        return _commit(text.getvalue(), (args.fields, args.plot), failed, progress)


def _grid_error(problem, friction, result, progress):
    """The grid error of the frictional figures (:func:`bem.frictional.grid_error.
    estimate_grid_error`), or ``{"not_estimated": why}`` when a coarse level cannot be
    solved (its contact reaches the region's edge, say): the result stands without it."""
    from .contact import ContactError
    from .frictional.grid_error import estimate_grid_error

    try:
        return estimate_grid_error(problem, friction, fine=result, progress=progress)
    except (ValueError, ContactError) as exc:
        why = f"the grid coarsened by 2 and 4 could not be solved: {type(exc).__name__}: {exc}"
        progress(f"grid error: not estimated: {why}")
        return {"not_estimated": why}


def _print_result(args, problem, friction, result, summary, LineContact) -> None:
    """The result as JSON or text on standard output."""
    if args.json:
        import json

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
        line = friction is not None and problem.plane_strain
        force, torque = ("N/m", "N m/m") if line else ("N", "N m")
        if line:
            print("plane strain (line contact), per unit length along the cylinder's axis")
        print(f"rolling resistance  {result.rolling_resistance:.6g} {force}")
        if friction is None and problem.loading.speed > 0:
            print(f"energy figure       {result.rolling_resistance_energy:.6g} N (P_visc / V)")
        print(f"indentation         {result.indentation:.6g} m")
        if line:
            print(f"half-width          {result.contact_radius:.6g} m (between the contact's edges)")
        else:
            print(f"contact radius      {result.contact_radius:.6g} m (equivalent, sqrt(area/pi))")
        print(f"load                {result.load:.6g} {force}")
        print(f"peak pressure       {result.peak_pressure:.6g} Pa")
        if friction is not None:
            print(f"  friction part     {result.rolling_resistance_friction:.6g} {force}")
            print(f"  viscous part      {result.rolling_resistance_viscous:.6g} {force}")
            print(f"energy figure       {result.rolling_resistance_energy:.6g} {force} ((P_visc + P_fric) / V)")
            print(f"omega               {result.omega:.6g} rad/s")
            print(f"driving force       {result.driving_force:.6g} {force}")
            print(f"driving torque      {result.driving_torque:.6g} {torque}")
            print(f"stick fraction      {result.stick_fraction:.4g}")


_paused = False  # the cyclic collector paused by the command while its modules load


def _pause_collection() -> None:
    """For a process of its own (:func:`command`): no cyclic garbage collection while numpy
    and the solver's modules load, which :func:`_modules_loaded` ends. What they build lives
    to the end of the process, so the collector found nothing to free there, in 45 passes
    over ever more survivors: 6-8 ms of a 0.23 s ``bem solve`` (the elastic paraboloid with
    friction at 0.2 mm)."""
    global _paused
    if gc.isenabled():
        gc.disable()
        _paused = True


def _modules_loaded() -> None:
    """The modules loaded: their objects frozen (:func:`gc.freeze`, never scanned again)
    and the collector back on for the solve, whose cycles it must free, if
    :func:`_pause_collection` paused it."""
    global _paused
    if _paused:
        _paused = False
        gc.freeze()
        gc.enable()


#: glibc's ``mallopt`` parameters (``malloc.h``) and the values :func:`_keep_freed_memory` sets
_M_TRIM_THRESHOLD, _M_TOP_PAD, _M_MMAP_THRESHOLD = -1, -2, -3
MMAP_THRESHOLD = 32 << 20
TRIM_THRESHOLD = 2 * MMAP_THRESHOLD
HEAP_PAD = 16 << 20
#: grids of at most this many nodes take :func:`_keep_freed_memory` (160 x 160)
KEEP_FREED_UPTO = 25_600
#: environment variables by which a user sets glibc's allocator themselves
MALLOC_VARIABLES = ("MALLOC_TOP_PAD_", "MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_", "MALLOC_MMAP_MAX_")
_own_process = False  # set by command(): the process's allocator is the command's to set


def _keep_freed_memory(nodes: int) -> bool:
    """For a process of its own (:func:`command`) solving on a grid of at most
    :data:`KEEP_FREED_UPTO` ``nodes``, with glibc's allocator: the memory the solve frees
    is kept for its next arrays instead of going back to the system, whose fresh pages
    then fault in one by one as they are written.

    glibc gives freed memory back: an array above its mmap threshold (128 KiB at first;
    the first kernels raise it to 31 MiB, :func:`bem.batches._keep_heap`) is unmapped when
    freed, and the heap's top is trimmed once twice that threshold is free there. After
    the kernels' large arrays are freed, a small grid's solve then writes fresh pages: at
    61 x 61 nodes 4430 page faults after the kernels (the fine active set 2740), 180 with
    :data:`HEAP_PAD` kept on the heap's top (``M_TOP_PAD``); two 1 MiB arrays made and
    freed 20 times in a fresh process fault 9600 pages, 480 with it. Setting the pad
    freezes glibc's thresholds, so they are set too, where glibc's own rule ends
    (``M_MMAP_THRESHOLD`` :data:`MMAP_THRESHOLD`, its ceiling; ``M_TRIM_THRESHOLD``
    twice that). Measured (``python -m bem.cli solve``, paired runs against
    the default allocator, one BLAS thread): the elastic paraboloid with friction at
    0.2 mm (61 x 61 nodes), 6700 against 11 700 page faults, 0.230 against 0.242 s
    (median ratio of 30 pairs 0.953); the viscoelastic half-space of
    ``benchmarks/bem_viscoelastic_rolling.py`` (155 x 155) 0.973, its peak 129 against
    106 MiB; the paraboloid at 0.1 mm (121 x 121) 1.01. On larger grids the default
    wins: at 0.05 mm (241 x 241) 1.06-1.10 times as long; section 11 with friction, the
    settings made at the process's start, 1.10 at 385 x 385 and 1.07 at 513 x 513.

    Nothing when the user sets the allocator (:data:`MALLOC_VARIABLES`, ``glibc.malloc``
    in ``GLIBC_TUNABLES``) or the C library is not glibc. Returns whether it was set."""
    if not _own_process or nodes > KEEP_FREED_UPTO:
        return False
    if any(os.environ.get(name) for name in MALLOC_VARIABLES) or "glibc.malloc" in os.environ.get("GLIBC_TUNABLES", ""):
        return False
    try:
        libc = os.confstr("CS_GNU_LIBC_VERSION") or ""
    except (AttributeError, ValueError, OSError):  # no confstr (Windows) or no such name (macOS, musl)
        return False
    if not libc.startswith("glibc"):
        return False
    import ctypes

    mallopt = ctypes.CDLL(None).mallopt
    return all(mallopt(param, value) for param, value in ((_M_MMAP_THRESHOLD, MMAP_THRESHOLD),
                                                          (_M_TRIM_THRESHOLD, TRIM_THRESHOLD), (_M_TOP_PAD, HEAP_PAD)))


def command() -> None:
    """The ``bem`` command (its console script, and ``python -m bem.cli``): :func:`main`
    with one BLAS thread from the start (:func:`bem.threads.one_blas_thread_from_start`)
    and, on a small grid, the allocator keeping the memory the solve frees
    (:func:`_keep_freed_memory`); then, its output flushed, the process ends at once
    (``os._exit``) instead of tearing down the interpreter, which freed every module and
    array one by one: 0.006 s of a 0.22 s ``bem solve`` (the elastic paraboloid with friction
    at 0.2 mm; median ratio of 30 pairs 0.977). Every file it writes is closed by then
    (:func:`_commit`). Usage errors and ``--help`` exit through ``SystemExit`` as usual;
    in-process callers (the tests) call :func:`main`."""
    global _own_process
    _own_process = True
    one_blas_thread_from_start()
    _pause_collection()
    status = main()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a reader gone, a stream closed
            stream.flush()
    os._exit(status)


if __name__ == "__main__":
    command()
