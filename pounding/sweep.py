"""Parametric studies: every combination of some case keys, estimated in
closed form and simulated by Monte Carlo, the records spread over Dask.

A sweep varies keys of the case *file* by their dotted path (``contact.gap``,
``buildings.2.storeys.1.period``, ``excitation.G0``; buildings and storeys
counted from 1), in the case's own units. Each combination (a *point*) is
the case file with those keys set, loaded and validated as any case file.

For each point, the records ``0 .. records - 1`` of the study seeded ``seed``
are split into chunks of ``chunk_records``; a chunk runs on a Dask worker,
which returns only sums (of F_max, F_max^2, impacts, ...), never per-record
arrays or time histories: memory stays flat however many records. The sums
are exact (rational), so the table does not depend on how the records were
chunked or on which worker ran what: record *i* is seeded by
``SeedSequence(seed, spawn_key=(i,))`` (see :func:`pounding.simulate`).

Resumable: the client writes each finished chunk (and each point's closed-form
estimate) to ``output_dir`` as a small JSON file, atomically, named by a hash
of the point's physics, the seed, the tolerance and the chunk's record range.
A rerun computes only the files that are missing, so an interrupted sweep
(Ctrl-C, a killed client) loses the chunks in flight only, and its final table
equals an uninterrupted run's. A worker lost mid-chunk costs that chunk only:
Dask reruns it elsewhere. Files land where the *client* runs; a remote cluster
needs no shared file system, only ``pounding`` installed on its workers.

Layout of ``output_dir``::

    sweep.json                           what was asked (case, vary, records, seed, ...)
    sweep.csv (or sweep.parquet)         the table, one row per point
    sweep.html                           the design chart (static, Bokeh)
    points/<key>/point.json              the point's case data and varied values
    points/<key>/estimate.json           closed-form figures
    points/<key>/chunk-<first>-<count>.json   sums over records first .. first + count - 1

This module imports nothing heavy at load (the CLI builds its parser from
:func:`add_arguments`): Dask, pandas and Bokeh are imported when used.
"""

from __future__ import annotations

import argparse
import copy
import hashlib
import itertools
import json
import math
import os
import sys
import tempfile
import types
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

from .errors import CaseError

__all__ = [
    "sweep",
    "parse_vary",
    "parse_values",
    "SweepInterrupted",
    "CHUNK_RECORDS",
    "TABLE_FORMATS",
    "add_arguments",
    "run",
    "write_chart",
    "DESCRIPTION",
    "EPILOG",
]

CHUNK_RECORDS = 100
"""Default records per chunk: about 0.4 s of work for 20 s records of two
SDOF buildings, against a few milliseconds of overhead per chunk
(``benchmarks/sweep.py``)."""

TABLE_FORMATS = ("csv", "parquet")
DEFAULT_TOLERANCE = 1e-6
SERIAL = "serial"
"""``scheduler=SERIAL`` runs every chunk in this process, without Dask."""

_FILE_FORMAT = 1  # bump when the chunk files' meaning changes: old ones are then ignored
_SIGNIFICANT_DIGITS = 12  # start:stop:count grids are rounded to this, so 0:0.05:11 gives 0.015, not 0.015000000000000001

DESCRIPTION = (
    "Parametric study: every combination of the --vary values, estimated in closed form and simulated by "
    "Monte Carlo with the records spread in chunks over Dask workers (a local cluster on this machine's cores, "
    "or --scheduler ADDRESS). Finished chunks are kept in the output folder: rerun the same command to resume."
)
EPILOG = """examples:
  pounding sweep section5-T2-0.4 --vary contact.gap=0.0:0.05:11 --records 300 --seed 1 -o gap-study/
  pounding sweep case.toml --vary contact.gap=0.5,1,2 --vary buildings.2.storeys.1.period=0.4,0.6,0.8 -o out/
  pounding sweep case.toml --vary excitation.G0=30:90:7 --records 2000 --scheduler tcp://10.0.0.5:8786 -o out/
--vary PATH=VALUES: PATH is a key of the case file (buildings and storeys counted from 1), in the case's
units; VALUES is start:stop:count (count values, both ends included) or a,b,c."""


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


# --- --vary specs --------------------------------------------------------------------------


