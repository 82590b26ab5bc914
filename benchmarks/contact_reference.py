"""CONTACT (E. A. H. Vollebregt's program for rolling and sliding contact) against ``bem
solve`` on the same cases: both programs' answers, checked to agree, and their whole
processes timed in alternated pairs.

The cases (CONTACT's inputs in ``benchmarks/contact/``, how to build CONTACT in its
README):

- ``paraboloid-0.2mm``, ``-0.1mm``, ``-0.05mm``: ``examples/elastic-paraboloid-creepage.toml``
  (a rigid paraboloid rolling with friction at the longitudinal creepage 0.01 on a thick
  elastic layer, ``H = 0.2 m`` for the half-space; 61 x 61, 121 x 121, 241 x 241 nodes,
  ``Nt = L / 2a``) against CONTACT's ``GDsteady`` solver on the same elements;
  ``...-steadygs`` (0.2 and 0.1 mm) against its default ``SteadyGS``. Answer: the driving
  force over ``mu P`` and the stick fraction.
- ``sls-halfspace``: frictionless rolling on the standard linear solid (3 -> 6 MPa, creep
  time 0.25 s), 0.09 mm, 155 x 155 (``benchmarks/contact/sls-halfspace.toml``, the case of
  ``benchmarks/bem_viscoelastic_rolling.py``). Answer: ``R_r``, from CONTACT's pressures
  ``sum p x dA / R``.

Each pair runs ``python -m bem.cli solve CASE --quiet --no-error-estimate`` (what CONTACT
computes: no grid error) and ``CONTACT 2 DIR/NAME``, in turn, the order swapped from pair
to pair, after one warm-up each; both with one thread (``OPENBLAS_NUM_THREADS``,
``OMP_NUM_THREADS``, ``MKL_NUM_THREADS`` = 1), ours with bytecode cached. Printed per case:
the answers, each program's median wall time and peak memory, the median of the pairs'
ratios (ours / CONTACT) with a 95 % bootstrap interval, and in how many pairs ours was
faster. The script exits 1 when the answers differ by more than :data:`AGREE` (the timing
would then compare different problems).

Run: ``CONTACT_BIN=/path/to/contact_linux64 python benchmarks/contact_reference.py [CASE
...] [--pairs N] [--pin CPU]`` (``--contact PATH`` instead of the variable); ``--markdown``
prints the table alone on stdout for ``benchmarks/collect.py``.
"""

import argparse
import json
import os
import random
import shutil
import statistics
import sys
import tempfile
import tomllib
from pathlib import Path

from _common import (PARABOLOID, machine, markdown_mode, markdown_table, paraboloid_grid, peak_rss_mb, reporter,
                     run_child)

ROOT = Path(__file__).resolve().parents[1]
INPUTS = ROOT / "benchmarks" / "contact"

#: name: (our case file and --set arguments, CONTACT's input, answer kind, default pairs)
CASES = {
    "paraboloid-0.2mm": ([PARABOLOID], "paraboloid_0p2mm_gdsteady", "friction", 30),
    "paraboloid-0.2mm-steadygs": ([PARABOLOID], "paraboloid_0p2mm_steadygs", "friction", 10),
    "paraboloid-0.1mm": ([PARABOLOID, *paraboloid_grid(0.1e-3)], "paraboloid_0p1mm_gdsteady", "friction", 10),
    "paraboloid-0.1mm-steadygs": ([PARABOLOID, *paraboloid_grid(0.1e-3)], "paraboloid_0p1mm_steadygs", "friction", 3),
    "paraboloid-0.05mm": ([PARABOLOID, *paraboloid_grid(0.05e-3)], "paraboloid_0p05mm_gdsteady", "friction", 5),
    "sls-halfspace": ([INPUTS / "sls-halfspace.toml"], "sls_halfspace", "rolling", 5),
}
#: largest relative difference of the answers (Fx / (mu P), R_r) for the two programs to count
#: as solving the same problem: measured 0.1-0.3 % for Fx / (mu P) (a layer of H = 0.2 m
#: against CONTACT's half-space, element against nodal forces; 0.03 % at H = 0.8 m) and
#: 0.02 % for R_r
AGREE = {"friction": 5e-3, "rolling": 1e-3}
THREADS = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
markdown = markdown_mode() if __name__ == "__main__" else False
say = reporter(markdown)


