"""The per-record peaks of a Monte Carlo study and their summary."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import bdtr, ndtri, stdtrit  # binomial CDF, normal and t quantiles; scipy.stats is slow to import

from pounding import defaults
from pounding.case.case import Case
from pounding.simulation.system import Settings

__all__ = ["SimulationResult", "quantile_interval", "wilson_interval"]


@dataclass(frozen=True)
class SimulationResult:
    """Per-record peaks of a Monte Carlo study, and their summary.

    All arrays have one entry per record, in record order.

    Attributes
    ----------
    force_max : ndarray
        Extreme pounding force max_t ``|F(t)|`` [N], Eq. 11 (0 without pounding).
    impacts : ndarray
        Number of impacts.
    penetration_max : ndarray
        Peak penetration [m].
    impact_velocity_max : ndarray
        Largest approach velocity at the onset of an impact [m/s].
    displacement_max : ndarray, shape (n_records, 2)
        Peak ``|displacement|`` of the contact floor of building 1 and 2 [m].
    relative_displacement_max : ndarray
        Peak of X = x1 - x2 at the contact floors over the accepted steps [m].
    steps : ndarray
        Accepted integration steps.
    """

    case: Case
    seed: int
    indices: np.ndarray
    force_max: np.ndarray
    impacts: np.ndarray
    penetration_max: np.ndarray
    impact_velocity_max: np.ndarray
    displacement_max: np.ndarray
    relative_displacement_max: np.ndarray
    steps: np.ndarray
    settings: Settings

    @property
    def n_records(self) -> int:
        return self.force_max.size

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
        """95 % confidence interval of the mean extreme force (Student t) [N], cut at 0 below: a force is never
        negative, so neither is its mean (a few pounding records among many that do not widen it past 0)."""
        if self.n_records < 2:
            return (0.0, math.inf)
        half = stdtrit(self.n_records - 1, 0.975) * self.force_max_std_error
        return (max(0.0, self.force_max_mean - half), self.force_max_mean + half)

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
        motions, ``record_files`` names each record and ``seed`` is null."""
        low, high = self.force_max_confidence_interval
        recorded = {"record_files": [self.case.hazard.records[int(i)].name for i in self.indices]} if self.case.recorded else {}
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
            "displacement_max": self.displacement_max.tolist(),
            "relative_displacement_max": self.relative_displacement_max.tolist(),
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
