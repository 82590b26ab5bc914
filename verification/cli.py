"""``verify``: run the verification suite and write its report.

Exit codes: 0 every gate passes; 1 a gate failed (or a case or a method could not run:
a method that raises, exits or returns what the gates cannot use fails its gates, with
the reason, in the report); 2 bad input or usage (a case file that breaks the schema, an
unknown case or method, a malformed results file or baseline, an ``--out`` that is not
the report's to replace): nothing was solved; 130 interrupted (Ctrl-C or SIGTERM): the
previous report is left as it was.

``--out`` is replaced only when it is a report ``verify`` wrote (it carries the marker
file :data:`verification.out_folder.MARKER`) or empty; see :mod:`verification.out_folder`.

``--workers N`` and ``--scheduler ADDRESS`` run the cases side by side on Dask
(:mod:`verification.parallel`); the report is the same as a serial run's but for its
timings.
"""

from __future__ import annotations

import argparse
import json
import math
import signal
import sys
from pathlib import Path

from .out_folder import FORMAT, MARKER, OutFolderError, marker_format
from .out_folder import check as check_out_folder
from .parallel import TIMEOUT, close_client, open_client, run_cases, workers_count

# The report and the runner (numpy, scipy, the solvers) are imported inside the functions,
# after the arguments are parsed: --help answers without loading them.
CASES_DIR = Path(__file__).resolve().parent / "cases"  # verification.runner.CASES_DIR

EXIT_PASS, EXIT_FAIL, EXIT_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130


class _Terminated(BaseException):
    """SIGTERM, raised where the run is, so the report folder is cleaned like on Ctrl-C."""


def _on_sigterm(signum, frame):
    raise _Terminated()


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="verify", description=__doc__.split("\n\n")[0].replace("``", ""),
                                epilog="Exit codes: 0 every gate passes; 1 a gate failed or a case could not run; 2 bad "
                                       "input or usage (nothing solved); 130 interrupted (the previous report kept).")
    p.add_argument("--quick", action="store_true", help="a fast subset: the cases with quick = true, some with fewer cells or speeds "
                   "(default: every case)")
    p.add_argument("--full", action="store_true", help="also the cases with full = true: finer levels, more memory "
                   "and time (default: without them)")
    p.add_argument("--out", type=Path, default=Path("verification-report"), metavar="DIR",
                   help="report folder; replaced only when it is an earlier report (or empty) "
                        "(default: verification-report)")
    p.add_argument("--overwrite", action="store_true",
                   help="let --out name a folder that is not a report: its content is kept beside the report, "
                        "renamed OUT.kept-DATE-TIME (never the working folder or the cases folder); "
                        "let --junit replace a file that is not a JUnit file verify wrote")
    p.add_argument("--case", action="append", default=[], metavar="NAME",
                   help="run only these cases (names or .toml paths); repeatable (default: every case)")
    p.add_argument("--cases-dir", type=Path, default=CASES_DIR, metavar="DIR",
                   help="folder of case files (default: the installed verification/cases)")
    p.add_argument("--method", action="append", default=[], metavar="NAME[=SPEC]",
                   help="hold another method to every gate the BEM is held to: an installed plugin NAME, "
                        "NAME=package.module:function, or NAME=FOLDER of results files (<case>.json); repeatable")
    p.add_argument("--junit", type=Path, metavar="FILE.xml", help="also write JUnit XML, one test case per gate")
    p.add_argument("--baseline", type=Path, metavar="OLD/metrics.json",
                   help="flag gates whose error moved by more than --drift of their tolerance since this run")
    p.add_argument("--drift", type=float, default=0.25, metavar="FRACTION",
                   help="fraction of a gate's tolerance that counts as drift (default 0.25)")
    p.add_argument("--fail-on-drift", action="store_true", help="exit 1 when any gate drifted")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=workers_count, metavar="N",
                       help="run the cases side by side on a local Dask cluster of N worker processes, one "
                            "thread each, BLAS at one thread (unless OPENBLAS_NUM_THREADS, MKL_NUM_THREADS or "
                            "OMP_NUM_THREADS says otherwise); the paper's sweeps run here and submit to it. "
                            "N cases are in memory at once: the peak is about the sum of the N largest cases' "
                            "own peaks (the 3D rolling FEM: 3.2 GB, 6.5 GB with --full) plus 0.2 GB for this "
                            "process (--quick: 1.1 GB with --workers 2, 0.7 GB serially). Progress: a line as "
                            "each case starts (naming its worker), its per-stage lines forwarded from the "
                            "worker (the lines of cases running together interleave), its verdict and time as "
                            "it ends. The report is the serial run's but for its timings and, where the "
                            "serial run's BLAS ran several threads, the last digits "
                            "(default: one case after another in this process)")
    where.add_argument("--scheduler", metavar="ADDRESS|FILE.json",
                       help="the same on an existing Dask scheduler (tcp://HOST:PORT or a scheduler file), "
                            f"which must answer within {TIMEOUT:g} s. Its workers need this project installed "
                            "and the files a case reads (a --method results folder, a DMA table) at the same "
                            "paths; a --method .py file travels with the case. Results come back as data: the "
                            "report and its figures are written here")
    return p


