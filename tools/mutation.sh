#!/usr/bin/env bash
# Mutation testing of one module of the numerical core with mutmut (>= 3.8), against the
# fast tests that cover it. Never touches the working tree: the project is copied into a
# scratch directory (git archive of REF, default HEAD) and mutmut runs there.
#
#   tools/mutation.sh MODULE [TEST_FILE ...]        e.g. tools/mutation.sh bem/kinematics.py
#                                                   (MODULE may be a glob in quotes: 'bem/frictional/*')
#   MUTATION_REF=<commit>  tools/mutation.sh ...    mutate/test another commit
#   MUTATION_TESTS_REF=<commit> ...                 take tests/ from this commit instead (e.g. mutate the
#                                                   sources of an older commit with newer tests)
#   MUTATION_OVERLAY='<ref>:<path> ...'             then put these files of these commits over the copy (e.g.
#                                                   new test files next to the old suite of MUTATION_TESTS_REF)
#   MUTATION_DIR=<dir>     tools/mutation.sh ...    scratch directory (default /tmp/viscolayer-mutation/<module>)
#   MUTATION_NAMES='<mutant names or globs>' ...    only these mutants (e.g. the survivors of a full run)
#   MUTATION_PYTEST_ARGS='--deselect NODE ...' ...  more pytest arguments (split on spaces), e.g. leave
#                                                   out a slow test that only some functions need
#   MUTATION_TIMEOUT_MULTIPLIER=<x> ...             a mutant times out after x (its tests' clean time
#                                                   + 1 s) wall seconds (2x that in CPU); default 20: under
#                                                   nice on a machine shared by five agents a mutant's tests ran
#                                                   3-20x slower than in the clean run, and lower multipliers
#                                                   timed out equivalent and even quickly-failing mutants
#   MUTATION_NICE=<n>  (default 15)                 niceness of the run (19 got ~5% of a core next to nice-10 jobs)
#
# Without TEST_FILE the default list of fast test files for MODULE (below) is used.
# Prints the summary line (killed / survived / ... / score) and the survivors' diffs;
# `cd $MUTATION_DIR && mutmut show NAME` shows one mutant. Runs under `nice -n 15` with
# one worker (the machine is shared); each mutant's tests run fastest first, so a killed
# mutant costs its cheapest failing test. See TESTING.md.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
module=${1:?usage: tools/mutation.sh MODULE [TEST_FILE ...]}
shift
py=${PYTHON:-$here/.venv/bin/python}
ref=${MUTATION_REF:-HEAD}

