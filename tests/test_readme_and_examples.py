"""The README and ``examples/`` run as written, so they cannot go stale.

- Every fenced ``python`` block of README.md is executed, in order, each in a fresh
  namespace (the asserts inside the blocks check the numbers they print).
- Every line of a fenced ``bash`` block that calls ``bem``, ``fem-reference`` or ``verify``
  (or ``.venv/bin/`` variants) runs with the console script of this environment and must
  exit 0, or the status written on the line as ``# exits N``. A line marked
  ``# not run: REASON`` is skipped. The two setup commands are not run (they install):
  the second must be ``.ci/run``'s last line, byte for byte, the first must end in
  ``.venv/bin/verify``. Any other command in a bash block is an error, so that a new kind
  of line needs a decision here.
- The numbers of the caption under the README's figure are those of the README's own
  ``verify --case`` line, and the figure is one that run writes.
- Every ``toml`` block is the example file it names, and that file passes the schema.
- Every ``examples/*.toml`` solves with ``bem solve --json --quiet``, and with
  ``fem-reference solve --json --quiet`` where :func:`casefile.read` lets the FEM read it.
- Every case file of ``benchmarks/`` passes the schema and makes a BEM problem.
- The relative links of the README, BENCHMARKS.md, TESTING.md and of every page of
  ``docs/`` and ``benchmarks/`` resolve.

Commands and blocks run in a scratch folder that mirrors the repository root (symbolic
links to its top-level entries), so the README's relative paths (``examples/...``) work
as written while what they write (``out/...``, ``verification-report-example``) lands in
the scratch folder, never in the working tree.
"""

from __future__ import annotations

import json
import math
import re
import shlex
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import casefile

REPO = Path(__file__).resolve().parents[1]
README = REPO / "README.md"
BIN = Path(sys.executable).parent
TOOLS = ("bem", "fem-reference", "verify", "sweep")
SETUP = "python3 -m venv "
# Files of the working tree the scratch folder must not share: outputs and environments.
NOT_MIRRORED = {".git", ".venv", "out", "verification-report", "verification-report-example"}
# examples/*.toml slower than ~10 s at their own settings, and the overrides that keep the
# check fast, used when no README line already solves the file at its own settings (the
# README's friction line does: 1.6 s with its plot and grid error on the 2-core machine
# these tests were timed on, load 1; with these overrides 0.6 s).
SPEEDUPS = {"paper-section11-friction.toml": ["grid.spacing=0.5e-3", "grid.half_width=5.0e-3"]}


def fenced(text: str, lang: str) -> list[str]:
    """The bodies of the fenced code blocks of ``text`` in language ``lang``, in order."""
    return [m.group(1) for m in re.finditer(rf"^```{lang}[ \t]*\n(.*?)^```[ \t]*$", text, re.M | re.S)]


TEXT = README.read_text(encoding="utf-8")
PYTHON_BLOCKS = fenced(TEXT, "python")
BASH_LINES = [line.strip() for block in fenced(TEXT, "bash") for line in block.splitlines()
              if line.strip() and not line.strip().startswith("#")]
SETUP_LINES = [line for line in BASH_LINES if line.startswith(SETUP)]
TOOL_LINES = [line for line in BASH_LINES if not line.startswith(SETUP)]
EXAMPLES = sorted((REPO / "examples").glob("*.toml"))


def _mirror(folder: Path) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    for entry in REPO.iterdir():
        if entry.name not in NOT_MIRRORED and not (folder / entry.name).exists():
            (folder / entry.name).symlink_to(entry, target_is_directory=entry.is_dir())
    return folder


@pytest.fixture(scope="module")
def scratch(tmp_path_factory) -> Path:
    return _mirror(tmp_path_factory.mktemp("readme"))


def _split(line: str) -> tuple[list[str], int | None, str | None]:
    """The argv of a README line (console script of this environment), the exit status it
    states (default 0), and the reason it is not run, if any."""
    command, _, comment = line.partition(" #")
    skip = re.search(r"not run:\s*(\S.*)", comment)
    status = re.search(r"exits?\s+(\d+)", comment)
    argv = shlex.split(command)
    name = argv[0].removeprefix(".venv/bin/")
    assert name in TOOLS, f"README bash line {line!r}: not a setup command nor one of {TOOLS}"
    return [str(BIN / name), *argv[1:]], int(status.group(1)) if status else 0, skip and skip.group(1)


_RUNS: dict[str, subprocess.CompletedProcess] = {}


def _run(line: str, cwd: Path) -> subprocess.CompletedProcess:
    if line not in _RUNS:
        argv, _, _ = _split(line)
        _RUNS[line] = subprocess.run(argv, cwd=cwd, capture_output=True, text=True, timeout=300)
    return _RUNS[line]


# --- (a) the Python blocks --------------------------------------------------------


def test_readme_has_python_for_each_package():
    joined = "\n".join(PYTHON_BLOCKS)
    for needle in ("from bem import", "from bem.case import read_case, problem_from_config",
                   "fem_reference.solve(ContactProblem(", "from fem_reference.case import load_case",
                   "verification.runner import", "load_case", "run_case", "write_report"):
        assert needle in joined, f"the README's Python examples lost {needle!r}"


