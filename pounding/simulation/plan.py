"""How a Monte Carlo study runs, held in one object: which records (count, seed, first), the integrator's
numerical settings, the Dask engine of a study of many points, and the caller's progress and cancel hooks.
:func:`~pounding.simulation.monte_carlo.simulate`, :func:`~pounding.simulation.monte_carlo.design_gap`,
:func:`pounding.sweep`, fragility curves and force spectra all take it."""

from __future__ import annotations

import dataclasses
import os
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from pounding import defaults
from pounding.errors import ArgumentError, described, whole_number
from pounding.simulation.system import Settings, check_records, check_settings

__all__ = ["MonteCarloPlan", "as_plan"]


@dataclass(frozen=True)
class MonteCarloPlan:
    """How a Monte Carlo study runs.

    Attributes
    ----------
    records : int or None
        Records of the study (at each point of a study of many points), 1 to ``defaults.MAX_RECORDS``. None: the
        taker's default (``defaults.RECORDS`` or a recorded case's whole suite for ``simulate``,
        ``defaults.DESIGN_GAP_RECORDS`` for ``design_gap``, ``defaults.SWEEP_RECORDS`` for a sweep).
    seed : int
        Seed of the study: record i is drawn alike by every taker and at every point; the same case and seed give
        the same numbers.
    work_dir : path, optional
        Folder of a study's finished chunks (fragility curves, force spectra): rerun with it to resume. None: a
        temporary folder, removed at the end. (A sweep writes to its own ``output_dir``.)
    scheduler : optional
        The Dask engine of a study of many points: None starts a local cluster, ``"serial"`` runs in this
        process, a ``distributed.Client`` or a scheduler's address uses that cluster.
    workers : int, optional
        Worker processes of that local cluster (default: one per core).
    progress : callable, optional
        ``progress(done, total)``, in records, after each chunk.
    cancel : threading.Event, optional
        When set, ``simulate`` and ``design_gap`` stop at the next chunk and raise ``Cancelled``.
    first_record : int
        Index of the first record (``simulate``).
    settings : Settings
        The integrator's numerical settings: tolerance, runaway limit, threads of one process, records per
        thread's chunk (None: the defaults).
    chunk_records : int
        Records per task of a study on Dask (resumed chunk by chunk; the numbers do not depend on it).
    """

    records: int | None = None
    seed: int = defaults.SEED
    work_dir: str | os.PathLike | None = None
    scheduler: object = None
    workers: int | None = None
    progress: Callable[[int, int], None] | None = None
    cancel: threading.Event | None = None
    first_record: int = 0
    settings: Settings | None = field(default_factory=Settings)
    chunk_records: int = defaults.CHUNK_RECORDS

    def __post_init__(self):
        if self.records is not None:
            records, seed, first_record = check_records(self.records, self.seed, self.first_record)
        else:
            _, seed, first_record = check_records(1, self.seed, self.first_record)
            records = None
        object.__setattr__(self, "settings", check_settings(self.settings))
        if self.progress is not None and not callable(self.progress):
            raise ArgumentError("progress", f"must be a function progress(done, total) or None, got {described(self.progress)}")
        if self.cancel is not None and not callable(getattr(self.cancel, "is_set", None)):
            raise ArgumentError("cancel", f"must be a threading.Event or None, got {described(self.cancel)}")
        workers = None if self.workers is None else whole_number("workers", self.workers, 1, error=ArgumentError)
        chunk_records = whole_number("chunk_records", self.chunk_records, 1, error=ArgumentError)
        for name, value in (("records", records), ("seed", seed), ("first_record", first_record), ("workers", workers),
                            ("chunk_records", chunk_records)):
            object.__setattr__(self, name, value)

    def with_records(self, default: int) -> MonteCarloPlan:
        """This plan, with ``default`` records where it names none."""
        return self if self.records is not None else dataclasses.replace(self, records=default)


_FIELDS = tuple(f.name for f in dataclasses.fields(MonteCarloPlan))


def as_plan(plan: MonteCarloPlan | None = None, changes: Mapping | None = None) -> MonteCarloPlan:
    """``plan`` (a default one when None) with ``changes``, fields of :class:`MonteCarloPlan` given as keyword
    arguments (``simulate(case, records=200, seed=1)``); an unknown name is refused, naming it."""
    if plan is None:
        plan = MonteCarloPlan()
    elif not isinstance(plan, MonteCarloPlan):
        raise ArgumentError("plan", f"must be a MonteCarloPlan or None, got {described(plan)}")
    changes = dict(changes or {})
    unknown = sorted(set(changes) - set(_FIELDS))
    if unknown:
        raise ArgumentError(unknown[0], f"is not an option of a Monte Carlo study; the options are {', '.join(_FIELDS)}")
    return dataclasses.replace(plan, **changes) if changes else plan