default_tests() {
    case "$1" in
        bem/kinematics.py|bem/indenters.py) echo tests/unit/test_mutation_kills_bem.py ;;
        verification/metrics.py) echo tests/unit/test_properties_richardson.py \
            tests/unit/test_verification_harness.py::test_richardson_recovers_order_and_limit_for_any_ratio \
            tests/unit/test_verification_harness.py::test_richardson_refuses_to_extrapolate_stagnant_or_oscillating_sequences \
            tests/unit/test_verification_harness.py::test_radius_fit_is_exact_for_the_hertz_edge \
            tests/unit/test_verification_harness.py::test_pressure_difference_of_a_scaled_field_is_known_exactly ;;
        bem/spectral.py) echo tests/unit/test_spectral.py \
            tests/unit/test_bem_speed_limits.py::test_non_finite_kernels_are_an_error_naming_the_speed_and_the_grid ;;
        bem/layer.py) echo tests/unit/test_layer.py tests/unit/test_properties_layer.py \
            tests/unit/test_derivation_eq45.py ;;
        bem/energy.py) echo tests/unit/test_properties_layer.py ;;
        bem/friction.py|bem/frictional/*) echo tests/unit/test_mutation_kills_friction.py tests/unit/test_row_filter.py \
            tests/unit/test_mutation_kills_active_set.py \
            tests/unit/test_mutation_friction_solve.py tests/unit/test_friction.py tests/unit/test_bem_friction_cli.py \
            tests/unit/test_bem_displacement_control.py::test_frictional_rolling_under_displacement_control ;;
        bem/linear.py) echo tests/unit/test_linear.py ;;
        bem/contact.py) echo tests/unit/test_mutation_kills_contact.py tests/unit/test_contact.py \
            tests/unit/test_properties_contact.py tests/unit/test_bem_displacement_control.py ;;
        fem_reference/forms.py|fem_reference/postprocess.py|fem_reference/solve.py)
            echo tests/unit/test_fem_contact.py tests/unit/test_fem_inputs.py tests/unit/test_mutation_kills_fem.py \
                tests/unit/test_fem_failures.py ;;
        *) echo "no default test list for $1: give the test files" >&2; exit 2 ;;
    esac
}
if [ $# -gt 0 ]; then tests=("$@"); else read -r -a tests <<<"$(default_tests "$module")"; fi

work=${MUTATION_DIR:-/tmp/viscolayer-mutation/$(echo "$module" | tr '/.*' '__x')}
rm -rf "$work"
mkdir -p "$work"
git -C "$here" archive "$ref" | tar -x -C "$work"
if [ -n "${MUTATION_TESTS_REF:-}" ]; then
    rm -rf "$work/tests"
    git -C "$here" archive "$MUTATION_TESTS_REF" tests | tar -x -C "$work"
fi
for item in ${MUTATION_OVERLAY:-}; do
    git -C "$here" archive "${item%%:*}" "${item#*:}" | tar -x -C "$work"
done
cd "$work"
present=()
for t in "${tests[@]}"; do [ -f "${t%%::*}" ] && present+=("$t"); done
toml_list() { local s="" x; for x in "$@"; do s+="\"$x\", "; done; echo "[${s%, }]"; }
cat >>pyproject.toml <<TOML

[tool.mutmut]
source_paths = ["bem/", "fem_reference/", "verification/", "casefile/", "sweeps/"]
only_mutate = ["$module"]
also_copy = ["examples/", "docs/", "benchmarks/", "README.md"]
pytest_add_cli_args_test_selection = $(toml_list "${present[@]}")
pytest_add_cli_args = $(toml_list -x -q -p no:cacheprovider -m "not slow" ${MUTATION_PYTEST_ARGS:-})
timeout_multiplier = ${MUTATION_TIMEOUT_MULTIPLIER:-20}
TOML
# hypothesis in mutation runs: fixed examples, no shrinking (a killed mutant needs no
# minimal example), no example database
mkdir -p tests
cat >tests/conftest.py <<'PY'
from hypothesis import Phase, settings
settings.register_profile("mutation", derandomize=True, database=None,
                          phases=[Phase.explicit, Phase.generate])
settings.load_profile("mutation")


def pytest_collection_modifyitems(config, items):
    """Run a mutant's tests fastest first (durations of mutmut's clean run): with -x a
    killed mutant then costs its cheapest failing test, not whatever test came first."""
    try:
        from mutmut.state import state
        duration = state().duration_by_test
    except Exception:  # the clean and the stats runs: keep pytest's order
        return
    if duration:
        items.sort(key=lambda item: duration.get(item.nodeid, 0.0))
PY
echo "mutating $module of $(git -C "$here" rev-parse --short "$ref")${MUTATION_TESTS_REF:+ with the tests of $(git -C "$here" rev-parse --short "$MUTATION_TESTS_REF")} in $work against: ${present[*]}" >&2
export MPLBACKEND=Agg OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
# MUTATION_NAMES="name1 name2 ..." (or globs such as 'bem.layer.x_system_matrix*') runs only those mutants
# shellcheck disable=SC2086
nice -n "${MUTATION_NICE:-15}" "$py" -m mutmut run --max-children 1 ${MUTATION_NAMES:-} >mutmut.log 2>&1 || { tail -40 mutmut.log; exit 1; }
nice -n "${MUTATION_NICE:-15}" "$py" -m mutmut results --all true >results.txt 2>&1 || true
"$py" - <<'PY'
import collections, re
counts = collections.Counter()
for line in open("results.txt"):
    m = re.match(r"\s*(\S+): (\w[\w ]*)$", line.rstrip())
    if m:
        counts[m.group(2)] += 1
killed = counts.get("killed", 0)
total = sum(v for k, v in counts.items() if k != "not checked")  # a partial run (MUTATION_NAMES)
alive = total - killed
print("mutants:", dict(counts), f"score {killed}/{total} = {100.0 * killed / max(total, 1):.1f}%")
PY
grep -E ": (survived|no tests|timeout|suspicious)" results.txt || true
