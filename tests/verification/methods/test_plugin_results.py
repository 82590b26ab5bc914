"""What a method hands back is read like user input. A plugin that returns garbage (NaN, a
negative load, a wrong type or shape), raises, exits with any code, or fails while its
module is imported fails its own gates with the reason, and the run ends with exit 1 and
a report; results files with non-finite numbers, a [problem] without a section every
method needs and a baseline that is not a metrics.json of this verify are input errors
(exit 2) before anything is solved."""

import json
from pathlib import Path

import pytest

from verification.cli import main as verify_main
from tests.verification.small_cases import THICK_LAYER_CASE as CASE
from verification.out_folder import MARKER


RUN = "import numpy as np\nfrom verification.results import Run\n"
# name: (the plugin file, what the gate's reason must say)
PLUGINS = {
    "nan": (RUN + "def solve(problem, level):\n    n = float('nan')\n"
                  "    return Run('nan', level.size, {'contact_radius': n, 'load': n}, np.full(3, n), np.full(3, n))\n",
            "scalar 'contact_radius' must be a finite number, got NaN"),
    "infpressure": (RUN + "def solve(problem, level):\n"
                          "    return Run('x', None, {'contact_radius': 2e-3}, np.zeros(2), np.array([1.0, np.inf]))\n",
                    "Run.pressure (Pa) holds 1 non-finite value(s) of 2"),
    "negload": (RUN + "def solve(problem, level):\n"
                      "    return Run('x', None, {'contact_radius': 2e-3, 'load': -10.0}, np.zeros(0), np.zeros(0))\n",
                "scalar 'load' must be > 0, got -10.0"),
    "negradius": (RUN + "def solve(problem, level):\n"
                        "    return Run('x', None, {'contact_radius': -2e-3}, np.zeros(0), np.zeros(0))\n",
                  "scalar 'contact_radius' cannot be negative"),
    "boolean": (RUN + "def solve(problem, level):\n"
                      "    return Run('x', None, {'contact_radius': True}, np.zeros(0), np.zeros(0))\n",
                "scalar 'contact_radius' must be a real number, got bool True"),
    "shapes": (RUN + "def solve(problem, level):\n"
                     "    return Run('x', None, {'contact_radius': 2e-3}, np.zeros(3), np.zeros(4))\n",
               "Run.r and Run.pressure must have one shape, got (3,) and (4,)"),
    "adict": ("def solve(problem, level):\n    return {'contact_radius': 2e-3}\n",
              "dict {'contact_radius': 0.002} is not a verification.results.Run"),
    "exit0": ("import sys\ndef solve(problem, level):\n    sys.exit(0)\n", "exited (SystemExit(0))"),
    "exit3": ("import sys\ndef solve(problem, level):\n    sys.exit(3)\n", "exited (SystemExit(3))"),
    "raises": ("def solve(problem, level):\n    raise RuntimeError('diverged')\n", "raised RuntimeError: diverged"),
    "syntax": ("def solve(problem, level)\n    return 1\n", "could not be imported: SyntaxError"),
    "atimport": ("raise RuntimeError('no licence server')\ndef solve(problem, level):\n    pass\n",
                 "could not be imported: RuntimeError: no licence server"),
    "exitatimport": ("import sys\nsys.exit(0)\n", "exited while imported (SystemExit(0))"),
    "dependency": ("import a_package_nobody_installed\ndef solve(problem, level):\n    pass\n",
                   "ModuleNotFoundError: No module named 'a_package_nobody_installed'"),
}


@pytest.fixture
def cases(tmp_path):
    folder = tmp_path / "cases"
    folder.mkdir()
    (folder / "hs.toml").write_text(CASE)
    return folder


def _gates(out: Path) -> dict:
    metrics = json.loads((out / "metrics.json").read_text())
    return {g["method"]: g for c in metrics["cases"] for g in c["gates"]}


def test_a_plugin_that_returns_garbage_raises_or_exits_fails_its_gates_and_the_run_goes_on(tmp_path, cases,
                                                                                           capsys):
    options = []
    for name, (text, _) in PLUGINS.items():
        path = tmp_path / f"{name}_method.py"
        path.write_text(text)
        options += ["--method", f"{name}={path}:solve"]
    out = tmp_path / "out"
    assert verify_main(["--cases-dir", str(cases), "--out", str(out), *options]) == 1
    gates = _gates(out)
    assert gates["bem"]["passed"]  # the BEM is untouched by what the plugins did
    report = (out / "report.md").read_text()
    for name, (_, says) in PLUGINS.items():
        g = gates[name]
        assert not g["passed"] and g["error"] is None, name
        assert says in g["reason"] and f"method {name!r}" in g["reason"] and f"{name}_method.py" in g["reason"], name
        assert says in report, name
    assert (out / MARKER).is_file()
    assert capsys.readouterr().out.startswith("FAIL:")


def test_a_plugin_spec_that_names_nothing_is_an_input_error(tmp_path, cases, capsys):
    (tmp_path / "ok_method.py").write_text("def solve(problem, level):\n    pass\n")
    for spec, says in ((f"{tmp_path / 'missing.py'}:solve", "no file"),
                       ("no_such_package_anywhere.module:solve", "cannot import 'no_such_package_anywhere.module'"),
                       (f"{tmp_path / 'ok_method.py'}:solv", "has no 'solv'; did you mean 'solve'?")):
        assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "o"), "--method", f"p={spec}"]) == 2
        assert says in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_a_case_whose_kind_exits_is_a_failed_case(tmp_path, cases, monkeypatch):
    from verification.kinds import stationary

    def run(case, ctx):
        raise SystemExit(4)

    monkeypatch.setattr(stationary, "run", run)
    out = tmp_path / "out"
    assert verify_main(["--cases-dir", str(cases), "--out", str(out)]) == 1
    assert "the case did not run: SystemExit: 4" in (out / "report.md").read_text()


