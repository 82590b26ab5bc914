"""Kernel reuse: points grouped by what the compliance depends on, and the on-disk cache.

The influence kernels (:func:`bem.problem.compute_kernels`) depend only on the layer
(thickness, density), the material, the speed and the grid's spacing, period and
truncation; the load, the friction and the indenter do not enter (the paper's
conclusion). A kernel table holds the influence of every node offset
``K[dy + K_y - 1, dx + K_x - 1]``, so the table of a larger region contains the table of
a smaller one as its central block: one kernel set, formed for the widest region of a
group, serves every point of the group (an automatically sized region grows with the
load). The cache stores one ``.npz`` per group key, with the checksums and the code
version that let a damaged or stale set be refused (:class:`KernelCache`).
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from bem.grid import Grid
from bem.problem import Problem, compute_kernels
from bem.spectral import BLOCKS

from .integrity import array_digest, code_version, open_envelope, point_envelope
from .table import check_values

__all__ = ["kernel_key", "KernelGroup", "group_points", "fit_kernels", "form_kernels", "KernelCache", "PointCache"]

#: the blocks a frictionless solve needs; a frictional one needs all nine (:data:`bem.spectral.BLOCKS`)
NORMAL_BLOCKS = ("ww",)


def _file_digest(path: str) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def kernel_key(config: dict, problem: Problem) -> str:
    """A hash of what the compliance depends on: ``[layer]``, ``[material]`` (a master-curve
    table by its content), the speed and the grid's spacing, period and truncation."""
    g = problem.grid
    material = dict(config["material"])
    if "file" in material:
        material["file"] = _file_digest(material["file"])
    what = {
        "layer": [problem.layer.thickness, problem.layer.density],
        "material": material,
        "speed": problem.loading.speed,
        "grid": [g.spacing_x, g.spacing_y, g.period_x, g.period_y, g.truncation_x, g.truncation_y],
    }
    return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()[:16]


@dataclass(frozen=True)
class KernelGroup:
    """Points sharing one compliance: the problem to form it for (the group's widest
    region), the blocks they need, and the point indices."""

    key: str
    problem: Problem
    blocks: tuple
    members: tuple

    @property
    def nodes(self) -> tuple[int, int]:
        return self.problem.grid.nodes_x, self.problem.grid.nodes_y


def group_points(problems: dict, frictional: dict, keys: dict) -> dict:
    """Groups of points by kernel key.

    Parameters
    ----------
    problems : dict of int -> Problem
    frictional : dict of int -> bool
        Whether the point needs the nine blocks.
    keys : dict of int -> str
        :func:`kernel_key` of each point.
    """
    out = {}
    for key in dict.fromkeys(keys.values()):
        members = tuple(i for i in problems if keys[i] == key)
        first = problems[members[0]]
        if getattr(first, "plane_strain", False):  # a line contact: no shared table (its own kernels)
            out[key] = KernelGroup(key, first, (), members)
            continue
        nx = max(problems[i].grid.nodes_x for i in members)
        ny = max(problems[i].grid.nodes_y for i in members)
        grid = replace(first.grid, nodes_x=nx, nodes_y=ny)
        blocks = tuple(BLOCKS) if any(frictional[i] for i in members) else NORMAL_BLOCKS
        out[key] = KernelGroup(key, replace(first, grid=grid), blocks, members)
    return out


def fit_kernels(kernels: dict, grid: Grid) -> dict:
    """The central block of each table for ``grid``'s node counts (the tables of a region at
    least as wide, same spacing, period and truncation).

    Raises
    ------
    ValueError
        A table smaller than the grid needs.
    """
    ky, kx = grid.nodes_y, grid.nodes_x
    out = {}
    for name, table in kernels.items():
        cy, cx = (table.shape[0] + 1) // 2, (table.shape[1] + 1) // 2  # the table's node counts
        if cy < ky or cx < kx:
            raise ValueError(f"kernel table {name!r} of {cx} x {cy} nodes cannot serve a grid of {kx} x {ky}")
        out[name] = table[cy - ky: cy + ky - 1, cx - kx: cx + kx - 1]
    return out


def form_kernels(problem: Problem, blocks: tuple) -> tuple[dict, float]:
    """Form the kernel tables (a Dask task): :func:`bem.problem.compute_kernels`, with the
    power tables that make every point's energy figure a few FFTs; returns them and the
    seconds taken."""
    return compute_kernels(problem, blocks, power=True)


