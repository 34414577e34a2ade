"""What the time-history kernel is given: the numerical settings of a
simulation, and a case packed into the kernel's arrays."""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from pounding import defaults
from pounding.case.case import Case, as_case
from pounding.errors import (
    ArgumentError,
    SimulationError,
    check_limit,
    described,
    finite_number,
    quote,
    whole_number,
)
from pounding.mechanics import integrator as kernel

__all__ = ["Cancelled", "KernelSystem", "Settings", "check_records", "check_settings", "check_study", "failure", "floor_index",
           "kernel_system"]

_LAST_INDEX = 2**63 - 1  # record indices are int64

_FAILURES = {
    kernel.NOT_FINITE: "the response became NaN or infinite",
    kernel.RUNAWAY: "a floor displacement exceeded the runaway limit of {limit:g} m",
    kernel.STEP_UNDERFLOW: "the step size fell below 1e-12 s (the system is too stiff to resolve)",
    kernel.STEP_LIMIT: f"it needs over {kernel.TRIALS_PER_SAMPLE} steps a sample: too stiff to integrate in time (check the contact "
    "stiffness and the masses)",
}


MAX_WORKERS = 1024
"""Most threads a study may run on (``Settings.workers``)."""


class Cancelled(Exception):
    """A simulation was cancelled through its ``cancel`` event."""


@dataclass(frozen=True)
class Settings:
    """Numerical settings of the time-history analysis.

    Parameters
    ----------
    tolerance : float
        Relative tolerance of the local error per step [-]; the absolute
        tolerances are tolerance * 1 mm on displacements and hysteretic
        displacements, tolerance * 1 cm/s on velocities.
    displacement_limit : float
        A floor displacement beyond this [m] is reported as a runaway response.
    workers : int or None
        Threads running records in parallel, 1 to 1024; None uses every core.
    chunk_size : int
        Records per task (progress is reported per chunk).
    """

    tolerance: float = defaults.INTEGRATOR_TOLERANCE
    displacement_limit: float = defaults.DISPLACEMENT_LIMIT
    workers: int | None = None
    chunk_size: int = 8

    def __post_init__(self):
        tolerance = finite_number("tolerance", self.tolerance, error=ArgumentError)
        if not 1e-12 <= tolerance <= 1e-2:
            raise ArgumentError("tolerance", f"must lie in [1e-12, 1e-2], got {quote(tolerance)}")
        limit = finite_number("displacement_limit", self.displacement_limit, error=ArgumentError)
        if not limit > 0:
            raise ArgumentError("displacement_limit", f"must be > 0 m, got {quote(limit)}")
        workers = None if self.workers is None else whole_number("workers", self.workers, 1, MAX_WORKERS, error=ArgumentError)
        chunk_size = whole_number("chunk_size", self.chunk_size, 1, error=ArgumentError)
        for name, value in (("tolerance", tolerance), ("displacement_limit", limit), ("workers", workers), ("chunk_size", chunk_size)):
            object.__setattr__(self, name, value)

    @property
    def n_workers(self) -> int:
        return self.workers or os.cpu_count() or 1


@dataclass(frozen=True)
class KernelSystem:
    """The case packed into the kernel's arrays."""

    floors: np.ndarray
    below: np.ndarray
    contacts: np.ndarray
    contact_floors: np.ndarray
    atol: np.ndarray

    @property
    def n_floors(self) -> int:
        return self.below.size


def check_records(records, seed, first_record) -> tuple[int, int, int]:
    """The record count, seed and first record as Python ints, checked
    (numpy integers accepted; the count against MAX_RECORDS)."""
    records = whole_number("records", records, 1, error=ArgumentError)
    check_limit("records", records, defaults.MAX_RECORDS, "records", "fewer records suffice for a mean", error=ArgumentError)
    seed = whole_number("seed", seed, 0, error=ArgumentError)
    first_record = whole_number("first_record", first_record, 0, error=ArgumentError)
    if first_record + records > _LAST_INDEX:
        raise ArgumentError("first_record", f"first_record + records must be at most 2^63 - 1, got {quote(first_record)}")
    return records, seed, first_record


def check_settings(settings) -> Settings:
    """``settings``, or the default ``Settings()`` for None; :class:`ArgumentError` for anything else."""
    settings = Settings() if settings is None else settings
    if not isinstance(settings, Settings):
        raise ArgumentError("settings", f"must be a Settings or None, got {described(settings)}")
    return settings


def check_study(case, settings) -> tuple[Case, Settings]:
    """The case (a Case, a preset name or a TOML path) and the settings, checked."""
    return as_case(case), check_settings(settings)


def kernel_system(case: Case, settings: Settings) -> KernelSystem:
    """``case`` packed into the kernel's arrays (:mod:`pounding.mechanics.integrator`), tolerances from ``settings``."""
    rows, below = [], []
    for building in case.buildings:
        offset = len(rows)
        for number, (storey, damping) in enumerate(zip(building.storeys, building.storey_damping())):
            bw = storey.bouc_wen
            rows.append([storey.mass, storey.stiffness, damping, bw.alpha, bw.A, bw.beta, bw.gamma, bw.n])
            below.append(offset + number - 1 if number > 0 else -1)
    contacts = np.array([[c.model_code, c.gap, c.stiffness, c.damping_ratio(), case.reduced_mass_of(c)] for c in case.contacts])
    contact_floors = np.array([[floor_index(case, b, level) for b, level in zip(c.between, c.levels)] for c in case.contacts],
                              dtype=np.int64)
    n = len(rows)
    atol = np.concatenate([np.full(n, 1e-3), np.full(n, 1e-2), np.full(n, 1e-3)]) * settings.tolerance
    return KernelSystem(
        floors=np.array(rows, dtype=float),
        below=np.array(below, dtype=np.int64),
        contacts=contacts,
        contact_floors=contact_floors,
        atol=atol,
    )


def floor_index(case: Case, building: int, level: int) -> int:
    """Index in the kernel's state of floor ``level`` of ``building`` (both counted from 1): the floors of
    building 1, then 2, and so on."""
    return sum(b.n_storeys for b in case.buildings[: building - 1]) + level - 1


def failure(summary: np.ndarray, label: str, settings: Settings) -> SimulationError:
    """The error for a record whose kernel status is not OK."""
    reason = _FAILURES[int(summary[kernel.S_STATUS])].format(limit=settings.displacement_limit)
    return SimulationError(f"{label} failed at t = {summary[kernel.S_TIME]:.4f} s: {reason}")