def environment() -> dict:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    return {**env, **THREADS}


def contact_answer(out: Path, kind: str, mat: Path, radius_mm: float) -> dict:
    """CONTACT's answer from its output ``out`` (and its field file ``mat`` for ``R_r`` of
    the paraboloid of radius ``radius_mm``)."""
    lines = out.read_text(errors="replace").splitlines()

    def after(head: str) -> list:
        i = next((k for k, line in enumerate(lines) if line.split()[:len(head.split())] == head.split()), None)
        if i is None:
            raise SystemExit(f"{out}: no line '{head}': not CONTACT's output of a converged case")
        return lines[i + 1].split()

    _, ncon, nadh = (int(v) for v in after("NPOT NCON NADH")[:3])  # potential, contact, adhesion (stick)
    if kind == "friction":  # its FX is our driving force with the opposite sign (its convention)
        return {"Fx / (mu P)": -float(after("FN/G FX/FSTAT/FN")[1]), "contact": ncon, "stick fraction": nadh / ncon}
    return {"R_r (N)": rolling_resistance(mat, radius_mm), "contact": ncon}


def rolling_resistance(mat: Path, radius_mm: float) -> float:
    """``sum p x dA / R`` (N) of a CONTACT field file (mm, N/mm^2): the frictionless rolling
    resistance of the paraboloid of radius ``radius_mm``."""
    lines = mat.read_text().splitlines()
    head = next(k for k, line in enumerate(lines) if line.split()[1:3] == ["MX", "MY"])
    mx, _, xl, _, dx, dy = (float(v) for v in lines[head + 1].split()[:6])
    first = next(k for k, line in enumerate(lines) if line.split()[1:3] == ["I", "IGS"]) + 1
    moment = 0.0
    for line in lines[first:]:
        if line.strip() and not line.lstrip().startswith("%"):
            fields = line.split()
            i, pn = int(fields[0]), float(fields[4])
            moment += pn * (xl + ((i - 1) % int(mx) + 0.5) * dx)
    return moment * dx * dy / radius_mm


def our_answer(args: list, kind: str) -> dict:
    cmd = [sys.executable, "-m", "bem.cli", "solve", *map(str, args), "--quiet", "--no-error-estimate", "--json"]
    r = json.loads(run_child(cmd, environment(), ROOT)[3])
    ax, ay = r["grid"]["spacing"]
    nodes = round(r["contact_area"] / (ax * ay))
    if kind == "friction":
        return {"Fx / (mu P)": r["driving_force"] / (r["mu"] * r["load"]), "contact": nodes,
                "stick fraction": r["stick_fraction"]}
    return {"R_r (N)": r["rolling_resistance"], "contact": nodes}


def median_interval(ratios: list, seed: int = 0) -> tuple[float, float]:
    """A 95 % bootstrap interval of the median of ``ratios`` (2000 resamples, seeded)."""
    rng = random.Random(seed)
    meds = sorted(statistics.median(rng.choices(ratios, k=len(ratios))) for _ in range(2000))
    return meds[50], meds[1949]