class KernelCache:
    """Kernel sets on disk, one ``<key>.npz`` per group under ``folder``.

    Each file holds the tables and ``__meta__``: the group key, the version of the code
    that formed them (:func:`sweeps.integrity.code_version`) and the SHA-256 of each
    table's dtype, shape and bytes. A cached set serves a request only when all of these
    match and it holds the blocks and at least the node counts asked for; otherwise
    :meth:`load` says why and the set is formed again. Writes go through a temporary file
    and a rename, so an interrupted run never leaves a truncated entry.
    """

    def __init__(self, folder: str | Path):
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)

    def path(self, key: str) -> Path:
        return self.folder / f"{key}.npz"

    def load(self, group: KernelGroup) -> tuple[dict | None, str]:
        """``(tables, "")`` for ``group``, or ``(None, why)``: ``why`` is empty when the set
        is absent, else the reason it cannot be used."""
        path = self.path(group.key)
        if not path.exists():
            return None, ""
        if not path.is_file():
            return None, f"{path} is not a file"
        try:
            with np.load(path, allow_pickle=False) as data:
                if "__meta__" not in data.files:
                    return None, f"{path} carries no checksums (written by another version of the code)"
                meta = json.loads(str(data["__meta__"]))
                if meta.get("key") != group.key:
                    return None, f"{path} holds the set of group {meta.get('key')!r}"
                if meta.get("code") != code_version():
                    return None, f"{path} was formed by another version of the code ({meta.get('code')})"
                sums = meta.get("sha256")
                if not isinstance(sums, dict):
                    return None, f"{path} carries no checksums of its tables"
                missing = [b for b in group.blocks if b not in sums or b not in data.files]
                if missing:
                    return None, f"{path} lacks the block(s) {', '.join(missing)}"
                tables = {name: data[name] for name in sums if name in data.files}  # power tables too
        except Exception as exc:  # a damaged file: zip, npy or JSON errors of every kind
            return None, f"{path} cannot be read ({type(exc).__name__}: {exc})"
        for b, table in tables.items():
            if array_digest(table) != sums[b]:
                return None, f"{path}: table {b!r} does not match its checksum (edited or damaged)"
        try:
            return fit_kernels(tables, group.problem.grid), ""
        except ValueError as exc:  # a narrower region than this group needs: formed again, wider
            return None, f"{path}: {exc}"

    def save(self, key: str, kernels: dict) -> None:
        """Store a set (through a temporary file and a rename).

        Raises
        ------
        OSError
            The entry cannot be written (e.g. a folder in its place).
        """
        meta = {"key": key, "code": code_version(), "sha256": {b: array_digest(t) for b, t in kernels.items()}}
        fd, tmp = tempfile.mkstemp(dir=self.folder, suffix=".npz.tmp")
        os.close(fd)
        try:
            with open(tmp, "wb") as fh:
                np.savez(fh, __meta__=np.array(json.dumps(meta)), **kernels)
            os.replace(tmp, self.path(key))
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)

    def __len__(self) -> int:
        return len(list(self.folder.glob("*.npz")))


class PointCache:
    """Finished points on disk, one ``<point_id>.json`` under ``folder``: a point of another
    sweep with the same checked case is not solved again (figures 8 and 9, tables 2 and 3
    share points). Each entry holds the row, the code version and the row's checksum
    (:func:`sweeps.integrity.point_envelope`); :meth:`load` refuses any other content and
    says why."""

    def __init__(self, folder: str | Path):
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)

    def path(self, point_id: str) -> Path:
        return self.folder / f"{point_id}.json"

    def load(self, point_id: str) -> tuple[dict | None, str]:
        """``(row, "")``, or ``(None, why)``: ``why`` is empty when the point is absent."""
        path = self.path(point_id)
        if not path.exists():
            return None, ""
        try:
            data = json.loads(path.read_bytes())
        except (OSError, ValueError) as exc:
            return None, f"{path} cannot be read ({type(exc).__name__}: {exc})"
        row, why = open_envelope(data, point_id)
        why = why or check_values(row)  # its values as a table row must hold them
        return (None if why else row), (f"{path} {why}" if why else "")

    def save(self, point_id: str, row: dict) -> None:
        """Store a finished point (through a temporary file and a rename).

        Raises
        ------
        OSError
            The entry cannot be written (e.g. a folder in its place).
        """
        fd, tmp = tempfile.mkstemp(dir=self.folder, suffix=".json.tmp")
        try:
            with os.fdopen(fd, "w") as fh:
                json.dump(point_envelope(point_id, row), fh)
            os.replace(tmp, self.path(point_id))
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)