@pytest.mark.parametrize("index", range(len(PYTHON_BLOCKS)))
def test_python_block_runs(index, scratch, monkeypatch):
    monkeypatch.chdir(scratch)
    code = compile(PYTHON_BLOCKS[index], f"README.md python block {index + 1}", "exec")
    exec(code, {"__name__": f"readme_block_{index + 1}"})


# --- (b) the bash blocks ----------------------------------------------------------


def test_setup_commands_are_the_ci_command():
    assert len(SETUP_LINES) == 2, SETUP_LINES
    main_job, tests = SETUP_LINES
    assert main_job.endswith(".venv/bin/verify"), main_job
    ci_last = (REPO / ".ci" / "run").read_text(encoding="utf-8").rstrip("\n").splitlines()[-1]
    assert tests == ci_last, f"README: {tests!r}\n.ci/run: {ci_last!r}"


def test_bash_lines_write_only_under_out():
    """Outputs of the README's commands go under ``out/`` (git-ignored), never beside the
    sources; ``verify`` without ``--out`` would write ``verification-report/``."""
    for line in TOOL_LINES:
        argv, _, skip = _split(line)
        for option in ("--plot", "--fields", "--vtu", "--out"):
            if option in argv:
                assert argv[argv.index(option) + 1].startswith("out/"), line
        if argv[0].endswith("verify") and not skip:
            assert "--out" in argv, f"{line!r}: give --out out/... so a run does not write into the tree"
            assert "--quick" in argv or "--case" in argv, \
                f"{line!r}: the full suite is too slow here; use --quick or --case, or mark it '# not run: why'"


@pytest.mark.parametrize("line", TOOL_LINES)
def test_bash_line_runs(line, scratch):
    _, status, skip = _split(line)
    if skip:
        pytest.skip(f"README marks it not run: {skip}")
    done = _run(line, scratch)
    assert done.returncode == status, f"{line!r} exited {done.returncode}\n{done.stdout}\n{done.stderr[-3000:]}"
    if "--json" in line and status == 0:
        summary = json.loads(done.stdout)
        assert {"load", "indentation", "contact_radius"} <= set(summary)
    argv, _, _ = _split(line)
    for option in ("--plot", "--fields", "--vtu", "--out"):
        if option in argv and status == 0:
            assert (scratch / argv[argv.index(option) + 1]).exists(), f"{line!r} did not write {option}"


def _line(pattern: str) -> str:
    line = next((l for l in TOOL_LINES if re.search(pattern, l)), None)
    assert line, f"README: no command line matches {pattern!r}"
    return line


def test_numbers_in_the_prose_are_those_of_the_readme_runs(scratch):
    """The rolling resistances the README quotes are what its own command lines print."""
    text = " ".join(TEXT.split())
    done = _run(_line(r"^(\.venv/bin/)?bem solve examples/paper-section11-frictionless\.toml"), scratch)
    printed = re.search(r"rolling resistance\s+(\S+) N", done.stdout)
    assert printed, done.stdout
    assert f"`R_r = {float(printed.group(1)):.5f} N`" in text, f"the run prints R_r = {printed.group(1)} N"
    done = _run(_line(r"^(\.venv/bin/)?bem solve examples/paper-section11-friction\.toml .*--json"), scratch)
    summary = json.loads(done.stdout)
    for quoted in (f"`R_r = {summary['rolling_resistance']:.3f} N`",
                   f"{summary['rolling_resistance_friction']:.3f} N is slipping friction",
                   f"`rolling_resistance_energy = {summary['rolling_resistance_energy']:.3f} N`"):
        assert quoted in text, f"README should say {quoted!r} (the friction line's run)"


# --- the figure and its caption -------------------------------------------------------

FIGURE = re.search(r"!\[[^\]]*\]\((docs/images/[^)]+\.png)\)\s*\n\s*\n\*(.*?)\*\s*\n", TEXT, re.S)
# What each number of the caption is, in the order they appear:
# (quantity, method, against) of a gate of the case, and how the caption writes its error.
CAPTION_GATES = [
    ("contact_radius", "bem", "analytic", "percent"),
    ("contact_radius", "fem", "analytic", "percent"),
    ("peak_pressure", "bem", "analytic", "percent"),
    ("peak_pressure", "fem", "analytic", "percent"),
    ("pressure_rms_interior", "bem", "analytic", "ratio"),
    ("pressure_rms_interior", "fem", "analytic", "ratio"),
    ("indentation", "bem", "fem", "ratio"),
]


