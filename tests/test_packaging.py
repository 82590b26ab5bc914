"""Packaging and dependencies: the license, the optional pyamg, gmsh's system libraries.

A missing dependency ends in one line that says what to install, never in a raw
traceback from deep inside gmsh or pyamg; ``bem`` and ``verification`` never need gmsh.
"""

from __future__ import annotations

import builtins
import json
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from fem_reference import FemReferenceError, InputError
from fem_reference._deps import APT_INSTALL, DNF_INSTALL, import_gmsh, import_pyamg, missing_library
from fem_reference.errors import MissingDependencyError

ROOT = Path(__file__).resolve().parents[1]

PYAMG_MISSING = ('fem.solver = "minres" needs pyamg, which is not installed: install it with '
                 "pip install 'viscolayer[minres]' (or pip install pyamg), "
                 'or use fem.solver = "direct"')
LIBGLU_ERROR = "libGLU.so.1: cannot open shared object file: No such file or directory"


def _pyproject() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


# --- license ---------------------------------------------------------------------------

def test_license_file_is_the_mit_license_pyproject_declares():
    assert _pyproject()["project"]["license"] == {"text": "MIT"}
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License\n")
    assert "Copyright (c) 2026 The viscolayer developers" in text
    assert "Permission is hereby granted, free of charge" in text
    assert 'THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND' in text


# --- pyamg (fem.solver = "minres") -------------------------------------------------------

def test_minres_extra_declares_pyamg():
    # the error message tells users to install viscolayer[minres]: it must exist
    extras = _pyproject()["project"]["optional-dependencies"]
    assert any(req.replace(" ", "").startswith("pyamg") for req in extras["minres"])


def test_missing_pyamg_is_a_clear_input_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "pyamg", None)  # `import pyamg` raises ImportError
    with pytest.raises(MissingDependencyError) as info:
        import_pyamg()
    assert str(info.value) == PYAMG_MISSING
    assert isinstance(info.value, InputError) and isinstance(info.value, FemReferenceError)
    assert isinstance(info.value.__cause__, ImportError)


def test_minres_solver_without_pyamg_fails_before_any_work(monkeypatch):
    from fem_reference.linsolve import MinresSolver

    monkeypatch.setitem(sys.modules, "pyamg", None)
    S = sp.csr_matrix(np.array([[2.0, -1.0], [-1.0, 0.0]]))
    with pytest.raises(MissingDependencyError, match=r"needs pyamg, which is not installed"):
        MinresSolver(S, 1, sp.eye(1), 1e6, np.ones(2))


def test_broken_pyamg_says_it_failed_to_import(monkeypatch):
    real_import = builtins.__import__

    def broken(name, *args, **kwargs):
        if name == "pyamg":
            raise ImportError("cannot import name 'x' from 'scipy.sparse'", name="scipy.sparse")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", broken)
    with pytest.raises(MissingDependencyError) as info:
        import_pyamg()
    assert "needs pyamg, which failed to import (cannot import name 'x'" in str(info.value)
    assert str(info.value).endswith('or use fem.solver = "direct"')


def test_cli_exits_2_with_the_message_when_pyamg_is_missing(monkeypatch, capsys):
    from fem_reference.cli import main

    monkeypatch.setitem(sys.modules, "pyamg", None)
    code = main(["solve", str(ROOT / "examples" / "paper-section10-thick.toml"), "--quiet",
                 "--set", 'fem.solver="minres"', "--set", "fem.element_size=2e-4"])
    assert code == 2
    assert capsys.readouterr().err.strip() == f"fem-reference: error: {PYAMG_MISSING}"


# --- gmsh and its system libraries -------------------------------------------------------

def _fail_import_of_gmsh(monkeypatch, exc: BaseException) -> None:
    real_import = builtins.__import__

    def failing(name, *args, **kwargs):
        if name == "gmsh":
            raise exc
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", failing)


@pytest.mark.parametrize("text, lib", [
    (LIBGLU_ERROR, "libGLU.so.1"),
    ("libXcursor.so.1: cannot open shared object file: No such file or directory", "libXcursor.so.1"),
    ("/venv/lib/libgmsh.so.4.15: cannot open shared object file: No such file or directory",
     "libgmsh.so.4.15"),
    ("libstdc++.so.6: version `GLIBCXX_3.4.30' not found", None),
])
def test_missing_library_is_read_from_the_loader_message(text, lib):
    assert missing_library(text) == lib


