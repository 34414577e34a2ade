"""The Monte Carlo side of a fragility curve or a force spectrum: every
record's F_max at each adjusted case, on the sweep's engine (Dask, resumable,
the same numbers whatever the workers), in a folder of the user's or a
temporary one."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from .case import as_case
from .errors import CaseError

__all__ = ["forces_at"]


def forces_at(
    case,
    adjustments: Sequence[Mapping],
    records: int,
    seed: int,
    work_dir: str | os.PathLike | None,
    scheduler,
    workers: int | None,
    progress: Callable[[int, int], None] | None,
    label: str,
) -> list[np.ndarray]:
    """Every record's F_max [N] at each of ``adjustments`` of ``case`` (a preset name, a case file or the parsed
    file): :func:`pounding.sweeps.monte_carlo_forces`, its chunks in ``work_dir`` (resumable) or in a temporary
    folder removed at the end. A recorded case takes the first ``records`` of its suite."""
    loaded = as_case(case)
    if loaded.recorded and records > len(loaded.hazard.records):
        raise CaseError("records", f"the case has {len(loaded.hazard.records)} recorded motions; give --records at most that")
    from .sweeps import monte_carlo_forces

    if work_dir is not None:
        return monte_carlo_forces(case, adjustments, records, seed, work_dir, scheduler, progress=progress, workers=workers, label=label)
    with tempfile.TemporaryDirectory(prefix="pounding-") as folder:
        return monte_carlo_forces(case, adjustments, records, seed, folder, scheduler, progress=progress, workers=workers, label=label)
