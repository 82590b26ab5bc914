"""Regression check of the suite itself: plausible bugs, planted one at a time in a copy of
the packages, are caught by the fast tests (issue 14's table).

Each planted bug edits a copy of the packages in a temporary directory (the real files
are never touched), then runs the few fast tests that must catch it in a forked Python
whose ``bem``, ``fem_reference`` and ``verification`` are imported afresh from the copy
(checked), and asserts that they fail (pytest exit 1). One driver process imports the
heavy dependencies once and forks for each run, so the whole check costs about one
import of the project per bug. A control run of the same tests on the unmodified copy must pass, so a
failure is the bug's doing and not the copy's. If a planted edit no longer applies (the
source changed), the test says which text it looked for: update the table.

Full mutation testing of the numerical core (slow, not in CI) is ``tools/mutation.sh``;
see TESTING.md.
"""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
UNIT = ROOT / "tests" / "unit"
PACKAGES = ("bem", "fem_reference", "verification", "casefile", "sweeps")

KILLS_BEM = "test_mutation_kills_bem.py"
# the plain test first: with -x, hypothesis then never spends time shrinking a failure
RICHARDSON = ("test_verification_harness.py::test_richardson_recovers_order_and_limit_for_any_ratio",
              "test_properties_richardson.py::test_richardson_is_exact_on_any_geometric_sequence")

# name: (module, [(text, replacement, occurrences)], tests that must fail)
PLANTED = {
    "omega_m sign flipped": (
        "bem/spectral.py",
        [("layer.material.modulus(-nu_x * speed)", "layer.material.modulus(nu_x * speed)", 2)],
        ["test_spectral.py::test_moving_load_leaves_a_trailing_depression"],
    ),
    "downwind instead of upwind difference": (
        "bem/kinematics.py",
        [("out[:, :-1] = (kernel[:, 1:] - kernel[:, :-1]) / spacing_x\n    out[:, -1] = out[:, -2]",
          "out[:, 1:] = (kernel[:, 1:] - kernel[:, :-1]) / spacing_x\n    out[:, 0] = out[:, 1]", 1),
         ("out[:, :-1] = (f[:, 1:] - f[:, :-1]) / spacing_x\n    out[:, -1] = out[:, -2]",
          "out[:, 1:] = (f[:, 1:] - f[:, :-1]) / spacing_x\n    out[:, 0] = out[:, 1]", 1)],
        [f"{KILLS_BEM}::test_upwind_difference_of_a_quadratic_is_the_slope_half_a_step_upstream"],
    ),
    "cylinder rolling arm -x / 2R": (
        "bem/indenters.py",
        [("g, np.inf)\n\n    def rolling_arm(self, X, Y):\n        return np.asarray(X, float) / self.radius",
          "g, np.inf)\n\n    def rolling_arm(self, X, Y):\n        return -np.asarray(X, float) / (2 * self.radius)", 1)],
        [f"{KILLS_BEM}::test_cylinder_profile_ends_and_arm"],
    ),
    "Richardson ratio hard-coded to 2": (
        "verification/metrics.py",
        [("math.log(ratio)", "math.log(2.0)", 1), ("ratio**p - 1", "2.0**p - 1", 1)],
        list(RICHARDSON),
    ),
    "Richardson error_finest replaced": (
        "verification/metrics.py",
        [("abs(ext - q3), True)", "abs(d2), True)", 1)],
        list(RICHARDSON),
    ),
    "FEM layer pressure sign flipped": (
        "fem_reference/solve.py",
        [("u, p = full[:ub.N], full[ub.N:]", "u, p = full[:ub.N], -full[ub.N:]", 1)],
        ["test_mutation_kills_fem.py::test_base_pressure_carries_the_load"],
    ),
    "FEM hoop strain halved": (
        "fem_reference/forms.py",
        [("ur / r, 0.5 *", "0.5 * ur / r, 0.5 *", 1)],
        ["test_mutation_kills_fem.py::test_axisymmetric_stiffness_on_exact_fields"],
    ),
}

_DRIVER = r"""
import json, os, pathlib, sys
root, spec = pathlib.Path(sys.argv[1]).resolve(), json.loads(sys.argv[2])
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
                results[name] = f"edit: {old!r} found {text.count(old)} time(s), expected {count}"
                break
            text = text.replace(old, new)
        else:
            path.write_text(text)
        if name in results:
            continue
    sys.stdout.flush()
    pid = os.fork()
    if pid == 0:
        import bem, fem_reference, verification
        for m in (bem, fem_reference, verification):
            assert pathlib.Path(m.__file__).resolve().is_relative_to(root), m.__file__
        rc = pytest.main(["-q", "-x", "-p", "no:cacheprovider", "--no-header", "-o", "addopts="] + tests)
        sys.stdout.flush()
        os._exit(int(rc))
    _, status = os.waitpid(pid, 0)
    results[name] = os.waitstatus_to_exitcode(status)
    if path:
        path.write_text(original)
print("PLANTED-RESULTS " + json.dumps(results))
"""

CONTROL = "control: the unmodified copy"


def _copy(dest: Path) -> Path:
    for name in PACKAGES:
        shutil.copytree(ROOT / name, dest / name, ignore=shutil.ignore_patterns("__pycache__"))
    return dest


@pytest.fixture(scope="module")
def outcome(tmp_path_factory):
    """Run the control and every planted bug in one driver process (one fork each)."""
    copy = _copy(tmp_path_factory.mktemp("copy"))
    all_tests = sorted({t for _, _, ts in PLANTED.values() for t in ts})
    spec = [(CONTROL, None, [], [str(UNIT / t) for t in all_tests])]
    spec += [(name, module, edits, [str(UNIT / t) for t in tests]) for name, (module, edits, tests) in PLANTED.items()]
    env = dict(os.environ, PYTHONPATH=str(copy), MPLBACKEND="Agg", PYTHONDONTWRITEBYTECODE="1")
    out = subprocess.run([sys.executable, "-c", _DRIVER, str(copy), json.dumps(spec)], cwd=copy, env=env,
                         capture_output=True, text=True, timeout=900)
    lines = [x for x in out.stdout.splitlines() if x.startswith("PLANTED-RESULTS ")]
    assert out.returncode == 0 and lines, out.stdout[-4000:] + out.stderr[-4000:]
    return json.loads(lines[-1].split(" ", 1)[1]), out.stdout


def test_control_the_copy_passes_every_test_used_below(outcome):
    results, log = outcome
    assert results[CONTROL] == 0, log[-4000:]


@pytest.mark.parametrize("name", list(PLANTED))
def test_planted_bug_is_caught(name, outcome):
    results, log = outcome
    got = results[name]
    assert not isinstance(got, str), f"{got}: update the planted bug {name!r} in {Path(__file__).name}"
    assert got == 1, f"planted bug {name!r} was not caught (pytest exit {got}):\n{log[-4000:]}"
