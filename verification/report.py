"""The verification report: ``summary.md`` (one screen, for a CI job summary),
``report.md``, ``report.html``, ``metrics.json`` (strict JSON) and the figures; optionally
a JUnit XML file with one test case per gate, and drift flags against an earlier run.

Everything is written into a fresh folder beside ``out`` and renamed into place at the
end: an interrupted run leaves the previous report complete and untouched, and nothing of
an older run survives in the new one.
"""

from __future__ import annotations

import html
import json
import math
import os
import shutil
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from xml.etree import ElementTree as ET

from .formatting import fmt
from .kinds import KINDS
from .results import CaseResult, Gate, Table

__all__ = ["write_report", "summary_line", "check_out", "check_junit", "load_baseline", "drift", "Drift", "ReportError"]

GATE_HEAD = ("quantity", "method", "against", "level", "value", "reference", "error", "tolerance", "verdict",
             "why this tolerance")


class ReportError(ValueError):
    """A report that cannot be written where asked, or a baseline that cannot be read."""


def _probe(folder: Path, what: str) -> None:
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryDirectory(dir=folder, prefix=".verify-probe-"):
            pass
    except OSError as exc:
        raise ReportError(f"{what}: cannot write in {str(folder)!r}: {exc.strerror or exc}") from None


def check_out(out: Path) -> Path:
    """``--out``: a folder (existing or to be made) in a writable place; checked before any solve."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise ReportError(f"--out {str(out)!r} is a file, not a folder")
    parent = out.parent
    while not parent.exists():
        if parent.is_file():
            raise ReportError(f"--out {str(out)!r}: {str(parent)!r} is a file")
        parent = parent.parent
    if parent.is_file() or not os.access(parent, os.W_OK):
        raise ReportError(f"--out {str(out)!r}: {str(parent)!r} is not a writable folder")
    return out


def check_junit(path: Path) -> Path:
    """``--junit FILE.xml``: an XML file name in a writable folder."""
    path = Path(path)
    if path.suffix != ".xml":
        raise ReportError(f"--junit {str(path)!r}: the file name must end in .xml")
    if path.is_dir():
        raise ReportError(f"--junit {str(path)!r} is a folder")
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir() or not os.access(parent, os.W_OK):
        raise ReportError(f"--junit {str(path)!r}: {str(parent)!r} is not a writable folder")
    return path


# --- strict JSON --------------------------------------------------------------------


def _strict(obj):
    """NaN and infinities as null: metrics.json is strict JSON (RFC 8259)."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {str(k): _strict(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_strict(v) for v in obj]
    if hasattr(obj, "item"):  # numpy scalars
        return _strict(obj.item())
    return obj


def _gate_dict(g: Gate) -> dict:
    return {"key": g.key, "quantity": g.quantity, "method": g.method, "against": g.against, "level": g.level,
            "value": g.value, "reference": g.reference, "error": g.error, "tolerance": g.tolerance,
            "margin": g.margin, "passed": g.passed, "verdict": g.verdict, "reason": g.reason}


def _metrics(results: list[CaseResult], drifts: list) -> dict:
    return _strict({
        "passed": bool(results) and all(r.passed for r in results),
        "drift": [d.as_dict() for d in drifts],
        "cases": [
            {
                "name": r.name, "title": r.title, "kind": r.kind, "passed": r.passed, "seconds": r.seconds,
                "runs": {m: [{"size": run.size, **run.scalars, "seconds": run.seconds} for run in runs]
                         for m, runs in r.runs.items()},
                "convergence": {f"{m}.{q}": {"values": list(c.values), "order": c.order,
                                              "extrapolated": c.extrapolated, "error_finest": c.error_finest,
                                              "asymptotic": c.asymptotic}
                                for (m, q), c in r.convergence.items()},
                "gates": [_gate_dict(g) for g in r.gates],
            }
            for r in results
        ],
    })


# --- drift against a baseline -------------------------------------------------------


@dataclass(frozen=True)
class Drift:
    """A gate whose error moved by more than ``fraction`` of its tolerance since the baseline."""

    key: str
    before: float | None
    now: float | None
    tolerance: float
    note: str

    def as_dict(self) -> dict:
        return {"key": self.key, "before": self.before, "now": self.now, "tolerance": self.tolerance,
                "note": self.note}


def load_baseline(path: Path) -> dict:
    """The gates of an earlier ``metrics.json``, by key; checked before any solve."""
    path = Path(path)
    try:
        doc = json.loads(path.read_text())
        gates = {g["key"]: g for c in doc["cases"] for g in c["gates"]}
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise ReportError(f"--baseline {str(path)!r}: not a metrics.json of this harness ({exc})") from None
    return gates


