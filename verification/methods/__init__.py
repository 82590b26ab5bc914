"""Methods: what the harness puts through its cases and gates.

A method is a callable ``solve(problem: dict, level: Level) -> Run``: it takes a case's
``[problem]`` (the checked dict of the case-file schema, SI units) and one refinement
level (:class:`verification.results.Level`), and returns a :class:`verification.results.Run`.
Built in: ``bem`` and ``fem``. Others come

- from an installed package, registered under the entry-point group ``viscolayer.methods``
  (``[project.entry-points."viscolayer.methods"] mymethod = "mypkg.contact:solve"``);
- from the command line, ``verify --method NAME=package.module:function`` (or
  ``NAME=path/file.py:function``);
- from results computed elsewhere: ``verify --method NAME=FOLDER`` (one ``<case>.json``
  per case, :mod:`.external`) or a case's ``[methods.NAME] results = "file.json"``;
- from a case file: ``[methods.NAME] entry = "package.module:function"``.

A case lists its levels for a method in the method's section (``[bem] spacings``,
``[fem] element_sizes``, ``[methods.NAME] sizes``); a method without sizes is run once
(``level.size = None``), and an external one has the levels of its file.

A method that is not built in is called the way user input is read: it gets its own copy
of the problem and the level, a result that breaks :func:`verification.results.check_run`
(not finite, a wrong type or shape, a load that is not > 0, ...) and anything it raises,
including ``SystemExit`` and errors while its module is imported (a syntax error), is a
:class:`verification.results.MethodError` that fails that method's gates with the reason;
the run goes on. A spec that names nothing (no such file, module or function) is an input
error (:class:`verification.schema.CaseError`) before anything is solved.
"""

from __future__ import annotations

import copy
import importlib
import importlib.metadata
import re
import sys
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from ..results import Level, MethodError, check_run
from ..schema import CaseError, Field, check_table, close
from . import bem as _bem
from . import fem as _fem
from .external import ExternalResults

__all__ = ["ENTRY_POINT_GROUP", "Method", "builtin", "installed", "parse_option", "from_section",
           "load_callable", "plugin", "RESERVED"]

ENTRY_POINT_GROUP = "viscolayer.methods"
RESERVED = ("analytic", "published", "elastic", "dissipation")
_NAME = re.compile(r"[a-z][a-z0-9_-]*\Z")


@dataclass(frozen=True)
class Method:
    """A named method, where its levels are read from, and where it came from."""

    name: str
    solve: Callable
    section: str = ""  # the case's section with its levels and settings
    sizes_key: str = "sizes"
    origin: str = "built-in"
    check: Callable | None = field(default=None, compare=False)  # check(settings, problem, where)

    def settings(self, case: dict) -> dict:
        """The method's section of ``case`` (``{}`` when it has none)."""
        node = case
        for part in self.section.split("."):
            node = node.get(part, {}) if isinstance(node, dict) else {}
        return node if isinstance(node, dict) else {}

    def levels(self, case: dict) -> list[Level]:
        """The levels ``case`` asks of this method, coarse to fine."""
        settings = self.settings(case)
        inner = getattr(self.solve, "func", self.solve)
        if isinstance(inner, ExternalResults):
            sizes = inner.sizes(case["name"])
        else:
            sizes = settings.get(self.sizes_key, [None])
        rest = {k: v for k, v in settings.items() if k not in (self.sizes_key, "entry", "results")}
        return [Level(index=i, size=s, settings=rest, case=case["name"], sizes=tuple(sizes))
                for i, s in enumerate(sizes)]


def builtin() -> dict[str, Method]:
    return {
        "bem": Method("bem", _bem.solve, "bem", "spacings", check=_bem.check),
        "fem": Method("fem", _fem.solve, "fem", "element_sizes", check=_fem.check),
    }


def check_name(name: str, where: str) -> str:
    if not isinstance(name, str) or not _NAME.match(name):
        raise CaseError(f"{where}: a method name is lower-case letters, digits, '-' and '_', "
                        f"starting with a letter; got {name!r}")
    if name in RESERVED:
        raise CaseError(f"{where}: {name!r} names a reference, not a method")
    return name


def load_callable(spec: str, where: str) -> Callable:
    """``package.module:function`` (or ``path/file.py:function``) imported.

    Raises
    ------
    CaseError
        The spec names nothing: malformed, no such file or module, no such function, or
        not callable (an input error, before anything is solved).
    MethodError
        The module's own code fails while it is imported: it raises (a syntax error, a
        missing dependency) or exits.
    """
    module_name, sep, attr = str(spec).rpartition(":")
    if not sep or not module_name or not attr:
        raise CaseError(f"{where}: a method entry is 'package.module:function' or 'path/file.py:function', "
                        f"got {spec!r}")
    if module_name.endswith(".py") and not Path(module_name).is_file():
        raise CaseError(f"{where}: no file {module_name!r}")
    try:
        if module_name.endswith(".py"):
            module = _import_file(Path(module_name))
        else:
            module = importlib.import_module(module_name)
    except ModuleNotFoundError as exc:
        if exc.name and (module_name == exc.name or module_name.startswith(exc.name + ".")):
            raise CaseError(f"{where}: cannot import {module_name!r}: {exc}") from None
        raise MethodError(f"{module_name!r} could not be imported: {type(exc).__name__}: {exc}") from None
    except SystemExit as exc:
        raise MethodError(f"{module_name!r} exited while imported (SystemExit({exc.code!r}))") from None
    except Exception as exc:  # its own code: a syntax error, an exception at import
        raise MethodError(f"{module_name!r} could not be imported: {type(exc).__name__}: {exc}") from None
    obj = module
    for part in attr.split("."):
        if not hasattr(obj, part):
            known = [n for n in dir(obj) if not n.startswith("_")]
            raise CaseError(f"{where}: {module_name!r} has no {part!r}{close(part, known)}")
        obj = getattr(obj, part)
    if not callable(obj):
        raise CaseError(f"{where}: {spec!r} is not callable")
    return obj


