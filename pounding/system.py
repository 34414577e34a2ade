"""What the time-history kernel is given: the numerical settings of a
simulation, and a case packed into the kernel's arrays."""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from . import defaults
from . import integrator as kernel
from .case import Case
from .errors import CaseError, SimulationError

__all__ = ["Cancelled", "KernelSystem", "Settings", "failure", "kernel_system"]

_FAILURES = {
    kernel.NOT_FINITE: "the response became NaN or infinite",
    kernel.RUNAWAY: "a floor displacement exceeded the runaway limit of {limit:g} m",
    kernel.STEP_UNDERFLOW: "the step size fell below 1e-12 s (the system is too stiff to resolve)",
}


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
        Threads running records in parallel; None uses every core.
    chunk_size : int
        Records per task (progress is reported per chunk).
    """

    tolerance: float = defaults.INTEGRATOR_TOLERANCE
    displacement_limit: float = 10.0
    workers: int | None = None
    chunk_size: int = 8

    def __post_init__(self):
        if not (isinstance(self.tolerance, float | int) and 1e-12 <= self.tolerance <= 1e-2):
            raise CaseError("tolerance", f"must lie in [1e-12, 1e-2], got {self.tolerance!r}")
        if not (isinstance(self.displacement_limit, float | int) and self.displacement_limit > 0):
            raise CaseError("displacement_limit", f"must be > 0 m, got {self.displacement_limit!r}")
        if self.workers is not None and not (isinstance(self.workers, int) and self.workers >= 1):
            raise CaseError("workers", f"must be a whole number >= 1, got {self.workers!r}")
        if not (isinstance(self.chunk_size, int) and self.chunk_size >= 1):
            raise CaseError("chunk_size", f"must be a whole number >= 1, got {self.chunk_size!r}")

    @property
    def n_workers(self) -> int:
        return self.workers or os.cpu_count() or 1


@dataclass(frozen=True)
class KernelSystem:
    """The case packed into the kernel's arrays."""

    floors: np.ndarray
    below: np.ndarray
    contact: np.ndarray
    floor_1: int
    floor_2: int
    atol: np.ndarray

    @property
    def n_floors(self) -> int:
        return self.below.size


def kernel_system(case: Case, settings: Settings) -> KernelSystem:
    """``case`` packed into the kernel's arrays (:mod:`pounding.integrator`), tolerances from ``settings``."""
    rows, below = [], []
    for building in case.buildings:
        offset = len(rows)
        for number, (storey, damping) in enumerate(zip(building.storeys, building.storey_damping())):
            bw = storey.bouc_wen
            rows.append([storey.mass, storey.stiffness, damping, bw.alpha, bw.A, bw.beta, bw.gamma, bw.n])
            below.append(offset + number - 1 if number > 0 else -1)
    n1 = case.buildings[0].n_storeys
    contact = case.contact
    contact_vector = np.array(
        [contact.model_code, contact.gap, contact.stiffness, contact.damping_ratio(), case.reduced_mass]
    )
    n = len(rows)
    atol = np.concatenate([np.full(n, 1e-3), np.full(n, 1e-2), np.full(n, 1e-3)]) * settings.tolerance
    return KernelSystem(
        floors=np.array(rows, dtype=float),
        below=np.array(below, dtype=np.int64),
        contact=contact_vector,
        floor_1=contact.levels[0] - 1,
        floor_2=n1 + contact.levels[1] - 1,
        atol=atol,
    )


def failure(summary: np.ndarray, label: str, settings: Settings) -> SimulationError:
    """The error for a record whose kernel status is not OK."""
    reason = _FAILURES[int(summary[kernel.S_STATUS])].format(limit=settings.displacement_limit)
    return SimulationError(f"{label} failed at t = {summary[kernel.S_TIME]:.4f} s: {reason}")