def drift(results: list[CaseResult], baseline: dict, fraction: float) -> list[Drift]:
    """Gates that moved by more than ``fraction`` of their tolerance, and gates that
    appeared or vanished (of the cases run)."""
    out = []
    now = {g.key: g for r in results for g in r.gates if not g.report_only}
    cases = {r.name for r in results}
    for key, g in now.items():
        old = baseline.get(key)
        if old is None:
            out.append(Drift(key, None, g.error, g.tolerance, "new gate (not in the baseline)"))
            continue
        before = old.get("error")
        if before is None or not math.isfinite(g.error):
            if (before is None) != (not math.isfinite(g.error)):
                out.append(Drift(key, before, g.error, g.tolerance, "error became undefined or defined"))
            continue
        moved = abs(g.error - before)
        if moved > fraction * g.tolerance:
            out.append(Drift(key, before, g.error, g.tolerance,
                             f"moved by {moved / g.tolerance:.2f} of the tolerance ({'worse' if g.error > before else 'better'})"))
    for key, old in baseline.items():
        case = key.split(":", 1)[0].split("[", 1)[0]
        if case in cases and key not in now and old.get("verdict") != "REPORTED":
            out.append(Drift(key, old.get("error"), None, old.get("tolerance") or math.nan, "gate gone since the baseline"))
    return out


# --- text ---------------------------------------------------------------------------


def _gate_rows(result: CaseResult):
    return [(g.quantity, g.method, g.against, g.level, fmt(g.value), fmt(g.reference), f"{g.error:.2e}",
             f"{g.tolerance:.1e}" if math.isfinite(g.tolerance) else "-", g.verdict, g.reason) for g in result.gates]


def _md_table(head, rows) -> str:
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(str(c).replace("|", "/").replace("\n", " ") for c in row) + " |" for row in rows]
    return "\n".join(out)


def _html_table(head, rows) -> str:
    h = "".join(f"<th>{html.escape(c)}</th>" for c in head)
    body = ""
    for row in rows:
        cls = ' class="fail"' if "FAIL" in row else ""
        body += f"<tr{cls}>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
    return f"<table><tr>{h}</tr>{body}</table>"


def summary_line(results: list[CaseResult]) -> str:
    """``PASS: 6 of 6 cases, 120 of 120 gates pass (...), 79 s.`` (or FAIL)."""
    gated = [g for r in results for g in r.gates if not g.report_only]
    reported = sum(g.report_only for r in results for g in r.gates)
    ok = bool(results) and all(r.passed for r in results)
    seconds = sum(r.seconds for r in results)
    return (f"{'PASS' if ok else 'FAIL'}: {sum(r.passed for r in results)} of {len(results)} cases, "
            f"{sum(g.passed for g in gated)} of {len(gated)} gates pass ({reported} further comparisons "
            f"reported without a gate), {seconds:.0f} s.")


def _summary(results: list[CaseResult], drifts: list[Drift]) -> tuple[str, Table, Table | None]:
    line = summary_line(results)
    rows = []
    for r in results:
        w = r.worst
        n = [g for g in r.gates if not g.report_only]
        rows.append((r.name, "PASS" if r.passed else "FAIL", f"{sum(g.passed for g in n)}/{len(n)}",
                     f"{w.method} {w.quantity} vs {w.against} ({w.level})" if w else "-",
                     f"{w.margin:.2f}" if w and math.isfinite(w.margin) else "-", f"{r.seconds:.0f}"))
    cases = Table("Summary", ("case", "verdict", "gates", "worst gate", "error / tolerance", "time (s)"), tuple(rows))
    flags = None
    if drifts:
        flags = Table("Drift since the baseline", ("gate", "error before", "error now", "tolerance", "note"),
                      tuple((d.key, fmt(d.before), fmt(d.now), fmt(d.tolerance), d.note) for d in drifts))
    return line, cases, flags


def _junit(results: list[CaseResult]) -> bytes:
    suites = ET.Element("testsuites", name="verify")
    for r in results:
        suite = ET.SubElement(suites, "testsuite", name=r.name, tests=str(len(r.gates)),
                              failures=str(sum(not g.passed for g in r.gates)),
                              skipped=str(sum(g.report_only for g in r.gates)), time=f"{r.seconds:.3f}")
        for g in r.gates:
            case = ET.SubElement(suite, "testcase", classname=f"verify.{r.name}",
                                 name=f"{g.method} {g.quantity} vs {g.against} ({g.level})")
            text = (f"error {g.error:.3e}, tolerance {g.tolerance:.1e} (value {fmt(g.value)}, reference "
                    f"{fmt(g.reference)}): {g.reason}")
            if g.report_only:
                ET.SubElement(case, "skipped", message="reported without a gate").text = text
            elif not g.passed:
                ET.SubElement(case, "failure", message=f"error {g.error:.3e} > tolerance {g.tolerance:.1e}",
                              type="GateFailed").text = text
            else:
                ET.SubElement(case, "system-out").text = text
    return ET.tostring(suites, encoding="utf-8", xml_declaration=True)