def test_missing_system_library_names_it_and_the_packages(monkeypatch):
    original = OSError(LIBGLU_ERROR)
    _fail_import_of_gmsh(monkeypatch, original)
    with pytest.raises(ImportError) as info:
        import_gmsh()
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith("fem_reference cannot load gmsh: the system library libGLU.so.1 "
                              "is missing (Debian/Ubuntu package libglu1-mesa).")
    assert ("apt-get install libglu1-mesa libgl1 libxrender1 libxcursor1 libxft2 libxinerama1 "
            "libfontconfig1 libx11-6 libgomp1") in message
    assert ("dnf install mesa-libGLU libXrender libXcursor libXft libXinerama fontconfig "
            "libX11 libgomp") in message
    assert APT_INSTALL in message and DNF_INSTALL in message
    assert info.value.__cause__ is original
    assert info.value.name == "gmsh"


def test_gmsh_not_installed_says_pip_install(monkeypatch):
    _fail_import_of_gmsh(monkeypatch, ModuleNotFoundError("No module named 'gmsh'", name="gmsh"))
    with pytest.raises(ImportError, match=r"needs the gmsh Python package.*pip install gmsh"):
        import_gmsh()


def test_other_load_failures_keep_the_original_text(monkeypatch):
    _fail_import_of_gmsh(monkeypatch, OSError("libstdc++.so.6: version `GLIBCXX_3.4.30' not found"))
    with pytest.raises(ImportError) as info:
        import_gmsh()
    assert "loading it failed (libstdc++.so.6: version `GLIBCXX_3.4.30' not found)" in str(info.value)
    assert APT_INSTALL in str(info.value)


_BLOCK_GMSH = textwrap.dedent(f"""
    import importlib, importlib.abc, json, pkgutil, sys

    attempts = []

    class NoGmsh(importlib.abc.MetaPathFinder):
        # as on a machine without libGLU: gmsh.py's ctypes.CDLL raises OSError
        def find_spec(self, name, path=None, target=None):
            if name == "gmsh":
                attempts.append(name)
                raise OSError({LIBGLU_ERROR!r})

    sys.meta_path.insert(0, NoGmsh())
    loaded = []
    for package in ("bem", "verification"):
        module = importlib.import_module(package)
        for info in pkgutil.walk_packages(module.__path__, package + "."):
            if not info.name.endswith("__main__"):
                importlib.import_module(info.name)
                loaded.append(info.name)
    state = dict(loaded=loaded, attempts=list(attempts),
                 fem_reference_imported="fem_reference" in sys.modules)
    import fem_reference  # its names load on first use
    try:
        fem_reference.solve
    except ImportError as exc:
        state.update(error=str(exc), cause=repr(exc.__cause__))
    print(json.dumps(state))
""")


def _source_modules(*packages: str) -> set[str]:
    """Every module and subpackage under ``packages`` (dotted names), read from the source
    tree without importing anything: the files of folders that are packages all the way
    up (an ``__init__.py`` in each, as setuptools ships them); the packages themselves and
    ``__main__`` left out."""
    names = set()
    for package in packages:
        for path in (ROOT / package).rglob("*.py"):
            folders = path.relative_to(ROOT).parents[:-1]  # the file's folders, up to the package
            if not all((ROOT / folder / "__init__.py").is_file() for folder in folders):
                continue
            parts = path.relative_to(ROOT).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            if parts[-1] != "__main__" and len(parts) > 1:
                names.add(".".join(parts))
    return names


def test_bem_and_verification_work_without_gmsh_and_fem_reference_says_why():
    done = subprocess.run([sys.executable, "-c", _BLOCK_GMSH], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr
    state = json.loads(done.stdout.strip().splitlines()[-1])
    expected = _source_modules("bem", "verification")
    assert {"bem.cli", "bem.plots", "bem.frictional", "verification.cli",
            "verification.runner", "verification.report"} <= expected
    assert set(state["loaded"]) == expected  # every module of both packages was imported
    assert state["attempts"] == []  # bem and verification never even try to import gmsh
    assert not state["fem_reference_imported"]
    assert "the system library libGLU.so.1 is missing (Debian/Ubuntu package libglu1-mesa)" \
        in state["error"]
    assert APT_INSTALL in state["error"]
    assert state["cause"].startswith("OSError('libGLU.so.1: cannot open shared object file")
