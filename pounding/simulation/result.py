"""The per-record peaks of a Monte Carlo study and their summary."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.special import bdtr, ndtri, stdtrit  # binomial CDF, normal and t quantiles; scipy.stats is slow to import

from pounding import defaults
from pounding.case.case import Case
from pounding.mechanics.contact import Contact
from pounding.simulation.system import Settings

__all__ = ["ContactPeaks", "SimulationResult", "mean_interval", "quantile_interval", "wilson_interval"]


def mean_interval(values: np.ndarray) -> tuple[float, float]:
    """95 % confidence interval of the mean of per-record peaks (Student t) [same unit], cut at 0 below: a peak
    force is never negative, so neither is its mean; (0, inf) from one record."""
    if values.size < 2:
        return (0.0, math.inf)
    mean = float(np.mean(values))
    half = stdtrit(values.size - 1, 0.975) * float(np.std(values, ddof=1)) / math.sqrt(values.size)
    return (max(0.0, mean - half), mean + half)


@dataclass(frozen=True)
class ContactPeaks:
    """Per-record peaks at one contact of a Monte Carlo study, one entry per record.

    Attributes
    ----------
    contact : Contact
    force_max : ndarray
        Extreme pounding force max_t ``|F(t)|`` at this contact [N], Eq. 11 (0 without pounding).
    impacts : ndarray
        Number of impacts.
    penetration_max : ndarray
        Peak penetration [m].
    impact_velocity_max : ndarray
        Largest approach velocity at the onset of an impact [m/s].
    displacement_max : ndarray, shape (n_records, 2)
        Peak ``|displacement|`` of the contact's left and right floor [m].
    relative_displacement_max : ndarray
        Peak of X = x_left - x_right at the contact's floors over the accepted steps [m].
    """

    contact: Contact
    force_max: np.ndarray
    impacts: np.ndarray
    penetration_max: np.ndarray
    impact_velocity_max: np.ndarray
    displacement_max: np.ndarray
    relative_displacement_max: np.ndarray

    def to_dict(self) -> dict:
        """JSON-ready, SI units: the summary and the per-record values."""
        low, high = mean_interval(self.force_max)
        return {
            "between": list(self.contact.between),
            "levels": list(self.contact.levels),
            "force_max_mean": float(np.mean(self.force_max)),
            "force_max_confidence_interval": [_finite_or_none(low), _finite_or_none(high)],
            "pounding_fraction": float(np.mean(self.impacts > 0)),
            "impacts_mean": float(np.mean(self.impacts)),
            "force_max": self.force_max.tolist(),
            "impacts": self.impacts.astype(int).tolist(),
            "penetration_max": self.penetration_max.tolist(),
            "relative_displacement_max": self.relative_displacement_max.tolist(),
        }


def _joined_arrays(kind, parts: list):
    """Consecutive studies' dataclasses of ``kind``, their arrays joined in record order."""
    arrays = {f.name: np.concatenate([getattr(p, f.name) for p in parts]) for f in dataclasses.fields(kind)
              if isinstance(getattr(parts[0], f.name), np.ndarray)}
    return dataclasses.replace(parts[0], **arrays)


