"""The Monte Carlo side of a fragility curve or a force spectrum: every
record's F_max at each adjusted case, on the sweep's engine (Dask, resumable,
the same numbers whatever the workers), run as a :class:`~pounding.simulation.plan.MonteCarloPlan` says, in
its folder or a temporary one."""

from __future__ import annotations

import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from pounding import defaults
from pounding.case.case import as_case
from pounding.errors import ArgumentError, check_limit, quote
from pounding.simulation.plan import MonteCarloPlan
from pounding.simulation.result import quantile_interval, wilson_interval

__all__ = ["MonteCarloForces", "check_plan_records", "monte_carlo_forces_at"]


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


def check_plan_records(plan: MonteCarloPlan, minimum: int, why: str) -> None:
    """:class:`ArgumentError` naming ``records`` unless the plan names at least ``minimum`` records (``why`` says what
    for)."""
    if plan.records is None or plan.records < minimum:
        raise ArgumentError("records", f"must be at least {minimum} {why}, got {quote(plan.records)}")


def monte_carlo_forces_at(plan: MonteCarloPlan, case, adjustments: Sequence[Mapping], label: str) -> MonteCarloForces:
    """Every record's F_max at each of ``adjustments`` of ``case`` (a preset name, a case file or the parsed
    file; a loaded Case has no file for the workers to load), on the sweep's engine as ``plan`` says, in its
    ``work_dir`` (resumable) or a temporary folder: :func:`pounding.studies.sweeps.monte_carlo_forces`."""
    from pounding.case.case import Case

    if isinstance(case, Case):
        raise ArgumentError("case", "the Monte Carlo runs on the case file: give a preset name, a path or the parsed file")
    check_limit("records", len(adjustments) * plan.records, defaults.MAX_TIME_HISTORIES, "time histories (points x records)",
                "give fewer points or records", error=ArgumentError)
    loaded = as_case(case)
    if loaded.recorded and plan.records > len(loaded.hazard.records):
        raise ArgumentError("records", f"the case has {len(loaded.hazard.records)} recorded motions; give records at most that")
    from pounding.studies.sweeps import monte_carlo_forces

    if plan.work_dir is not None:
        return MonteCarloForces(tuple(monte_carlo_forces(case, adjustments, plan, plan.work_dir, label=label)), plan.seed)
    with tempfile.TemporaryDirectory(prefix="pounding-") as folder:
        return MonteCarloForces(tuple(monte_carlo_forces(case, adjustments, plan, folder, label=label)), plan.seed)