def run(name: str, contact: Path, pairs: int, cpu: int | None, scratch: Path) -> list:
    """One row of the table: case ``name`` timed in ``pairs`` alternated pairs."""
    args, stem, kind, _ = CASES[name]
    shutil.copy(INPUTS / f"{stem}.inp", scratch / f"{stem}.inp")
    ours = [sys.executable, "-m", "bem.cli", "solve", *map(str, args), "--quiet", "--no-error-estimate"]
    theirs = [str(contact), "2", str(scratch / stem)]
    times = {"ours": [], "theirs": []}
    peaks = {"ours": [], "theirs": []}
    for cmd in (ours, theirs):  # warm-up: bytecode written, files in the page cache
        run_child(cmd, environment(), ROOT, cpu)
    for i in range(pairs):
        order = (("ours", ours), ("theirs", theirs)) if i % 2 == 0 else (("theirs", theirs), ("ours", ours))
        for who, cmd in order:
            wall, _, peak, _ = run_child(cmd, environment(), ROOT, cpu)
            times[who].append(wall)
            peaks[who].append(peak)
        say(f"{name}, pair {i + 1}: ours {times['ours'][-1]:.3f} s, CONTACT {times['theirs'][-1]:.3f} s")
    radius_mm = 1e3 * tomllib.loads(Path(args[0]).read_text())["indenter"]["radius"]
    a = our_answer(args, kind)
    b = contact_answer(scratch / f"{stem}.out", kind, scratch / f"{stem}.0001.mat", radius_mm)
    key = next(iter(a))
    diff = abs(a[key] - b[key]) / abs(b[key])
    if diff > AGREE[kind]:
        raise SystemExit(f"{name}: {key} {a[key]:.6g} (ours) against {b[key]:.6g} (CONTACT), {diff:.2%} apart "
                         f"(more than {AGREE[kind]:.1%}): the two programs do not solve the same problem")
    ratios = [x / y for x, y in zip(times["ours"], times["theirs"])]
    low, high = median_interval(ratios)
    med = statistics.median
    say(f"{name}: ours / CONTACT {med(ratios):.3f} (95 % interval {low:.3f}-{high:.3f}); {key} {a[key]:.6g} "
        f"against {b[key]:.6g}")

    def answer(r):
        return ", ".join(f"{k} {v:.4f}" if isinstance(v, float) else f"{k} {v}" for k, v in r.items())

    return [name, answer(b), answer(a), f"{med(times['theirs']):.3f}, {med(peaks['theirs']):.0f}",
            f"{med(times['ours']):.3f}, {med(peaks['ours']):.0f}",
            f"{med(ratios):.3f} ({low:.3f}-{high:.3f})", f"{sum(r < 1 for r in ratios)} of {pairs}"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="*", metavar="CASE",
                    help=f"cases to run (default: all): {', '.join(CASES)}")
    ap.add_argument("--contact", type=Path, default=os.environ.get("CONTACT_BIN"),
                    help="CONTACT's program (default: the CONTACT_BIN variable)")
    ap.add_argument("--pairs", type=int, help="pairs per case (default: 30 at 0.2 mm, fewer on larger cases)")
    ap.add_argument("--pin", type=int, metavar="CPU", help="run both programs on this CPU alone")
    args = ap.parse_args()
    unknown = [c for c in args.cases if c not in CASES]
    if unknown:
        ap.error(f"unknown case {', '.join(unknown)}; the cases: {', '.join(CASES)}")
    if args.contact is None or not (args.contact.is_file() and os.access(args.contact, os.X_OK)):
        ap.error(f"CONTACT's program not found ({args.contact or 'give --contact or set CONTACT_BIN'}); "
                 "benchmarks/contact/README.md says how to build it")
    if args.pairs is not None and args.pairs < 1:
        ap.error("--pairs must be >= 1")
    say(f"{machine()}; load average {os.getloadavg()[0]:.1f} at the start"
        + (f"; both pinned to CPU {args.pin}" if args.pin is not None else "")
        + f"; a child's peak memory reads at least this process's, {peak_rss_mb():.0f} MiB")
    with tempfile.TemporaryDirectory(prefix="contact-") as scratch:
        rows = [run(c, args.contact.resolve(), args.pairs or CASES[c][3], args.pin, Path(scratch))
                for c in args.cases or CASES]
    head = ["case", "CONTACT's answer", "ours (`bem solve`, H = 0.2 m)", "CONTACT whole run (s), peak MiB",
            "ours whole run (s), peak MiB", "ours / CONTACT: median of the pairs (95 % interval)", "pairs ours faster"]
    table = markdown_table(head, rows)
    print(table if markdown else "\nsummary (medians)\n" + table)


if __name__ == "__main__":
    main()
