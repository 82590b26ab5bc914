"""The verification report: ``report.md``, ``report.html``, ``metrics.json`` and figures."""

from __future__ import annotations

import html
import json
import math
from pathlib import Path

import numpy as np

__all__ = ["write_report"]


def _figure(figsize):
    """A bare :class:`matplotlib.figure.Figure` with constrained layout: no pyplot and no
    ``matplotlib.use``, so writing a report never switches the caller's backend."""
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout="constrained")


def _reference_profile(result):
    """The pressure field the maps are drawn against: FEM if run, else the analytic one."""
    if "fem" in result.runs:
        run = result.runs["fem"][-1]
        order = np.argsort(run.r)
        return "FEM", lambda x: np.interp(x, run.r[order], run.pressure[order], right=0.0)
    if result.reference is not None:
        return "analytic", result.reference.pressure
    return None, None


def _figures(result, out: Path) -> list[str]:
    files = []
    if result.kind == "stationary" and result.runs:
        fig = _figure((6.4, 4.2))
        ax = fig.subplots()
        if "bem" in result.runs:
            b = result.runs["bem"][-1]
            ax.plot(b.r * 1e3, b.pressure / 1e6, ".", ms=2, alpha=0.4, label=f"BEM nodes, a = {b.size * 1e3:g} mm")
        if "fem" in result.runs:
            f = result.runs["fem"][-1]
            o = np.argsort(f.r)
            ax.plot(f.r[o] * 1e3, f.pressure[o] / 1e6, "-", lw=1.5, label=f"FEM, h = {f.size * 1e3:g} mm")
        if result.reference is not None:
            rr = np.linspace(0, 1.05 * result.reference.contact_radius, 300)
            ax.plot(rr * 1e3, result.reference.pressure(rr) / 1e6, "k--", lw=1, label="analytic")
        ax.set_xlabel("r (mm)")
        ax.set_ylabel("contact pressure (MPa)")
        ax.legend()
        ax.grid(alpha=0.3)
        files.append(f"{result.name}-profiles.png")
        fig.savefig(out / files[-1], dpi=110)

        name, ref = _reference_profile(result)
        if "bem" in result.runs and ref is not None:
            b = result.runs["bem"][-1]
            X, Y = b.grid.coordinates()
            peak = float(np.max(ref(np.linspace(0, b.r.max(), 500))))
            diff = (b.field - ref(np.hypot(X, Y))) / peak * 100
            lim = max(float(np.abs(diff).max()), 1e-6)
            fig = _figure((5.6, 4.6))
            ax = fig.subplots()
            m = ax.pcolormesh(b.grid.x * 1e3, b.grid.y * 1e3, diff, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="nearest")
            fig.colorbar(m, ax=ax, label=f"(BEM - {name}) / peak (%)")
            ax.set_aspect("equal")
            ax.set_xlabel("x (mm)")
            ax.set_ylabel("y (mm)")
            files.append(f"{result.name}-difference.png")
            fig.savefig(out / files[-1], dpi=110)

        fig = _figure((6.4, 4.2))
        ax = fig.subplots()
        for method, runs in result.runs.items():
            if len(runs) < 3:
                continue
            h = np.array([r.size for r in runs]) * 1e3
            for q, marker in (("contact_radius", "o"), ("indentation", "s")):
                conv = result.convergence.get((method, q))
                if conv is None or not math.isfinite(conv.extrapolated):
                    continue
                err = np.abs(np.array(conv.values) - conv.extrapolated) / abs(conv.extrapolated)
                ok = err > 0
                if ok.any():
                    ax.loglog(h[ok], err[ok], marker + "-", label=f"{method} {q} (p = {conv.order:.2f})")
        ax.set_xlabel("element size / node spacing (mm)")
        ax.set_ylabel("|q - q_Richardson| / |q|")
        ax.grid(alpha=0.3, which="both")
        if ax.lines:
            ax.legend(fontsize=8)
            files.append(f"{result.name}-convergence.png")
            fig.savefig(out / files[-1], dpi=110)

    if result.kind == "sweep" and result.extra.get("sweep"):
        rows = result.extra["sweep"]
        H = np.array([h for h, _ in rows]) * 1e3
        fig = _figure((10, 4))
        axes = fig.subplots(1, 2)
        for q, ax in zip(("contact_radius", "indentation"), axes):
            for method, style in (("bem", "o-"), ("fem", "s--")):
                vals = [part.runs[method][-1].scalars[q] * 1e3 for _, part in rows if method in part.runs]
                if vals:
                    ax.semilogx(H[: len(vals)], vals, style, label=method.upper())
            ax.set_xlabel("layer thickness H (mm)")
            ax.set_ylabel(f"{q.replace('_', ' ')} (mm)")
            ax.grid(alpha=0.3, which="both")
            ax.legend()
        files.append(f"{result.name}-sweep.png")
        fig.savefig(out / files[-1], dpi=110)

    if result.kind == "table1" and result.extra.get("table1"):
        cells = result.extra["table1"]
        fig = _figure((6.4, 4))
        ax = fig.subplots()
        for a in sorted({c[0] for c in cells}, reverse=True):
            sel = [c for c in cells if c[0] == a]
            ax.plot([c[1] for c in sel], [(c[2] - c[3]) * 1e4 for c in sel], "o-", label=f"a = {a:g} mm")
        ax.axhspan(-1, 1, color="g", alpha=0.1, label="gate +/- 1e-4 N")
        ax.set_xlabel("truncation order Nt")
        ax.set_ylabel("R_r (ours) - R_r (paper)  (1e-4 N)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        files.append(f"{result.name}-table1.png")
        fig.savefig(out / files[-1], dpi=110)
    return files


def _fmt(v: float) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{v:.6g}"


def _gate_rows(result):
    return [
        [g.quantity, g.method, g.against, g.level, _fmt(g.value), _fmt(g.reference), f"{g.error:.2e}",
         f"{g.tolerance:.1e}", g.verdict, g.reason]
        for g in result.gates
    ]


GATE_HEAD = ["quantity", "method", "against", "level", "value", "reference", "error", "tolerance", "verdict", "why this tolerance"]


def _run_rows(result):
    rows = []
    for method, runs in result.runs.items():
        for r in runs:
            s = r.scalars
            rows.append([method, f"{r.size * 1e3:g}", _fmt(s["contact_radius"] * 1e3), _fmt(s["indentation"] * 1e3),
                         _fmt(s["peak_pressure"] / 1e6), f"{r.seconds:.1f}"])
        for q in ("contact_radius", "indentation"):
            c = result.convergence.get((method, q))
            if c is not None:
                scale = 1e3
                note = f"order {c.order:.2f}" + ("" if c.asymptotic else " (not asymptotic: finest kept)")
                rows.append([method, f"Richardson {q}", _fmt(c.extrapolated * scale) if q == "contact_radius" else "",
                             _fmt(c.extrapolated * scale) if q == "indentation" else "", note, ""])
    return rows


RUN_HEAD = ["method", "h or a (mm)", "r_c (mm)", "d (mm)", "p_max (MPa)", "time (s)"]


def _md_table(head, rows):
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(str(c).replace("|", "/") for c in row) + " |" for row in rows]
    return "\n".join(out)


