"""The report's pages: ``summary.md`` (one screen, for a CI job summary), ``report.md``
and ``report.html`` (the verdict in colour and a linked contents at the top, then each
case: its tables, its gates, the comparisons reported without a gate, its figures).

Values and references are shown in one unit per quantity, the unit of the kinds' Runs
tables (:func:`verification.formatting.unit`: mm, MPa, N); ``metrics.json`` keeps SI.
"""

from __future__ import annotations

import html
import math
import sys
from pathlib import Path

from .formatting import fmt, parameters, plain_quantity, shown, unit
from .kinds import KINDS
from .results import CaseResult, Gate, Table

__all__ = ["write_pages", "summary_line", "GATE_HEAD"]

GATE_HEAD = ("verdict", "quantity", "method", "against", "level", "value", "reference", "unit", "error", "tolerance",
             "why this tolerance")
REPORTED_HEAD = ("quantity", "method", "against", "level", "value", "reference", "unit", "difference", "note")
SUMMARY_HEAD = ("case", "verdict", "gates", "worst gate", "error / tolerance", "time (s)")

STYLE = """
body{font-family:system-ui,sans-serif;max-width:1180px;margin:auto;padding:0 12px;line-height:1.4}
.verdict{border-radius:6px;padding:10px 16px;margin:12px 0;color:#fff}
.verdict h1{margin:0;font-size:26px}.verdict p{margin:4px 0 0}
.verdict.ok{background:#1b7f3b}.verdict.bad{background:#b3261e}
.scroll{overflow-x:auto}
table{border-collapse:collapse;margin:8px 0}
td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px;vertical-align:top}
th{background:#f3f3f3}
tr.fail td{background:#fde3e1}
tr.info td{color:#555;background:#f7f7fb}
.pass{color:#1b7f3b;font-weight:bold}.fail{color:#b3261e;font-weight:bold}
td.num,td.nowrap{white-space:nowrap}
td.num{text-align:right;font-variant-numeric:tabular-nums}
nav.local{font-size:13px;margin:-6px 0 8px}
h2{border-top:2px solid #ddd;padding-top:12px;margin-top:28px}
details{margin:14px 0}ol.notes{font-size:13px;margin:4px 0 12px}summary{cursor:pointer}
@media (max-width:600px){td,th{font-size:12px;padding:2px 4px}.verdict h1{font-size:21px}}
.figs{display:flex;flex-wrap:wrap;gap:8px}
.figs img{width:560px;max-width:100%;height:auto;border:1px solid #eee}
"""


def _sci(v: float, digits: int) -> str:
    return f"{v:.{digits}e}" if v is not None and math.isfinite(v) else "-"


def summary_line(results: list[CaseResult]) -> str:
    """``PASS: 6 of 6 cases, 120 of 120 gates pass (...), 79 s.`` (or FAIL)."""
    gated = [g for r in results for g in r.gates if not g.report_only]
    reported = sum(g.report_only for r in results for g in r.gates)
    ok = bool(results) and all(r.passed for r in results)
    seconds = sum(r.seconds for r in results)
    return (f"{'PASS' if ok else 'FAIL'}: {sum(r.passed for r in results)} of {len(results)} cases, "
            f"{sum(g.passed for g in gated)} of {len(gated)} gates pass ({reported} further comparisons "
            f"reported without a gate), {seconds:.0f} s.")


def _worst(r: CaseResult) -> str:
    w = r.worst
    if w is None:
        return "-"
    where = parameters(r.name, w.case, w.quantity)
    return f"{w.method} {plain_quantity(w.quantity)} vs {w.against} ({w.level})" + (f", {where}" if where else "")


def summary_rows(results: list[CaseResult]) -> list[tuple]:
    rows = []
    for r in results:
        w = r.worst
        n = [g for g in r.gates if not g.report_only]
        rows.append((r.name, "PASS" if r.passed else "FAIL", f"{sum(g.passed for g in n)}/{len(n)}", _worst(r),
                     f"{w.margin:.2f}" if w and math.isfinite(w.margin) else "-", f"{r.seconds:.0f}"))
    return rows


def drift_table(drifts) -> Table | None:
    if not drifts:
        return None
    return Table("Drift since the baseline", ("gate", "error before", "error now", "tolerance", "note"),
                 tuple((d.key, fmt(d.before), fmt(d.now), fmt(d.tolerance), d.note) for d in drifts))


