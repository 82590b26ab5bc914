"""``verify``: run the verification suite and write its report.

Exit codes: 0 every gate passes; 1 a gate failed (or a case could not run); 2 bad input
or usage (a case file that breaks the schema, an unknown case or method, an unwritable
``--out``): nothing was solved; 130 interrupted (Ctrl-C or SIGTERM): the previous report
is left as it was.
"""

from __future__ import annotations

import argparse
import signal
import sys
from pathlib import Path

from .report import ReportError, check_junit, check_out, drift, load_baseline, summary_line, write_report
from .runner import CASES_DIR, CaseError, list_cases, load_cases, run_case

EXIT_PASS, EXIT_FAIL, EXIT_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130


class _Terminated(BaseException):
    """SIGTERM, raised where the run is, so the report folder is cleaned like on Ctrl-C."""


def _on_sigterm(signum, frame):
    raise _Terminated()


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="verify", description=__doc__.split("\n\n")[0],
                                epilog="Exit codes: 0 pass, 1 a gate failed, 2 bad input, 130 interrupted.")
    p.add_argument("--quick", action="store_true", help="the fast subset CI runs (cases with quick = true)")
    p.add_argument("--out", type=Path, default=Path("verification-report"), help="report folder")
    p.add_argument("--case", action="append", default=[], metavar="NAME",
                   help="run only these cases (names or .toml paths); repeatable")
    p.add_argument("--cases-dir", type=Path, default=CASES_DIR, help="folder of case files")
    p.add_argument("--method", action="append", default=[], metavar="NAME[=SPEC]",
                   help="hold another method to every gate the BEM is held to: an installed plugin NAME, "
                        "NAME=package.module:function, or NAME=FOLDER of results files (<case>.json); repeatable")
    p.add_argument("--junit", type=Path, metavar="FILE.xml", help="also write JUnit XML, one test case per gate")
    p.add_argument("--baseline", type=Path, metavar="OLD/metrics.json",
                   help="flag gates whose error moved by more than --drift of their tolerance since this run")
    p.add_argument("--drift", type=float, default=0.25, metavar="FRACTION",
                   help="fraction of a gate's tolerance that counts as drift (default 0.25)")
    p.add_argument("--fail-on-drift", action="store_true", help="exit 1 when any gate drifted")
    return p


def _select(args) -> list[Path]:
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


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)

    def progress(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    try:
        if not args.drift > 0:
            raise CaseError(f"--drift must be > 0, got {args.drift}")
        check_out(args.out)
        if args.junit:
            check_junit(args.junit)
        baseline = load_baseline(args.baseline) if args.baseline else None
        cases = load_cases(_select(args), args.method)
    except (CaseError, ReportError) as exc:
        for line in str(exc).splitlines():
            print(f"verify: error: {line}", file=sys.stderr)
        return EXIT_INPUT
    if args.quick and not args.case:
        cases = [c for c in cases if c.get("quick", False)]
        if not cases:
            print(f"verify: error: no case in {args.cases_dir} has quick = true", file=sys.stderr)
            return EXIT_INPUT

    previous = signal.signal(signal.SIGTERM, _on_sigterm)
    results = []
    try:
        for i, case in enumerate(cases, 1):
            progress(f"[{i}/{len(cases)}] {case['name']}: {case['title']}")
            result = run_case(case, progress, quick=args.quick)
            failed = [g for g in result.gates if not g.passed]
            n = sum(not g.report_only for g in result.gates)
            progress(f"  {case['name']}: {'PASS' if result.passed else 'FAIL'} ({n - len(failed)}/{n} gates, "
                     f"{len(result.gates) - n} reported, {result.seconds:.1f} s)")
            for g in failed:
                progress(f"    FAIL {g.method} {g.quantity} vs {g.against} ({g.level}): error {g.error:.3e} > "
                         f"{g.tolerance:.1e}: {g.reason}")
            results.append(result)
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
