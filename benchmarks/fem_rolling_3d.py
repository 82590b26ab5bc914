"""3D steady rolling of a rigid sphere (fem_reference, fem.model = "3d"): the paper's
section 11 example without friction, mesh convergence, domain-size check, time and
memory, and the BEM's R_r.

The case: R = 20 mm, P = 150 N, H = 5 mm, rho = 1000 kg/m^3, three-parameter solid
G0 = 3 MPa, f = 1, tau = 0.25 s, V = 0.05 m/s (examples/paper-section11-frictionless.toml);
the BEM (paper's Table 1, reproduced by ``bem solve``) gives R_r = 3.0257 N.

Levels are systematic refinements of one graded mesh: at level s the zone size is
h0 / s, the grading g0 / s and the far size H / s (every local size divided by s), with
s = r^k, r = 2^(1/3) (about twice the elements per level). Each level runs in its own
process (its time and peak memory alone). Richardson from the last three levels:
p = ln((f1 - f2) / (f2 - f3)) / ln r, f_inf = f3 + (f3 - f2) / (r^p - 1).

Usage::

    python benchmarks/fem_rolling_3d.py [--levels 4] [--first 0] [--h0 1e-3] [--g0 0.2]
                                        [--domain] [--superlu] [--bem] [--json out.json] [--markdown]

``--domain`` adds a solve at the first level with upstream, downstream and lateral
lengths doubled; ``--superlu`` the first level with SuperLU instead of Pardiso; ``--bem``
solves the case with the BEM: its R_r and its horizontal force sum F ds/dx, which the
FEM's D/V equals in the continuum (energy balance; 1.0167 R_r here, a/R = 0.22).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import markdown_table, reporter  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CASE = os.path.join(ROOT, "examples", "paper-section11-frictionless.toml")
BEM_TABLE1 = 3.0257  # N, the paper's Table 1 (frictionless)
H = 5e-3
RATIO = 2.0 ** (1.0 / 3.0)
KEYS = ("rolling_resistance", "rolling_resistance_energy", "indentation", "leading_edge",
        "trailing_edge", "contact_length", "pressure_centroid_x", "energy_balance")


def one(h: float, grading: float, far: float, scale_domain: float, solver: str = "auto") -> dict:
    """One solve in this process; a JSON-ready dict. ``solver``: the linear solver of
    :mod:`fem_reference.rolling.solve` ("auto", "pardiso" or "superlu")."""
    from fem_reference import (ContactProblem, FemSettings, Indenter, Layer, Loading,
                               ThreeParameterMaterial, solve)
    from fem_reference.rolling import solve as rolling_solve
    from fem_reference.rolling.three_d.discretization import resolve_box

    rolling_solve.LINEAR_SOLVER = solver

    base = ContactProblem(Layer(H, 1000.0), ThreeParameterMaterial(3e6, 0.25, 1.0),
                          Indenter("sphere", 0.02), Loading(load=150.0, speed=0.05),
                          FemSettings(model="3d", element_size=h, grading=grading, far_size=far))
    disc = resolve_box(base)
    fem = FemSettings(model="3d", element_size=h, grading=grading, far_size=far,
                      upstream=scale_domain * disc.upstream,
                      downstream=scale_domain * disc.downstream,
                      domain_radius=scale_domain * disc.lateral)
    problem = ContactProblem(base.layer, base.material, base.indenter, base.loading, fem)
    t0 = time.perf_counter()
    r = solve(problem)
    wall = time.perf_counter() - t0
    s = r.summary()
    out = {k: s[k] for k in KEYS}
    out.update(h=h, grading=grading, far=far, domain_scale=scale_domain, wall=wall,
               unknowns=r.mesh.unknowns, elements=r.mesh.elements,
               contact_nodes=r.mesh.contact_nodes, factor_nonzeros=r.solver.factor_nonzeros,
               linear_solver=r.solver.linear_solver, times=r.solver.times,
               peak_memory=r.peak_memory, factor_memory=s["factor_memory"],
               upstream=r.mesh.upstream, downstream=r.mesh.downstream, lateral=r.mesh.lateral,
               lateral_edge=r.lateral_edge)
    return out


def _child(h, grading, far, scale_domain, solver="auto"):
    cmd = [sys.executable, __file__, "--one", repr(h), repr(grading), repr(far), repr(scale_domain),
           solver]
    res = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if res.returncode != 0:
        raise RuntimeError(f"level h = {h} failed:\n{res.stderr[-2000:]}")
    return json.loads(res.stdout.strip().splitlines()[-1])


def richardson(f1, f2, f3, r=RATIO):
    """Observed order p and extrapolated value from three levels (coarse to fine), or
    (nan, nan) when the differences do not shrink monotonically."""
    d1, d2 = f1 - f2, f2 - f3
    if d1 == 0 or d2 == 0 or d1 * d2 < 0 or abs(d2) >= abs(d1):
        return float("nan"), float("nan")
    p = math.log(d1 / d2) / math.log(r)
    return p, f3 - d2 / (r ** p - 1.0)


def bem_figures() -> dict:
    """The BEM on the case file: R_r = sum F x / R (N), the horizontal force sum F ds/dx
    (N; what D / V of the FEM equals by the energy balance, exact sphere slope
    ds/dx = x / sqrt(R^2 - x^2 - y^2)), the indentation (m) and the time (s)."""
    import numpy as np

    from bem import solve
    from bem.case import problem_from_config, read_case

    t0 = time.perf_counter()
    problem, _ = problem_from_config(read_case(CASE))
    r = solve(problem, energy=False)
    X, Y = r.grid.coordinates()
    R = 0.02
    return {"rolling_resistance": float(r.rolling_resistance),
            "horizontal_force": float(np.sum(r.force * X / np.sqrt(R * R - X * X - Y * Y))),
            "indentation": float(r.indentation), "wall": time.perf_counter() - t0}


def _table_head() -> list:
    return ["case", "h (mm)", "unknowns", "candidate nodes", "wall (s)", "peak RSS (GB)", "R_r (N)", "D/V (N)",
            "indentation (mm)", "edges on y = 0 (mm)", "energy balance"]


def _table_row(row: dict) -> list:
    return [f"section 11 sphere, frictionless, 3D FEM level {row['level']}", f"{row['h'] * 1e3:.3f}",
            row["unknowns"], row["contact_nodes"], f"{row['wall']:.0f}", f"{row['peak_memory'] / 1e9:.1f}",
            f"{row['rolling_resistance']:.5f}", f"{row['rolling_resistance_energy']:.5f}",
            f"{row['indentation'] * 1e3:.5f}", f"{row['trailing_edge'] * 1e3:.4f} / {row['leading_edge'] * 1e3:.4f}",
            f"{row['energy_balance']:+.2%}"]


def _bem_row(b: dict) -> list:
    return ["the BEM on the paper's grid (41 x 41)", "", "", "", f"{b['wall']:.0f}", "",
            f"{b['rolling_resistance']:.5f}", f"{b['horizontal_force']:.5f} (sum F ds/dx)",
            f"{b['indentation'] * 1e3:.5f}", "", ""]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", type=int, default=4)
    ap.add_argument("--first", type=int, default=0, help="index k of the coarsest level")
    ap.add_argument("--h0", type=float, default=1.0e-3)
    ap.add_argument("--g0", type=float, default=0.2)
    ap.add_argument("--domain", action="store_true")
    ap.add_argument("--bem", action="store_true")
    ap.add_argument("--json", default=None)
    ap.add_argument("--superlu", action="store_true",
                    help="also solve the first level with SuperLU (time, fill, memory)")
    ap.add_argument("--markdown", action="store_true", help="print the levels table alone, in Markdown")
    ap.add_argument("--one", nargs=5, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.one:
        print(json.dumps(one(*map(float, args.one[:4]), solver=args.one[4])))
        return 0
    say = reporter(args.markdown)
    rows = []
    for k in range(args.first, args.first + args.levels):
        s = RATIO ** k
        row = _child(args.h0 / s, args.g0 / s, H / s, 1.0)
        row["level"] = k
        rows.append(row)
        say(f"level {k}: h = {row['h'] * 1e3:.3f} mm, {row['unknowns']} unknowns, "
              f"{row['contact_nodes']} nodes: R_r {row['rolling_resistance']:.5f} N, D/V "
              f"{row['rolling_resistance_energy']:.5f} N, d {row['indentation'] * 1e3:.5f} mm, "
              f"edges [{row['trailing_edge'] * 1e3:.4f}, {row['leading_edge'] * 1e3:.4f}] mm, "
              f"balance {row['energy_balance']:+.2e}, {row['wall']:.0f} s, "
              f"peak {row['peak_memory'] / 2 ** 20:.0f} MiB", flush=True)
    out = {"levels": rows, "ratio": RATIO, "bem_table1": BEM_TABLE1}
    if len(rows) >= 3:
        rich = {}
        for key in KEYS[:-1]:
            p, f = richardson(*(row[key] for row in rows[-3:]))
            rich[key] = {"order": p, "extrapolated": f,
                         "error_estimate_finest": (rows[-1][key] - f) if f == f else float("nan")}
            say(f"Richardson {key}: order {p:.2f}, extrapolated {f:.6g}", flush=True)
        out["richardson"] = rich
    if args.domain:
        s = RATIO ** args.first
        for scale in (2.0,):  # against the first level (the same mesh sizes)
            row = _child(args.h0 / s, args.g0 / s, H / s, scale)
            out.setdefault("domain", []).append(row)
            say(f"domain x{scale:g}: R_r {row['rolling_resistance']:.6f} N, D/V "
                  f"{row['rolling_resistance_energy']:.6f} N, d {row['indentation'] * 1e3:.6f} mm, "
                  f"edges [{row['trailing_edge'] * 1e3:.5f}, {row['leading_edge'] * 1e3:.5f}] mm, "
                  f"{row['unknowns']} unknowns, {row['wall']:.0f} s", flush=True)
    if args.superlu:
        s = RATIO ** args.first
        row = _child(args.h0 / s, args.g0 / s, H / s, 1.0, "superlu")
        out["superlu"] = row
        t = row["times"]
        say(f"superlu at level {args.first}: R_r {row['rolling_resistance']:.6f} N, "
              f"factorization {t['factorization']:.1f} s ({row['factor_nonzeros']} nonzeros), "
              f"compliance {t['compliance']:.1f} s, total {row['wall']:.0f} s, peak "
              f"{row['peak_memory'] / 2 ** 20:.0f} MiB", flush=True)
    if args.bem:
        b = out["bem"] = bem_figures()
        say(f"bem: R_r {b['rolling_resistance']:.5f} N, sum F ds/dx {b['horizontal_force']:.5f} N "
              f"(the FEM's D/V), indentation {b['indentation'] * 1e3:.5f} mm ({b['wall']:.0f} s)",
              flush=True)
        if rows:
            f = rows[-1]
            say(f"finest FEM against the BEM: R_r {f['rolling_resistance'] / b['rolling_resistance'] - 1:+.3%}, "
                  f"D/V {f['rolling_resistance_energy'] / b['horizontal_force'] - 1:+.3%}, indentation "
                  f"{f['indentation'] / b['indentation'] - 1:+.3%}", flush=True)
    if args.markdown:
        print(markdown_table(_table_head(), [_table_row(row) for row in rows]
                             + ([_bem_row(out["bem"])] if "bem" in out else [])))
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