@dataclass(frozen=True)
class SimulationResult:
    """Per-record peaks of a Monte Carlo study, and their summary.

    All arrays have one entry per record, in record order. The force, impact
    and penetration arrays are over all contacts (the largest force, the
    impacts' count); ``contacts`` has each contact's.

    Attributes
    ----------
    contacts : tuple of ContactPeaks
        In the case's order.
    steps : ndarray
        Accepted integration steps.
    """

    case: Case
    seed: int
    indices: np.ndarray
    contacts: tuple[ContactPeaks, ...]
    steps: np.ndarray
    settings: Settings

    @classmethod
    def joined(cls, parts: list[SimulationResult]) -> SimulationResult:
        """Consecutive studies of one case and seed as one."""
        if len(parts) == 1:
            return parts[0]
        contacts = tuple(_joined_arrays(ContactPeaks, [p.contacts[c] for p in parts]) for c in range(len(parts[0].contacts)))
        return dataclasses.replace(_joined_arrays(cls, parts), contacts=contacts)

    @cached_property
    def force_max(self) -> np.ndarray:
        """Extreme pounding force over all contacts [N], Eq. 11 (0 without pounding)."""
        return np.max([c.force_max for c in self.contacts], axis=0)

    @cached_property
    def impacts(self) -> np.ndarray:
        """Number of impacts, all contacts together."""
        return np.sum([c.impacts for c in self.contacts], axis=0)

    @cached_property
    def penetration_max(self) -> np.ndarray:
        """Peak penetration over all contacts [m]."""
        return np.max([c.penetration_max for c in self.contacts], axis=0)

    @cached_property
    def impact_velocity_max(self) -> np.ndarray:
        """Largest approach velocity at the onset of an impact, over all contacts [m/s]."""
        return np.max([c.impact_velocity_max for c in self.contacts], axis=0)

    @property
    def displacement_max(self) -> np.ndarray:
        """Peak ``|displacement|`` of the one contact's floors, shape (n_records, 2) [m]
        (a case of several contacts: each contact's, in ``contacts``)."""
        return self._one_contact.displacement_max

    @property
    def relative_displacement_max(self) -> np.ndarray:
        """Peak of X = x1 - x2 at the one contact's floors [m] (several contacts: each contact's, in ``contacts``)."""
        return self._one_contact.relative_displacement_max

    @property
    def _one_contact(self) -> ContactPeaks:
        self.case.contact  # noqa: B018 -- CaseError naming ``contacts`` when the case has several
        return self.contacts[0]

    @property
    def n_records(self) -> int:
        return self.steps.size

    @property
    def force_max_mean(self) -> float:
        """Mean extreme pounding force over all records [N] (records without
        pounding count as 0)."""
        return float(np.mean(self.force_max))

    @property
    def force_max_std_error(self) -> float:
        """Standard error of ``force_max_mean`` [N]."""
        if self.n_records < 2:
            return math.inf
        return float(np.std(self.force_max, ddof=1) / math.sqrt(self.n_records))

    @property
    def force_max_confidence_interval(self) -> tuple[float, float]:
        """95 % confidence interval of the mean extreme force (:func:`mean_interval`) [N]."""
        return mean_interval(self.force_max)

    @property
    def pounding_fraction(self) -> float:
        """Fraction of records with at least one impact [-]."""
        return float(np.mean(self.impacts > 0))

    @property
    def impacts_mean(self) -> float:
        """Mean number of impacts per record."""
        return float(np.mean(self.impacts))

    def force_max_quantile(self, probability: float) -> tuple[float, float | None, float | None]:
        """The empirical ``probability`` quantile of F_max [N] and its 95 % interval (:func:`quantile_interval`)."""
        return quantile_interval(self.force_max, probability)

    def exceedance(self, capacity: float) -> dict:
        """The fraction of records with F_max > capacity [N] and its 95 % Wilson interval (JSON keys)."""
        exceeding = int(np.sum(self.force_max > capacity))
        return {"probability_exceeding": exceeding / self.n_records,
                "probability_exceeding_interval": list(wilson_interval(exceeding, self.n_records))}

    def to_dict(self) -> dict:
        """JSON-ready summary and per-record values, SI units; for recorded
        motions, ``record_files`` names each record and ``seed`` is null. The top-level force is the
        largest over all contacts; ``contacts`` has each contact's, in the case's order."""
        low, high = self.force_max_confidence_interval
        recorded = {"record_files": [self.case.hazard.records[int(i)].name for i in self.indices]} if self.case.recorded else {}
        one_contact = len(self.contacts) == 1
        return {
            "case": self.case.name,
            "seed": None if self.case.recorded else self.seed,
            **recorded,
            "records": self.n_records,
            "duration": _durations(self),
            "force_max_mean": self.force_max_mean,
            # One record has no standard error: null, not JSON's non-standard Infinity.
            "force_max_std_error": _finite_or_none(self.force_max_std_error),
            "force_max_ci95": [_finite_or_none(low), _finite_or_none(high)],
            "pounding_fraction": self.pounding_fraction,
            "force_max_quantiles": {key: self.force_max_quantile(float(key))[0] for key in defaults.FORCE_QUANTILES},
            "force_max_quantiles_ci95": {key: list(self.force_max_quantile(float(key))[1:]) for key in defaults.FORCE_QUANTILES},
            "impacts_mean": self.impacts_mean,
            "force_max": self.force_max.tolist(),
            "impacts": self.impacts.astype(int).tolist(),
            "penetration_max": self.penetration_max.tolist(),
            "impact_velocity_max": self.impact_velocity_max.tolist(),
            **({"displacement_max": self.displacement_max.tolist(),
                "relative_displacement_max": self.relative_displacement_max.tolist()} if one_contact else {}),
            "contacts": [c.to_dict() for c in self.contacts],
            "units": {"force": "N", "length": "m", "velocity": "m/s", "duration": "s"},
        }


def _finite_or_none(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def quantile_interval(values, probability: float) -> tuple[float, float | None, float | None]:
    """The empirical ``probability`` quantile of ``values`` and a distribution-free 95 % interval from the
    order statistics: x_(l) and x_(u) with P(B < l) <= 0.025 and P(B < u) >= 0.975, B binomial(n, probability)
    (then P(x_(l) <= q < x_(u)) >= 0.95 for any continuous law); an end is None where n is too small for it."""
    ordered = np.sort(np.asarray(values, dtype=float))
    n = ordered.size
    cumulative = bdtr(np.arange(n + 1), n, probability)  # P(B <= k), k = 0..n
    lows = np.flatnonzero(cumulative[:n] <= 0.025)  # P(B <= l - 1) <= 0.025, l = k + 1
    highs = np.flatnonzero(cumulative[:n] >= 0.975)  # P(B <= u - 1) >= 0.975, u = k + 1
    low = float(ordered[lows[-1]]) if lows.size else None
    high = float(ordered[highs[0]]) if highs.size else None
    return float(np.quantile(ordered, probability)), low, high


def wilson_interval(successes: int, trials: int) -> tuple[float, float]:
    """Wilson's 95 % score interval of a binomial proportion."""
    z = float(ndtri(0.975))
    fraction = successes / trials
    centre = (fraction + z * z / (2 * trials)) / (1 + z * z / trials)
    half = z * math.sqrt(fraction * (1 - fraction) / trials + z * z / (4 * trials * trials)) / (1 + z * z / trials)
    return max(0.0, centre - half), min(1.0, centre + half)


def _durations(result: SimulationResult) -> float | list[float]:
    """The records' duration [s]: one for synthetic records, one per record for recorded motions."""
    if result.case.recorded:
        return [result.case.hazard.records[int(i)].duration for i in result.indices]
    return result.case.excitation.duration
