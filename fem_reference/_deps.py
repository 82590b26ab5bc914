"""The dependencies of :mod:`fem_reference` that can fail to load, imported in one place.

gmsh is a Python wrapper around ``libgmsh.so``, which needs system libraries (OpenGL,
X11, fontconfig, OpenMP) that slim machines and containers lack. Without them ``import
gmsh`` ends in a raw ``OSError`` from ctypes; :func:`import_gmsh` turns that into one
line naming the missing library and the packages that provide it. pyamg is optional
(only ``fem.solver = "minres"`` needs it); :func:`import_pyamg` says how to get it.

The Debian/Ubuntu package of each library was found with ``dpkg -S`` on Debian 12 (the
libraries ``readelf -d`` lists as NEEDED by the gmsh 4.15 wheel's ``libgmsh.so``).
``libglu1-mesa`` does not pull in ``libgl1`` on Debian 12 (it depends on ``libopengl0``),
so ``libgl1`` is listed on its own.
"""

from __future__ import annotations

import re

from .errors import MissingDependencyError

__all__ = ["import_gmsh", "import_pyamg", "APT_INSTALL", "DNF_INSTALL"]

#: shared library -> Debian/Ubuntu package providing it (``dpkg -S``, Debian 12)
DEBIAN_PACKAGE = {
    "libGLU.so.1": "libglu1-mesa",
    "libGL.so.1": "libgl1",
    "libOpenGL.so.0": "libopengl0",
    "libGLX.so.0": "libglx0",
    "libGLdispatch.so.0": "libglvnd0",
    "libX11.so.6": "libx11-6",
    "libXrender.so.1": "libxrender1",
    "libXcursor.so.1": "libxcursor1",
    "libXfixes.so.3": "libxfixes3",
    "libXext.so.6": "libxext6",
    "libXft.so.2": "libxft2",
    "libXinerama.so.1": "libxinerama1",
    "libfontconfig.so.1": "libfontconfig1",
    "libfreetype.so.6": "libfreetype6",
    "libxcb.so.1": "libxcb1",
    "libXau.so.6": "libxau6",
    "libXdmcp.so.6": "libxdmcp6",
    "libexpat.so.1": "libexpat1",
    "libpng16.so.16": "libpng16-16",
    "libgomp.so.1": "libgomp1",
    "libz.so.1": "zlib1g",
}

#: everything gmsh's wheel needs beyond a minimal Debian/Ubuntu (dependencies follow)
APT_INSTALL = ("apt-get install libglu1-mesa libgl1 libxrender1 libxcursor1 libxft2 "
               "libxinerama1 libfontconfig1 libx11-6 libgomp1")
#: the Fedora/RHEL equivalents
DNF_INSTALL = ("dnf install mesa-libGLU libXrender libXcursor libXft libXinerama "
               "fontconfig libX11 libgomp")

_MISSING = re.compile(r"([^\s:/\\]+?\.so(?:\.[0-9A-Za-z_]+)*): cannot open shared object file")


def missing_library(text: str) -> str | None:
    """The shared library a loader error ``text`` names as missing (``dlopen``'s
    "libGLU.so.1: cannot open shared object file"), or None."""
    found = _MISSING.search(text)
    return found.group(1) if found else None


def _gmsh_error(exc: BaseException) -> str:
    """One line saying why gmsh did not load and what to install."""
    if isinstance(exc, ModuleNotFoundError) and exc.name == "gmsh":
        return ("fem_reference needs the gmsh Python package, which is not installed: "
                "pip install gmsh (the bem package does not need it)")
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    lib = missing_library(str(exc))
    if lib is not None and lib.startswith("libgmsh"):
        return (f"fem_reference cannot load gmsh: its own library {lib} is missing; "
                f"reinstall it: pip install --force-reinstall gmsh")
    if lib is not None:
        package = DEBIAN_PACKAGE.get(lib)
        what = f"the system library {lib} is missing" + (
            f" (Debian/Ubuntu package {package})" if package else "")
    else:
        what = f"loading it failed ({text})"
    return (f"fem_reference cannot load gmsh: {what}. gmsh needs these system libraries: "
            f"{APT_INSTALL} (Fedora/RHEL: {DNF_INSTALL}); see docs/install.md. "
            f"The bem package needs none of them.")


def import_gmsh():
    """Import and return the gmsh module.

    Raises
    ------
    ImportError
        If gmsh or a system library it needs cannot be loaded; the message names the
        missing library and the packages to install, and the original error is chained.
    """
    try:
        import gmsh
    except (ImportError, OSError) as exc:
        raise ImportError(_gmsh_error(exc), name="gmsh") from exc
    if not hasattr(gmsh.lib, "gmshInitialize"):
        # gmsh.py fell back to ctypes.CDLL(None) (the Python executable itself) because
        # it found no libgmsh next to it: it would fail at the first gmsh call instead.
        raise ImportError(f"fem_reference cannot load gmsh: gmsh.py ({gmsh.__file__}) "
                          f"found no libgmsh shared library; reinstall it: "
                          f"pip install --force-reinstall gmsh", name="gmsh")
    return gmsh


def import_pyamg():
    """Import and return pyamg, needed only by ``fem.solver = "minres"``.

    Raises
    ------
    MissingDependencyError
        If pyamg cannot be imported (an :class:`~fem_reference.errors.InputError`:
        the command line exits with status 2).
    """
    try:
        import pyamg
    except ImportError as exc:
        if getattr(exc, "name", None) == "pyamg":
            why = "which is not installed"
            how = "install it with pip install 'viscolayer[minres]' (or pip install pyamg)"
        else:
            why = f"which failed to import ({exc})"
            how = ("reinstall it with pip install --force-reinstall 'viscolayer[minres]' "
                   "(or pip install --force-reinstall pyamg)")
        raise MissingDependencyError(f'fem.solver = "minres" needs pyamg, {why}: {how}, '
                                     f'or use fem.solver = "direct"') from exc
    return pyamg
