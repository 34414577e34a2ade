"""The sweep itself: the tasks, the Dask client, running and resuming, the
chunks' totals, the Monte Carlo summary and the table."""

from __future__ import annotations

import contextlib
import itertools
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from pounding import defaults
from pounding.errors import ArgumentError, check_limit
from pounding.output import check_folder, check_target
from pounding.studies.sweeps.chart import write_chart
from pounding.studies.sweeps.points import Point, adjusted_points, case_data, sweep_points
from pounding.studies.sweeps.spec import normalized_vary
from pounding.studies.sweeps.store import FIELD, Store, write_json
from pounding.studies.sweeps.table import need_parquet, write_table
from pounding.studies.sweeps.table import table as summary_table
from pounding.studies.sweeps.work import chunk_sums, point_estimate, warm

if TYPE_CHECKING:  # the simulation loads when a study runs: the command line builds its parser from here
    from pounding.simulation.plan import MonteCarloPlan

TABLE_FORMATS = ("csv", "parquet")
SERIAL = "serial"
"""``scheduler=SERIAL`` runs every chunk in this process, without Dask."""


class SweepInterrupted(RuntimeError):
    """A sweep stopped before its end (``max_chunks`` reached); the chunks
    finished so far are saved and a rerun resumes from them.

    Attributes
    ----------
    chunks_computed : int
        Chunks computed (and saved) by the interrupted call.
    chunks_missing : int
        Chunks still to compute.
    """

    def __init__(self, message: str, chunks_computed: int, chunks_missing: int):
        super().__init__(message)
        self.chunks_computed = chunks_computed
        self.chunks_missing = chunks_missing


@dataclass(frozen=True)
class _Task:
    point: Point
    first: int | None = None  # None: the closed-form estimate
    count: int = 0

    @property
    def is_chunk(self) -> bool:
        return self.first is not None


def _chunks(records: int, chunk_records: int) -> list[tuple[int, int]]:
    return [(first, min(chunk_records, records - first)) for first in range(0, records, chunk_records)]


