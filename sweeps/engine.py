"""Running a sweep on ``dask.distributed``.

By default a local cluster sized to the machine (one single-threaded worker process per
core); with ``scheduler`` the same sweep runs unchanged on an existing Dask cluster. Per
kernel group (:mod:`sweeps.kernels`) one task forms the kernel set, unless the on-disk
cache holds it (then it is scattered to the cluster); one task per point solves it with
that set (:func:`sweeps.point.solve_point`), so the points of a group run in parallel on
every worker while the compliance is formed once. The client saves each new kernel set
to the cache, appends each row to the table as it arrives and draws the progress bar. A
rerun reads the table back and computes only the points it lacks or that failed (a
changed point has a new ``point_id`` and is computed again).
"""

from __future__ import annotations

import json
import logging
import os
import sys
import time
from dataclasses import asdict, dataclass, field
from operator import getitem
from pathlib import Path

from bem.case import friction_from_config, problem_from_config

from .kernels import KernelCache, PointCache, group_points, form_kernels, kernel_key
from .point import solve_point
from .progress import Progress, duration
from .spec import Point, Sweep, SweepError, expand
from .table import ResultTable, columns, read_rows

__all__ = ["RunReport", "run_sweep", "connect"]

TABLE = "results.csv"
SUMMARY = "summary.json"


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
    errors: list = field(default_factory=list)
    rows: list = field(default_factory=list, repr=False)


def connect(scheduler: str | None = None, workers: int | None = None, processes: bool = True,
            timeout: float = 10.0):
    """A ``distributed.Client``: to ``scheduler`` (``tcp://host:port`` or a scheduler file
    ``*.json``), else to a new local cluster of ``workers`` (default: the machine's cores)
    single-threaded workers (processes, or threads with ``processes=False``).

    Raises
    ------
    SweepError
        The scheduler does not answer within ``timeout`` seconds.
    """
    from distributed import Client, LocalCluster

    if scheduler:
        try:
            if scheduler.endswith(".json"):
                return Client(scheduler_file=scheduler, timeout=f"{timeout}s")
            return Client(scheduler, timeout=f"{timeout}s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise SweepError(f"--scheduler {scheduler}: no Dask scheduler answers there within {timeout:g} s "
                             f"({type(exc).__name__}: {exc}); start one with `dask scheduler` and "
                             "`dask worker ADDRESS`, or leave out --scheduler to run on a local cluster") from None
    n = workers or os.cpu_count() or 1
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=processes, dashboard_address=":0",
                           silence_logs=logging.ERROR)
    return Client(cluster)


def _prior(out: Path, header: list[str], points: list[Point], keep_failed: bool) -> dict:
    """Rows of an earlier run of the same points, by index."""
    ids = {p.index: p.point_id for p in points}
    keep = {}
    for row in read_rows(out / TABLE, header):
        i = int(row["index"])
        if ids.get(i) == row["point_id"] and (row["status"] == "ok" or keep_failed):
            keep[i] = row
    return keep


def run_sweep(sweep: Sweep, out: str | Path, *, scheduler: str | None = None, workers: int | None = None,
              cache: str | Path | None = None, processes: bool = True, keep_failed: bool = False,
              timeout: float = 10.0,
              stream=sys.stderr, client=None) -> RunReport:
    """Run ``sweep``, writing ``results.csv`` and ``summary.json`` in ``out``.

    Parameters
    ----------
    sweep : Sweep
        From :func:`sweeps.spec.read_sweep`.
    out : path
        Output folder; a table already there from the same sweep is resumed.
    scheduler : str, optional
        Address of a running Dask scheduler (or its scheduler file), waited for
        ``timeout`` seconds; default a local cluster of ``workers`` processes (threads
        with ``processes=False``).
    cache : path, optional
        Cache folder (``None``: no cache): ``kernels/`` holds kernel sets by group key,
        ``points/`` finished points by ``point_id`` (any sweep's).
    keep_failed : bool
        Keep the points an earlier run recorded as failed (by default they are computed
        again, with the finished ones kept).
    stream : file or None
        Progress and messages (stderr).
    client : distributed.Client, optional
        Use this client (not closed here) instead of connecting.

    Raises
    ------
    SweepError
        A point that breaks the case schema, or a scheduler that does not answer: before
        anything runs.
    """
    from distributed import as_completed

    points = expand(sweep)
    out = Path(out)
    header = columns([a.key for a in sweep.axes])
    prior = _prior(out, header, points, keep_failed)
    store = KernelCache(Path(cache) / "kernels") if cache is not None else None
    done = PointCache(Path(cache) / "points") if cache is not None else None
    for p in points:
        row = done.load(p.point_id) if done and p.index not in prior else None
        if row is not None and row.get("status") == "ok":
            prior[p.index] = {**row, "index": p.index, "point_id": p.point_id, **p.values}
    todo = [p for p in points if p.index not in prior]
    report = RunReport(sweep.name, len(points), resumed=len(prior), table=str(out / TABLE))
    own_client = client is None
    t_start = time.perf_counter()
    if todo and client is None:
        client = connect(scheduler, workers, processes, timeout)
    try:
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
            cached = store.load(group) if store is not None and not key.startswith("plane-") else None
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
                        store.save(key, kernels)
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
                    done.save(row["point_id"], {k: v for k, v in row.items() if k not in axis_values[i]})
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
    (out / SUMMARY).write_text(json.dumps({k: v for k, v in asdict(report).items() if k != "rows"}, indent=2))
    if stream is not None:
        stream.write(f"sweep {sweep.name}: {report.computed} computed, {report.resumed} resumed, {report.failed} failed; "
                     f"{report.kernels_formed} kernel set(s) formed, {report.kernels_from_cache} from the cache; "
                     f"{duration(report.wall_seconds)} on {report.workers} worker(s); table {report.table}\n")
    return report
