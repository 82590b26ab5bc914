#!/usr/bin/env bash
# Mutation testing of one module with mutmut (>= 3.8), against the fast tests that cover it.
# Never touches the sources of the working tree: the project is copied into a scratch
# directory (git archive of REF, default HEAD) and mutmut runs there. A full run with the
# default tests writes the module's row of docs/mutation-scores.md.
#
#   tools/mutation.sh MODULE [TEST ...]             e.g. tools/mutation.sh bem/kinematics.py
#                                                   (MODULE may be a glob in quotes: 'bem/frictional/*';
#                                                   TEST a file, a folder or a node id)
#   MUTATION_REF=<commit>  tools/mutation.sh ...    mutate/test another commit; MUTATION_REF=worktree
#                                                   copies the working tree as it is (tracked and new,
#                                                   unignored files), uncommitted changes included
#   MUTATION_TESTS_REF=<commit> ...                 take tests/ from this commit instead (e.g. mutate the
#                                                   sources of an older commit with newer tests)
#   MUTATION_OVERLAY='<ref>:<path> ...'             then put these files of these commits over the copy
#   MUTATION_DIR=<dir>     tools/mutation.sh ...    scratch directory (default /tmp/viscolayer-mutation/<module>)
#   MUTATION_NAMES='<mutant names or globs>' ...    only these mutants (e.g. the survivors of a full run)
#   MUTATION_PYTEST_ARGS='--deselect NODE ...' ...  more pytest arguments (split on spaces)
#   MUTATION_TIMEOUT_MULTIPLIER=<x> ...             a mutant times out after x (its tests' clean time
#                                                   + 1 s) wall seconds; default 20: under nice on a
#                                                   shared machine a mutant's tests run 3-20x slower than
#                                                   in the clean run
#   MUTATION_NICE=<n>  (default 15)                 niceness of the run (19 gets ~5% of a core next to
#                                                   nice-10 jobs)
#
# Without TEST the module's default tests (its mirrored folder under tests/, below) are used;
# mutmut then runs, for each mutant, only the tests that reach the mutated function, fastest
# first, so a broad folder costs one clean run and little per mutant.
# Prints the summary line (killed / survived / ... / score) and the survivors' names;
# `cd $MUTATION_DIR && mutmut show NAME` shows one mutant. Runs under `nice -n 15` with one
# worker. See TESTING.md.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
module=${1:?usage: tools/mutation.sh MODULE [TEST ...]}
shift
py=${PYTHON:-$here/.venv/bin/python}
ref=${MUTATION_REF:-HEAD}

