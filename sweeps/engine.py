"""Running a sweep on ``dask.distributed``.

By default a local cluster sized to the machine (one single-threaded worker process per
core); with ``scheduler`` the same sweep runs unchanged on an existing Dask cluster. Per
kernel group (:mod:`sweeps.kernels`) one task forms the kernel set, unless the on-disk
cache holds it (then it is scattered to the cluster); one task per point solves it with
that set (:func:`sweeps.point.solve_point`), so the points of a group run in parallel on
every worker while the compliance is formed once. The client saves each new kernel set
to the cache, appends each row to the table as it arrives and draws the progress bar. A
rerun reads the table back and computes only the points it lacks or that failed (a
changed point has a new ``point_id`` and is computed again). Nothing an earlier run or
the cache left is used unchecked (:mod:`sweeps.resume`, :mod:`sweeps.integrity`): a
stale or damaged entry is computed again with a line saying so, a damaged table without a
cache to rebuild it from and another sweep's folder are refused.
"""

from __future__ import annotations

import json
import sys
import time
from dataclasses import asdict, dataclass, field
from operator import getitem
from pathlib import Path

from bem.case import friction_from_config, problem_from_config

from .cluster import connect
from .grid_error import write_grid_error
from .kernels import KernelCache, PointCache, group_points, form_kernels, kernel_key
from .point import solve_point
from .progress import Progress, duration
from .resume import SUMMARY, TABLE, claim, prepare
from .spec import Sweep, SweepError, expand
from .table import ResultTable, columns

__all__ = ["RunReport", "run_sweep", "connect"]


@dataclass
class RunReport:
    """What a run did (``summary.json``); times in seconds.

    ``kernel_seconds`` sums the kernel tasks' own time, ``solve_seconds`` and
    ``energy_seconds`` the points' solves and energy figures, ``point_seconds`` the points'
    wall time on the workers; ``overhead_seconds = wall * workers - kernel - point``
    (scheduling, transfers, idle workers).
    """

    name: str
    points: int
    computed: int = 0
    resumed: int = 0
    failed: int = 0
    groups: int = 0
    kernels_formed: int = 0
    kernels_from_cache: int = 0
    workers: int = 0
    scheduler: str = ""
    wall_seconds: float = 0.0
    kernel_seconds: float = 0.0
    point_seconds: float = 0.0
    solve_seconds: float = 0.0
    energy_seconds: float = 0.0
    overhead_seconds: float = 0.0
    table: str = ""
    grid_error: str = ""
    errors: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    rows: list = field(default_factory=list, repr=False)


def _caches(cache) -> tuple:
    if cache is None:
        return None, None
    try:
        return KernelCache(Path(cache) / "kernels"), PointCache(Path(cache) / "points")
    except OSError as exc:
        raise SweepError(f"--cache {cache}: cannot be used as the cache folder ({type(exc).__name__}: {exc})") from None