def _results(folder: Path, level: dict) -> Path:
    folder.mkdir(exist_ok=True)
    doc = {"units": {"length": "mm", "pressure": "MPa", "force": "N"}, "levels": [level]}
    (folder / "hs.json").write_text(json.dumps(doc))  # json writes NaN and Infinity as JavaScript does
    return folder


@pytest.mark.parametrize("level, says", [
    ({"size": float("inf"), "scalars": {"contact_radius": 2.3}}, "levels[0]: size must be a finite number, got Infinity"),
    ({"size": 0.1, "scalars": {"contact_radius": float("nan")}},
     "levels[0]: scalar 'contact_radius' must be a finite number, got NaN"),
    ({"scalars": {"contact_radius": 2.3, "load": float("-inf")}},
     "levels[0]: scalar 'load' must be a finite number, got -Infinity"),
    ({"scalars": {"contact_radius": 2.3}, "seconds": float("nan")}, "levels[0]: seconds must be a finite number"),
    ({"scalars": {"contact_radius": 2.3, "load": 0}}, "levels[0]: scalar 'load' must be > 0, got 0.0"),
    ({"scalars": {"contact_radius": 2.3}, "pressure": 7}, "levels[0]: pressure must be the name of a CSV file"),
])
def test_a_results_file_with_non_finite_or_unphysical_numbers_is_an_input_error(tmp_path, cases, capsys, level, says):
    folder = _results(tmp_path / "abaqus", level)
    assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "o"), "--method", f"ab={folder}"]) == 2
    err = capsys.readouterr().err
    assert f"{folder / 'hs.json'}: {says}" in err
    assert "[1/1]" not in err and not (tmp_path / "o").exists()


@pytest.mark.parametrize("drop", ["layer", "loading", "layer|loading", "material", "indenter"])
def test_a_problem_without_a_section_every_method_needs_is_an_input_error(tmp_path, capsys, drop):
    folder = tmp_path / "cases"
    folder.mkdir()
    names = drop.split("|")
    text = "\n".join(line for line in CASE.splitlines() if line.split(" ")[0] not in names)
    (folder / "hs.toml").write_text(text)
    assert verify_main(["--cases-dir", str(folder), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    for name in names:
        assert f"{folder / 'hs.toml'} [problem]: " in err and f"needs a [problem.{name}] section" in err
    assert "[1/1]" not in err and not (tmp_path / "o").exists()


def _metrics(**gate) -> dict:
    g = {"key": "hs: bem contact_radius vs analytic (finest)", "verdict": "PASS", "error": 0.004,
         "tolerance": 0.01, **gate}
    return {"passed": True, "drift": [], "cases": [{"name": "hs", "gates": [{k: v for k, v in g.items()
                                                                            if v is not ...}]}]}


@pytest.mark.parametrize("text, says", [
    (json.dumps(_metrics(error=...)), "cases[0].gates[0]: no 'error' (a metrics.json of another version"),
    (json.dumps(_metrics(error="0.004")), "cases[0].gates[0]: 'error' must be a finite number or null, got '0.004'"),
    (json.dumps(_metrics(tolerance=float("nan"))), "'tolerance' must be a finite number or null, got nan"),
    (json.dumps(_metrics(verdict="OK")), "'verdict' PASS, FAIL or REPORTED"),
    (json.dumps({"gates": []}), "not a metrics.json of this harness"),
    ('{"cases": [', "not a metrics.json of this harness"),
    (None, "its folder's .verification-report says report format 7"),
])
def test_a_baseline_of_another_version_or_malformed_is_an_input_error(tmp_path, cases, capsys, text, says):
    path = tmp_path / "old" / "metrics.json"
    path.parent.mkdir()
    path.write_text(json.dumps(_metrics()) if text is None else text)
    if text is None:  # a report folder of another format
        (path.parent / MARKER).write_text("verify report format 7\n")
    assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "o"), "--baseline", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"--baseline {str(path)!r}" in err and says in err
    assert "[1/1]" not in err and not (tmp_path / "o").exists()


def test_a_valid_baseline_is_read(tmp_path, cases):
    path = tmp_path / "metrics.json"
    path.write_text(json.dumps(_metrics(tolerance=None)))
    assert verify_main(["--cases-dir", str(cases), "--out", str(tmp_path / "o"), "--baseline", str(path)]) == 0


def test_the_forms_a_sound_method_returns_are_accepted_as_they_are():
    import numpy as np

    from verification.results import MethodError, Run, check_run

    grid = np.arange(6.0).reshape(2, 3)
    run = check_run(Run("m", np.float32(1e-4), {"load": 10, "contact_radius": np.float32(2e-3),
                                                "rolling_resistance": -1e-17, "trailing_edge": -1e-3,
                                                "leading_edge": 1e-3},
                        grid.tolist(), grid * 1e5, seconds=np.int64(2)))
    assert run.scalars == {"load": 10.0, "contact_radius": float(np.float32(2e-3)), "rolling_resistance": -1e-17,
                           "trailing_edge": -1e-3, "leading_edge": 1e-3}
    assert run.r.shape == run.pressure.shape == (6,) and run.pressure[-1] == 5e5 and run.seconds == 2.0
    for bad in (Run("m", None, {}, np.zeros(2), np.zeros(2, complex)),
                Run("m", 0.0, {}, np.zeros(0), np.zeros(0)),
                Run("m", None, {"leading_edge": -1.0, "trailing_edge": 1.0}, np.zeros(0), np.zeros(0))):
        with pytest.raises(MethodError):
            check_run(bad)