# The default tests of a module: its mirrored folder or files (globs, read in the copy).
default_tests() {
    local name
    name=$(basename "$1" .py)
    case "$1" in
        bem/frictional/*) echo "tests/bem/frictional/ tests/bem/test_displacement_control.py" ;;
        bem/dma/*) echo "tests/bem/dma/" ;;
        bem/contact.py) echo "tests/bem/test_contact*.py tests/bem/test_displacement_control.py" ;;
        bem/energy.py) echo "tests/bem/test_energy*.py tests/bem/test_layer_properties.py" ;;
        bem/spectral.py) echo "tests/bem/test_spectral*.py tests/bem/test_speed_limits.py" ;;
        bem/layer.py) echo "tests/bem/test_layer*.py" ;;
        bem/convergence.py) echo "tests/verification/test_metrics.py tests/bem/frictional/test_grid_error.py" ;;
        bem/*.py) echo "tests/bem/test_${name}*.py" ;;
        fem_reference/*) echo "tests/fem_reference/" ;;
        verification/metrics.py) echo "tests/verification/test_metrics.py tests/verification/kinds/test_stationary.py" ;;
        verification/*) echo "tests/verification/" ;;
        sweeps/*) echo "tests/sweeps/" ;;
        casefile/*) echo "tests/casefile/" ;;
        *) echo "no default tests for $1: give the test files" >&2; exit 2 ;;
    esac
}
default_selection=0
if [ $# -gt 0 ]; then patterns=("$@"); else read -r -a patterns <<<"$(default_tests "$module")"; default_selection=1; fi

work=${MUTATION_DIR:-/tmp/viscolayer-mutation/$(echo "$module" | tr '/.*' '__x')}
rm -rf "$work"
mkdir -p "$work"
if [ "$ref" = worktree ]; then
    # the files git knows of or would add, as they are now (deleted ones skipped)
    (cd "$here" && git ls-files -z --cached --others --exclude-standard \
        | while IFS= read -r -d '' f; do [ -f "$f" ] && printf '%s\0' "$f"; done \
        | tar --null -T - -c) | tar -x -C "$work"
    commit="$(git -C "$here" rev-parse --short HEAD)+worktree"
else
    git -C "$here" archive "$ref" | tar -x -C "$work"
    commit=$(git -C "$here" rev-parse --short "$ref")
fi
if [ -n "${MUTATION_TESTS_REF:-}" ]; then
    rm -rf "$work/tests"
    git -C "$here" archive "$MUTATION_TESTS_REF" tests | tar -x -C "$work"
    commit+=" (tests $(git -C "$here" rev-parse --short "$MUTATION_TESTS_REF"))"
fi
for item in ${MUTATION_OVERLAY:-}; do
    git -C "$here" archive "${item%%:*}" "${item#*:}" | tar -x -C "$work"
done
cd "$work"
# the patterns that exist in the copy (a folder, a file or a glob of files; a node id by its file)
present=()
shopt -s nullglob
for p in "${patterns[@]}"; do
    if [[ "$p" == *::* ]]; then [ -f "${p%%::*}" ] && present+=("$p")
    else for t in $p; do [ -e "$t" ] && present+=("$t"); done
    fi
done
shopt -u nullglob
[ ${#present[@]} -gt 0 ] || { echo "none of the tests exist in the copy: ${patterns[*]}" >&2; exit 2; }
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
# minimal example), no example database; appended to the project's conftest if it has one
mkdir -p tests
cat >>tests/conftest.py <<'PY'

from hypothesis import Phase, settings as _mutation_settings
_mutation_settings.register_profile("mutation", derandomize=True, database=None,
                                    phases=[Phase.explicit, Phase.generate])
_mutation_settings.load_profile("mutation")


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
echo "mutating $module of $commit in $work against: ${present[*]}" >&2
export MPLBACKEND=Agg OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
# MUTATION_NAMES="name1 name2 ..." (or globs such as 'bem.layer.x_system_matrix*') runs only those mutants
# shellcheck disable=SC2086
nice -n "${MUTATION_NICE:-15}" "$py" -m mutmut run --max-children 1 ${MUTATION_NAMES:-} >mutmut.log 2>&1 || { tail -40 mutmut.log; exit 1; }
nice -n "${MUTATION_NICE:-15}" "$py" -m mutmut results --all true >results.txt 2>&1 || true
# the summary; a full run with the default tests also writes the module's row in docs/mutation-scores.md
record=""
if [ -z "${MUTATION_NAMES:-}" ] && [ "$default_selection" = 1 ]; then record="$here/docs/mutation-scores.md"; fi
"$py" - "$module" "$commit" "$record" <<'PY'
import collections, datetime, re, sys
module, commit, record = sys.argv[1:4]
counts = collections.Counter()
for line in open("results.txt"):
    m = re.match(r"\s*(\S+): (\w[\w ]*)$", line.rstrip())
    if m:
        counts[m.group(2)] += 1
killed = counts.get("killed", 0)
total = sum(v for k, v in counts.items() if k != "not checked")  # a partial run (MUTATION_NAMES)
survived = counts.get("survived", 0)
score = 100.0 * killed / max(total, 1)
print("mutants:", dict(counts), f"score {killed}/{total} = {score:.1f}%")
if record and total:
    start, end = "<!-- mutation-scores -->", "<!-- end -->"
    text = open(record).read()
    i, j = text.index(start) + len(start), text.index(end, text.index(start))
    head = ["| module | mutants | killed | survived | other | score | commit | date |",
            "|---|---|---|---|---|---|---|---|"]
    rows = {r.split("|")[1].strip(): r for r in text[i:j].strip().splitlines()[2:] if r.startswith("|")}
    rows[f"`{module}`"] = (f"| `{module}` | {total} | {killed} | {survived} | {total - killed - survived} "
                           f"| {score:.1f}% | {commit} | {datetime.date.today().isoformat()} |")
    table = "\n".join(head + [rows[k] for k in sorted(rows)])
    open(record, "w").write(text[:i] + "\n" + table + "\n" + text[j:])
    print(f"row of {module} written in {record}")
PY
grep -E ": (survived|no tests|timeout|suspicious)" results.txt || true
