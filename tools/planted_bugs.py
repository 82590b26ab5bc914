"""Check that the fast tests catch a fixed list of plausible bugs.

Each bug is planted, one at a time, in a copy of the packages in a temporary directory (the
working tree is never touched); the tests named for it then run in a forked Python whose
``bem``, ``fem_reference`` and ``verification`` are imported from the copy (checked), and
must fail. A control run of every named test on the unmodified copy must pass first, so a
failure is the bug's doing. One driver process imports the heavy dependencies once and
forks for each run.

Run: ``.venv/bin/python tools/planted_bugs.py`` (a few seconds). Prints one line per bug;
exits 1 when a bug is not caught, a planted text no longer matches the source (a refactor
of the planted line: update the text below, keeping the bug), a named test is missing, or
the control fails; 0 when every bug is caught. Full mutation testing is
``tools/mutation.sh`` (TESTING.md).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("bem", "fem_reference", "verification", "casefile", "sweeps")

# the plain test first: with -x, hypothesis then never spends time shrinking a failure
RICHARDSON = ["tests/verification/test_metrics.py::test_richardson_recovers_order_and_limit_for_any_ratio",
              "tests/verification/test_metrics.py::test_richardson_is_exact_on_any_geometric_sequence"]

# name: (module, [(text, replacement, occurrences)], tests that must fail)
PLANTED = {
    "omega_m sign flipped": (
        "bem/spectral.py",
        [("layer.material.modulus(-nu_x * speed)", "layer.material.modulus(nu_x * speed)", 2)],
        ["tests/bem/test_spectral.py::test_moving_load_leaves_a_trailing_depression"],
    ),
    "downwind instead of upwind difference": (
        "bem/kinematics.py",
        [("out[:, :-1] = (kernel[:, 1:] - kernel[:, :-1]) / spacing_x\n    out[:, -1] = out[:, -2]",
          "out[:, 1:] = (kernel[:, 1:] - kernel[:, :-1]) / spacing_x\n    out[:, 0] = out[:, 1]", 1),
         ("out[:, :-1] = (f[:, 1:] - f[:, :-1]) / spacing_x\n    out[:, -1] = out[:, -2]",
          "out[:, 1:] = (f[:, 1:] - f[:, :-1]) / spacing_x\n    out[:, 0] = out[:, 1]", 1)],
        ["tests/bem/test_kinematics.py::test_upwind_difference_of_a_quadratic_is_the_slope_half_a_step_upstream"],
    ),
    "second-order inertia term 1 % off in one coefficient": (
        "bem/layer.py",
        [('(-960, 1, 1, "c")', '(-970, 1, 1, "c")', 1)],
        ["tests/bem/test_layer.py::test_a_little_inertia_terms_are_the_general_routes_derivatives"],
    ),
    "cylinder rolling arm -x / 2R": (
        "bem/indenters.py",
        [("np.inf)\n\n    def rolling_arm(self, X, Y):\n        return np.asarray(X, float) / self.radius",
          "np.inf)\n\n    def rolling_arm(self, X, Y):\n        return -np.asarray(X, float) / (2 * self.radius)", 1)],
        ["tests/bem/test_indenters.py::test_cylinder_is_a_circle_in_x_and_infinite_beyond_its_ends"],
    ),
    "Richardson ratio hard-coded to 2": (
        "bem/convergence.py",
        [("math.log(ratio)", "math.log(2.0)", 1), ("ratio**p - 1", "2.0**p - 1", 1)],
        RICHARDSON,
    ),
    "Richardson error_finest replaced": (
        "bem/convergence.py",
        [("abs(ext - q3), True)", "abs(d2), True)", 1)],
        RICHARDSON,
    ),
    "FEM layer pressure sign flipped": (
        "fem_reference/stationary/solve.py",
        [("u, p = full[:ub.N], full[ub.N:]", "u, p = full[:ub.N], -full[ub.N:]", 1)],
        ["tests/fem_reference/stationary/test_solve.py::test_base_pressure_carries_the_load"],
    ),
    "FEM hoop strain halved": (
        "fem_reference/stationary/forms.py",
        [("ur / r, 0.5 *", "0.5 * ur / r, 0.5 *", 1)],
        ["tests/fem_reference/stationary/test_forms.py::test_axisymmetric_stiffness_on_exact_fields"],
    ),
}

_DRIVER = r"""
import json, os, pathlib, sys
root, spec, args = pathlib.Path(sys.argv[1]).resolve(), json.loads(sys.argv[2]), json.loads(sys.argv[3])
sys.path.insert(0, str(root))
sys.dont_write_bytecode = True
# the heavy dependencies once, shared by every forked run; the project's packages are
# imported afresh in each child, from the edited copy
import numpy, scipy.fft, scipy.interpolate, scipy.linalg, scipy.signal, scipy.sparse  # noqa
import matplotlib; matplotlib.use("Agg")
import hypothesis, pytest, skfem  # noqa
results = {}
for name, module, edits, tests in spec:
    path = root / module if module else None
    original = path.read_text() if path else None
    if path:
        text = original
        for old, new, count in edits:
            if text.count(old) != count:
                results[name] = f"{module}: {old!r} found {text.count(old)} time(s), expected {count}"
                break
            text = text.replace(old, new)
        else:
            path.write_text(text)
        if name in results:
            continue
    print(f"=== RUN {name}", flush=True)
    pid = os.fork()
    if pid == 0:
        import bem, fem_reference, verification
        for m in (bem, fem_reference, verification):
            assert pathlib.Path(m.__file__).resolve().is_relative_to(root), m.__file__
        rc = pytest.main(args + tests)
        sys.stdout.flush()
        os._exit(int(rc))
    _, status = os.waitpid(pid, 0)
    results[name] = os.waitstatus_to_exitcode(status)
    if path:
        path.write_text(original)
