"""The gap-aware estimator's counts (docs/theory.md, G2-G22): the free
relative motion's sigma_X(t), sigma_V(t) from rest (:class:`Crossings`),
the expected number of approaches faster than v on the gap, the impacting
motion damped by its impacts, the expected largest approach speed and force,
and the gap for a target probability of no pounding.

The relative displacement X = x1 - x2 of the linearized pair, with the
response to the linearization's residual added, is seen as a Gaussian
process of frequency omega = sigma_V / sigma_X:

- an impact's approach velocity is that of an upcrossing of the gap by the
  free motion: Rayleigh, Rice's rate omega / (2 pi) exp(-(u^2 + rho^2) / 2)
  for crossings faster than v = rho sigma_V, u = d / sigma_X (G4);
- impacts start only from below the gap: Rice's rate per unit of time spent
  below it, divided by P(X < d) = Phi(u) (the time cut, G5);
- crossings of a high level come in clumps (Vanmarcke's factor, G6-G7);
- the largest approach is counted on the motion the impacts before it leave
  (:mod:`pounding.closed_form.impact_damping`, G10-G14); the pounding probability and the
  gap for a target probability on the free motion, which the first impact meets;
- counted as a Poisson process over the record, the largest approach
  velocity V_max (0 without impact) has P(V_max <= v) = exp(-Lambda(v)) (G8-G9);
- each impact peaks at the contact law's own force K F_H(v) against the
  buildings' mean force at the gap f0 = m (sigma_V / sigma_X)^2 d (G16-G18), and
  E[F_max] = int P(V_max > v) dF(v) (G19).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pounding.closed_form.impact_damping import DampedMotion, ImpactDamping
from pounding.errors import ConvergenceError
from pounding.mechanics.contact import Contact, impact_peak_force
from pounding.random_vibration.crossing_kernels import U_MAX, approach_intensity, merged_instants, required_gap
from pounding.random_vibration.peak_factors import VANMARCKE_CLUMP_EXPONENT
from pounding.random_vibration.peaks import VANMARCKE_DOUBLE_BARRIER

__all__ = [
    "Crossings",
    "expected_force_maximum",
    "expected_maximum",
    "gap_for_probability",
    "opposing_forces",
]

# The clump constant of G7 is Vanmarcke's sqrt(pi / 2) q^1.2: the impacts cross one barrier, the gap, yet are counted
# with his double-barrier constant, chosen by looking at Monte Carlo results (peaks.VANMARCKE_DOUBLE_BARRIER).
_MERGE_TOLERANCE = 1e-4  # instants whose sigmas agree to this are one (the built-up stationary part)


@dataclass(frozen=True)
class Crossings:
    """sigma_X(t), sigma_V(t) of the free linearized pair (with the residual's
    response) on a time grid, with trapezoid weights [s]; the bandwidth q of X
    and its stationary (sigma_V / sigma_X)^2 [1/s^2]; the impacts' damping of
    the relative motion."""

    sigma_x: np.ndarray
    sigma_v: np.ndarray
    weights: np.ndarray
    bandwidth: float
    frequency_squared: float
    damping: ImpactDamping

    @classmethod
    def of(cls, pair) -> Crossings:
        """The crossings of a :class:`~pounding.closed_form.pair.LinearizedPair`: its
        covariance history from rest, each variance scaled by its stationary
        ratio with the residual's response to the linearized one (G2-G3)."""
        pair.check_relative_motion()
        weights, history = pair.history_from_rest
        response, linear = pair.response_with_residual, pair.stationary_response
        variance_x = (history[:, 0, 0] + history[:, 1, 1] - 2 * history[:, 0, 1]) * (
            response.sigma_relative_displacement / linear.sigma_relative_displacement
        ) ** 2
        variance_v = (history[:, 2, 2] + history[:, 3, 3] - 2 * history[:, 2, 3]) * (
            response.sigma_relative_velocity / linear.sigma_relative_velocity
        ) ** 2
        # At the onset the buildings are at rest: their variances are rounding noise, whose ratio is no rate.
        alive = (variance_x > 1e-12 * variance_x.max()) & (variance_v > 1e-12 * variance_v.max())
        if not np.any(alive & (weights > 0.0)):
            raise ConvergenceError("the relative motion does not build up over the record: there is nothing to count")
        damping = pair.impact_damping
        x, v, w = merged_instants(
            *(np.ascontiguousarray(a, dtype=float) for a in (np.sqrt(variance_x[alive]), np.sqrt(variance_v[alive]), weights[alive])),
            _MERGE_TOLERANCE,
        )
        frequency_squared = (response.sigma_relative_velocity / response.sigma_relative_displacement) ** 2
        return cls(x, v, w, damping.bandwidth, frequency_squared, damping)

    def intensity(self, gaps, velocities) -> np.ndarray:
        """Lambda(gap, v) of the free motion (G8): expected number of approaches
        faster than v before the impacts change the motion, shape (gaps, velocities).

        The count of the probability of pounding and of the gap for a target
        probability: the first impact meets the free motion."""
        gaps = np.ascontiguousarray(gaps, dtype=float).ravel()
        ones = np.ones(gaps.size)
        clumping = VANMARCKE_DOUBLE_BARRIER * self.bandwidth**VANMARCKE_CLUMP_EXPONENT
        return self._kernel(gaps, velocities, np.full(gaps.size, clumping), ones, ones)

    def damped(self, gaps) -> DampedMotion:
        """The motion between impacts at each gap [m]: the free motion damped by
        its impacts (G12-G13)."""
        return self.damping.damped(np.ascontiguousarray(gaps, dtype=float).ravel())

    def impacting_intensity(self, gaps, velocities, motion: DampedMotion) -> np.ndarray:
        """Lambda(gap, v) of the impacting motion, ``motion`` from :meth:`damped`
        at the same gaps: the count of the largest approach speed."""
        gaps = np.ascontiguousarray(gaps, dtype=float).ravel()
        clumping = VANMARCKE_DOUBLE_BARRIER * motion.bandwidth**VANMARCKE_CLUMP_EXPONENT
        return self._kernel(gaps, velocities, clumping, motion.ratio_displacement, motion.ratio_velocity)

    def _kernel(self, gaps, velocities, clumping, scale_x, scale_v) -> np.ndarray:
        return approach_intensity(
            gaps,
            np.ascontiguousarray(velocities, dtype=float).ravel(),
            self.sigma_x,
            self.sigma_v,
            self.weights,
            np.ascontiguousarray(clumping, dtype=float),
            np.ascontiguousarray(scale_x, dtype=float),
            np.ascontiguousarray(scale_v, dtype=float),
        )