def _number(text: str, spec: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise CaseError("--vary", f"{spec!r}: {text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise CaseError("--vary", f"{spec!r}: {text.strip()!r} is not a finite number")
    return value


def parse_values(text: str, spec: str | None = None) -> tuple[float, ...]:
    """The values of a ``--vary`` spec.

    Parameters
    ----------
    text : str
        ``start:stop:count`` (``count`` evenly spaced values, both ends
        included, rounded to 12 significant digits) or ``a,b,c``.
    spec : str, optional
        The whole spec, for error messages.

    Returns
    -------
    tuple of float

    Raises
    ------
    CaseError
        Field ``--vary``: malformed range or list, a value that is not a
        finite number, a count that is not a whole number >= 1, a repeated value.
    """
    spec = text if spec is None else spec
    if not text.strip():
        raise CaseError("--vary", f"{spec!r}: no values; give start:stop:count or a,b,c")
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise CaseError("--vary", f"{spec!r}: a range is start:stop:count (three parts), got {len(parts)} part(s)")
        start, stop = _number(parts[0], spec), _number(parts[1], spec)
        try:
            count = int(parts[2])
        except ValueError:
            raise CaseError("--vary", f"{spec!r}: count must be a whole number >= 1, got {parts[2].strip()!r}") from None
        if count < 1:
            raise CaseError("--vary", f"{spec!r}: count must be a whole number >= 1, got {count}")
        if count == 1:
            if start != stop:
                raise CaseError("--vary", f"{spec!r}: one value from start != stop is ambiguous; give count >= 2")
            return (start,)
        step = (stop - start) / (count - 1)
        values = [float(f"{start + i * step:.{_SIGNIFICANT_DIGITS}g}") for i in range(count - 1)] + [stop]
    else:
        items = text.split(",")
        if any(not item.strip() for item in items):
            raise CaseError("--vary", f"{spec!r}: empty value in the list; give a,b,c")
        values = [_number(item, spec) for item in items]
    seen = set()
    for value in values:
        if value in seen:
            raise CaseError("--vary", f"{spec!r}: value {value:g} appears twice")
        seen.add(value)
    return tuple(values)


def parse_vary(spec: str) -> tuple[str, tuple[float, ...]]:
    """Split a ``--vary`` spec ``PATH=VALUES`` into its path and values.

    Only the syntax is checked here; whether ``PATH`` names a key of the case
    is checked by :func:`sweep`.

    Raises
    ------
    CaseError
        Field ``--vary``, naming the spec and what is wrong.
    """
    path, equals, values = spec.partition("=")
    path = path.strip()
    if not equals:
        raise CaseError("--vary", f"{spec!r}: expected PATH=VALUES, e.g. contact.gap=0:2:5 or contact.gap=0.5,1,2")
    if not path:
        raise CaseError("--vary", f"{spec!r}: no key path before '='")
    _check_path_syntax(path, spec)
    return path, parse_values(values, spec)


def _check_path_syntax(path: str, spec: str) -> None:
    if any(not part for part in path.split(".")):
        raise CaseError("--vary", f"{spec!r}: empty part in the key path {path!r}")


def _normalized_vary(vary: Mapping[str, Sequence[float] | str] | Iterable[str] | None) -> list[tuple[str, tuple[float, ...]]]:
    """``vary`` as a list of (path, values); values given as a spec string are parsed."""
    if vary is None:
        return []
    if isinstance(vary, str):
        raise CaseError("vary", "give a dict {path: values} or a list of PATH=VALUES specs, not one string")
    items = vary.items() if isinstance(vary, Mapping) else [parse_vary(spec) for spec in vary]
    out, seen = [], set()
    for path, values in items:
        if not isinstance(path, str) or not path:
            raise CaseError("--vary", f"key path must be a non-empty string, got {path!r}")
        _check_path_syntax(path, path)
        if path in seen:
            raise CaseError("--vary", f"{path!r} is varied twice; give all its values in one --vary")
        seen.add(path)
        if isinstance(values, str):
            values = parse_values(values, f"{path}={values}")
        else:
            values = tuple(values)
            if not values:
                raise CaseError("--vary", f"{path!r}: no values")
            for value in values:
                if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                    raise CaseError("--vary", f"{path!r}: {value!r} is not a finite number")
            if len(set(values)) != len(values):
                raise CaseError("--vary", f"{path!r}: a value appears twice")
        out.append((path, values))
    return out


# --- points: the case file with the varied keys set -----------------------------------------


def _case_data(case) -> tuple[dict, str]:
    """The parsed case file of ``case`` (preset name, TOML path or dict) and its name."""
    import tomllib

    from .presets import preset_names, preset_text

    if isinstance(case, Mapping):
        data = copy.deepcopy(dict(case))
        return data, str(data.get("name", "case"))
    if isinstance(case, str) and preset_text(case) is not None:
        data = tomllib.loads(preset_text(case))
        return data, case
    if isinstance(case, (str, os.PathLike)):
        path = Path(case)
        if not path.is_file():
            raise CaseError("case", f"{str(case)!r} is neither a TOML file nor a preset; presets: {', '.join(preset_names())}")
        try:
            return tomllib.loads(path.read_text()), path.stem
        except tomllib.TOMLDecodeError as error:
            raise CaseError(str(path), f"not valid TOML: {error}") from None
    raise CaseError(
        "case",
        f"give a preset name, a TOML file or the parsed case file as a dict (--vary paths are keys of the file), "
        f"got {type(case).__name__}",
    )


def _set_path(data: dict, path: str, value: float) -> None:
    """Set key ``path`` of the case file ``data`` (lists counted from 1)."""
    parts = path.split(".")
    node = data
    for depth, part in enumerate(parts):
        where = ".".join(parts[:depth]) or "the case file"
        last = depth == len(parts) - 1
        if isinstance(node, list):
            if not part.isdigit() or not 1 <= int(part) <= len(node):
                raise CaseError("--vary", f"{path!r}: {where} has {len(node)} entries, counted from 1; got {part!r}")
            index = int(part) - 1
            if last:
                node[index] = _like(node[index], value, path)
                return
            node = node[index]
        elif isinstance(node, dict):
            if last:
                node[part] = _like(node.get(part), value, path)
                return
            if part not in node:
                keys = ", ".join(sorted(node)) or "none"
                raise CaseError("--vary", f"{path!r}: {where} has no {part!r}; keys there: {keys}")
            node = node[part]
        else:
            raise CaseError("--vary", f"{path!r}: {where} is a value, not a table")


def _like(existing, value: float, path: str):
    """``value`` in the type of the key it replaces (a whole number stays an int)."""
    if existing is None:
        return value
    if isinstance(existing, bool) or not isinstance(existing, (int, float)):
        raise CaseError("--vary", f"{path!r} is {existing!r} in the case, not a number; only numeric keys can be varied")
    if isinstance(existing, int) and float(value).is_integer():
        return int(value)
    return value


def _physics(data: dict) -> dict:
    """The part of a case file that determines the numbers (not its name)."""
    return {key: value for key, value in data.items() if key not in ("name", "description")}


@dataclass(frozen=True)
class _Point:
    index: int
    values: tuple[float, ...]  # one per varied path, in the case's units
    data: dict  # the case file with the varied keys set
    key: str  # hash of the physics, the seed and the tolerance


def _points(data: dict, name: str, vary: list[tuple[str, tuple[float, ...]]], seed: int, tolerance: float) -> list[_Point]:
    """Every combination of the varied values, each loaded (and so validated) once here."""
    from .case import case_from_dict

    paths = [path for path, _ in vary]
    points = []
    for index, values in enumerate(itertools.product(*(values for _, values in vary))):
        point = copy.deepcopy(data)
        for path, value in zip(paths, values):
            _set_path(point, path, value)
        label = ", ".join(f"{path}={value:g}" for path, value in zip(paths, values))
        point["name"] = f"{name}[{label}]" if label else name
        try:
            case_from_dict(point, name=point["name"])
        except CaseError as error:
            where = f" (at {label})" if label else ""
            raise CaseError(error.field, f"{error.message}{where}") from None
        points.append(_Point(index, tuple(values), point, _point_key(point, seed, tolerance)))
    return points


def _point_key(data: dict, seed: int, tolerance: float) -> str:
    text = json.dumps({"format": _FILE_FORMAT, "case": _physics(data), "seed": seed, "tolerance": tolerance}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:20]


# --- the work: done on Dask workers -----------------------------------------------------------


def _fraction_text(value: Fraction) -> str:
    return f"{value.numerator}/{value.denominator}"


def chunk_sums(data: dict, seed: int, first: int, count: int, tolerance: float = DEFAULT_TOLERANCE) -> dict:
    """Monte Carlo over records ``first .. first + count - 1`` of one point, reduced to sums.

    Runs on one thread (a Dask worker runs one task per thread).

    Parameters
    ----------
    data : dict
        The point's case file (parsed TOML).
    seed, first, count : int
        Seed of the study, first record, number of records.
    tolerance : float
        Relative tolerance of the integrator [-].

    Returns
    -------
    dict
        JSON-ready: ``records``; exact sums (as ``"p/q"`` strings) of F_max
        [N], F_max^2 [N^2] and of the peak approach velocity at impact [m/s];
        the number of records with pounding and of impacts; the largest
        F_max [N] and penetration [m]. Sums of exact rationals do not depend
        on the order of addition: any chunking gives the same totals.
    """
    from .case import case_from_dict
    from .simulation import Settings, simulate

    case = case_from_dict(data, name=str(data.get("name", "case")))
    result = simulate(case, records=count, seed=seed, settings=Settings(tolerance=tolerance, workers=1), first_record=first)
    forces = [Fraction(float(f)) for f in result.force_max]
    return {
        "first": first,
        "records": count,
        "force_sum": _fraction_text(sum(forces, Fraction(0))),
        "force_square_sum": _fraction_text(sum((f * f for f in forces), Fraction(0))),
        "impact_velocity_sum": _fraction_text(sum((Fraction(float(v)) for v in result.impact_velocity_max), Fraction(0))),
        "pounding_records": int((result.impacts > 0).sum()),
        "impacts": int(result.impacts.sum()),
        "force_max": float(result.force_max.max()),
        "penetration_max": float(result.penetration_max.max()),
    }


def point_estimate(data: dict) -> dict:
    """The closed-form figures of one point (``pounding.estimator.estimate``), JSON-ready, SI.

    An estimate that cannot be made (e.g. a record too short for Davenport's
    peak factor) gives None figures and its reason in ``warnings``.
    """
    from .case import case_from_dict
    from .errors import ConvergenceError
    from .estimator import estimate

    case = case_from_dict(data, name=str(data.get("name", "case")))
    try:
        result = estimate(case)
    except (CaseError, ConvergenceError) as error:
        return {"force": None, "paper_force": None, "pounding_probability": None, "impacts": None,
                "required_gap": None, "sigma_relative_displacement": None, "warnings": [f"estimate failed: {error}"]}
    return {
        "force": result.force_expected,
        "paper_force": result.paper.force_expected,
        "pounding_probability": result.pounding_probability,
        "impacts": result.impacts_expected,
        "required_gap": result.required_gap,
        "sigma_relative_displacement": result.sigma_relative_displacement,
        "warnings": list(result.warnings),
    }


_WARM = False


def _warm(data: dict) -> None:
    """Load the numba kernels in this process once (about 1 s from the disk cache)."""
    global _WARM
    if not _WARM:
        try:
            point_estimate(data)
            chunk_sums(data, 0, 0, 1)
        except Exception:  # noqa: BLE001  warming is best effort: the task itself will report the error
            return
        _WARM = True


# --- files ------------------------------------------------------------------------------------


def _write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to a temporary file beside ``path``, then rename it over
    ``path``: a reader sees the whole file or none."""
    path.parent.mkdir(parents=True, exist_ok=True)
    descriptor, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(descriptor, "wb") as stream:
            stream.write(data)
            stream.flush()
            os.fsync(stream.fileno())
        os.chmod(temporary, 0o644)  # mkstemp makes it private
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def _write_json(path: Path, value) -> None:
    _write_atomic(path, (json.dumps(value, indent=1) + "\n").encode())


def _read_json(path: Path):
    """The JSON in ``path``, or None when it is missing or unreadable (it is then recomputed)."""
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


class _Store:
    """The files of a sweep in ``root``."""

    def __init__(self, root: Path):
        self.root = root

    def point_dir(self, point: _Point) -> Path:
        return self.root / "points" / point.key

    def estimate_path(self, point: _Point) -> Path:
        return self.point_dir(point) / "estimate.json"

    def chunk_path(self, point: _Point, first: int, count: int) -> Path:
        return self.point_dir(point) / f"chunk-{first:09d}-{count}.json"

    def write_manifest(self, manifest: dict) -> None:
        if self.root.exists() and not self.root.is_dir():
            raise CaseError("output", f"{str(self.root)!r} exists and is not a folder")
        _write_json(self.root / "sweep.json", manifest)

    def write_point(self, point: _Point, paths: list[str]) -> None:
        path = self.point_dir(point) / "point.json"
        if not path.exists():
            _write_json(path, {"values": dict(zip(paths, point.values)), "case": point.data})

    def estimate(self, point: _Point) -> dict | None:
        value = _read_json(self.estimate_path(point))
        return value if isinstance(value, dict) and "force" in value else None

    def chunk(self, point: _Point, first: int, count: int) -> dict | None:
        value = _read_json(self.chunk_path(point, first, count))
        if not (isinstance(value, dict) and value.get("first") == first and value.get("records") == count):
            return None
        return value


# --- the sweep --------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Task:
    point: _Point
    first: int | None = None  # None: the closed-form estimate
    count: int = 0

    @property
    def is_chunk(self) -> bool:
        return self.first is not None


def _chunks(records: int, chunk_records: int) -> list[tuple[int, int]]:
    return [(first, min(chunk_records, records - first)) for first in range(0, records, chunk_records)]


def _check_whole(name: str, value, minimum: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise CaseError(name, f"must be a whole number >= {minimum}, got {value!r}")


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
                silence_logs=logging.ERROR,
            )
            self.client = Client(self.cluster)
        elif isinstance(scheduler, str):
            try:
                self.client = Client(scheduler, timeout="20s")
            except (OSError, TimeoutError, ValueError) as error:
                raise CaseError("--scheduler", f"cannot connect to {scheduler!r}: {error}") from None
        else:
            raise CaseError("scheduler", f"give a scheduler address, a distributed.Client, {SERIAL!r} or None, got {scheduler!r}")

    def close(self) -> None:
        if self.owned and self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _run_tasks(tasks: list[_Task], client, seed: int, tolerance: float, done: Callable[[_Task, dict], None]) -> None:
    """Run ``tasks`` serially (``client`` None) or on Dask, a bounded window in
    flight at a time (client memory stays flat however many chunks), calling
    ``done(task, result)`` in this thread as each finishes."""

    def call(task: _Task):
        if task.is_chunk:
            return chunk_sums, (task.point.data, seed, task.first, task.count, tolerance)
        return point_estimate, (task.point.data,)

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


def _missing(points: list[_Point], chunks: list[tuple[int, int]], store: _Store) -> tuple[list[_Task], int]:
    """The tasks whose files are missing (or unreadable), and the number of chunks found done."""
    tasks, found = [], 0
    for point in points:
        if store.estimate(point) is None:
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


def _compute(tasks: list[_Task], store: _Store, scheduler, workers, seed: int, tolerance: float,
             progress: Callable[[int, int], None] | None, done: int, total: int) -> int:
    """Run ``tasks``, saving each result as it arrives; returns the chunks computed."""
    computed = 0
    if progress is not None:
        progress(done, total)

    def finished(task: _Task, result: dict) -> None:
        nonlocal computed, done
        if not task.is_chunk:
            _write_json(store.estimate_path(task.point), result)
            return
        _write_json(store.chunk_path(task.point, task.first, task.count), result)
        computed += 1
        done += task.count
        if progress is not None:
            progress(done, total)

    if tasks:
        client = _Client(scheduler, workers)
        try:
            if client.client is not None:
                client.client.run(_warm, tasks[0].point.data)
            _run_tasks(tasks, client.client, seed, tolerance, finished)
        finally:
            client.close()
    return computed


def sweep(
    case,
    vary: Mapping[str, Sequence[float] | str] | Iterable[str] | None,
    records: int = 100,
    seed: int = 0,
    output_dir: str | os.PathLike = "sweep",
    scheduler=None,
    chunk_records: int = CHUNK_RECORDS,
    progress: Callable[[int, int], None] | None = None,
    *,
    workers: int | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    table_format: str = "csv",
    chart: bool = True,
    max_chunks: int | None = None,
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
    records : int
        Monte Carlo records per point.
    seed : int
        Seed of the study; records are seeded one by one, so the numbers do
        not depend on ``chunk_records``, workers or scheduler.
    output_dir : str or path
        Folder of the finished chunks, the table and the chart (made if missing).
        Rerunning with the same folder computes only what is missing.
    scheduler : None, str or distributed.Client
        None: a local Dask cluster of ``workers`` processes (default: one per
        core), started and stopped here. An address (``"tcp://host:8786"``):
        that cluster. A ``distributed.Client``: used as is (not closed).
        ``"serial"``: everything in this process, without Dask.
    chunk_records : int
        Records per Dask task.
    progress : callable, optional
        ``progress(done, total)`` in records, after each chunk (chunks found
        on disk count as done from the start).
    workers : int, optional
        Worker processes of the local cluster (scheduler None).
    tolerance : float
        Relative tolerance of the integrator [-].
    table_format : {"csv", "parquet"}
        Format of the table written to ``output_dir`` (Parquet needs pyarrow).
    chart : bool
        Write the design chart ``sweep.html`` (imports Bokeh).
    max_chunks : int, optional
        Stop, with :class:`SweepInterrupted`, once this many chunks have been
        computed by this call (their files kept): a budgeted run, or a test
        of resuming.

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
    CaseError
        A bad varied path or value (field ``--vary``), a point whose case is
        invalid (naming its field and the point), bad counts.
    SweepInterrupted
        ``max_chunks`` reached.
    pounding.SimulationError
        A record failed to integrate.
    """
    _check_whole("records", records, 1)
    _check_whole("seed", seed, 0)
    _check_whole("chunk_records", chunk_records, 1)
    if workers is not None:
        _check_whole("workers", workers, 1)
    if max_chunks is not None:
        _check_whole("max_chunks", max_chunks, 0)
    if table_format not in TABLE_FORMATS:
        raise CaseError("format", f"unknown table format {table_format!r}; allowed: {', '.join(TABLE_FORMATS)}")
    if table_format == "parquet":
        _need_parquet()
    from .simulation import Settings

    Settings(tolerance=tolerance)  # validates it
    data, name = _case_data(case)
    varied = _normalized_vary(vary)
    paths = [path for path, _ in varied]
    points = _points(data, name, varied, seed, tolerance)
    store = _Store(Path(output_dir))
    units = str(data.get("units", "SI"))
    store.write_manifest({
        "case": name, "units": units, "vary": {path: list(values) for path, values in varied}, "records": records,
        "seed": seed, "chunk_records": chunk_records, "tolerance": tolerance,
        "points": [{"point": p.index, "key": p.key, **dict(zip(paths, p.values))} for p in points],
    })
    for point in points:
        store.write_point(point, paths)

    chunks = _chunks(records, chunk_records)
    tasks, reused = _missing(points, chunks, store)
    missing = sum(task.is_chunk for task in tasks)
    if max_chunks is not None and missing > max_chunks:
        tasks = _within_budget(tasks, max_chunks)
    found = sum(count for _, count in chunks) * len(points) - sum(task.count for task in tasks if task.is_chunk)
    computed = _compute(tasks, store, scheduler, workers, seed, tolerance, progress, found, records * len(points))
    if computed < missing:
        raise SweepInterrupted(
            f"stopped after {computed} chunk(s), {missing - computed} still missing; rerun to resume", computed, missing - computed
        )

    table = _table(points, paths, chunks, store, records, seed)
    table.attrs.update(chunks_computed=computed, chunks_reused=reused, units=units)
    table_path = store.root / f"sweep.{table_format}"
    _write_table(table, table_path, table_format)
    table.attrs["table"] = str(table_path)
    table.attrs["chart"] = None
    if chart:
        table.attrs["chart"] = str(write_chart(table, paths, store.root / "sweep.html", units=units, title=f"Sweep of {name}"))
    return table


def _totals(point: _Point, chunks: list[tuple[int, int]], store: _Store) -> dict:
    """The chunks' sums added up, exactly."""
    n = pounding = impacts = 0
    force = square = velocity = Fraction(0)
    force_max = penetration_max = 0.0
    for first, count in chunks:
        chunk = store.chunk(point, first, count)
        n += chunk["records"]
        force += Fraction(chunk["force_sum"])
        square += Fraction(chunk["force_square_sum"])
        velocity += Fraction(chunk["impact_velocity_sum"])
        pounding += chunk["pounding_records"]
        impacts += chunk["impacts"]
        force_max = max(force_max, chunk["force_max"])
        penetration_max = max(penetration_max, chunk["penetration_max"])
    return dict(n=n, force=force, square=square, velocity=velocity, pounding=pounding, impacts=impacts,
                force_max=force_max, penetration_max=penetration_max)


def monte_carlo_summary(totals: dict) -> dict:
    """Mean, standard error and 95 % CI of F_max [N] from exact sums (see :func:`chunk_sums`).

    The mean is the exact mean correctly rounded; the variance is formed
    exactly, so there is no cancellation in sum(F^2) - sum(F)^2 / n.
    """
    from scipy.special import stdtrit

    n = totals["n"]
    mean = totals["force"] / n
    if n >= 2:
        variance = (totals["square"] - totals["force"] * mean) / (n - 1)
        std_error = math.sqrt(float(variance / n))
        half = float(stdtrit(n - 1, 0.975)) * std_error
    else:
        std_error = half = math.inf
    mean = float(mean)
    return {
        "mc_force_mean_N": mean,
        "mc_force_std_error_N": std_error,
        "mc_force_ci_low_N": mean - half,
        "mc_force_ci_high_N": mean + half,
        "mc_force_max_N": totals["force_max"],
        "mc_pounding_fraction": totals["pounding"] / n,
        "mc_impacts_mean": totals["impacts"] / n,
        "mc_impact_velocity_mean_m_s": float(totals["velocity"] / n),
        "mc_penetration_max_m": totals["penetration_max"],
    }


def _table(points: list[_Point], paths: list[str], chunks, store: _Store, records: int, seed: int):
    import pandas as pd

    def number(value):
        return math.nan if value is None else value

    rows = []
    for point in points:
        estimate = store.estimate(point)
        rows.append({
            "point": point.index,
            **dict(zip(paths, point.values)),
            "records": records,
            "seed": seed,
            "estimate_force_N": number(estimate["force"]),
            "paper_force_N": number(estimate["paper_force"]),
            "estimate_pounding_probability": number(estimate["pounding_probability"]),
            "estimate_impacts": number(estimate["impacts"]),
            "required_gap_m": number(estimate["required_gap"]),
            "sigma_relative_displacement_m": number(estimate["sigma_relative_displacement"]),
            **monte_carlo_summary(_totals(point, chunks, store)),
            "estimate_warnings": "; ".join(estimate["warnings"]),
            "key": point.key,
        })
    return pd.DataFrame(rows)


def _need_parquet() -> None:
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        raise CaseError("format", "parquet needs pyarrow (python -m pip install pyarrow); or use csv") from None


def _write_table(table, path: Path, table_format: str) -> None:
    import io

    if table_format == "csv":
        _write_atomic(path, table.to_csv(index=False).encode())
    else:
        buffer = io.BytesIO()
        table.to_parquet(buffer, index=False)
        _write_atomic(path, buffer.getvalue())


# --- the design chart -------------------------------------------------------------------------


def write_chart(table, paths: Sequence[str], path: str | os.PathLike, units: str = "SI", title: str = "Sweep") -> Path:
    """The design chart: expected extreme force and pounding probability
    against the first varied key, closed form (lines) and Monte Carlo (dots,
    95 % CI whiskers); one colour per combination of the other varied keys.

    A static HTML page (Bokeh, resources inline: no server, no network),
    written atomically. Returns ``path``.
    """
    from bokeh.embed import file_html
    from bokeh.layouts import row
    from bokeh.models import ColumnDataSource, Legend, Whisker
    from bokeh.palettes import Category10_10
    from bokeh.plotting import figure
    from bokeh.resources import INLINE

    path = Path(path)
    x_path = paths[0] if paths else None
    x_label = f"{x_path} [{units} units of the case file]" if x_path else "point"
    x_column = x_path or "point"
    others = list(paths[1:])
    groups = [((), table)] if not others else list(table.groupby(others, sort=False))
    force = figure(title="Expected extreme pounding force", x_axis_label=x_label, y_axis_label="E[F_max] [kN]",
                   width=560, height=420, tools="pan,wheel_zoom,box_zoom,reset,save,hover")
    probability = figure(title="Probability of pounding", x_axis_label=x_label, y_axis_label="P(at least one impact) [-]",
                         width=560, height=420, y_range=(-0.02, 1.02), tools="pan,wheel_zoom,box_zoom,reset,save,hover")
    items_force, items_probability = [], []
    for number, (group_values, group) in enumerate(groups):
        colour = Category10_10[number % 10]
        group = group.sort_values(x_column)
        group_values = group_values if isinstance(group_values, tuple) else (group_values,)
        label = ", ".join(f"{p}={v:g}" for p, v in zip(others, group_values)) or "case"
        source = ColumnDataSource({
            "x": group[x_column].to_numpy(),
            "estimate": group["estimate_force_N"].to_numpy() / 1e3,
            "paper": group["paper_force_N"].to_numpy() / 1e3,
            "mc": group["mc_force_mean_N"].to_numpy() / 1e3,
            "low": group["mc_force_ci_low_N"].to_numpy() / 1e3,
            "high": group["mc_force_ci_high_N"].to_numpy() / 1e3,
            "p_estimate": group["estimate_pounding_probability"].to_numpy(),
            "p_mc": group["mc_pounding_fraction"].to_numpy(),
        })
        lines = [force.line("x", "estimate", source=source, color=colour, line_width=2)]
        paper = force.line("x", "paper", source=source, color=colour, line_dash="dashed")
        dots = force.scatter("x", "mc", source=source, color=colour, size=7)
        force.add_layout(Whisker(source=source, base="x", lower="low", upper="high", line_color=colour))
        items_force += [(f"{label}: closed form", lines), (f"{label}: paper Eq. 12-30", [paper]), (f"{label}: Monte Carlo, 95 % CI", [dots])]
        p_line = probability.line("x", "p_estimate", source=source, color=colour, line_width=2)
        p_dots = probability.scatter("x", "p_mc", source=source, color=colour, size=7)
        items_probability += [(f"{label}: closed form", [p_line]), (f"{label}: Monte Carlo fraction", [p_dots])]
    for plot, items in ((force, items_force), (probability, items_probability)):
        legend = Legend(items=items, click_policy="hide", label_text_font_size="8pt")
        plot.add_layout(legend, "below")
    text = file_html(row(force, probability), resources=INLINE, title=title)
    _write_atomic(path, text.encode("utf-8"))
    return path


# --- command line -----------------------------------------------------------------------------


def add_arguments(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Add the ``pounding sweep`` arguments to ``parser`` (the subcommand's
    parser; :data:`DESCRIPTION` and :data:`EPILOG` are its texts). Returns ``parser``."""
    parser.add_argument("case", metavar="CASE", help="a preset name (see 'pounding cases') or a TOML case file")
    parser.add_argument("--vary", action="append", default=[], metavar="PATH=VALUES",
                        help="a key of the case file and its values, in the case's units: start:stop:count or a,b,c "
                        "(repeat for more keys; every combination is run)")
    from .cli import whole_number  # the command line's own argument types

    parser.add_argument("--records", type=whole_number(1), default=100, help="Monte Carlo records per point (default 100)")
    parser.add_argument("--seed", type=whole_number(0), default=0, help="seed of the study (default 0)")
    parser.add_argument("-o", "--output", required=True, metavar="DIR",
                        help="folder of the results and of the finished chunks (rerun with it to resume)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="Dask scheduler address (tcp://host:8786); default: a local cluster on this machine's cores; "
                        f"'{SERIAL}': in this process, without Dask")
    parser.add_argument("--workers", type=whole_number(1), default=None, help="worker processes of the local cluster (default: one per core)")
    parser.add_argument("--chunk-records", type=whole_number(1), default=CHUNK_RECORDS,
                        help=f"records per Dask task (default {CHUNK_RECORDS})")
    parser.add_argument("--format", choices=TABLE_FORMATS, default="csv", help="format of the table (default csv; parquet needs pyarrow)")
    parser.add_argument("--no-chart", action="store_true", help="do not write the design chart sweep.html")
    parser.add_argument("--json", action="store_true", help="print one JSON object (forces in N, lengths in m)")
    return parser


def _json_value(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if hasattr(value, "item"):  # numpy scalars
        return _json_value(value.item())
    return value


def run(args: argparse.Namespace) -> int:
    """Execute ``pounding sweep`` with the arguments of :func:`add_arguments`.

    Returns 0. Raises :class:`CaseError` on bad input (the CLI prints it on one
    line and exits 2); on Ctrl-C, says how to resume and re-raises.
    """
    vary = _normalized_vary(args.vary)
    bar = None
    if sys.stderr.isatty():
        from tqdm import tqdm

        bar = tqdm(unit="record", file=sys.stderr, dynamic_ncols=True)

    def progress(done: int, total: int) -> None:
        bar.total = total
        bar.update(done - bar.n)

    try:
        table = sweep(
            args.case, dict(vary), records=args.records, seed=args.seed, output_dir=args.output, scheduler=args.scheduler,
            chunk_records=args.chunk_records, progress=progress if bar is not None else None, workers=args.workers,
            table_format=args.format, chart=not args.no_chart,
        )
    except KeyboardInterrupt:
        print(f"pounding sweep: finished chunks are kept in {args.output}; rerun the same command to resume", file=sys.stderr)
        raise
    finally:
        if bar is not None:
            bar.close()
    paths = [path for path, _ in vary]
    if args.json:
        rows = [{key: _json_value(value) for key, value in row.items()} for row in table.to_dict(orient="records")]
        print(json.dumps({
            "case": str(args.case), "records": args.records, "seed": args.seed, "vary": {p: list(v) for p, v in vary},
            "case_units": table.attrs["units"], "table": table.attrs["table"], "chart": table.attrs["chart"],
            "chunks_computed": table.attrs["chunks_computed"], "chunks_reused": table.attrs["chunks_reused"],
            "units": {"force": "N", "length": "m", "velocity": "m/s"}, "rows": rows,
        }))
        return 0
    print(f"{len(table)} point(s) x {args.records} records, seed {args.seed}; "
          f"{table.attrs['chunks_computed']} chunk(s) computed, {table.attrs['chunks_reused']} found done")
    header = [*paths, "F_e closed form", "F_max Monte Carlo (s.e.)", "P closed form", "P Monte Carlo"]
    lines = []
    for row in table.to_dict(orient="records"):
        lines.append([
            *(f"{row[p]:g}" for p in paths),
            _kn(row["estimate_force_N"]),
            f"{_kn(row['mc_force_mean_N'])} ({_kn(row['mc_force_std_error_N'])})",
            _fraction(row["estimate_pounding_probability"]),
            _fraction(row["mc_pounding_fraction"]),
        ])
    widths = [max(len(header[i]), *(len(line[i]) for line in lines)) for i in range(len(header))]
    for line in [header, *lines]:
        print("  ".join(cell.rjust(width) for cell, width in zip(line, widths)))
    print(f"forces in kN; varied keys in the case's units ({table.attrs['units']})")
    print(f"table  {table.attrs['table']}")
    if table.attrs["chart"]:
        print(f"chart  {table.attrs['chart']}")
    return 0


def _kn(newtons: float) -> str:
    return "n/a" if not math.isfinite(newtons) else f"{newtons / 1e3:.2f}"


def _fraction(value: float) -> str:
    return "n/a" if not math.isfinite(value) else f"{value:.3f}"


# ``pounding.sweep(...)``: the module is callable, so the name works whether
# ``pounding.sweep`` resolves to this module or to the function.
class _CallableModule(types.ModuleType):
    def __call__(self, *args, **kwargs):
        return sweep(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
