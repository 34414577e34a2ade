"""The distribution of the extreme pounding force F_max, closed form
(docs/theory.md, G31), from the same count that gives its mean (G19).

The largest approach speed V_max is the extreme of a Poisson count of
approaches: P(V_max <= v) = exp(-Lambda(gap, v)), Lambda the impacting
motion's expected number of approaches faster than v (G8, G12-G13). The peak
force of one impact F(v) rises with v (G18), so

    P(F_max <= F(v)) = exp(-Lambda(gap, v)),   P(F_max = 0) = exp(-Lambda(gap, 0))     (G31)

(no impact: no force). Its mean is G19's E[F_max] = int P(F_max > f) df. Like G19 it counts the
impacting motion, also at v = 0; G21's pounding probability counts the free motion that the first impact
meets, so 1 - P(F_max = 0) differs from it by the impacts' damping (about 1 % on the Section 5 case).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pounding.closed_form.gap_aware import Crossings, opposing_forces
from pounding.closed_form.pair import LinearizedPair
from pounding.errors import ArgumentError, CaseError, ConvergenceError, check_probability, finite_number
from pounding.mechanics.contact import impact_peak_force
from pounding.random_vibration.crossing_kernels import U_MAX

__all__ = ["ForceDistribution", "force_distribution", "force_distribution_of", "gap_for_capacity"]

POINTS = 121
"""Speeds of the grid on which G31 is tabulated: G19's grid (uniform in v^p), so that :meth:`ForceDistribution.mean` is G19."""


@dataclass(frozen=True, eq=False)
class ForceDistribution:
    """P(F_max <= f) tabulated on ``forces`` [N] (increasing, from 0), G31."""

    forces: np.ndarray
    cdf: np.ndarray

    @property
    def no_impact_probability(self) -> float:
        """P(F_max = 0): no impact during the record [-]."""
        return float(self.cdf[0])

    def probability_below(self, force) -> np.ndarray:
        """P(F_max <= force) for forces [N] >= 0."""
        force = np.asarray(force, dtype=float)
        return np.interp(force, self.forces, self.cdf, right=1.0)

    def probability_exceeding(self, capacity: float) -> float:
        """P(F_max > capacity) for a capacity [N] > 0."""
        capacity = finite_number("capacity", capacity, error=ArgumentError)
        if not capacity > 0:
            raise ArgumentError("capacity", f"must be > 0 N, got {capacity:g}")
        return float(1.0 - self.probability_below(capacity))

    def quantile(self, probability: float) -> float:
        """The force [N] that F_max stays at or below with ``probability`` (0 where no impact is that likely)."""
        probability = check_probability(probability, "probability")
        if probability <= self.cdf[0]:
            return 0.0
        if probability >= self.cdf[-1]:
            return float(self.forces[-1])
        # the cdf may be flat in places: the first force where it reaches the probability
        return float(np.interp(probability, *_strictly_increasing(self.cdf, self.forces)))

    def mean(self) -> float:
        """E[F_max] = int (1 - P(F_max <= f)) df [N] (G19, on this grid)."""
        return float(np.trapezoid(1.0 - self.cdf, self.forces))


def _strictly_increasing(cdf: np.ndarray, forces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    keep = np.concatenate([[True], np.diff(cdf) > 0.0])
    return cdf[keep], forces[keep]


def force_distribution(crossings: Crossings, gap: float, contact, reduced_mass: float, motion, points: int = POINTS) -> ForceDistribution:
    """G31 at ``gap`` [m]: ``motion`` the impacting motion (``crossings.damped``) at that gap."""
    gaps = np.array([gap], dtype=float)
    power = contact.law.peak_force_exponent
    velocities = np.linspace(0.0, (U_MAX * crossings.sigma_v.max()) ** power, points) ** (1.0 / power)
    counts = crossings.impacting_intensity(gaps, velocities, motion)[0]
    opposing = opposing_forces(crossings, gaps, reduced_mass)[0] if counts[0] > 0.0 else 0.0
    forces = np.asarray(impact_peak_force(contact, velocities, reduced_mass, opposing), dtype=float)
    cdf = np.exp(-np.maximum(counts, 0.0))  # 1 - cdf is G19's exceedance
    cdf = np.maximum.accumulate(cdf)  # a count that does not fall (rounding) would make the cdf fall
    if not (np.all(np.isfinite(forces)) and np.all(np.diff(forces) >= 0.0) and math.isfinite(cdf[0])):
        raise CaseError("contact", "the peak force of an impact does not rise with its speed here: no distribution of F_max")
    return ForceDistribution(forces, cdf)


def force_distribution_of(case) -> ForceDistribution:
    """G31 of ``case`` (a Case, or its :class:`~pounding.closed_form.pair.LinearizedPair`) at its own gap, without the
    rest of an estimate (its mean is :func:`~pounding.estimate`'s E[F_max]). Two buildings that move alike never
    pound: F_max = 0 for sure (where :func:`~pounding.estimate` refuses the case, a spectrum passing T1 = T2 takes
    this point)."""
    pair = case if isinstance(case, LinearizedPair) else LinearizedPair.of(case)
    case = pair.case
    if pair.moves_alike:
        pair.check_runaway()
        return ForceDistribution(np.array([0.0, 1.0]), np.ones(2))
    crossings = Crossings.of(pair)
    gap = case.contact.gap
    return force_distribution(crossings, gap, case.contact, case.reduced_mass, crossings.damped(np.array([gap])))


SCAN_POINTS = 48
"""Gaps of the scan that brackets :func:`gap_for_capacity`'s answer before it is bisected: P(F_max > capacity) need
not fall monotonically with the gap (fewer but faster impacts), so the answer is the last crossing of the scan."""


def gap_for_capacity(crossings: Crossings, contact, reduced_mass: float, capacity: float, target_probability: float,
                     no_pounding_gap: float) -> float:
    """The smallest gap [m] from which on P(F_max > ``capacity`` [N]) stays at or below 1 - ``target_probability``
    (G31 at each gap): the gap sized to a force the connection or the slab can take, not to no contact at all.
    Scanned from 0 to twice ``no_pounding_gap`` [m] (G22's gap for the target, where no impact is that likely)
    and bisected where the probability last crosses the target; 0 where even touching buildings keep to it."""
    capacity = finite_number("capacity", capacity, error=ArgumentError)
    if not capacity > 0:
        raise ArgumentError("capacity", f"must be > 0 N, got {capacity:g}")
    limit = 1.0 - check_probability(target_probability, "target_probability")

    def exceeding(gap: float) -> float:
        distribution = force_distribution(crossings, gap, contact, reduced_mass, crossings.damped(np.array([gap])))
        return distribution.probability_exceeding(capacity)

    if exceeding(0.0) <= limit:
        return 0.0
    gaps = np.linspace(0.0, 2.0 * no_pounding_gap, SCAN_POINTS + 1)[1:]
    above = np.flatnonzero([exceeding(gap) > limit for gap in gaps])
    last = int(above[-1]) if above.size else -1
    if last == gaps.size - 1:
        raise ConvergenceError(f"P(F_max > {capacity:g} N) stays above {limit:g} up to twice the gap for no pounding "
                               f"({2.0 * no_pounding_gap:g} m): no gap for this capacity")
    low, high = (0.0 if last < 0 else float(gaps[last])), float(gaps[last + 1])
    while high - low > 1e-6 * high:
        middle = 0.5 * (low + high)
        low, high = (middle, high) if exceeding(middle) > limit else (low, middle)
    return high