def _select(args) -> list[Path]:
    from .runner import CaseError, list_cases

    if args.case:
        chosen = []
        by_name = None
        for name in args.case:
            p = Path(name)
            if p.suffix == ".toml":
                if not p.is_file():
                    raise CaseError(f"--case {name}: no such file")
                chosen.append(p)
                continue
            by_name = by_name or {q.stem: q for q in list_cases(args.cases_dir)}
            if name not in by_name:
                from .schema import close

                raise CaseError(f"--case {name}: unknown case; known in {args.cases_dir}: "
                                f"{', '.join(sorted(by_name))}{close(name, by_name)}")
            chosen.append(by_name[name])
        return chosen
    return list_cases(args.cases_dir)


def _baseline(path: Path) -> dict:
    """``--baseline``: a metrics.json of this report format, every gate with its key,
    verdict, error and tolerance; a :class:`ReportError` naming the file and the field."""
    from .report import ReportError, load_baseline

    gates = load_baseline(path)  # unreadable, not JSON, no cases, gates or keys
    fmt = marker_format(path.parent)
    if fmt is not None and fmt != FORMAT:
        raise ReportError(f"--baseline {str(path)!r}: its folder's {MARKER} says report format "
                          f"{fmt or 'unreadable'}; this verify reads format {FORMAT}. Make a new baseline with it")
    doc = json.loads(path.read_text())
    cases = doc.get("cases") if isinstance(doc, dict) else None
    if not isinstance(cases, list):
        raise ReportError(f"--baseline {str(path)!r}: 'cases' must be a list (not a metrics.json of verify)")
    for i, case in enumerate(cases):
        for j, g in enumerate(case["gates"] if isinstance(case, dict) else [None]):
            where = f"--baseline {str(path)!r} cases[{i}].gates[{j}]"
            if not isinstance(g, dict):
                raise ReportError(f"{where}: a gate is a table, got {g!r}")
            for key in ("key", "verdict", "error", "tolerance"):
                if key not in g:
                    raise ReportError(f"{where}: no {key!r} (a metrics.json of another version of verify?)")
            if not isinstance(g["key"], str) or g["verdict"] not in ("PASS", "FAIL", "REPORTED"):
                raise ReportError(f"{where}: 'key' must be a string and 'verdict' PASS, FAIL or REPORTED, got "
                                  f"{g['key']!r} and {g['verdict']!r}")
            for key in ("error", "tolerance"):
                v = g[key]
                if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v)):
                    raise ReportError(f"{where}: {key!r} must be a finite number or null, got {v!r}")
    return gates


def _ours(junit: Path) -> bool:
    """Whether ``junit`` is absent or a JUnit file verify wrote (its root is <testsuites name="verify">)."""
    try:
        with open(junit, "rb") as fh:
            head = fh.read(200)
    except FileNotFoundError:
        return True
    except OSError:
        return False
    return b'<testsuites name="verify"' in head


def _inside(path: Path, folder: Path) -> bool:
    path, folder = Path(path).resolve(), Path(folder).resolve()
    return folder in path.parents


