"""Closed-form estimates of the expected extreme pounding force, without a
time-history analysis: the paper's method as published (Section 4, Eq. 12-30,
with the printing errors of NOTES.md fixed) and this project's gap-aware
estimator (derived in docs/estimator.md), side by side.

Both stand on the same statistically linearized pair (Eq. 19-21) and its
response at the contact floors (Eq. 16-18, 25).

The recommended estimator counts impacts on the gap d by the relative
displacement X = x1 - x2 of the linearized pair, with the response to the
linearization's residual added (``response.response_with_residual``), seen as
a Gaussian process of frequency omega = sigma_V / sigma_X:

- an impact's approach velocity is that of an upcrossing of the gap by the
  free motion: Rayleigh, Rice's rate omega / (2 pi) exp(-(u^2 + rho^2) / 2)
  for crossings faster than v = rho sigma_V, u = d / sigma_X;
- impacts start only from below the gap, so the impacting motion lives there;
  its stretches below the gap being like the free motion's, it crosses the
  gap at Rice's rate per unit of time spent below it: divided by
  P(X < d) = Phi(u) (the time cut; twice Rice's rate at the mean position,
  Rice's far from it);
- crossings of a high level come in clumps (Vanmarcke's factor);
- the impacts before an approach have taken energy out of the relative motion,
  as much as the pair has not yet forgotten: the largest approach is counted on
  the linearized pair damped by its impacts (``impact_damping``: a dashpot
  between the contact floors that leaves the motion the energy the impacts
  leave it), the pounding probability and the gap for a target probability on
  the free motion, which the first impact meets;
- counted as a Poisson process over the record, the largest approach velocity
  V_max (0 without impact) has P(V_max <= v) = exp(-Lambda(v)), Lambda(v) the
  expected number of impacts faster than v;
- each impact peaks at the contact law's own force K F_H(v), F_H the
  undamped Hertz peak (``contact.impact_peak_force``); K depends on the
  restitution and on the buildings' own forces, which brake the approach
  during the impact: at the gap they average f0 = m sigma_V^2 / sigma_X^2 d
  (the mean of X'' given X = d is -(sigma_V / sigma_X)^2 d), m the reduced
  mass. E[F_max] = int P(V_max > v) dF(v).

sigma_X(t) and sigma_V(t) are those of the linearized pair started from rest
(the records start with the buildings at rest; the slow, yielded response
builds up over several seconds), modulated by the envelope when there is one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from .case import Case
from .contact import Contact, impact_peak_force, peak_force_ratio, undamped_peak_force
from .errors import CaseError, check_probability
from .excitation import CloughPenzien
from . import impact_damping as impacts
from .linearization import StateSpace, linearize_pair, pair_state_space
from .peaks import (
    VANMARCKE_DOUBLE_BARRIER,
    merged_instants,
    davenport_peak_factor,
    envelope_variance,
    equivalent_stationary,
    expected_absolute_peak,
    vanmarcke_clumps,
)
from .response import (
    ContactResponse,
    bandwidth_relative_displacement,
    contact_covariance_history,
    contact_floor_bandwidths,
    contact_floor_frfs,
    response_lyapunov,
    response_with_residual,
    trapezoid_weights,
)

__all__ = [
    "DEFAULT_MICHAELOV_N1",
    "DEFAULT_TARGET_PROBABILITY",
    "MICHAELOV_N1_RANGE",
    "PAPER_VARIANCE_METHODS",
    "REGIMES",
    "Estimate",
    "GapCurve",
    "PaperEstimate",
    "accuracy_regime",
    "estimate",
    "force_versus_gap",
    "paper_estimate",
]

PAPER_VARIANCE_METHODS = ("eq28", "exact")
"""How the paper's method gets sigma_V(t) under an envelope: Eq. 28 or the
time-varying covariance of the linearized pair."""

DEFAULT_TARGET_PROBABILITY = 0.95
"""Default target probability of *no* pounding during the record [-]."""

_HISTORY_STEP = 0.1  # [s] time grid of the non-stationary variances


@dataclass(frozen=True)
class PaperEstimate:
    """Rahimi & Soltani's estimate, Eq. 12-30 (Eq. 14 with delta^1.5).

    Attributes
    ----------
    force_expected : float or None
        F_e of Eq. 14 [N]; None for the ``linear`` contact law, for which
        Eq. 13-14 (Hertz) do not apply.
    relative_velocity_expected : float
        Expected extreme relative velocity delta_dot_e [m/s], Eq. 23 (30).
    crossing_rate : float
        nu = sigma_V / (pi sigma_X) [1/s], Eq. 24.
    duration_effective : float
        T (stationary) or Michaelov's T_eq (Eq. 29) [s].
    peak_factor : float
        Davenport's factor of Eq. 23 / 30 [-].
    sigma_relative_velocity_equivalent : float or None
        sigma_eq of Eq. 29 for non-stationary motion [m/s].
    penetration_expected : float or None
        delta_e of Eq. 13 with e delta_dot_e [m].
    michaelov_n1 : float or None
        The order n1 of Eq. 29's moments for non-stationary motion [-].
    """

    force_expected: float | None
    relative_velocity_expected: float
    crossing_rate: float
    duration_effective: float
    peak_factor: float
    sigma_relative_velocity_equivalent: float | None
    penetration_expected: float | None
    michaelov_n1: float | None = None


@dataclass(frozen=True)
class Estimate:
    """The recommended gap-aware estimate, with the paper's beside it.

    Attributes
    ----------
    force_expected : float
        Expected extreme pounding force E[F_max] [N] (0 counted for records without impact).
    relative_velocity_expected : float
        Expected largest approach velocity at impact E[V_max] [m/s].
    sigma_relative_displacement, sigma_relative_velocity : float
        Stationary standard deviations of X = x1 - x2 [m] and V [m/s] at the
        contact floors (for non-stationary motion: under the unmodulated
        excitation), of the linearized pair with its response to the
        linearization's residual added; the paper's, without it, are
        ``response``'s.
    impacts_expected : float
        Expected number of impacts during the record, counted as approaches
        from below the gap; the rebounds that follow an impact within a
        fraction of a second are not counted (Monte Carlo counts 1.1 to 1.6
        times as many, docs/estimator.md).
    pounding_probability : float
        Probability of at least one impact [-].
    required_gap : float
        Gap giving ``target_probability`` of no pounding [m].
    target_probability : float
        Target probability of no pounding [-].
    upcrossing_rate : float
        nu0+ = sigma_V / (2 pi sigma_X) [1/s] (stationary, with the residual's response).
    peak_force_ratio : float
        K(e): the law's peak force over the undamped Hertz one, for free
        masses [-].
    opposing_force : float
        The buildings' mean force braking the approach at the gap,
        m (sigma_V / sigma_X)^2 gap [N]; it lowers the peak force of slow impacts.
    impacting_velocity_ratio : float
        sigma_V of the motion between impacts over the free motion's [-]: what
        the impacts before an approach leave it (:mod:`pounding.impact_damping`);
        the force and the largest approach speed are counted on it, the pounding
        probability and the gap for the target on the free motion.
    impact_memory : float
        Share of an impact's disturbance still in the relative motion at the
        next approach [-] (0: the pair forgets an impact before the next).
    impact_dashpot : float
        The dashpot between the contact floors that damps the relative motion
        alike [N s/m].
    separation_rules : dict
        Gaps by the SRSS, ABS and DDC rules [m] from the expected peak |x| of
        each contact floor (``peak_displacement`` [m]: the linearized floor from
        rest with Vanmarcke's clumps, :func:`~pounding.peaks.expected_absolute_peak`)
        and their stationary correlation (``displacement_correlation`` [-]).
    paper : PaperEstimate
    response : ContactResponse
        The linearized pair's stationary response at the contact floors, the
        paper's (Eq. 16-18, 25), without the residual's response.
    warnings : tuple of str
        Where the case lies outside the range in which the estimate was found
        within 10 % of Monte Carlo (docs/estimator.md).
    accuracy_regime : str
        One of :data:`REGIMES` (:func:`accuracy_regime`): where the estimate's
        accuracy was measured alike.
    measured_accuracy : str
        How far from Monte Carlo the recommended force was measured in that
        regime: on the grid of docs/estimator.md and on random draws of cases.
    """

    case: Case
    force_expected: float
    relative_velocity_expected: float
    sigma_relative_displacement: float
    sigma_relative_velocity: float
    impacts_expected: float
    pounding_probability: float
    required_gap: float
    target_probability: float
    upcrossing_rate: float
    peak_force_ratio: float
    opposing_force: float
    impacting_velocity_ratio: float
    impact_memory: float
    impact_dashpot: float
    separation_rules: dict
    paper: PaperEstimate
    response: ContactResponse = field(repr=False)
    warnings: tuple[str, ...] = ()
    crossings: _Crossings | None = field(default=None, repr=False)
    accuracy_regime: str = ""
    measured_accuracy: str = ""

    def gap_curve(self, gaps) -> GapCurve:
        """This estimate at other gaps [m], reusing its response statistics."""
        return _gap_curve(self.case, self.crossings, gaps, self.paper.force_expected)

    def to_dict(self) -> dict:
        """JSON-ready, SI units."""
        paper = self.paper
        out = {
            "case": self.case.name,
            "force_expected": self.force_expected,
            "relative_velocity_expected": self.relative_velocity_expected,
            "sigma_relative_velocity": self.sigma_relative_velocity,
            "sigma_relative_displacement": self.sigma_relative_displacement,
            "impacts_expected": self.impacts_expected,
            "pounding_probability": self.pounding_probability,
            "required_gap": self.required_gap,
            "target_probability": self.target_probability,
            "upcrossing_rate": self.upcrossing_rate,
            "peak_force_ratio": self.peak_force_ratio,
            "opposing_force": self.opposing_force,
            "impacting_velocity_ratio": self.impacting_velocity_ratio,
            "impact_memory": self.impact_memory,
            "impact_dashpot": self.impact_dashpot,
            "separation_rules": dict(self.separation_rules),
            "warnings": list(self.warnings),
            "accuracy_regime": self.accuracy_regime,
            "measured_accuracy": self.measured_accuracy,
            "gap": self.case.contact.gap,
            "duration": self.case.excitation.duration,
            "paper": {
                "force_expected": paper.force_expected,
                "relative_velocity_expected": paper.relative_velocity_expected,
                "crossing_rate": paper.crossing_rate,
                "duration_effective": paper.duration_effective,
                "peak_factor": paper.peak_factor,
                "penetration_expected": paper.penetration_expected,
                "sigma_relative_displacement": self.response.sigma_relative_displacement,
                "sigma_relative_velocity": self.response.sigma_relative_velocity,
            },
            "units": {"force": "N", "length": "m", "velocity": "m/s", "rate": "1/s", "duration": "s"},
        }
        if not self.case.excitation.stationary:
            out["paper"]["sigma_relative_velocity_equivalent"] = paper.sigma_relative_velocity_equivalent
            out["paper"]["michaelov_n1"] = paper.michaelov_n1
        return out


# --- the paper's method ------------------------------------------------------


DEFAULT_MICHAELOV_N1 = 3.0
"""Order n1 of Michaelov's moments (Eq. 29); the paper finds 3 or 4 usually within 10 %."""
MICHAELOV_N1_RANGE = (0.5, 20.0)
"""Allowed n1: below 0.5 the moments weigh the long quiet tail of the record, above 20 only its peak instant."""


def _check_michaelov_n1(n1) -> None:
    low, high = MICHAELOV_N1_RANGE
    if isinstance(n1, bool) or not isinstance(n1, (int, float)) or not low <= n1 <= high:
        raise CaseError("michaelov_n1", f"must lie in [{low:g}, {high:g}], got {n1!r}")


def paper_estimate(
    case: Case,
    linearized,
    response: ContactResponse,
    variance_method: str = "eq28",
    model: StateSpace | None = None,
    michaelov_n1: float = DEFAULT_MICHAELOV_N1,
) -> PaperEstimate:
    """The published estimator, Eq. 12-30.

    Parameters
    ----------
    case : Case
    linearized : tuple of two LinearizedBuilding
    response : ContactResponse
        Stationary response of the linearized pair at the contact floors.
    variance_method : str
        How sigma_V(t) is found for a modulated motion: ``"eq28"``, the paper's
        A(t)^2 sigma_inf^2, or ``"exact"``, the time-varying covariance.
    model : StateSpace, optional
        The pair's :func:`~pounding.linearization.pair_state_space`, if built already.
    michaelov_n1 : float
        Order n1 of Eq. 29's moments under an envelope, in :data:`MICHAELOV_N1_RANGE`.
    """
    _check_michaelov_n1(michaelov_n1)
    sigma_v = response.sigma_relative_velocity
    rate = response.zero_crossing_rate  # Eq. 24 (NOTES.md 11: the displacement's rate)
    excitation = case.excitation
    if excitation.stationary:
        duration, sigma = excitation.duration, sigma_v
        sigma_equivalent = None
    else:
        times = np.arange(0.0, excitation.duration + 1e-9, _HISTORY_STEP)
        if variance_method == "eq28":
            variance = envelope_variance(excitation.envelope, times, sigma_v**2)
        elif variance_method == "exact":
            history = contact_covariance_history(case, linearized, times, model=model)
            variance = history[:, 2, 2] + history[:, 3, 3] - 2 * history[:, 2, 3]
        else:
            raise CaseError("variance_method", f"must be one of {', '.join(PAPER_VARIANCE_METHODS)}, got {variance_method!r}")
        variance_eq, duration = equivalent_stationary(variance, times, n1=michaelov_n1)  # Eq. 29
        sigma = sigma_equivalent = math.sqrt(variance_eq)
    factor = davenport_peak_factor(rate, duration)  # Eq. 23 / 30
    velocity = factor * sigma
    contact = case.contact
    if not contact.law.hertzian:
        force = penetration = None
    else:
        # Eq. 13-14: the Hertz peak for the separation velocity e * delta_dot_e (NOTES.md 10), with
        # delta^1.5 as Eq. 3 and 14 have it (Eq. 12's delta^2 is a misprint, NOTES.md 1).
        separation = contact.restitution * velocity
        force = float(undamped_peak_force(contact, separation, case.reduced_mass))
        penetration = (force / contact.stiffness) ** (2.0 / 3.0)
    n1 = None if excitation.stationary else float(michaelov_n1)
    return PaperEstimate(force, float(velocity), float(rate), float(duration), float(factor), sigma_equivalent, penetration, n1)


# --- the recommended estimator ----------------------------------------------

_U_MAX = impacts.U_MAX


@njit(cache=True)
def _intensity_kernel(gaps, velocities, sigma_x, sigma_v, weights, clumping, scale_x, scale_v):
    """Lambda(gap, v) = sum_t w_t nu_t / Phi(u_t) exp(-(u_t^2 + rho_t^2) / 2) c(r_t),
    nu_t = sigma_V(t) / (2 pi sigma_X(t)), u_t = gap / sigma_X(t), rho_t = v / sigma_V(t),
    r_t^2 = u_t^2 + rho_t^2, Phi the standard normal distribution (the time cut)
    and Vanmarcke's clump factor c(r) = min(1, (1 - exp(-clumping r)) / (1 - exp(-r^2 / 2))).
    Per gap i the sigmas are multiplied by scale_x[i], scale_v[i] and the clump
    constant is clumping[i] (the impacts' damping, :mod:`pounding.impact_damping`)."""
    out = np.zeros((gaps.size, velocities.size))
    for i in range(gaps.size):
        for t in range(sigma_x.size):
            sx = sigma_x[t] * scale_x[i]
            sv = sigma_v[t] * scale_v[i]
            u = gaps[i] / sx
            factor = weights[t] * impacts.time_cut_rate(gaps[i], sx, sv)
            if factor == 0.0:
                continue
            level = math.exp(-0.5 * u * u)
            for j in range(velocities.size):
                rho = velocities[j] / sv
                if rho >= _U_MAX:
                    continue
                speed = math.exp(-0.5 * rho * rho)
                r2 = u * u + rho * rho
                clumps = 1.0
                if r2 > 1e-18:
                    # 1 - exp(-r^2 / 2) from the two factors already at hand, but by expm1 where it is small.
                    envelope_tail = 1.0 - level * speed if r2 > 1e-2 else -math.expm1(-0.5 * r2)
                    clumps = vanmarcke_clumps(clumping[i], math.sqrt(r2), envelope_tail)
                out[i, j] += factor * speed * clumps
    return out


# Vanmarcke's double-barrier constant sqrt(pi / 2), two crossings a period while the
# envelope is high, as the time cut counts them at the mean position; the one-sided
# sqrt(2 pi) was measured worse (docs/estimator.md, "Clumps").
_VANMARCKE = VANMARCKE_DOUBLE_BARRIER


@dataclass(frozen=True)
class _Crossings:
    """sigma_X(t), sigma_V(t) of the free linearized pair (with the residual's
    response) on a time grid, with trapezoid weights [s]; the bandwidth of X
    and its stationary (sigma_V / sigma_X)^2 [1/s^2]; the impacts' damping of
    the relative motion (None: none)."""

    sigma_x: np.ndarray
    sigma_v: np.ndarray
    weights: np.ndarray
    bandwidth: float = 1.0
    frequency_squared: float = 0.0
    damping: impacts.ImpactDamping | None = None

    def intensity(self, gaps, velocities, clumps: bool = True) -> np.ndarray:
        """Lambda(gap, v) of the free motion: expected number of approaches faster
        than v before the impacts change the motion, shape (gaps, velocities).

        The count of the probability of pounding and of the gap for a target
        probability: the first impact meets the free motion. ``clumps=False``
        counts every crossing (no Vanmarcke factor): an upper bound on the
        number of clumps."""
        gaps = np.ascontiguousarray(gaps, dtype=float).ravel()
        ones = np.ones(gaps.size)
        clumping = _VANMARCKE * self.bandwidth**1.2 if clumps else math.inf
        return self._kernel(gaps, velocities, np.full(gaps.size, clumping), ones, ones)

    def damped(self, gaps) -> impacts.DampedMotion:
        """The motion between impacts at each gap [m]: the free motion damped by
        its impacts (:mod:`pounding.impact_damping`; undamped without ``damping``)."""
        gaps = np.ascontiguousarray(gaps, dtype=float).ravel()
        if self.damping is None:
            ones, zeros = np.ones(gaps.size), np.zeros(gaps.size)
            return impacts.DampedMotion(zeros, ones, ones, np.full(gaps.size, self.bandwidth), zeros)
        return self.damping.damped(gaps)

    def impacting_intensity(self, gaps, velocities, motion: impacts.DampedMotion) -> np.ndarray:
        """Lambda(gap, v) of the impacting motion, ``motion`` from :meth:`damped`
        at the same gaps: the count of the largest approach speed."""
        gaps = np.ascontiguousarray(gaps, dtype=float).ravel()
        clumping = _VANMARCKE * motion.bandwidth**1.2
        return self._kernel(gaps, velocities, clumping, motion.ratio_displacement, motion.ratio_velocity)

    def _kernel(self, gaps, velocities, clumping, scale_x, scale_v) -> np.ndarray:
        return _intensity_kernel(
            gaps,
            np.ascontiguousarray(velocities, dtype=float).ravel(),
            self.sigma_x,
            self.sigma_v,
            self.weights,
            np.ascontiguousarray(clumping, dtype=float),
            np.ascontiguousarray(scale_x, dtype=float),
            np.ascontiguousarray(scale_v, dtype=float),
        )


@dataclass(frozen=True)
class _PairStatistics:
    """What an estimate needs of the free linearized pair, none of it depending
    on the gap: its state space, stationary response (the paper's) and the
    response with the residual's part (the recommended estimator's); the
    contact outputs' covariance history from rest with the instants' trapezoid
    weights [s]; the contact floors' FRFs; and the crossings history."""

    model: StateSpace
    linear: ContactResponse
    response: ContactResponse
    weights: np.ndarray
    history: np.ndarray
    floor_frfs: tuple
    crossings: _Crossings


def _pair_statistics(case: Case, linearized, impact_damping: bool = True) -> _PairStatistics:
    model = pair_state_space(case, linearized)
    linear = response_lyapunov(case, linearized, model)
    _check_relative_motion(case, linear)
    response = response_with_residual(case, linearized, model, linear)
    weights, history = _history(case, linearized, model)
    floor_frfs = contact_floor_frfs(case, linearized)
    crossings = _crossings(case, linearized, model, response, linear, weights, history, floor_frfs, impact_damping)
    return _PairStatistics(model, linear, response, weights, history, floor_frfs, crossings)


_STATIONARY_STEP = 0.25  # [s] time grid of the build-up from rest (it takes seconds)
_MODULATED_STEP = 0.25  # [s] time grid under an envelope (which varies over seconds)


def _history(case: Case, linearized, model: StateSpace) -> tuple[np.ndarray, np.ndarray]:
    """Trapezoid weights [s] of a time grid over the record and the contact
    outputs' covariance on it (:data:`~pounding.response.OUTPUTS`, SI): the
    ground motion switched on at t = 0 on buildings at rest (stationary case),
    or modulated by the envelope."""
    excitation = case.excitation
    step = _STATIONARY_STEP if excitation.stationary else _MODULATED_STEP
    times = np.arange(0.0, excitation.duration + 1e-9, step)
    if times[-1] < excitation.duration - 1e-9:
        times = np.append(times, excitation.duration)
    modulation = "ground" if excitation.stationary else "bedrock"
    history = contact_covariance_history(case, linearized, times, modulation=modulation, model=model)
    return trapezoid_weights(times), history


def _crossings(
    case: Case,
    linearized,
    model: StateSpace,
    response: ContactResponse,
    linear: ContactResponse,
    weights: np.ndarray,
    history: np.ndarray,
    floor_frfs: tuple,
    damped: bool = True,
) -> _Crossings:
    """sigma_X(t), sigma_V(t) from the linearized pair's covariance ``history``
    (:func:`_history`), each variance scaled by its stationary ratio of
    ``response`` (with the residual's part, :func:`~pounding.response.response_with_residual`)
    to ``linear``'s. ``damped``: with the impacts' damping of the motion
    between impacts (:mod:`pounding.impact_damping`)."""
    variance_x = (history[:, 0, 0] + history[:, 1, 1] - 2 * history[:, 0, 1]) * (
        response.sigma_relative_displacement / linear.sigma_relative_displacement
    ) ** 2
    variance_v = (history[:, 2, 2] + history[:, 3, 3] - 2 * history[:, 2, 3]) * (
        response.sigma_relative_velocity / linear.sigma_relative_velocity
    ) ** 2
    # At the onset the buildings are at rest: their variances are rounding noise, whose ratio is no rate.
    alive = (variance_x > 1e-12 * variance_x.max()) & (variance_v > 1e-12 * variance_v.max())
    if damped:
        damping = impacts.impact_damping(case, linearized, model, response, floor_frfs)
        bandwidth = damping.bandwidth
    else:
        damping, bandwidth = None, bandwidth_relative_displacement(case, linearized)
    frequency_squared = (response.sigma_relative_velocity / response.sigma_relative_displacement) ** 2
    return _merged(np.sqrt(variance_x[alive]), np.sqrt(variance_v[alive]), weights[alive], bandwidth, frequency_squared, damping)


def _check_relative_motion(case: Case, linear: ContactResponse) -> None:
    """Raise :class:`CaseError` where there is no relative motion to count
    crossings of: no ground motion, or buildings that move alike (the variance
    of x1 - x2 within rounding of zero against the floors')."""
    c = linear.covariance
    floors = max(c[0, 0], c[1, 1])
    if floors == 0.0:
        raise CaseError("excitation.G0", f"must be > 0 for the closed-form estimate, got {case.excitation.spectrum.G0:g}: "
                        "without ground motion nothing moves and nothing pounds")
    # c11 + c22 - 2 c12 of two identical buildings is rounding noise, up to ~1e-13 of c11 and of either sign.
    if c[0, 0] + c[1, 1] - 2.0 * c[0, 1] <= 1e-12 * floors:
        raise CaseError("buildings", "the two buildings move alike at the contact floors (x1 - x2 is 0): under one "
                        "ground motion they never approach each other, so there is no pounding to estimate")


def _merged(
    sigma_x: np.ndarray,
    sigma_v: np.ndarray,
    weights: np.ndarray,
    bandwidth: float,
    frequency_squared: float,
    damping: impacts.ImpactDamping | None,
    tolerance: float = 1e-4,
) -> _Crossings:
    """Join consecutive instants whose sigmas agree to ``tolerance``: once the
    response has built up, a stationary record is one instant of weight T - t."""
    x, v, w = merged_instants(*(np.ascontiguousarray(a, dtype=float) for a in (sigma_x, sigma_v, weights)), tolerance)
    return _Crossings(x, v, w, bandwidth, frequency_squared, damping)


def _opposing_forces(crossings: _Crossings, gaps: np.ndarray, reduced_mass: float) -> np.ndarray:
    """f0 = m E[-X'' | X = d] = m (sigma_V / sigma_X)^2 d [N] for each gap: the
    buildings' restoring and damping forces at the gap, averaged (for a
    stationary X, Cov(X'', X) = -sigma_V^2 and Cov(X'', X') = 0), with the
    stationary sigmas (an envelope scales both alike)."""
    return reduced_mass * crossings.frequency_squared * np.asarray(gaps, dtype=float)


def _expected_maximum(
    crossings: _Crossings, gaps: np.ndarray, size, power: float, motion: impacts.DampedMotion, points: int = 121
) -> np.ndarray:
    """E[size(V_max)] for each gap, V_max = 0 without impact and ``size`` an
    increasing function of the speed with size(0) = 0 (``size(v)`` gets v of
    shape (1, points) and may broadcast it against the gaps):
    int P(V_max > v) d size(v), P(V_max > v) = 1 - exp(-Lambda(v)), Lambda the
    impacting motion's count (``motion``: the damped motion at the gaps).

    On a grid uniform in v^power, power the growth of ``size`` (smooth there,
    unlike p v^(p-1) at v = 0: 121 points give 2e-5, 81 points 1e-4)."""
    velocities = np.linspace(0.0, (_U_MAX * crossings.sigma_v.max()) ** power, points) ** (1.0 / power)
    exceedance = -np.expm1(-crossings.impacting_intensity(gaps, velocities, motion))
    return np.trapezoid(exceedance, np.broadcast_to(size(velocities[None, :]), exceedance.shape), axis=-1)


def _expected_force_maximum(
    crossings: _Crossings, gaps: np.ndarray, contact: Contact, reduced_mass: float, motion: impacts.DampedMotion, points: int = 121
) -> np.ndarray:
    """E[F_max] [N] for each gap, F(v) the peak force of an impact at speed v
    against the gap's opposing force (increasing in v, as v^p)."""
    opposing = _opposing_forces(crossings, gaps, reduced_mass)[:, None]
    return _expected_maximum(
        crossings, gaps, lambda v: impact_peak_force(contact, v, reduced_mass, opposing), contact.law.peak_force_exponent, motion, points
    )


def _required_gap(crossings: _Crossings, target_probability: float) -> float:
    """Smallest gap with exp(-Lambda(gap, 0)) >= target, Lambda counting every
    crossing of the gap by the free motion (no clumps).

    A design value, so on the safe side of the best-estimate probability:
    P(pounding) <= E[crossings], while Vanmarcke's clump factor (kept for
    ``pounding_probability``) was measured optimistic for a pair of close
    periods (docs/estimator.md)."""
    return _required_gap_kernel(-math.log(target_probability), crossings.sigma_x, crossings.sigma_v, crossings.weights)


@njit(cache=True)
def _required_gap_kernel(allowed, sigma_x, sigma_v, weights):
    """Bisection for Lambda(gap, 0) = allowed, Lambda(gap, 0) = sum_t w_t nu_t(gap)
    the time-cut rate summed over the history: it falls with the gap (as
    exp(-u^2 / 2) / Phi(u)), so it crosses ``allowed`` once; the gap returned
    is on the safe side of the crossing, to 1e-10 of it."""
    low, high = 0.0, _U_MAX * sigma_x.max()
    if _free_approaches(low, sigma_x, sigma_v, weights) <= allowed:
        return 0.0
    for _ in range(200):  # 1e-10 takes about 34 halvings; the cap ends it where rounding stops them shrinking
        if high - low <= 1e-10 * high:
            break
        middle = 0.5 * (low + high)
        if _free_approaches(middle, sigma_x, sigma_v, weights) > allowed:
            low = middle
        else:
            high = middle
    return high


@njit(cache=True)
def _free_approaches(gap, sigma_x, sigma_v, weights):
    """Lambda(gap, 0) with every crossing counted: what the intensity kernel
    gives at v = 0 without clumps (its factor c(r) is then 1)."""
    total = 0.0
    for t in range(sigma_x.size):
        total += weights[t] * impacts.time_cut_rate(gap, sigma_x[t], sigma_v[t])
    return total


def _separation_rules(case: Case, linearized, response: ContactResponse, weights, history, floor_frfs) -> dict:
    """SRSS, ABS and DDC gaps [m] from the expected peak |displacement| of each
    contact floor: the linearized floor's sigmas from rest (``history``, as
    :func:`_history` gives it) with Vanmarcke's clumps
    (:func:`~pounding.peaks.expected_absolute_peak`); DDC with the floors'
    stationary correlation (``response``)."""
    bandwidths = contact_floor_bandwidths(case, linearized, floor_frfs)
    # history's outputs are x1, x2, v1, v2, ...; at rest a variance may round to just below 0.
    sigmas = np.sqrt(np.maximum(np.diagonal(history, axis1=1, axis2=2), 0.0))
    peaks = [expected_absolute_peak(sigmas[:, floor], sigmas[:, 2 + floor], weights, q) for floor, q in enumerate(bandwidths)]
    sigma_x = np.array(response.sigma_displacement)
    u1, u2 = peaks
    correlation = response.covariance_displacement / (sigma_x[0] * sigma_x[1])
    return {
        "srss": float(math.hypot(u1, u2)),
        "abs": float(u1 + u2),
        "ddc": float(math.sqrt(max(u1**2 + u2**2 - 2.0 * correlation * u1 * u2, 0.0))),
        "peak_displacement": [float(u1), float(u2)],
        "displacement_correlation": float(correlation),
    }


# --- how far the recommended estimate was measured from Monte Carlo --------------
# By regime. Kanai-Tajimi: the 33-case grid (`pounding validate --grid`), random draws from the estimator's
# ranges (docs/out_of_sample.py) and docs/rare_pounding.py; Clough-Penzien: docs/record_synthesis.py.

MODERATE_GAP = 0.5
"""gap / sigma_X above which pounding is no longer frequent and the yielding pairs' heavier tail shows."""
NARROW_BAND_LIMIT = 0.55
"""Below this bandwidth q of X Vanmarcke's clumps and the impacts' damping, taken on average, leave the estimate
less accurate (docs/estimator.md)."""
RESIDUAL_SHARE_LIMIT = 0.2
"""Above this, sigma_X or sigma_V with the residual's response exceeds the linearized one by more than its
share, and the one-pass response overshoots (docs/estimator.md)."""

REGIMES = ("frequent", "moderate gap", "narrow band", "large residual", "rare")


def accuracy_regime(gap: float, sigma_x: float, residual_share: float, bandwidth: float) -> str:
    """Which of :data:`REGIMES` ``gap`` [m] lies in: the first that applies of
    rare pounding (gap > sigma_X [m], with the residual's response), a large
    residual (``residual_share``, what the residual's response adds to sigma_X
    or sigma_V, the larger, over :data:`RESIDUAL_SHARE_LIMIT`), a narrow band
    (``bandwidth`` q of X below :data:`NARROW_BAND_LIMIT`), a moderate gap
    (gap > sigma_X / 2), else frequent pounding."""
    if gap > sigma_x:
        return "rare"
    if residual_share > RESIDUAL_SHARE_LIMIT:
        return "large residual"
    if bandwidth < NARROW_BAND_LIMIT:
        return "narrow band"
    if gap > MODERATE_GAP * sigma_x:
        return "moderate gap"
    return "frequent"


# What was measured in each regime of a Kanai-Tajimi case with the gap below sigma_X (docs/out_of_sample.py:
# the 33-case grid and four random draws of 100 cases, the fourth held out when the impacts' damping was
# chosen): the range of errors, and how many within 10 %.
MEASURED_KANAI_TAJIMI = {
    "frequent": ("from -13 % to +15 %, one case +38 %", "within 10 % on 149 of 159 cases, median 3.3 %"),
    "moderate gap": ("from -26 % to +14 %", "within 10 % on 20 of 29 cases, median 6.9 %"),
    "narrow band": ("from -25 % to +85 %", "within 10 % on 81 of 114 cases, median 6.9 %"),
    "large residual": ("from -12 % to +79 %", "within 10 % on 11 of 25 cases, median 12.6 %"),
}
_WHERE = {
    "frequent": "where the gap is below sigma_X / 2, the relative motion broad-band and the residual's share small",
    "moderate gap": "where the gap lies between sigma_X / 2 and sigma_X",
    "narrow band": "where the relative motion is narrow-band and the gap below sigma_X",
    "large residual": "where the residual's response is large and the gap below sigma_X",
}
ACCURACY_CLOUGH_PENZIEN = (
    "measured from -14 % to +19 % of Monte Carlo where the gap is below sigma_X with a Clough-Penzien "
    "spectrum (within 10 % on 10 of 13 cases)"
)
# Where the gap exceeds sigma_X; keys: (spectrum, does a building yield?).
ACCURACY_RARE = {
    ("kanai-tajimi", True): "from -100 % to +456 % on 57 yielding pairs of the grid and random draws (within 10 % on 6), and up to +7500 % "
    "for nearly elastic-perfectly plastic storeys (the Section 6 frames at 1.5-2.5 sigma_X, where under 1 record in 5 "
    "pounds)",
    ("kanai-tajimi", False): "from -70 % to +55 % on 28 elastic pairs of the grid and random draws (within 10 % on 9; the low "
    "side is pairs of close periods, whose crossings Vanmarcke's factor counts in clumps too long)",
    ("clough-penzien", True): "-73 % and -72 % (2 yielding cases tested with a Clough-Penzien spectrum; the estimate "
    "misses most of the pounding caused by plastic drift)",
    ("clough-penzien", False): "from -22 % to +1 % (3 elastic cases tested with a Clough-Penzien spectrum)",
}
MOVING_TOGETHER = 0.9
"""Correlation of the contact floors' displacements x1, x2 (linearized) from which a yielding pair's design gap
was measured unsafe: X is then the small difference of two motions alike, much of it their different plastic drift,
whose tail is heavier than Gaussian (docs/estimator.md, "The gap for 95 %": set on the first random draw, where
every unsafe pair lay at 0.92 or above, and held on the other two)."""

# The fraction of simulated records that pound at the gap given for 95 % (Kanai-Tajimi:
# docs/out_of_sample.py --required-gap; Clough-Penzien: docs/record_synthesis.py). Kanai-Tajimi yielding pairs
# are split by whether their floors move together (MOVING_TOGETHER).
REQUIRED_GAP_CHECK = {
    ("kanai-tajimi", True, True): "0.069 on average over 48 random one-storey yielding pairs whose floors move together "
    "like these (400 records each), and up to 0.150: above 0.072, two standard errors over 0.05, for 20 of them, so the "
    "closed-form gap is not safe for such pairs (the Section 6 frames, whose residual widens it: at most 0.048 on 21; "
    "three-storey against two-storey pairs: up to 0.077 on 9)",
    ("kanai-tajimi", True, False): "0.035 on average over 102 random one-storey yielding pairs whose floors move less "
    "together (correlation below {limit}; 400 records each), and at most 0.0725, one just over two standard errors above 0.05 (the Section 6 "
    "frames: at most 0.028 on 39; three-storey against two-storey pairs: at most 0.060 on 21)",
    ("kanai-tajimi", False, None): "0.04 on average over 60 random elastic pairs and at most 0.062, within sampling error of 0.05",
    ("clough-penzien", True, None): "0.002 to 0.106 on the 3 yielding pairs tested with a Clough-Penzien spectrum: "
    "0.089 and 0.106, on the unsafe side, for the Section 5 pairs (plastic drift)",
    ("clough-penzien", False, None): "0.036 on the elastic pair tested with a Clough-Penzien spectrum (on the safe side)",
}

_CHECK = " (docs/estimator.md); check it with `pounding simulate`"
TAIL_WARNING = (
    "the gap exceeds sigma_X of the relative displacement: pounding is rare and the estimate rests on the "
    "Gaussian tail of the linearized response, where it was measured {range} off Monte Carlo" + _CHECK
)
REQUIRED_GAP_WARNING = (
    "the gap for the target probability lies where pounding is rare (beyond sigma_X); simulated at the gap "
    "given for 95 %, the fraction of records that pounded was {range} (docs/estimator.md); size the gap by "
    "Monte Carlo: `pounding simulate --design-gap`, or the dashboard's Monte Carlo design gap"
)
MOVING_TOGETHER_NOTE = (
    "the contact floors move together (correlation of x1 and x2 {correlation:.2f}, {limit} or more) and the "
    "buildings yield: X is the small difference of two motions alike, much of it their different plastic drift, and "
    "its tail is heavier than the estimate's; "
)
NARROW_BAND_WARNING = (
    "the relative displacement is narrow-band (bandwidth q = {bandwidth:.2f} < {limit}): Vanmarcke's factor counts "
    "its crossings in clumps too long, which puts elastic pairs low (under modulated records down to -25 %), and the "
    "impacts' damping of its motion is taken on average, which puts elastic pairs of nearly equal periods (q below "
    "0.15) high" + _CHECK
)
RESIDUAL_WARNING = (
    "the linearization's residual adds {share:.0f} % to sigma_X or sigma_V (over {limit:.0f} %), as for storeys near "
    "elastic-perfectly plastic: its one-pass response overshoots there, and the gap looks nearer the mean "
    "position than it is" + _CHECK
)
MODERATE_GAP_WARNING = (
    "the gap lies between sigma_X / 2 and sigma_X: pounding is less frequent and the yielding pairs' heavier than "
    "Gaussian tail shows" + _CHECK
)
DRIFT_WARNING = (
    "a building yields and the Clough-Penzien spectrum has no ground motion at low frequency: the estimate's "
    "buildings then drift only through the linearization's residual, and yielding buildings drift further, "
    "with a heavier tail; at the gap given for 95 % no pounding, 9 % and 11 % of simulated records pounded for "
    "two of the 3 pairs tested (docs/estimator.md); size the gap with `pounding simulate`"
)


def _spectrum_kind(case: Case) -> str:
    return "clough-penzien" if isinstance(case.excitation.spectrum, CloughPenzien) else "kanai-tajimi"


def _yielding(linearized) -> bool:
    """Whether a storey of either linearized building yields (k_e != 0)."""
    return any(np.any(building.k_e != 0.0) for building in linearized)


def _residual_share(response: ContactResponse, linear: ContactResponse) -> float:
    """How much the residual's response adds to sigma_X or sigma_V, the larger [-]."""
    return max(
        response.sigma_relative_displacement / linear.sigma_relative_displacement,
        response.sigma_relative_velocity / linear.sigma_relative_velocity,
    ) - 1.0


def _warnings(
    case: Case, linearized, sigma: float, share: float, required_gap: float, bandwidth: float, correlation: float
) -> tuple[str, ...]:
    """The measured limits of the recommended estimator that apply to ``case`` (``sigma``: sigma_X [m];
    ``share``: the residual's, as in :func:`accuracy_regime`; ``correlation``: of x1 and x2, linearized)."""
    gap = case.contact.gap
    key = (_spectrum_kind(case), _yielding(linearized))
    warnings = []
    if key == ("clough-penzien", True):
        warnings.append(DRIFT_WARNING)
    if share > RESIDUAL_SHARE_LIMIT:
        warnings.append(RESIDUAL_WARNING.format(share=100 * share, limit=100 * RESIDUAL_SHARE_LIMIT))
    if bandwidth < NARROW_BAND_LIMIT:
        warnings.append(NARROW_BAND_WARNING.format(bandwidth=bandwidth, limit=NARROW_BAND_LIMIT))
    if MODERATE_GAP * sigma < gap <= sigma:
        warnings.append(MODERATE_GAP_WARNING)
    if gap > sigma:
        warnings.append(TAIL_WARNING.format(range=ACCURACY_RARE[key]))
    if required_gap > sigma:
        warnings.append(_required_gap_warning(key, correlation))
    return tuple(warnings)


def _required_gap_warning(key: tuple[str, bool], correlation: float) -> str:
    """What was measured of the gap for 95 % on pairs like this one: by spectrum, yielding and, for yielding
    pairs under Kanai-Tajimi, whether the floors move together (:data:`MOVING_TOGETHER`)."""
    together = correlation >= MOVING_TOGETHER if key == ("kanai-tajimi", True) else None
    warning = REQUIRED_GAP_WARNING.format(range=REQUIRED_GAP_CHECK[(*key, together)].format(limit=MOVING_TOGETHER))
    if together:
        warning = MOVING_TOGETHER_NOTE.format(correlation=correlation, limit=MOVING_TOGETHER) + warning
    return warning


def _measured_accuracy(case: Case, linearized, regime: str) -> str:
    spectrum = _spectrum_kind(case)
    if regime == "rare":
        rare = ACCURACY_RARE[(spectrum, _yielding(linearized))]
        return f"measured {rare} off Monte Carlo where the gap exceeds sigma_X (rare pounding)"
    if spectrum == "clough-penzien":
        return ACCURACY_CLOUGH_PENZIEN
    span, tally = MEASURED_KANAI_TAJIMI[regime]
    return f"measured {span} off Monte Carlo {_WHERE[regime]} ({tally}: the grid and random draws of cases)"


def estimate(
    case: Case,
    target_probability: float = DEFAULT_TARGET_PROBABILITY,
    linearized=None,
    paper_variance: str = "eq28",
    impact_damping: bool = True,
    michaelov_n1: float = DEFAULT_MICHAELOV_N1,
) -> Estimate:
    """Expected extreme pounding force of ``case`` by both closed forms.

    Parameters
    ----------
    case : Case
    target_probability : float
        Probability of no pounding the ``required_gap`` must give [-].
    linearized : tuple of two LinearizedBuilding, optional
        Reuse a linearization (it does not depend on the gap).
    paper_variance : str
        For the paper's method under an envelope: ``"eq28"`` (as published)
        or ``"exact"`` (see :data:`PAPER_VARIANCE_METHODS`).
    impact_damping : bool
        Count the largest approach on the motion damped by the impacts before
        it (default); ``False`` counts it on the free motion, as this
        estimator did before (for comparisons, docs/estimator.md).
    michaelov_n1 : float
        For the paper's method under an envelope: the order n1 of Eq. 29's
        moments (default 3, as the paper), in :data:`MICHAELOV_N1_RANGE`.
    """
    check_probability(target_probability)
    _check_michaelov_n1(michaelov_n1)
    linearized = linearized or linearize_pair(case)
    pair = _pair_statistics(case, linearized, impact_damping)
    model, linear, response, crossings = pair.model, pair.linear, pair.response, pair.crossings
    contact = case.contact
    gap = np.array([contact.gap])
    impacts = float(crossings.intensity(gap, np.zeros(1))[0, 0])
    required_gap = _required_gap(crossings, target_probability)
    impacting = crossings.damped(gap)
    (velocity,) = _expected_maximum(crossings, gap, lambda v: v, 1.0, impacting)
    share = _residual_share(response, linear)
    regime = accuracy_regime(contact.gap, response.sigma_relative_displacement, share, crossings.bandwidth)
    return Estimate(
        case=case,
        force_expected=float(_expected_force_maximum(crossings, gap, contact, case.reduced_mass, impacting)[0]),
        relative_velocity_expected=float(velocity),
        sigma_relative_displacement=response.sigma_relative_displacement,
        sigma_relative_velocity=response.sigma_relative_velocity,
        impacts_expected=impacts,
        pounding_probability=float(-math.expm1(-impacts)),
        required_gap=required_gap,
        target_probability=float(target_probability),
        upcrossing_rate=response.upcrossing_rate,
        peak_force_ratio=peak_force_ratio(contact.model, contact.restitution),
        opposing_force=float(_opposing_forces(crossings, gap, case.reduced_mass)[0]),
        impacting_velocity_ratio=float(impacting.ratio_velocity[0]),
        impact_memory=float(impacting.memory[0]),
        impact_dashpot=float(impacting.dashpot[0]),
        separation_rules=_separation_rules(case, linearized, linear, pair.weights, pair.history, pair.floor_frfs),
        paper=paper_estimate(case, linearized, linear, paper_variance, model, michaelov_n1),
        response=linear,
        warnings=_warnings(
            case, linearized, response.sigma_relative_displacement, share, required_gap, crossings.bandwidth,
            linear.correlation_displacement,
        ),
        crossings=crossings,
        accuracy_regime=regime,
        measured_accuracy=_measured_accuracy(case, linearized, regime),
    )


@dataclass(frozen=True)
class GapCurve:
    """Estimates against the gap [m]: expected extreme force (recommended) [N],
    pounding probability [-], expected impacts; the paper's F_e does not depend
    on the gap [N]."""

    gaps: np.ndarray
    force_expected: np.ndarray
    pounding_probability: np.ndarray
    impacts_expected: np.ndarray
    paper_force_expected: float | None


def _gap_curve(case: Case, crossings: _Crossings, gaps, paper_force: float | None) -> GapCurve:
    gaps = np.asarray(gaps, dtype=float).ravel()
    if gaps.size == 0 or np.any(gaps < 0) or not np.all(np.isfinite(gaps)):
        raise CaseError("gaps", "must be finite numbers >= 0 m")
    impacts = crossings.intensity(gaps, np.zeros(1))[:, 0]
    # A curve for plots and design charts: 81 points in v^p (1e-4) keep 100 gaps within 10 ms.
    force = _expected_force_maximum(crossings, gaps, case.contact, case.reduced_mass, crossings.damped(gaps), 81)
    return GapCurve(gaps, force, -np.expm1(-impacts), impacts, paper_force)


def force_versus_gap(case: Case, gaps, linearized=None) -> GapCurve:
    """The recommended estimate over many gaps [m]; the linearization and the
    response statistics are computed once (see also :meth:`Estimate.gap_curve`)."""
    linearized = linearized or linearize_pair(case)
    pair = _pair_statistics(case, linearized)
    model, linear, crossings = pair.model, pair.linear, pair.crossings
    return _gap_curve(case, crossings, gaps, paper_estimate(case, linearized, linear, model=model).force_expected)