def run_sweep(sweep: Sweep, out: str | Path, *, scheduler: str | None = None, workers: int | None = None,
              cache: str | Path | None = None, processes: bool = True, keep_failed: bool = False,
              overwrite: bool = False, timeout: float = 10.0, stream=sys.stderr, client=None) -> RunReport:
    """Run ``sweep``, writing ``results.csv``, ``summary.json`` and ``sweep.json`` in ``out``.

    Parameters
    ----------
    sweep : Sweep
        From :func:`sweeps.spec.read_sweep`.
    out : path
        Output folder; a table already there from the same sweep is checked and resumed
        (:mod:`sweeps.resume`).
    scheduler : str, optional
        Address of a running Dask scheduler (or its scheduler file), waited for
        ``timeout`` seconds (:func:`sweeps.cluster.connect`); default a local cluster of
        ``workers`` processes (threads with ``processes=False``).
    cache : path, optional
        Cache folder (``None``: no cache): ``kernels/`` holds kernel sets by group key,
        ``points/`` finished points by ``point_id`` (any sweep's), each with its checksum
        and the code version that made it.
    keep_failed : bool
        Keep the points an earlier run recorded as failed (by default they are computed
        again, with the finished ones kept).
    overwrite : bool
        Replace what ``out`` holds (another sweep's table, refused otherwise, or this
        sweep's earlier run, resumed otherwise) and start afresh there.
    stream : file or None
        Progress and messages (stderr); with ``None`` no progress, but the lines that say
        a cached or tabulated result is computed again still go to stderr.
    client : distributed.Client, optional
        Use this client (not closed here) instead of connecting.

    Raises
    ------
    SweepError
        A point that breaks the case schema, a scheduler that does not answer, another
        sweep's folder, a damaged table with no cache to rebuild it from, a cache folder
        that cannot be used: before anything runs.
    """
    from distributed import as_completed

    points = expand(sweep)
    out = Path(out)
    header = columns([a.key for a in sweep.axes])
    store, done = _caches(cache)
    prior, notes, remove = prepare(sweep, points, out, header, done, keep_failed, overwrite)
    say_to = stream if stream is not None else sys.stderr

    def say(text: str) -> None:
        notes.append(text)
        say_to.write(("\r\033[K" if getattr(say_to, "isatty", lambda: False)() else "") + text + "\n")
        say_to.flush()

    for text in notes:
        say_to.write(text + "\n")
    todo = [p for p in points if p.index not in prior]
    report = RunReport(sweep.name, len(points), resumed=len(prior), table=str(out / TABLE), notes=notes)
    own_client = client is None
    t_start = time.perf_counter()
    if todo and client is None:
        client = connect(scheduler, workers, processes, timeout)
    try:
        claim(sweep, out, remove)
        if client is not None:
            report.workers = len(client.scheduler_info().get("workers", {}))
            report.scheduler = client.scheduler.address if scheduler else "local"
        table = ResultTable(out / TABLE, header, list(prior.values()))
        bar = Progress(sweep.name, len(points), len(prior), stream)
        if prior:
            bar.say(f"sweep {sweep.name}: {len(prior)} of {len(points)} points done by an earlier run, "
                    f"{len(todo)} to compute")
        axis_values = {p.index: p.values for p in points}
        problems, frictional, keys = {}, {}, {}
        for p in todo:
            try:
                problems[p.index], _ = problem_from_config(p.config)
                frictional[p.index] = friction_from_config(p.config) is not None
                # a line contact (plane strain) forms its own one-dimensional kernels
                plane = getattr(problems[p.index], "plane_strain", False)
                keys[p.index] = f"plane-{p.index}" if plane else kernel_key(p.config, problems[p.index])
            except ValueError as exc:  # e.g. a speed at or above the shear-wave speed
                row = {"index": p.index, "point_id": p.point_id, **p.values, "status": "failed",
                       "error": f"{type(exc).__name__}: {exc}", "seconds": 0.0}
                table.add(row)
                report.failed += 1
                report.computed += 1
                bar.update(failed=True)
        groups = group_points(problems, frictional, keys)
        report.groups = len(groups)
        by_index = {p.index: p for p in todo}
        futures, kernel_tasks = [], {}
        for key, group in groups.items():
            cached, why = store.load(group) if store is not None and not key.startswith("plane-") else (None, "")
            if why:
                say(f"sweep {sweep.name}: kernel set {key}: {why}; formed again")
            if key.startswith("plane-"):
                kfut = None
                report.groups -= 1
            elif cached is not None:
                [kfut] = client.scatter([cached], hash=False)
                report.kernels_from_cache += 1
            else:
                tfut = client.submit(form_kernels, group.problem, group.blocks, key=f"kernels-{key}-{time.time_ns()}",
                                     priority=10, pure=False)
                kernel_tasks[tfut.key] = key
                futures.append(tfut)
                kfut = client.submit(getitem, tfut, 0, priority=10, pure=False)
            for i in group.members:
                p = by_index[i]
                futures.append(client.submit(solve_point, i, p.config, kfut, key=f"point-{i}-{p.point_id}-{time.time_ns()}",
                                             pure=False))
        try:
            for fut in (as_completed(futures) if futures else ()):
                if fut.key in kernel_tasks:
                    key = kernel_tasks[fut.key]
                    try:
                        kernels, seconds = fut.result()
                    except Exception as exc:  # the group's points fail with the same error
                        report.errors.append(f"kernels {key}: {type(exc).__name__}: {exc}")
                        continue
                    report.kernels_formed += 1
                    report.kernel_seconds += seconds
                    if store is not None:
                        try:
                            store.save(key, kernels)
                        except OSError as exc:
                            say(f"sweep {sweep.name}: kernel set {key} not cached ({type(exc).__name__}: {exc})")
                    continue
                try:
                    row = fut.result()
                except Exception as exc:  # the kernel task failed
                    i = int(str(fut.key).split("-")[1])
                    row = {"index": i, "status": "failed", "error": f"{type(exc).__name__}: {exc}", "seconds": 0.0}
                i = row["index"]
                row.update(point_id=by_index[i].point_id, kernel_key=keys.get(i, ""), **axis_values[i])
                table.add(row)
                if done and row["status"] == "ok":
                    try:
                        done.save(row["point_id"], {k: v for k, v in row.items() if k not in axis_values[i]})
                    except OSError as exc:
                        say(f"sweep {sweep.name}: point {i} not cached ({type(exc).__name__}: {exc})")
                report.computed += 1
                report.failed += row["status"] != "ok"
                report.point_seconds += row.get("seconds") or 0.0
                report.solve_seconds += row.get("solve_s") or 0.0
                report.energy_seconds += row.get("energy_s") or 0.0
                bar.update(failed=row["status"] != "ok")
        except KeyboardInterrupt:
            client.cancel(futures)
            bar.say(f"sweep {sweep.name}: interrupted; {table.path} keeps the {len(table.rows)} finished points "
                    "(run again to compute the rest)")
            raise
        finally:
            rows = table.finish()
            if client is not None:  # workers may join a running cluster after the start
                report.workers = max(report.workers, len(client.scheduler_info().get("workers", {})))
    finally:
        if own_client and client is not None:
            cluster = getattr(client, "cluster", None)
            client.close()
            if cluster is not None:
                cluster.close()
    report.failed += sum(r["status"] == "failed" for r in prior.values())
    report.wall_seconds = time.perf_counter() - t_start
    report.overhead_seconds = max(0.0, report.wall_seconds * report.workers - report.kernel_seconds
                                  - report.point_seconds)
    report.rows = rows
    written, why = write_grid_error(sweep, rows, out)
    report.grid_error = str(written or "")
    if why:  # a spacing axis that does not refine by 2
        notes.append(f"sweep {sweep.name}: no grid-error.csv: {why}")
        if stream is not None:
            stream.write(notes[-1] + "\n")
    (out / SUMMARY).write_text(json.dumps({k: v for k, v in asdict(report).items() if k != "rows"}, indent=2))
    if stream is not None:
        stream.write(f"sweep {sweep.name}: {report.computed} computed, {report.resumed} resumed, {report.failed} failed; "
                     f"{report.kernels_formed} kernel set(s) formed, {report.kernels_from_cache} from the cache; "
                     f"{duration(report.wall_seconds)} on {report.workers} worker(s); table {report.table}"
                     + (f"; grid error {report.grid_error}" if report.grid_error else "") + "\n")
    return report