def _html_table(head, rows):
    h = "".join(f"<th>{html.escape(c)}</th>" for c in head)
    body = ""
    for row in rows:
        cls = ' class="fail"' if "FAIL" in row else ""
        body += f"<tr{cls}>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
    return f"<table><tr>{h}</tr>{body}</table>"


def _metrics(results) -> dict:
    return {
        "passed": all(r.passed for r in results),
        "cases": [
            {
                "name": r.name,
                "title": r.title,
                "passed": r.passed,
                "seconds": r.seconds,
                "runs": {m: [{"size": run.size, **{k: float(v) for k, v in run.scalars.items()}, "seconds": run.seconds}
                             for run in runs] for m, runs in r.runs.items()},
                "convergence": {f"{m}.{q}": {"values": list(c.values), "order": c.order, "extrapolated": c.extrapolated,
                                              "error_finest": c.error_finest, "asymptotic": c.asymptotic}
                                for (m, q), c in r.convergence.items()},
                "gates": [{"quantity": g.quantity, "method": g.method, "against": g.against, "level": g.level,
                           "value": g.value, "reference": g.reference, "error": g.error, "tolerance": g.tolerance,
                           "passed": g.passed, "verdict": g.verdict, "reason": g.reason} for g in r.gates],
            }
            for r in results
        ],
    }