def _write_all(results, folder: Path, drifts: list[Drift]) -> None:
    line, summary, flags = _summary(results, drifts)
    top = [f"# Verification report\n\n**{line}**\n", _md_table(summary.head, summary.rows) + "\n"]
    if flags:
        top += [f"## {flags.title}\n", _md_table(flags.head, flags.rows) + "\n"]
    (folder / "summary.md").write_text("\n".join(top))
    md = list(top)
    body = [f"<h1>Verification report</h1><p><b>{html.escape(line)}</b></p>", _html_table(summary.head, summary.rows)]
    if flags:
        body += [f"<h2>{flags.title}</h2>", _html_table(flags.head, flags.rows)]
    for r in results:
        kind = KINDS.get(r.kind)
        ran = kind is not None and "error" not in r.extra  # a case that raised has nothing to draw
        figs, tables, broken = [], [], ""
        try:  # a table or figure that cannot be drawn must not lose the run's verdicts
            if ran:
                tables = kind.tables(r)
                figs = kind.figures(r, folder)
        except Exception as exc:
            broken = f"The kind's tables or figures could not be drawn: {type(exc).__name__}: {exc}"
            print(f"verify: warning: {r.name}: {broken}", file=sys.stderr)
        verdict = "PASS" if r.passed else "FAIL"
        md.append(f"## {r.name}: {verdict}\n\n**{r.title}** ({r.seconds:.1f} s)\n\n{r.why.strip()}\n")
        body.append(f"<h2 id='{html.escape(r.name)}'>{html.escape(r.name)}: <span class='{verdict.lower()}'>{verdict}"
                    f"</span></h2><p><b>{html.escape(r.title)}</b> ({r.seconds:.1f} s)</p>"
                    f"<p>{html.escape(r.why.strip())}</p>")
        if broken:
            md.append(f"*{broken}*\n")
            body.append(f"<p><i>{html.escape(broken)}</i></p>")
        for table in tables:
            md.append(f"**{table.title}**\n\n" + _md_table(table.head, table.rows) + "\n")
            body.append(f"<h3>{html.escape(table.title)}</h3>" + _html_table(table.head, table.rows))
        md.append("**Gates**\n\n" + _md_table(GATE_HEAD, _gate_rows(r)) + "\n")
        body.append("<h3>Gates</h3>" + _html_table(GATE_HEAD, _gate_rows(r)))
        for f in figs:
            md.append(f"![{f}]({f})\n")
            body.append(f"<img src='{html.escape(f)}' alt='{html.escape(f)}'>")
    (folder / "report.md").write_text("\n".join(md))
    style = ("body{font-family:sans-serif;max-width:1100px;margin:auto}table{border-collapse:collapse;margin:8px 0}"
             "td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px}tr.fail{background:#fdd}"
             ".pass{color:green}.fail{color:#b00}img{max-width:49%;margin:4px}")
    (folder / "report.html").write_text(f"<!doctype html><html><head><meta charset='utf-8'><title>Verification "
                                        f"report</title><style>{style}</style></head><body>{''.join(body)}</body></html>")
    # metrics.json last: its presence says the folder is complete
    (folder / "metrics.json").write_text(json.dumps(_metrics(results, drifts), indent=1, allow_nan=False))


def _clean_stale(out: Path) -> None:
    """Remove staging folders of runs that were killed (their process is gone)."""
    for stale in out.parent.glob(f".{out.name}.partial-*"):
        try:
            pid = int(stale.name.rsplit("-", 1)[1])
            os.kill(pid, 0)
        except (ValueError, ProcessLookupError):
            shutil.rmtree(stale, ignore_errors=True)
        except PermissionError:
            pass


def _replace(folder: Path, out: Path) -> None:
    """Put the complete ``folder`` where ``out`` is; the old one goes only after."""
    old = out.parent / f".{out.name}.old-{os.getpid()}"
    if out.exists():
        os.rename(out, old)
    os.rename(folder, out)
    shutil.rmtree(old, ignore_errors=True)


def write_report(results: list[CaseResult], out: Path, junit: Path | None = None,
                 drifts: list[Drift] = ()) -> Path:
    """Write the report of ``results`` into the folder ``out`` (atomically: built beside
    it and renamed into place); return ``out / "report.md"``.

    ``junit``: also a JUnit XML file, one test case per gate. ``drifts``: the gates that
    moved since a baseline (:func:`drift`), flagged in the summary.
    """
    out = check_out(Path(out))
    out.parent.mkdir(parents=True, exist_ok=True)
    _clean_stale(out)
    staging = out.parent / f".{out.name}.partial-{os.getpid()}"
    shutil.rmtree(staging, ignore_errors=True)
    staging.mkdir()
    try:
        _write_all(results, staging, drifts)
        if junit is not None:
            junit = Path(junit)
            tmp = junit.with_name(f".{junit.name}.partial-{os.getpid()}")
            tmp.write_bytes(_junit(results))
            os.replace(tmp, junit)
        _replace(staging, out)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return out / "report.md"