def _gate_cells(r: CaseResult, g: Gate) -> tuple:
    where = parameters(r.name, g.case, g.quantity)
    quantity = g.quantity.split("[", 1)[0] + (f" ({where})" if where else "")
    own = getattr(KINDS.get(r.kind), "UNITS", {})  # a kind's own quantities' units
    return (quantity, g.method, g.against, g.level, shown(g.value, g.quantity, r.kind, own),
            shown(g.reference, g.quantity, r.kind, own), unit(g.quantity, r.kind, own)[0], _sci(g.error, 2))


def gate_rows(r: CaseResult) -> list[tuple]:
    """The gated comparisons: value and reference in their unit, error, tolerance, verdict."""
    return [(g.verdict, *_gate_cells(r, g), _sci(g.tolerance, 1), g.reason) for g in r.gates if not g.report_only]


def reported_rows(r: CaseResult) -> list[tuple]:
    """The comparisons shown without a gate: no tolerance, no verdict."""
    return [(*_gate_cells(r, g), g.reason) for g in r.gates if g.report_only]


# --- markdown -----------------------------------------------------------------------


def _md_table(head, rows) -> str:
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(str(c).replace("|", "/").replace("\n", " ") for c in row) + " |" for row in rows]
    return "\n".join(out)


def _summary_md(results, drifts, links: bool) -> list[str]:
    rows = summary_rows(results)
    if links:
        rows = [(f"[{row[0]}](#{row[0]})", *row[1:]) for row in rows]
    top = [f"# Verification report\n\n**{summary_line(results)}**\n", _md_table(SUMMARY_HEAD, rows) + "\n"]
    flags = drift_table(drifts)
    if flags:
        top += [f"## {flags.title}\n", _md_table(flags.head, flags.rows) + "\n"]
    return top


def _case_md(r: CaseResult, tables, figs, broken) -> list[str]:
    verdict = "PASS" if r.passed else "FAIL"
    md = [f"<a id=\"{r.name}\"></a>\n\n## {r.name}: {verdict}\n\n**{r.title}** ({r.seconds:.1f} s)\n\n{r.why.strip()}\n"]
    if broken:
        md.append(f"*{broken}*\n")
    for table in tables:
        md.append(f"**{table.title}**\n\n" + _md_table(table.head, table.rows) + "\n")
    md.append("**Gates**\n\n" + _md_table(GATE_HEAD, gate_rows(r)) + "\n")
    reported = reported_rows(r)
    if reported:
        md.append("**Reported without a gate** (information: no tolerance, never a failure)\n\n"
                  + _md_table(REPORTED_HEAD, reported) + "\n")
    md += [f"![{f}]({f})\n" for f in figs]
    return md


# --- html ---------------------------------------------------------------------------

_NUMERIC = {"value", "reference", "error", "tolerance", "difference", "gates", "error / tolerance", "time (s)"}
_NOWRAP = {"unit", "level", "verdict", "method", "against", "case"}


def _number(cell) -> bool:
    try:
        float(str(cell))
    except ValueError:
        return False
    return True


def _html_table(head, rows, row_class=None, links: dict | None = None) -> str:
    h = "".join(f"<th>{html.escape(c)}</th>" for c in head)
    body = ""
    for row in rows:
        kind = row_class(row) if row_class else ("fail" if "FAIL" in row else "")
        cells = ""
        for name, c in zip(head, row):
            text = html.escape(str(c))
            if links and name == "case" and c in links:
                text = f"<a href='#{html.escape(links[c])}'>{text}</a>"
            if name == "verdict" and c in ("PASS", "FAIL"):
                text = f"<span class='{c.lower()}'>{text}</span>"
            align = "num" if name in _NUMERIC or _number(c) else "nowrap" if name in _NOWRAP else ""
            cells += f"<td class='{align}'>{text}</td>" if align else f"<td>{text}</td>"
        body += f"<tr class='{kind}'>{cells}</tr>" if kind else f"<tr>{cells}</tr>"
    return f"<div class='scroll'><table><tr>{h}</tr>{body}</table></div>"


def _noted(rows: list[tuple]) -> tuple[list[tuple], str]:
    """Rows whose last cell (the reason) repeats: the reason once below the table, the
    rows pointing to it as ``[1]``, ``[2]``... (a narrower table, one line a row)."""
    reasons = list(dict.fromkeys(row[-1] for row in rows))
    if len(reasons) == len(rows):
        return rows, ""
    number = {reason: i for i, reason in enumerate(reasons, 1)}
    notes = "".join(f"<li value='{i}'>{html.escape(reason)}</li>" for reason, i in number.items())
    return [(*row[:-1], f"[{number[row[-1]]}]") for row in rows], f"<ol class='notes'>{notes}</ol>"


def _anchor(r: CaseResult, what: str) -> str:
    return html.escape(f"{r.name}-{what}")


