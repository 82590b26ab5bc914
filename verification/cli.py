"""``verify``: run the verification suite, write the report, exit non-zero if a gate fails."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from .report import write_report
from .runner import CASES_DIR, list_cases, load_case, run_case


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="verify", description=__doc__)
    parser.add_argument("--quick", action="store_true", help="the fast subset CI runs (a few minutes)")
    parser.add_argument("--out", type=Path, default=Path("verification-report"), help="report folder")
    parser.add_argument("--case", action="append", default=[], metavar="NAME",
                        help="run only these cases (names or .toml paths); repeatable")
    parser.add_argument("--cases-dir", type=Path, default=CASES_DIR, help="folder of case files")
    args = parser.parse_args(argv)

    paths = list_cases(args.cases_dir)
    if args.case:
        by_name = {p.stem: p for p in paths}
        chosen = []
        for name in args.case:
            p = Path(name)
            if p.suffix == ".toml" and p.exists():
                chosen.append(p)
            elif name in by_name:
                chosen.append(by_name[name])
            else:
                print(f"verify: unknown case {name!r}; known: {', '.join(sorted(by_name))}", file=sys.stderr)
                return 2
        paths = chosen
    try:
        cases = [load_case(p) for p in paths]
    except ValueError as exc:  # casefile.CaseFileError: a case that breaks the schema
        print(f"verify: error: {exc}", file=sys.stderr)
        return 2
    if args.quick and not args.case:
        cases = [c for c in cases if c.get("quick", False)]
    if not cases:
        print("verify: no case to run", file=sys.stderr)
        return 2

    def progress(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    results, t0 = [], time.perf_counter()
    for i, case in enumerate(cases, 1):
        progress(f"[{i}/{len(cases)}] {case['name']}: {case['title']}")
        try:
            result = run_case(case, progress, quick=args.quick)
        except Exception as exc:  # a case that cannot run is a failed case, reported
            progress(f"  {case['name']}: ERROR {type(exc).__name__}: {exc}")
            from .runner import CaseResult, Gate

            result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
            result.gates.append(Gate(case["name"], "run", "-", "-", "-", float("nan"), float("nan"),
                                     float("nan"), 0.0, f"{type(exc).__name__}: {exc}"))
        verdicts = [g for g in result.gates if not g.passed]
        progress(f"  {case['name']}: {'PASS' if not verdicts else 'FAIL'} "
                 f"({len(result.gates) - len(verdicts)}/{len(result.gates)} gates, {result.seconds:.1f} s)")
        for g in verdicts:
            progress(f"    FAIL {g.method} {g.quantity} vs {g.against} ({g.level}): error {g.error:.3e} > {g.tolerance:.1e}")
        results.append(result)
    report = write_report(results, args.out)
    ok = all(r.passed for r in results)
    print(f"{'PASS' if ok else 'FAIL'}: {sum(r.passed for r in results)}/{len(results)} cases in "
          f"{time.perf_counter() - t0:.0f} s. Report: {report} and {report.with_suffix('.html')}, "
          f"metrics: {report.parent / 'metrics.json'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