def _import_file(path: Path):
    """A module from a file (``verify --method NAME=my_method.py:solve``), named after the
    file's full path so that two files of one name stay two modules."""
    import importlib.util

    stem = re.sub(r"\W", "_", path.stem)
    name = f"verify_method_{stem}_{zlib.crc32(str(path.resolve()).encode()):08x}"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        sys.modules.pop(name, None)
        raise
    return module


class _Guarded:
    """A method that is not built in, called like user input is read: a copy of the
    problem and level, its result through :func:`check_run`, and whatever it raises or
    exits with as a :class:`MethodError` naming the method and where it came from.
    Ctrl-C and SIGTERM (not ``Exception``s) still end the run."""

    def __init__(self, func: Callable, name: str, origin: str):
        self.func, self.name, self.origin = func, name, origin

    def __call__(self, problem: dict, level: Level):
        where = f"method {self.name!r} ({self.origin})"
        try:
            run = self.func(copy.deepcopy(problem), copy.deepcopy(level))
        except SystemExit as exc:
            raise MethodError(f"{where} exited (SystemExit({exc.code!r})) instead of returning a Run") from None
        except MethodError as exc:
            raise MethodError(f"{where}: {exc}") from None
        except Exception as exc:
            raise MethodError(f"{where} raised {type(exc).__name__}: {exc}") from exc
        try:
            return check_run(run)
        except MethodError as exc:
            raise MethodError(f"{where} returned a result the gates cannot use: {exc}") from None


class _Broken:
    """A plugin whose module failed at import: every call fails with that error."""

    def __init__(self, error: MethodError):
        self.error = str(error)

    def __call__(self, problem, level):
        raise MethodError(self.error)


def plugin(name: str, func: Callable, origin: str) -> Method:
    """A method that is not built in: ``func`` guarded (:class:`_Guarded`), its levels in
    the case's ``[methods.NAME]``."""
    return Method(name, _Guarded(func, name, origin), f"methods.{name}", origin=origin)


def _loaded(spec: str, where: str) -> Callable:
    """:func:`load_callable`, with a module that fails at import kept as a method that fails."""
    try:
        return load_callable(spec, where)
    except MethodError as exc:
        return _Broken(exc)


def installed() -> dict[str, Method]:
    """Methods registered by installed packages under :data:`ENTRY_POINT_GROUP` (loaded
    when used, so a broken plugin only fails the runs that ask for it)."""
    out = {}
    for ep in importlib.metadata.entry_points(group=ENTRY_POINT_GROUP):
        if ep.name in builtin() or not _NAME.match(ep.name) or ep.name in RESERVED:
            continue
        out[ep.name] = plugin(ep.name, _Deferred(ep.value, f"entry point {ep.name}"), f"entry point {ep.value}")
    return out


class _Deferred:
    """A plugin imported at its first call."""

    def __init__(self, spec: str, where: str):
        self.spec, self.where, self._func = spec, where, None

    def __call__(self, problem, level):
        if self._func is None:
            self._func = load_callable(self.spec, self.where)
        return self._func(problem, level)


def parse_option(text: str, known: dict[str, Method]) -> Method:
    """``--method NAME``, ``NAME=package.module:function`` or ``NAME=FOLDER_OR_FILE``."""
    where = f"--method {text}"
    name, sep, target = text.partition("=")
    check_name(name, where)
    if not sep:
        if name not in known:
            raise CaseError(f"{where}: no installed method {name!r}; known: {', '.join(sorted(known))}"
                            f"{close(name, known)}. Give NAME=package.module:function or NAME=FOLDER")
        return known[name]
    if name in builtin():
        raise CaseError(f"{where}: {name!r} is built in; choose another name")
    path = Path(target)
    if ":" not in target or path.suffix == ".json" or path.is_dir():
        if not path.exists():
            raise CaseError(f"{where}: {target!r} is neither a results folder or file nor 'package.module:function'")
        return plugin(name, ExternalResults(name, path), f"results {path}")
    return plugin(name, _loaded(target, where), where)


SECTION = {
    "entry": Field("string", doc="package.module:function"),
    "results": Field("string", doc="a results JSON file (relative to the case file) or a folder of them"),
    "sizes": Field("numbers", positive=True, doc="refinement parameters (m), coarse to fine"),
}


def from_section(name: str, section: dict, folder: Path, known: dict[str, Method], where: str) -> Method:
    """A method declared by a case's ``[methods.NAME]``; its other keys are its settings."""
    check_name(name, where)
    check_table(section, SECTION, where, open_=True)
    if name in builtin():
        raise CaseError(f"{where}: {name!r} is built in; its levels go in [{name}]")
    if "entry" in section and "results" in section:
        raise CaseError(f"{where}: give 'entry' or 'results', not both")
    if "results" in section:
        if "sizes" in section:
            raise CaseError(f"{where}: the levels of a results file are its own; drop 'sizes'")
        path = (folder / section["results"]).resolve()
        if not path.exists():
            raise CaseError(f"{where}: results file {section['results']!r} not found (looked at {path})")
        return plugin(name, ExternalResults(name, path), f"results {path}")
    if "entry" in section:
        return plugin(name, _loaded(section["entry"], f"{where} entry"), f"case entry {section['entry']}")
    if name in known:
        return known[name]
    raise CaseError(f"{where}: {name!r} is not an installed method; give 'entry' or 'results'"
                    f"{close(name, known)}")
