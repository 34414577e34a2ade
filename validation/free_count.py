"""The gap-aware force counted otherwise than the estimator counts it: on the
free motion (without the impacts' damping of the motion between impacts, the
count the estimator used before, ``estimate(case, impact_damping=False)``
until the library dropped that option), or with another count of the largest
approach in place of Vanmarcke's clumps. Built from the public blocks of
:mod:`pounding.closed_form.gap_aware`, for comparisons only.

    from validation.free_count import free_estimate
    free_estimate(case).force_expected          # the free count [N]
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from pounding.case.case import Case
from pounding.closed_form.gap_aware import Crossings, expected_force_maximum, opposing_forces
from pounding.closed_form.impact_damping import DampedMotion
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import accuracy_regime

__all__ = ["CountedCrossings", "FreeEstimate", "free_estimate", "free_estimate_force", "linearized"]


def linearized(case_or_pair) -> LinearizedPair:
    """``case_or_pair`` as a :class:`~pounding.closed_form.pair.LinearizedPair` (a case is linearized)."""
    return case_or_pair if isinstance(case_or_pair, LinearizedPair) else LinearizedPair.of(case_or_pair)


@dataclasses.dataclass(frozen=True)
class CountedCrossings(Crossings):
    """:class:`~pounding.closed_form.gap_aware.Crossings` whose count of the largest approach
    (:meth:`impacting_intensity`) is ``count(crossings, gaps, velocities, motion)``
    -> Lambda of shape (gaps, velocities), ``motion`` the damped motion at the gaps
    (ratios 1 on the free motion: ``free=True``, the count without the impacts'
    damping); the pounding probability and the required gap (:meth:`intensity`)
    keep the estimator's."""

    count: Callable | None = None
    free: bool = False

    def damped(self, gaps) -> DampedMotion:
        if self.free:
            return DampedMotion.undamped(np.asarray(gaps, dtype=float).size, self.bandwidth)
        return super().damped(gaps)

    def impacting_intensity(self, gaps, velocities, motion) -> np.ndarray:
        if self.count is None:
            return super().impacting_intensity(gaps, velocities, motion)
        return np.asarray(self.count(self, gaps, velocities, motion), dtype=float)


@dataclasses.dataclass(frozen=True)
class FreeEstimate:
    """What the scripts read of an estimate counted otherwise: the force [N]
    and what it stood on (the sigmas with the residual's response, [m] and
    [m/s]; the braking force at the gap [N]; the regime the estimator states)."""

    case: Case
    crossings: Crossings
    force_expected: float
    sigma_relative_displacement: float
    sigma_relative_velocity: float
    opposing_force: float
    accuracy_regime: str


def free_estimate(case_or_pair, count: Callable | None = None, damped: bool = False) -> FreeEstimate:
    """The gap-aware force of a case or :class:`~pounding.closed_form.pair.LinearizedPair`,
    the largest approach counted on the free motion (``damped=False``) or on
    the motion the impacts damp (``damped=True``, the estimator's), by the
    estimator's count or by ``count`` (see :class:`CountedCrossings`)."""
    pair = linearized(case_or_pair)
    case = pair.case
    crossings = Crossings.of(pair)
    fields = {f.name: getattr(crossings, f.name) for f in dataclasses.fields(Crossings)}
    crossings = CountedCrossings(**fields, count=count, free=not damped)
    gap = np.array([case.contact.gap])
    response = pair.response_with_residual
    force = float(expected_force_maximum(crossings, gap, case.contact, case.reduced_mass, crossings.damped(gap))[0])
    regime = accuracy_regime(case.contact.gap, response.sigma_relative_displacement, pair.residual_share, pair.bandwidth)
    return FreeEstimate(
        case=case,
        crossings=crossings,
        force_expected=force,
        sigma_relative_displacement=response.sigma_relative_displacement,
        sigma_relative_velocity=response.sigma_relative_velocity,
        opposing_force=float(opposing_forces(crossings, gap, case.reduced_mass)[0]),
        accuracy_regime=regime,
    )


def free_estimate_force(case_or_pair) -> float:
    """E[F_max] [N] with the largest approach counted on the free motion."""
    return free_estimate(case_or_pair).force_expected