def write_report(results, out: Path) -> Path:
    """Write the report of ``results`` (list of CaseResult) into ``out``; return report.md."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "metrics.json").write_text(json.dumps(_metrics(results), indent=1, default=float))
    gated = [g for r in results for g in r.gates if not g.report_only]
    reported = sum(g.report_only for r in results for g in r.gates)
    line = (f"{sum(g.passed for g in gated)} of {len(gated)} gates pass in {len(results)} case(s); "
            f"{reported} further comparisons are reported without a gate.")
    md = [f"# Verification report\n\n{line}\n"]
    body = [f"<h1>Verification report</h1><p>{html.escape(line)}</p>"]
    for r in results:
        figs = _figures(r, out)
        verdict = "PASS" if r.passed else "FAIL"
        md.append(f"## {r.name}: {verdict}\n\n**{r.title}** ({r.seconds:.1f} s)\n\n{r.why.strip()}\n")
        body.append(f"<h2>{html.escape(r.name)}: <span class='{verdict.lower()}'>{verdict}</span></h2>"
                    f"<p><b>{html.escape(r.title)}</b> ({r.seconds:.1f} s)</p><p>{html.escape(r.why.strip())}</p>")
        if r.runs:
            md.append(_md_table(RUN_HEAD, _run_rows(r)) + "\n")
            body.append(_html_table(RUN_HEAD, _run_rows(r)))
        if r.kind == "sweep":
            rows = []
            for H, part in r.extra.get("sweep", []):
                b, f = part.runs["bem"][-1].scalars, part.runs["fem"][-1].scalars
                rc = part.runs["bem"][-1].scalars["contact_radius"]
                rows.append([f"{H * 1e3:g}", f"{H / rc:.3g}", _fmt(b["contact_radius"] * 1e3), _fmt(f["contact_radius"] * 1e3),
                             _fmt(b["indentation"] * 1e3), _fmt(f["indentation"] * 1e3)])
            head = ["H (mm)", "H / r_c", "r_c BEM (mm)", "r_c FEM (mm)", "d BEM (mm)", "d FEM (mm)"]
            md.append(_md_table(head, rows) + "\n")
            body.append(_html_table(head, rows))
        md.append(_md_table(GATE_HEAD, _gate_rows(r)) + "\n")
        body.append(_html_table(GATE_HEAD, _gate_rows(r)))
        for f in figs:
            md.append(f"![{f}]({f})\n")
            body.append(f"<img src='{html.escape(f)}' alt='{html.escape(f)}'>")
    (out / "report.md").write_text("\n".join(md))
    style = ("body{font-family:sans-serif;max-width:1100px;margin:auto}table{border-collapse:collapse;margin:8px 0}"
             "td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px}tr.fail{background:#fdd}"
             ".pass{color:green}.fail{color:#b00}img{max-width:49%;margin:4px}")
    (out / "report.html").write_text(f"<!doctype html><html><head><meta charset='utf-8'><title>Verification report"
                                     f"</title><style>{style}</style></head><body>{''.join(body)}</body></html>")
    return out / "report.md"
