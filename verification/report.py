"""The verification report: ``summary.md`` (one screen, for a CI job summary),
``report.md``, ``report.html``, ``metrics.json`` (strict JSON) and the figures; optionally
a JUnit XML file with one test case per gate, and drift flags against an earlier run.
The pages themselves (what a reader sees, in which units) are drawn by
:mod:`verification.pages`.

Everything is written into a fresh folder beside ``out`` and renamed into place at the
end: an interrupted run leaves the previous report complete and untouched, and nothing of
an older run survives in the new one.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from xml.etree import ElementTree as ET

from .formatting import fmt, parameters
from .pages import summary_line, write_pages
from .results import CaseResult, Gate

__all__ = ["write_report", "summary_line", "check_out", "check_junit", "load_baseline", "drift", "Drift", "ReportError"]


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
    """``--out``: a folder (existing or to be made) in a writable place, never the working
    or home folder or one holding them (:func:`verification.out_folder.never`); checked
    before any solve. Returns it resolved (symlinks followed)."""
    from .out_folder import OutFolderError, never

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise ReportError(f"--out {str(out)!r} is a file, not a folder")
    try:
        out = never(out)
    except OutFolderError as exc:
        raise ReportError(str(exc)) from None
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


# --- JUnit ---------------------------------------------------------------------------


def _junit(results: list[CaseResult]) -> bytes:
    suites = ET.Element("testsuites", name="verify")
    for r in results:
        suite = ET.SubElement(suites, "testsuite", name=r.name, tests=str(len(r.gates)),
                              failures=str(sum(not g.passed for g in r.gates)),
                              skipped=str(sum(g.report_only for g in r.gates)), time=f"{r.seconds:.3f}")
        for g in r.gates:
            where = parameters(r.name, g.case, "")  # a sweep's part, e.g. H = 0.5 mm
            case = ET.SubElement(suite, "testcase", classname=f"verify.{r.name}",
                                 name=f"{g.method} {g.quantity} vs {g.against} ({g.level})"
                                      + (f", {where}" if where else ""))
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
    write_pages(results, folder, drifts)  # summary.md, report.md, report.html, figures
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
    """Put the complete ``folder`` where ``out`` is, marked as a report; the old one goes
    only after, and only if it is a report or empty (else it is kept beside, and said)."""
    from .out_folder import replace

    kept = replace(folder, out)
    if kept is not None:
        print(f"verify: {out} held files of its own: they are kept in {kept}", file=sys.stderr)


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