def test_figure_and_caption_match_the_readme_verify_run(scratch):
    assert FIGURE, "README: the figure and its italic caption are missing"
    image, caption = FIGURE.group(1), " ".join(FIGURE.group(2).split())
    assert (REPO / image).is_file(), image
    case = re.search(r"verify --case ([\w-]+)", caption)
    assert case, "the caption names the verify command that drew the figure"
    line = next((l for l in TOOL_LINES if re.search(rf"^(\.venv/bin/)?verify .*--case {case.group(1)}\b", l)), None)
    assert line, f"README: no 'verify --case {case.group(1)}' line to check the caption against"
    done = _run(line, scratch)
    assert done.returncode == 0, done.stderr[-3000:]
    argv, _, _ = _split(line)
    out = scratch / argv[argv.index("--out") + 1]
    assert (out / Path(image).name).is_file(), f"{line!r} does not draw {Path(image).name}"
    gates = json.loads((out / "metrics.json").read_text())["cases"][0]["gates"]
    numbers = re.findall(r"(\d+(?:\.\d+)?(?:e-?\d+)?)(%?)", caption.split("Against", 1)[1])
    written = [float(v) / (100 if pct else 1) for v, pct in numbers]
    assert len(written) == len(CAPTION_GATES), f"caption numbers {numbers} against {CAPTION_GATES}"
    for value, (quantity, method, against, _) in zip(written, CAPTION_GATES):
        gate = next(g for g in gates if (g["quantity"], g["method"], g["against"], g["level"])
                    == (quantity, method, against, "finest"))
        assert math.isclose(value, gate["error"], rel_tol=0.05), \
            f"caption says {value:.3g} for {quantity} {method} vs {against}; the run gives {gate['error']:.3g}"


# --- toml blocks and examples/ ---------------------------------------------------------


def test_toml_blocks_are_the_examples_they_name():
    blocks = fenced(TEXT, "toml")
    assert blocks, "README: the minimal case file is missing"
    for block in blocks:
        before = TEXT[:TEXT.index(block)]
        named = re.findall(r"`(examples/[\w.-]+\.toml)`", before)
        assert named, "a toml block of the README names the example file it shows"
        assert tomllib.loads(block) == tomllib.loads((REPO / named[-1]).read_text()), named[-1]
        casefile.read(REPO / named[-1], tool="bem")


def test_examples_exist_with_their_speedups():
    assert len(EXAMPLES) >= 4 and set(SPEEDUPS) <= {p.name for p in EXAMPLES}


def _fem_reads(path: Path) -> bool:
    from fem_reference import InputError
    from fem_reference.case import load_case

    try:
        load_case(path)  # casefile's checks for the FEM, and what fem_reference can solve
    except InputError:
        return False
    return True


def _readme_bem_json_line(path: Path) -> str | None:
    """A README line that already runs ``bem solve`` on this example at its own settings
    with ``--json`` and expects exit 0: its run (shared) checks the example too."""
    for line in TOOL_LINES:
        argv, status, skip = _split(line)
        if (Path(argv[0]).name == "bem" and argv[1:3] == ["solve", f"examples/{path.name}"]
                and "--json" in argv and "--set" not in argv and status == 0 and not skip):
            return line
    return None


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_each_example_solves_with_the_bem(path, scratch):
    line = _readme_bem_json_line(path)
    if line is not None:
        done = _run(line, scratch)
    else:
        sets = [a for s in SPEEDUPS.get(path.name, []) for a in ("--set", s)]
        done = subprocess.run([str(BIN / "bem"), "solve", str(path), "--json", "--quiet", *sets],
                              cwd=REPO, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    summary = json.loads(done.stdout)
    assert {"load", "indentation", "contact_radius", "rolling_resistance"} <= set(summary)
    assert all(math.isfinite(summary[k]) for k in ("load", "indentation", "contact_radius"))


FEM_EXAMPLES = [p for p in EXAMPLES if _fem_reads(p)]


def test_some_examples_are_for_the_fem():
    assert FEM_EXAMPLES, "no example is elastic, stationary and frictionless"


@pytest.mark.parametrize("path", FEM_EXAMPLES, ids=lambda p: p.name)
def test_each_fem_readable_example_solves_with_the_fem(path):
    done = subprocess.run([str(BIN / "fem-reference"), "solve", str(path), "--json", "--quiet"],
                          cwd=REPO, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    summary = json.loads(done.stdout)
    assert {"load", "indentation", "contact_radius", "peak_pressure"} <= set(summary)


@pytest.mark.parametrize("path", sorted((REPO / "benchmarks").rglob("*.toml")), ids=lambda p: p.name)
def test_benchmark_case_files_make_problems(path):
    from bem.case import problem_from_config, read_case

    problem, _ = problem_from_config(read_case(path, []))
    assert problem.grid.nodes_x > 1


# --- links ------------------------------------------------------------------------------


DOCS = ["README.md", "BENCHMARKS.md", "TESTING.md",
        *sorted(p.relative_to(REPO).as_posix() for folder in ("docs", "benchmarks")
                for p in (REPO / folder).rglob("*.md"))]


@pytest.mark.parametrize("doc", DOCS)
def test_relative_links_resolve(doc):
    path = REPO / doc
    for target in re.findall(r"\]\(([^)\s]+)\)", path.read_text(encoding="utf-8")):
        if re.match(r"[a-z]+:", target) or not re.search(r"[./#]", target):
            continue  # a URL, or LaTeX such as U[p](X) rather than a link
        file = target.split("#", 1)[0]
        if file:
            assert (path.parent / file).exists(), f"{doc}: broken link {target!r}"
