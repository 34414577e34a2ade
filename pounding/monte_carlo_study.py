"""The Monte Carlo side of a fragility curve or a force spectrum: every
record's F_max at each adjusted case, on the sweep's engine (Dask, resumable,
the same numbers whatever the workers), in a folder of the user's or a
temporary one."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from .case import as_case
from .errors import CaseError
from .monte_carlo_result import quantile_interval, wilson_interval

__all__ = ["MonteCarloForces", "forces_at"]


@dataclass(frozen=True, eq=False)
class MonteCarloForces:
    """Every record's F_max [N] at each point of a fragility curve or a force spectrum, record i seeded alike at
    every point (``seed``)."""

    force_max: tuple[np.ndarray, ...]
    seed: int

    @property
    def records(self) -> int:
        return int(self.force_max[0].size)

    @property
    def force_mean(self) -> np.ndarray:
        """E[F_max] at each point [N]."""
        return np.array([float(np.mean(f)) for f in self.force_max])

    def force_mean_interval(self) -> np.ndarray:
        """95 % Student-t interval of each mean [N], shape (points, 2)."""
        from scipy.special import stdtrit

        half = float(stdtrit(self.records - 1, 0.975)) * np.array([np.std(f, ddof=1) for f in self.force_max]) / np.sqrt(self.records)
        return np.column_stack([self.force_mean - half, self.force_mean + half])

    def quantile(self, probability: float) -> tuple[np.ndarray, np.ndarray]:
        """The empirical quantile [N] at each point, and its distribution-free 95 % interval, shape (points, 2)."""
        rows = [quantile_interval(f, probability) for f in self.force_max]
        return np.array([r[0] for r in rows]), np.array([[r[1], r[2]] for r in rows], dtype=float)

    def exceeding(self, capacity: float) -> np.ndarray:
        """Records with F_max > capacity [N] at each point."""
        return np.array([int(np.sum(forces > capacity)) for forces in self.force_max])

    def intervals(self, capacity: float) -> np.ndarray:
        """Wilson's 95 % interval of the exceeding fraction at each point, shape (points, 2)."""
        return np.array([wilson_interval(int(k), self.records) for k in self.exceeding(capacity)])


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
