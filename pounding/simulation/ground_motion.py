"""The ground-motion records a Monte Carlo study integrates: synthetic records
drawn from the case's excitation (seeded one by one), or the case's recorded
accelerograms, each once, as sampled."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from pounding.case.case import Case
from pounding.errors import ArgumentError
from pounding.hazard.excitation import ground_accelerations

__all__ = ["check_suite_range", "ground_motion_batches", "record_names", "samples_per_record", "suite_size"]


def suite_size(case: Case) -> int | None:
    """The number of recorded accelerograms of ``case``; None for synthetic records."""
    return len(case.hazard.records) if case.recorded else None


def samples_per_record(case: Case) -> int:
    """The most samples of one record of the study."""
    if case.recorded:
        return max(record.acceleration.size for record in case.hazard.records)
    return case.excitation.n_samples


def record_names(case: Case, seed: int, indices) -> list[str]:
    """How each record is named in messages and files: its file for a recorded suite, else its index and seed."""
    if case.recorded:
        return [case.hazard.records[int(i)].name for i in indices]
    return [f"record {int(i)} (seed {seed})" for i in indices]


def check_suite_range(case: Case, records: int, first_record: int) -> None:
    """:class:`ArgumentError` (``records``) when records ``first_record .. first_record + records - 1`` are not all in the recorded suite."""
    size = suite_size(case)
    if size is not None and first_record + records > size:
        raise ArgumentError("records", f"the case has {size} recorded motions; records {first_record}..{first_record + records - 1} "
                            "are not all among them")


def ground_motion_batches(case: Case, seed: int, indices) -> Iterator[tuple[slice, np.ndarray, float]]:
    """The records ``indices`` as (rows, accelerations [m/s^2] one per row, time step [s]) batches:
    one batch of synthetic records, or one recorded accelerogram per batch (lengths and steps differ)."""
    indices = np.asarray(indices, dtype=np.int64).ravel()
    if not case.recorded:
        yield slice(0, indices.size), ground_accelerations(case.excitation, seed, indices), case.excitation.time_step
        return
    for row, index in enumerate(indices):
        record = case.hazard.records[int(index)]
        yield slice(row, row + 1), record.acceleration[None, :], record.time_step
