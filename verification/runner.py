"""The verification runner: load every case and check it against the schema before
anything is solved, then run each through its kind.

A case file (``verification/cases/*.toml``) holds the physical problem (the schema of
``bem solve``), the levels of each method, the analytic reference and the gates: which
quantity of which method is compared against which reference, with its tolerance and the
reason for it (:mod:`verification.schema`, ``docs/verification.md``).
"""

from __future__ import annotations

import copy
import time
import tomllib
from pathlib import Path
from typing import Callable

from casefile.schema import BOTH, SCHEMA

from . import methods as method_registry
from .kinds import KINDS, Context
from .results import CaseResult, Gate
from .schema import GATE, HEADER, CaseError, check_problem, check_table, close

__all__ = ["CASES_DIR", "CaseError", "list_cases", "load_case", "load_cases", "run_case", "failed_result",
           "add_method"]

CASES_DIR = Path(__file__).resolve().parent / "cases"
#: the sections of [problem] every method needs (those the case-file schema requires of
#: both solvers): the physical problem is not posed without them
NEEDED = tuple(s for s in SCHEMA if set(BOTH) <= set(s.required_by))


def list_cases(directory: Path = CASES_DIR) -> list[Path]:
    """The case files (``*.toml``) of ``directory``; an error if there is none."""
    directory = Path(directory)
    if not directory.is_dir():
        raise CaseError(f"cases folder {str(directory)!r} does not exist")
    paths = sorted(directory.glob("*.toml"))
    if not paths:
        raise CaseError(f"cases folder {str(directory)!r} holds no case file (*.toml)")
    return paths


def _methods_of(case: dict, path: Path, known: dict) -> dict:
    """The methods a case may name: built in, installed, and its own ``[methods.NAME]``."""
    out = dict(known)
    declared = case.get("methods", {})
    if not isinstance(declared, dict):
        raise CaseError(f"{path} [methods] must be a table of [methods.NAME] tables")
    for name, section in declared.items():
        out[name] = method_registry.from_section(name, section, path.parent, known, f"{path} [methods.{name}]")
    return out


def load_case(path: Path, known: dict | None = None) -> dict:
    """Read one case file and check all of it (header, ``[problem]``, the kind's sections,
    every gate): a :class:`CaseError` naming the file, the section or gate and the field.

    ``known``: the methods a case may name (default: built in and installed)."""
    path = Path(path)
    known = {**method_registry.builtin(), **method_registry.installed()} if known is None else known
    try:
        with path.open("rb") as fh:
            case = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"{path}: not a valid TOML file: {exc}") from None
    except OSError as exc:
        raise CaseError(f"{path}: cannot read: {exc}") from None
    kind_name = case.get("kind")
    if not isinstance(kind_name, str) or kind_name not in KINDS:
        raise CaseError(f"{path} kind: unknown kind {kind_name!r}; known: {', '.join(KINDS)}{close(kind_name, KINDS)}")
    kind = KINDS[kind_name]
    header = dict(HEADER)
    if not getattr(kind, "NEEDS_PROBLEM", True):
        header.pop("problem")
    fields = {**header, **{s: None for s in kind.SECTIONS}}
    for key in case:
        if key not in fields:
            raise CaseError(f"{path}: unknown key or section {key!r}; known for a {kind_name} case: "
                            f"{', '.join(fields)}{close(key, fields)}")
    check_table({k: v for k, v in case.items() if k in header}, header, str(path))
    if case["name"] != path.stem:
        raise CaseError(f"{path} name: {case['name']!r} must be the file's name {path.stem!r} "
                        "(the command line and the results files find a case by it)")
    if "problem" in header:
        case["problem"] = check_problem(case["problem"], path)
        missing = [s for s in NEEDED if s.name not in case["problem"]]
        if missing:
            raise CaseError(f"{path} [problem]: " + "; ".join(f"needs a [problem.{s.name}] section ({s.doc})"
                                                               for s in missing))
    for i, gate in enumerate(case["gates"]):
        check_table(gate, GATE, f"{path} gates[{i}]")
    methods = _methods_of(case, path, known)
    kind.check(case, path, methods)
    case["_methods"] = methods
    return case


def add_method(case: dict, method) -> None:
    """Hold ``method`` to every gate of ``case`` that holds the BEM (``verify --method``)."""
    if not getattr(KINDS[case["kind"]], "ADDS_METHODS", False):
        return
    case["_methods"][method.name] = method
    for gate in case["gates"]:
        if "bem" in gate.get("methods", []) and method.name not in gate["methods"]:
            gate["methods"].append(method.name)


def load_cases(paths: list[Path], extra_methods: list[str] = ()) -> list[dict]:
    """Every case checked, and every ``--method`` option; all errors at once, joined."""
    known = {**method_registry.builtin(), **method_registry.installed()}
    errors, added = [], []
    for text in extra_methods:
        try:
            added.append(method_registry.parse_option(text, known))
        except CaseError as exc:
            errors.append(str(exc))
    cases = []
    for path in paths:
        try:
            case = load_case(path, known)
            for method in added:
                add_method(case, method)
            if added:  # again, with the added methods
                KINDS[case["kind"]].check(case, path, case["_methods"])
            cases.append(case)
        except CaseError as exc:
            errors.append(str(exc))
    if errors:
        raise CaseError("\n".join(errors))
    return cases


def failed_result(case: dict, reason: str, seconds: float = 0.0) -> CaseResult:
    """The result of a case that did not run: no runs, one failed ``run`` gate whose
    reason is ``reason``; ``seconds`` the wall time it took to fail (s)."""
    result = CaseResult(case["name"], case["title"], case.get("why", ""), case["kind"])
    result.extra["error"] = reason
    result.gates.append(Gate(case=case["name"], quantity="run", method="-", against="-", level="-",
                             value=float("nan"), reference=float("nan"), error=float("nan"), tolerance=0.0,
                             reason=f"the case did not run: {reason}"))
    result.seconds = seconds
    return result


def run_case(case: dict, progress: Callable[[str], None] = print, quick: bool = False,
             client=None) -> CaseResult:
    """Solve one checked case with every method and level it names; evaluate its gates.
    An exception inside a kind (``SystemExit`` included) becomes a failed case with the
    error as its reason; Ctrl-C and SIGTERM end the run.

    ``client``: a ``distributed.Client`` a kind that runs on Dask itself submits to
    (``verify --workers``/``--scheduler``); default its own local cluster."""
    kind = KINDS[case["kind"]]
    methods = case.get("_methods") or {**method_registry.builtin(), **method_registry.installed()}
    ctx = Context(progress=progress, quick=quick, methods=methods, client=client)
    t0 = time.perf_counter()
    try:
        return kind.run(copy.deepcopy({k: v for k, v in case.items() if k != "_methods"}), ctx)
    except MemoryError:
        raise
    except (Exception, SystemExit) as exc:
        return failed_result(case, f"{type(exc).__name__}: {exc}", time.perf_counter() - t0)