def _check_whole(name: str, value, minimum: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise ArgumentError(name, f"must be a whole number >= {minimum}, got {value!r}")


class _Client:
    """A Dask client for the sweep: the given one, one connected to
    ``scheduler``, or a local cluster of processes; or none (serial)."""

    def __init__(self, scheduler, workers: int | None):
        self.client = self.cluster = None
        self.owned = True
        if scheduler == SERIAL:
            return
        from distributed import Client

        if isinstance(scheduler, Client):
            self.client, self.owned = scheduler, False
        elif scheduler is None:
            import logging

            from distributed import LocalCluster

            self.cluster = LocalCluster(
                n_workers=workers or os.cpu_count() or 1,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,
                # no dashboard, and the scheduler's own HTTP server (health checks) on a free port: on 8787, its
                # default, a second sweep on the machine warned "Port 8787 is already in use"
                scheduler_kwargs={"dashboard": False, "dashboard_address": ":0"},
                silence_logs=logging.ERROR,
            )
            self.client = Client(self.cluster)
        elif isinstance(scheduler, str):
            try:
                self.client = Client(scheduler, timeout="20s")
            except (OSError, TimeoutError, ValueError) as error:
                raise ArgumentError("scheduler", f"cannot connect to {scheduler!r}: {error}") from None
        else:
            raise ArgumentError("scheduler", f"give a scheduler address, a distributed.Client, {SERIAL!r} or None, got {scheduler!r}")

    def close(self) -> None:
        """Close what this made. The local cluster's workers stop their heartbeats first: a heartbeat in flight
        while the scheduler retired its worker logged "Failed to communicate with scheduler during heartbeat"
        with a CommClosedError traceback at the end of about 1 successful run in 20 (distributed's own race
        between ``remove_worker`` and a heartbeat). Then the client, then the cluster (workers, then scheduler)."""
        if self.cluster is not None and self.client is not None:
            with contextlib.suppress(Exception):  # a worker already gone: it sends no heartbeat either
                self.client.run(_stop_heartbeat)
        if self.owned and self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _stop_heartbeat(dask_worker) -> None:
    """On a Dask worker: no more heartbeats to the scheduler (the one running, if any, ends before this returns)."""
    dask_worker.periodic_callbacks["heartbeat"].stop()


def _run_tasks(tasks: list[_Task], client, seed: int, tolerance: float, done: Callable[[_Task, dict], None]) -> None:
    """Run ``tasks`` serially (``client`` None) or on Dask, a bounded window in
    flight at a time (client memory stays flat however many chunks), calling
    ``done(task, result)`` in this thread as each finishes."""

    def call(task: _Task):
        if task.is_chunk:
            return chunk_sums, (task.point.data, seed, task.first, task.count, tolerance, task.point.adjustment)
        return point_estimate, (task.point.data, task.point.adjustment)

    if client is None:
        for task in tasks:
            function, arguments = call(task)
            done(task, function(*arguments))
        return
    from distributed import as_completed

    window = max(4, 3 * sum(client.nthreads().values()))
    queue = iter(tasks)
    pending = {}

    def submit(task: _Task):
        function, arguments = call(task)
        label = f"chunk-{task.first}-{task.count}" if task.is_chunk else "estimate"
        future = client.submit(function, *arguments, key=f"pounding-sweep-{task.point.key}-{label}")
        pending[future] = task
        return future

    running = as_completed([submit(task) for task in itertools.islice(queue, window)])
    try:
        for future in running:
            task = pending.pop(future)
            result = future.result()
            future.release()
            done(task, result)
            following = next(queue, None)
            if following is not None:
                running.add(submit(following))
    finally:
        for future in pending:
            future.cancel()


def _missing(points: list[Point], chunks: list[tuple[int, int]], store: Store, estimates: bool = True) -> tuple[list[_Task], int]:
    """The tasks whose files are missing (or unreadable), and the number of chunks found done."""
    tasks, found = [], 0
    for point in points:
        if estimates and store.estimate(point) is None:
            tasks.append(_Task(point))
        for first, count in chunks:
            if store.chunk(point, first, count) is None:
                tasks.append(_Task(point, first, count))
            else:
                found += 1
    return tasks, found


def _within_budget(tasks: list[_Task], max_chunks: int) -> list[_Task]:
    """The first ``max_chunks`` chunk tasks, and every estimate task."""
    kept = []
    for task in tasks:
        if task.is_chunk:
            if max_chunks == 0:
                continue
            max_chunks -= 1
        kept.append(task)
    return kept


def _compute(tasks: list[_Task], store: Store, plan: MonteCarloPlan, done: int, total: int) -> int:
    """Run ``tasks`` as ``plan`` says, saving each result as it arrives; returns the chunks computed."""
    computed, progress = 0, plan.progress
    if progress is not None:
        progress(done, total)

    def finished(task: _Task, result: dict) -> None:
        nonlocal computed, done
        if not task.is_chunk:
            write_json(store.estimate_path(task.point), result)
            return
        write_json(store.chunk_path(task.point, task.first, task.count), result)
        computed += 1
        done += task.count
        if progress is not None:
            progress(done, total)

    if tasks:
        client = _Client(plan.scheduler, plan.workers)
        try:
            if client.client is not None:
                client.client.run(warm, tasks[0].point.data, tasks[0].point.adjustment)
            _run_tasks(tasks, client.client, plan.seed, plan.settings.tolerance, finished)
        finally:
            client.close()
    return computed


def _check_budget(max_chunks) -> None:
    if max_chunks is not None:
        _check_whole("max_chunks", max_chunks, 0)


def _run_points(points: list[Point], chunks, store: Store, plan: MonteCarloPlan, max_chunks: int | None,
                estimates: bool) -> tuple[int, int]:
    """Compute every missing chunk (and, with ``estimates``, closed-form figures) of ``points``; returns the
    chunks computed and those found done. :class:`SweepInterrupted` once ``max_chunks`` are computed."""
    tasks, reused = _missing(points, chunks, store, estimates)
    missing = sum(task.is_chunk for task in tasks)
    if max_chunks is not None and missing > max_chunks:
        tasks = _within_budget(tasks, max_chunks)
    records = sum(count for _, count in chunks)
    found = records * len(points) - sum(task.count for task in tasks if task.is_chunk)
    computed = _compute(tasks, store, plan, found, records * len(points))
    if computed < missing:
        raise SweepInterrupted(
            f"stopped after {computed} chunk(s), {missing - computed} still missing; rerun to resume", computed, missing - computed
        )
    return computed, reused


def monte_carlo_forces(case, adjustments: Sequence[Mapping], plan: MonteCarloPlan, output_dir: str | os.PathLike = "study",
                       *, max_chunks: int | None = None, label: str = "study") -> list[np.ndarray]:
    """Every record's F_max [N] at each adjusted case (:func:`pounding.case.scaling.adjusted`: another PGA, other
    periods), on the sweep's engine: the same chunks, Dask, resumable files in ``output_dir`` and numbers that
    do not depend on the workers or the chunking (record i of a point is seeded as in :func:`pounding.simulate`).

    ``case`` is a preset name, a TOML case file or a parsed case file (dict); ``adjustments`` one mapping per
    point; ``plan`` how the Monte Carlo runs (its ``records`` are required); ``label`` names the study in
    ``output_dir``'s manifest. Returns one array per point, in record order. Raises as :func:`sweep` does; an
    adjustment that makes the case invalid names its key.
    """
    if plan.records is None:
        raise ArgumentError("records", "must be given for a study of many points")
    _check_budget(max_chunks)
    records, seed, chunk_records, tolerance = plan.records, plan.seed, plan.chunk_records, plan.settings.tolerance
    data, name = case_data(case)
    points = adjusted_points(data, name, adjustments, seed, tolerance)
    check_folder(output_dir, FIELD)
    store = Store(Path(output_dir))
    store.write_manifest({
        "study": label, "case": name, "records": records, "seed": seed, "chunk_records": chunk_records, "tolerance": tolerance,
        "points": [{"point": p.index, "key": p.key, **p.adjustment} for p in points],
    })
    for point in points:
        store.write_point(point, [])
    chunks = _chunks(records, chunk_records)
    _run_points(points, chunks, store, plan, max_chunks, estimates=False)
    return [np.concatenate([np.asarray(store.chunk(point, first, count)["force_max_values"], dtype=float)
                            for first, count in chunks]) for point in points]


def sweep(
    case,
    vary: Mapping[str, Sequence[float] | str] | Iterable[str] | None,
    plan: MonteCarloPlan | None = None,
    output_dir: str | os.PathLike = "sweep",
    *,
    table_format: str = "csv",
    chart: bool = True,
    max_chunks: int | None = None,
    **options,
):
    """Closed form and Monte Carlo at every combination of the varied keys, resumable.

    Parameters
    ----------
    case : str, path or dict
        A preset name, a TOML case file, or a parsed case file (dict).
    vary : dict or list of str
        ``{path: values}`` (values a sequence of numbers or a spec string
        ``"start:stop:count"`` / ``"a,b,c"``), or ``["path=values", ...]``.
        A path is a key of the case file (``"contact.gap"``,
        ``"buildings.2.storeys.1.period"``; buildings and storeys counted from
        1); values are in the case's units. Points are all combinations, the
        last path varying fastest. Empty or None: the case alone.
    plan : MonteCarloPlan, optional
        How the Monte Carlo runs: ``records`` per point (``defaults.SWEEP_RECORDS`` when None); ``seed``
        (records are seeded one by one, so the numbers do not depend on ``chunk_records``, workers or
        scheduler); ``scheduler`` (None: a local Dask cluster of ``workers`` processes, default one per core,
        started and stopped here; an address ``"tcp://host:8786"``: that cluster; a ``distributed.Client``:
        used as is, not closed; ``"serial"``: everything in this process, without Dask); ``chunk_records``
        (records per Dask task); ``progress(done, total)`` in records, after each chunk (chunks found on disk
        count as done from the start); ``settings.tolerance`` (the integrator's relative tolerance).
    output_dir : str or path
        Folder of the finished chunks, the table and the chart (made if missing).
        Rerunning with the same folder computes only what is missing; temporary
        files left there by a killed run are removed.
    table_format : {"csv", "parquet"}
        Format of the table written to ``output_dir`` (Parquet needs pyarrow).
    chart : bool
        Write the design chart ``sweep.html`` (imports Bokeh).
    max_chunks : int, optional
        Stop, with :class:`SweepInterrupted`, once this many chunks have been
        computed by this call (their files kept): a budgeted run, or a test
        of resuming.
    **options
        Fields of the plan given one by one: ``sweep(case, vary, records=50, scheduler="serial")``.

    Returns
    -------
    pandas.DataFrame
        One row per point: ``point``; one column per varied path (case
        units); ``records``, ``seed``; closed form ``estimate_force_N``,
        ``paper_force_N`` (the paper's Eq. 12-30; NaN for laws it does not
        cover), ``estimate_pounding_probability``, ``estimate_impacts``,
        ``required_gap_m`` (95 % no pounding), ``sigma_relative_displacement_m``;
        Monte Carlo ``mc_force_mean_N``, ``mc_force_std_error_N``,
        ``mc_force_ci_low_N``, ``mc_force_ci_high_N`` (95 %, Student t),
        ``mc_force_max_N``, ``mc_pounding_fraction``, ``mc_impacts_mean``,
        ``mc_impact_velocity_mean_m_s``, ``mc_penetration_max_m``;
        ``estimate_warnings``; ``key`` (the point's folder). ``attrs`` holds
        ``chunks_computed``, ``chunks_reused``, ``table``, ``chart``, ``units``.

    Raises
    ------
    ArgumentError
        A bad varied path or value (field ``vary``), bad counts; an
        ``output_dir`` that is not a folder, or a table or chart target in it
        that is not a regular file (field ``output_dir``).
    CaseError
        A point whose case is invalid (naming its field and the point).
    OSError
        The system refused a write (read-only folder, full disk), naming the file.
    SweepInterrupted
        ``max_chunks`` reached.
    pounding.SimulationError
        A record failed to integrate.
    """
    from pounding.simulation.plan import as_plan

    plan = as_plan(plan, options).with_records(defaults.SWEEP_RECORDS)
    _check_budget(max_chunks)
    records, seed, chunk_records, tolerance = plan.records, plan.seed, plan.chunk_records, plan.settings.tolerance
    if table_format not in TABLE_FORMATS:
        raise ArgumentError("table_format", f"unknown table format {table_format!r}; allowed: {', '.join(TABLE_FORMATS)}")
    if table_format == "parquet":
        need_parquet()
    data, name = case_data(case)
    varied = normalized_vary(vary)
    paths = [path for path, _ in varied]
    points = sweep_points(data, name, varied, seed, tolerance)
    check_limit("records", len(points) * records, defaults.MAX_TIME_HISTORIES, "time histories (points x records)",
                "give fewer points or records", error=ArgumentError)
    check_folder(output_dir, FIELD)  # a bad folder, table or chart target is refused before any work
    store = Store(Path(output_dir))
    table_path = store.root / f"sweep.{table_format}"
    for target in (table_path, store.root / "sweep.html") if chart else (table_path,):
        check_target(target, FIELD, make_parents=True)
    units = str(data.get("units", "SI"))
    store.write_manifest({
        "case": name, "units": units, "vary": {path: list(values) for path, values in varied}, "records": records,
        "seed": seed, "chunk_records": chunk_records, "tolerance": tolerance,
        "points": [{"point": p.index, "key": p.key, **dict(zip(paths, p.values))} for p in points],
    })
    for point in points:
        store.write_point(point, paths)

    chunks = _chunks(records, chunk_records)
    computed, reused = _run_points(points, chunks, store, plan, max_chunks, estimates=True)
    table = summary_table(points, paths, chunks, store, records, seed)
    table.attrs.update(chunks_computed=computed, chunks_reused=reused, units=units)
    write_table(table, table_path, table_format)
    table.attrs["table"] = str(table_path)
    table.attrs["chart"] = None
    if chart:
        table.attrs["chart"] = str(write_chart(table, paths, store.root / "sweep.html", units=units, title=f"Sweep of {name}"))
    return table