def _case_html(r: CaseResult, tables, figs, broken) -> list[str]:
    verdict = "PASS" if r.passed else "FAIL"
    reported = reported_rows(r)
    local = [f"<a href='#{_anchor(r, 'tables')}'>tables</a>"] if tables else []
    local.append(f"<a href='#{_anchor(r, 'gates')}'>gates</a>")
    if reported:
        local.append(f"<a href='#{_anchor(r, 'reported')}'>reported</a>")
    if figs:
        local.append(f"<a href='#{_anchor(r, 'figures')}'>figures</a>")
    local.append("<a href='#contents'>contents</a>")
    body = [f"<h2 id='{html.escape(r.name)}'>{html.escape(r.name)}: <span class='{verdict.lower()}'>{verdict}</span>"
            f"</h2><nav class='local'>{' · '.join(local)}</nav>"
            f"<p><b>{html.escape(r.title)}</b> ({r.seconds:.1f} s)</p><p>{html.escape(r.why.strip())}</p>"]
    if broken:
        body.append(f"<p><i>{html.escape(broken)}</i></p>")
    for i, table in enumerate(tables):
        anchor = f" id='{_anchor(r, 'tables')}'" if i == 0 else ""
        body.append(f"<h3{anchor}>{html.escape(table.title)}</h3>" + _html_table(table.head, table.rows))
    rows, notes = _noted(gate_rows(r))
    body.append(f"<h3 id='{_anchor(r, 'gates')}'>Gates</h3>"
                + _html_table(GATE_HEAD, rows, lambda row: "fail" if row[0] == "FAIL" else "") + notes)
    if reported:
        body.append(f"<details id='{_anchor(r, 'reported')}'><summary><b>Reported without a gate</b>: "
                    f"{len(reported)} further comparison{'s' if len(reported) > 1 else ''}, information only (no tolerance, "
                    "never a failure)"
                    "</summary>" + _html_table(REPORTED_HEAD, reported, lambda row: "info") + "</details>")
    if figs:
        imgs = "".join(f"<a href='{html.escape(f)}'><img src='{html.escape(f)}' alt='{html.escape(f)}'></a>"
                       for f in figs)
        body.append(f"<h3 id='{_anchor(r, 'figures')}'>Figures</h3><div class='figs'>{imgs}</div>")
    return body


def _top_html(results, drifts) -> list[str]:
    ok = bool(results) and all(r.passed for r in results)
    line = summary_line(results)
    body = [f"<header class='verdict {'ok' if ok else 'bad'}'><h1>Verification report: "
            f"{'PASS' if ok else 'FAIL'}</h1><p>{html.escape(line)}</p></header>",
            "<h2 id='contents'>Contents</h2>",
            _html_table(SUMMARY_HEAD, summary_rows(results), links={r.name: r.name for r in results})]
    flags = drift_table(drifts)
    if flags:
        body += [f"<h2>{flags.title}</h2>", _html_table(flags.head, flags.rows)]
    return body


# --- the pages ----------------------------------------------------------------------


def _drawn(r: CaseResult, folder: Path):
    """(tables, figures, a note when they could not be drawn) of one case."""
    kind = KINDS.get(r.kind)
    if kind is None or "error" in r.extra:  # a case that raised has nothing to draw
        return [], [], ""
    tables = figs = []
    try:  # a table or figure that cannot be drawn must not lose the run's verdicts
        tables = kind.tables(r)
        figs = kind.figures(r, folder)
    except Exception as exc:
        broken = f"The kind's tables or figures could not be drawn: {type(exc).__name__}: {exc}"
        print(f"verify: warning: {r.name}: {broken}", file=sys.stderr)
        return tables, [], broken
    return tables, figs, ""


def write_pages(results: list[CaseResult], folder: Path, drifts) -> None:
    """``summary.md``, ``report.md``, ``report.html`` and the figures into ``folder``."""
    (folder / "summary.md").write_text("\n".join(_summary_md(results, drifts, links=False)))
    md = _summary_md(results, drifts, links=True)
    body = _top_html(results, drifts)
    for r in results:
        tables, figs, broken = _drawn(r, folder)
        md += _case_md(r, tables, figs, broken)
        body += _case_html(r, tables, figs, broken)
    (folder / "report.md").write_text("\n".join(md))
    (folder / "report.html").write_text(
        "<!doctype html><html lang='en'><head><meta charset='utf-8'>"
        "<meta name='viewport' content='width=device-width, initial-scale=1'><title>Verification report</title>"
        f"<style>{STYLE}</style></head><body>{''.join(body)}</body></html>")