def _client(args):
    """The Dask client of ``--workers``/``--scheduler``; ``None`` (the error said) when the
    scheduler cannot be reached."""
    from sweeps.spec import SweepError

    try:
        return open_client(args.workers, args.scheduler)
    except SweepError as exc:
        print(f"verify: error: {exc}", file=sys.stderr)
        return None


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    from .report import ReportError, check_junit, check_out, drift, summary_line, write_report
    from .runner import CaseError, load_cases, run_case

    def progress(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    def done(index: int, result) -> None:
        failed = [g for g in result.gates if not g.passed]
        n = sum(not g.report_only for g in result.gates)
        progress(f"  {result.name}: {'PASS' if result.passed else 'FAIL'} ({n - len(failed)}/{n} gates, "
                 f"{len(result.gates) - n} reported, {result.seconds:.1f} s)")
        for g in failed:
            progress(f"    FAIL {g.method} {g.quantity} vs {g.against} ({g.level}): error {g.error:.3e} > "
                     f"{g.tolerance:.1e}: {g.reason}")
        results.append(result)

    try:
        if not args.drift > 0:
            raise CaseError(f"--drift must be > 0, got {args.drift}")
        check_out(args.out)
        paths = _select(args)
        check_out_folder(args.out, [args.cases_dir, *(p.parent for p in paths)], args.overwrite)
        if args.junit:
            check_junit(args.junit)
            if _inside(args.junit, args.out):
                raise ReportError(f"--junit {str(args.junit)!r} is inside --out {str(args.out)!r}, which the "
                                  "report replaces; write it beside, e.g. --junit verify-junit.xml")
            if not args.overwrite and not _ours(args.junit):
                raise ReportError(f"--junit {str(args.junit)!r} exists and is not a JUnit file verify wrote; "
                                  "name another file, or give --overwrite to replace it")
        baseline = _baseline(args.baseline) if args.baseline else None
        cases = load_cases(paths, args.method)
    except (CaseError, ReportError, OutFolderError) as exc:
        for line in str(exc).splitlines():
            print(f"verify: error: {line}", file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        print("verify: interrupted while reading the cases; nothing was solved", file=sys.stderr)
        return EXIT_INTERRUPTED
    if not args.full and not args.case:
        cases = [c for c in cases if not c.get("full", False)]
    if args.quick and not args.case:
        cases = [c for c in cases if c.get("quick", False)]
        if not cases:
            print(f"verify: error: no case in {args.cases_dir} has quick = true", file=sys.stderr)
            return EXIT_INPUT

    previous = signal.signal(signal.SIGTERM, _on_sigterm)
    results, client = [], None
    try:
        if args.workers or args.scheduler:
            client = _client(args)
            if client is None:
                return EXIT_INPUT
            results = run_cases(cases, client, args.quick, progress, done)
        else:
            for i, case in enumerate(cases, 1):
                progress(f"[{i}/{len(cases)}] {case['name']}: {case['title']}")
                done(i - 1, run_case(case, progress, quick=args.quick))
        drifts = drift(results, baseline, args.drift) if baseline is not None else []
        report = write_report(results, args.out, junit=args.junit, drifts=drifts)
    except (KeyboardInterrupt, _Terminated):
        print(f"verify: interrupted after {len(results)} of {len(cases)} cases; the report in {args.out} "
              "is the previous one", file=sys.stderr)
        return EXIT_INTERRUPTED
    except OSError as exc:
        print(f"verify: error: the report could not be written: {exc}", file=sys.stderr)
        return EXIT_FAIL
    finally:
        if client is not None:
            close_client(client)
        signal.signal(signal.SIGTERM, previous)
    ok = all(r.passed for r in results)
    print(f"{summary_line(results)} Report: {report} and {report.with_suffix('.html')}, "
          f"metrics: {report.parent / 'metrics.json'}")
    for d in drifts:
        print(f"verify: drift: {d.key}: {d.note}")
    if not ok or (args.fail_on_drift and drifts):
        return EXIT_FAIL
    return EXIT_PASS


if __name__ == "__main__":
    sys.exit(main())