print("PLANTED-RESULTS " + json.dumps(results))
"""

CONTROL = "control: the unmodified copy"
PYTEST_ARGS = ["-q", "-x", "-p", "no:cacheprovider", "--no-header", "-o", "addopts=", "--import-mode=importlib",
               "--rootdir", str(ROOT)]


def missing_tests() -> list[str]:
    """One line per named test whose file or function is not where the table says."""
    out = []
    for test in sorted({t for _, _, ts in PLANTED.values() for t in ts}):
        file, _, func = test.partition("::")
        path = ROOT / file
        if path.is_file() and f"def {func}(" in path.read_text():
            continue
        found = [str(p.relative_to(ROOT)) for p in sorted((ROOT / "tests").rglob("test_*.py"))
                 if f"def {func}(" in p.read_text()]
        out.append(f"MISSING TEST {test}" + (f" (found in {', '.join(found)}: update the table)" if found else ""))
    return out


def run() -> int:
    problems = missing_tests()
    if problems:
        print("\n".join(problems))
        return 1
    with tempfile.TemporaryDirectory(prefix="planted-bugs-") as tmp:
        copy = Path(tmp)
        for name in PACKAGES:
            shutil.copytree(ROOT / name, copy / name, ignore=shutil.ignore_patterns("__pycache__"))
        tests = lambda names: [str(ROOT / t) for t in names]  # noqa: E731
        spec = [(CONTROL, None, [], tests(sorted({t for _, _, ts in PLANTED.values() for t in ts})))]
        spec += [(name, module, edits, tests(names)) for name, (module, edits, names) in PLANTED.items()]
        env = dict(os.environ, PYTHONPATH=str(copy), MPLBACKEND="Agg", PYTHONDONTWRITEBYTECODE="1",
                   OPENBLAS_NUM_THREADS=os.environ.get("OPENBLAS_NUM_THREADS", "1"))
        out = subprocess.run([sys.executable, "-c", _DRIVER, str(copy), json.dumps(spec), json.dumps(PYTEST_ARGS)],
                             cwd=copy, env=env, capture_output=True, text=True, timeout=900)
    lines = [x for x in out.stdout.splitlines() if x.startswith("PLANTED-RESULTS ")]
    if out.returncode != 0 or not lines:
        print(out.stdout[-4000:] + out.stderr[-4000:])
        print(f"FAILED the driver exited with {out.returncode}")
        return 1
    results = json.loads(lines[-1].split(" ", 1)[1])
    logs = {part.split("\n", 1)[0]: part for part in out.stdout.split("=== RUN ")[1:]}
    if results[CONTROL] != 0:
        print(logs.get(CONTROL, out.stdout)[-4000:])
        print(f"FAILED control: the named tests fail on the unmodified copy (pytest exit {results[CONTROL]})")
        return 1
    bad = 0
    for name in PLANTED:
        got = results[name]
        if isinstance(got, str):
            print(f"TEXT NO LONGER APPLIES {name!r}: {got}; update the planted text in tools/planted_bugs.py")
        elif got != 1:
            print(logs.get(name, "")[-3000:])
            print(f"NOT CAUGHT {name!r}: pytest exit {got} (1 expected: the tests fail)")
        else:
            print(f"caught {name!r}")
            continue
        bad += 1
    print(f"{len(PLANTED) - bad} of {len(PLANTED)} planted bugs caught")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(run())