def opposing_forces(crossings: Crossings, gaps, reduced_mass: float) -> np.ndarray:
    """f0 = m E[-X'' | X = d] = m (sigma_V / sigma_X)^2 d [N] for each gap (G17):
    the buildings' restoring and damping forces at the gap, averaged (for a
    stationary X, Cov(X'', X) = -sigma_V^2 and Cov(X'', X') = 0), with the
    stationary sigmas (an envelope scales both alike)."""
    return reduced_mass * crossings.frequency_squared * np.asarray(gaps, dtype=float)


def expected_maximum(crossings: Crossings, gaps, size, power: float, motion: DampedMotion, points: int = 121) -> np.ndarray:
    """E[size(V_max)] for each gap (G19-G20), V_max = 0 without impact and ``size`` an
    increasing function of the speed with size(0) = 0 (``size(v)`` gets v of
    shape (1, points) and may broadcast it against the gaps):
    int P(V_max > v) d size(v), P(V_max > v) = 1 - exp(-Lambda(v)), Lambda the
    impacting motion's count (``motion``: the damped motion at the gaps).

    On a grid uniform in v^power, power the growth of ``size`` (smooth there,
    unlike p v^(p-1) at v = 0: 121 points give 2e-5, 81 points 1e-4)."""
    velocities = np.linspace(0.0, (U_MAX * crossings.sigma_v.max()) ** power, points) ** (1.0 / power)
    exceedance = -np.expm1(-crossings.impacting_intensity(gaps, velocities, motion))
    return np.trapezoid(exceedance, np.broadcast_to(size(velocities[None, :]), exceedance.shape), axis=-1)


def expected_force_maximum(
    crossings: Crossings, gaps, contact: Contact, reduced_mass: float, motion: DampedMotion, points: int = 121
) -> np.ndarray:
    """E[F_max] [N] for each gap [m] (G19, G18), F(v) the peak force of an impact
    at speed v against the gap's opposing force (increasing in v, as v^p)."""
    opposing = opposing_forces(crossings, gaps, reduced_mass)[:, None]
    return expected_maximum(
        crossings, gaps, lambda v: impact_peak_force(contact, v, reduced_mass, opposing),
        contact.law.peak_force_exponent, motion, points,
    )


def gap_for_probability(crossings: Crossings, target_probability: float) -> float:
    """Smallest gap [m] with exp(-Lambda(gap, 0)) >= target (G22), Lambda
    counting every crossing of the gap by the free motion (no clumps).

    A design value, so on the safe side of the best-estimate probability:
    P(pounding) <= E[crossings], while Vanmarcke's clump factor (kept for the
    pounding probability) was measured optimistic for a pair of close
    periods (docs/accuracy.md)."""
    return required_gap(-math.log(target_probability), crossings.sigma_x, crossings.sigma_v, crossings.weights)
