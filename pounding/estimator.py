"""Closed-form estimates of the expected extreme pounding force, without a
time-history analysis: the paper's method as published (Section 4, Eq. 12-30,
with the printing errors of NOTES.md fixed) and this project's gap-aware
estimator (docs/estimator.md), side by side.

Both stand on the same statistically linearized pair (Eq. 19-21) and its
stationary response at the contact floors (Eq. 16-18, 25).

The recommended estimator treats impacts as upcrossings of the gap by the
relative displacement X = x1 - x2 (Rice): upcrossings of the level d with an
approach velocity above v arrive at the rate

    nu0+ exp(-d^2 / (2 sigma_X^2)) exp(-v^2 / (2 sigma_V^2)),

nu0+ = sigma_V / (2 pi sigma_X), since at an upcrossing the velocity has the
Rayleigh density. Counted as a Poisson process over the record, the largest
approach velocity V_max (0 when there is no impact) has
P(V_max <= v) = exp(-Lambda(v)), Lambda(v) the expected number of impacts
faster than v. Each impact's peak force is the contact law's own,
K(e) F_H(v) with F_H the undamped Hertz peak, proportional to v^1.2
(``contact.impact_peak_force``), so E[F_max] = K F_H(1) E[V_max^1.2].
Non-stationary motion enters through sigma_X(t), sigma_V(t) in Lambda.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from .case import Case
from .contact import Contact, impact_peak_force, peak_force_ratio, undamped_peak_force
from .errors import CaseError
from .linearization import linearize_pair
from .peaks import davenport_peak_factor, envelope_variance, equivalent_stationary
from .response import ContactResponse, contact_covariance_history, response_lyapunov

__all__ = ["PaperEstimate", "Estimate", "GapCurve", "estimate", "paper_estimate", "force_versus_gap", "DEFAULT_TARGET_PROBABILITY", "NONSTATIONARY_METHODS"]

DEFAULT_TARGET_PROBABILITY = 0.95
"""Default target probability of *no* pounding during the record [-]."""

_HISTORY_STEP = 0.1  # [s] time grid of the non-stationary variances
_PEAK_EXPONENT = {"linear": 1.0}  # the others: Hertz, v^1.2


def _exponent(contact: Contact) -> float:
    return _PEAK_EXPONENT.get(contact.model, 1.2)


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
    """

    force_expected: float | None
    relative_velocity_expected: float
    crossing_rate: float
    duration_effective: float
    peak_factor: float
    sigma_relative_velocity_equivalent: float | None
    penetration_expected: float | None


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
        contact floors (for non-stationary motion: under the unmodulated excitation).
    impacts_expected : float
        Expected number of impacts during the record.
    pounding_probability : float
        Probability of at least one impact [-].
    required_gap : float
        Gap giving ``target_probability`` of no pounding [m].
    target_probability : float
        Target probability of no pounding [-].
    upcrossing_rate : float
        nu0+ = sigma_V / (2 pi sigma_X) [1/s] (stationary).
    peak_force_ratio : float
        K(e): the law's peak force over the undamped Hertz one [-].
    separation_rules : dict
        Gaps by the SRSS, ABS and DDC rules from the expected peak
        displacements of the contact floors [m].
    paper : PaperEstimate
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
    separation_rules: dict
    paper: PaperEstimate
    response: ContactResponse = field(repr=False)

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
            "separation_rules": dict(self.separation_rules),
            "gap": self.case.contact.gap,
            "duration": self.case.excitation.duration,
            "paper": {
                "force_expected": paper.force_expected,
                "relative_velocity_expected": paper.relative_velocity_expected,
                "crossing_rate": paper.crossing_rate,
                "duration_effective": paper.duration_effective,
                "peak_factor": paper.peak_factor,
                "penetration_expected": paper.penetration_expected,
            },
            "units": {"force": "N", "length": "m", "velocity": "m/s", "rate": "1/s", "duration": "s"},
        }
        if not self.case.excitation.stationary:
            out["paper"]["sigma_relative_velocity_equivalent"] = paper.sigma_relative_velocity_equivalent
        return out


# --- the paper's method ------------------------------------------------------


def paper_estimate(case: Case, response: ContactResponse, nonstationary: str = "eq28") -> PaperEstimate:
    """The published estimator, Eq. 12-30.

    Parameters
    ----------
    case : Case
    response : ContactResponse
        Stationary response of the linearized pair at the contact floors.
    nonstationary : str
        How sigma_V(t) is found for a modulated motion: ``"eq28"``, the paper's
        A(t)^2 sigma_inf^2, or ``"exact"``, the time-varying covariance.
    """
    sigma_x = response.sigma_relative_displacement
    sigma_v = response.sigma_relative_velocity
    rate = response.zero_crossing_rate  # Eq. 24 (NOTES.md 11: the displacement's rate)
    excitation = case.excitation
    if excitation.stationary:
        duration, sigma = excitation.duration, sigma_v
        sigma_equivalent = None
    else:
        times = np.arange(0.0, excitation.duration + 1e-9, _HISTORY_STEP)
        _, variance = _relative_variances(case, response, times, nonstationary)
        variance_eq, duration = equivalent_stationary(variance, times, n1=3)  # Eq. 29
        sigma = sigma_equivalent = math.sqrt(variance_eq)
    factor = davenport_peak_factor(rate, duration)  # Eq. 23 / 30
    velocity = factor * sigma
    contact = case.contact
    if contact.model == "linear":
        force = penetration = None
    else:
        # Eq. 13-14: the Hertz peak for the separation velocity e * delta_dot_e (NOTES.md 10).
        separation = contact.restitution * velocity
        force = float(undamped_peak_force(contact, separation, case.reduced_mass))
        penetration = (force / contact.stiffness) ** (2.0 / 3.0)
    return PaperEstimate(force, float(velocity), float(rate), float(duration), float(factor), sigma_equivalent, penetration)


# --- the recommended estimator ----------------------------------------------


@dataclass(frozen=True)
class _Crossings:
    """sigma_X(t), sigma_V(t) on a time grid with trapezoid weights [s] (one
    point weighing the duration for a stationary motion).

    Lambda(gap, v), the expected number of impacts faster than v, is
    sum_t w_t nu0+(t) exp(-q_t / 2) with q_t = gap^2/sigma_X(t)^2 + v^2/sigma_V(t)^2.
    When both sigmas follow one modulation a(t) (stationary, Eq. 28), that is
    nu0+ W(q) with W(q) = sum_t w_t exp(-q / (2 a_t^2)) a function of the
    stationary q alone, tabulated once: a gap curve then costs microseconds.
    """

    sigma_x: np.ndarray
    sigma_v: np.ndarray
    weights: np.ndarray

    @property
    def rate(self) -> np.ndarray:
        return self.sigma_v / (2.0 * math.pi * self.sigma_x)

    @cached_property
    def _log_w_table(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(q grid, log W(q)) when X and V share one modulation a(t), else None."""
        a_x = self.sigma_x / self.sigma_x.max()
        a_v = self.sigma_v / self.sigma_v.max()
        if not np.allclose(a_x, a_v, rtol=1e-9, atol=0.0):
            return None
        # Beyond q = 200, W < T exp(-100): no impact in any record.
        grid = np.linspace(0.0, 200.0, 1025)
        table = np.sum(self.weights * np.exp(-0.5 * grid[:, None] / a_x**2), axis=-1)
        with np.errstate(divide="ignore"):
            return grid, np.log(table)

    def intensity(self, gaps, velocities) -> np.ndarray:
        """Lambda(gap, v), shape (gaps, velocities)."""
        gaps = np.asarray(gaps, dtype=float)[:, None]
        velocities = np.asarray(velocities, dtype=float)[None, :]
        table = self._log_w_table
        if table is None:
            exponent = -0.5 * ((gaps[..., None] / self.sigma_x) ** 2 + (velocities[..., None] / self.sigma_v) ** 2)
            return np.sum(self.weights * self.rate * np.exp(exponent), axis=-1)
        i = int(np.argmax(self.sigma_x))
        q = (gaps / self.sigma_x[i]) ** 2 + (velocities / self.sigma_v[i]) ** 2
        if self.weights.size == 1:
            return self.rate[i] * self.weights[0] * np.exp(-0.5 * q)
        grid, log_w = table
        return np.where(q <= grid[-1], self.rate[i] * np.exp(np.interp(q, grid, log_w)), 0.0)


NONSTATIONARY_METHODS = ("eq28", "exact")


def _relative_variances(case: Case, response: ContactResponse, times: np.ndarray, nonstationary: str):
    """Variances of X and V at ``times`` under the modulated motion: Eq. 28,
    A(t)^2 sigma_inf^2, or the exact time-varying covariance of the linearized pair."""
    if nonstationary == "eq28":
        return (
            envelope_variance(case.excitation.envelope, times, response.sigma_relative_displacement**2),
            envelope_variance(case.excitation.envelope, times, response.sigma_relative_velocity**2),
        )
    if nonstationary == "exact":
        history = contact_covariance_history(case, None, times)
        return (
            history[:, 0, 0] + history[:, 1, 1] - 2 * history[:, 0, 1],
            history[:, 2, 2] + history[:, 3, 3] - 2 * history[:, 2, 3],
        )
    raise CaseError("nonstationary", f"must be one of {', '.join(NONSTATIONARY_METHODS)}, got {nonstationary!r}")


def _crossings(case: Case, response: ContactResponse, nonstationary: str) -> _Crossings:
    excitation = case.excitation
    if excitation.stationary:
        return _Crossings(
            np.array([response.sigma_relative_displacement]),
            np.array([response.sigma_relative_velocity]),
            np.array([excitation.duration]),
        )
    times = np.arange(0.0, excitation.duration + 1e-9, _HISTORY_STEP)
    variance_x, variance_v = _relative_variances(case, response, times, nonstationary)
    # Trapezoid weights; instants with no response yet carry none.
    weights = np.full(times.size, _HISTORY_STEP)
    weights[[0, -1]] *= 0.5
    alive = (variance_x > 1e-30) & (variance_v > 1e-30)
    return _Crossings(np.sqrt(variance_x[alive]), np.sqrt(variance_v[alive]), weights[alive])


def _expected_power_of_maximum(crossings: _Crossings, gaps: np.ndarray, power: float) -> np.ndarray:
    """E[V_max^power] for each gap, V_max = 0 without impact: the integral of
    P(V_max^power > s) = 1 - exp(-Lambda(s^(1/power))) over s >= 0."""
    v_top = crossings.sigma_v.max() * (math.sqrt(2.0 * math.log(max(crossings.intensity(np.zeros(1), np.zeros(1))[0, 0], 1.0))) + 7.0)
    s = np.linspace(0.0, v_top**power, 401)
    survival = -np.expm1(-crossings.intensity(gaps, s ** (1.0 / power)))
    return np.trapezoid(survival, s, axis=-1)


def _required_gap(crossings: _Crossings, target_probability: float) -> float:
    """Smallest gap with P(no impact) = exp(-Lambda(gap, 0)) >= target."""
    allowed = -math.log(target_probability)

    def impacts(gap: float) -> float:
        return float(crossings.intensity(np.array([gap]), np.zeros(1))[0, 0])

    if impacts(0.0) <= allowed:
        return 0.0
    low, high = 0.0, crossings.sigma_x.max()
    while impacts(high) > allowed:
        low, high = high, 2.0 * high
    for _ in range(60):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if impacts(middle) > allowed else (low, middle)
    return high


def _separation_rules(case: Case, response: ContactResponse) -> dict:
    """SRSS, ABS and DDC gaps from the expected peak |displacement| of each
    contact floor (Davenport, with twice the upcrossing rate for |x|)."""
    excitation = case.excitation
    sigma_x = np.array(response.sigma_displacement)
    sigma_v = np.array(response.sigma_velocity)
    rate = 2.0 * sigma_v / (2.0 * math.pi * sigma_x)
    if excitation.stationary:
        peaks = sigma_x * davenport_peak_factor(rate, excitation.duration)
    else:
        times = np.arange(0.0, excitation.duration + 1e-9, _HISTORY_STEP)
        peaks = []
        for sigma, nu in zip(sigma_x, rate):
            variance_eq, duration_eq = equivalent_stationary(envelope_variance(excitation.envelope, times, sigma**2), times)
            peaks.append(math.sqrt(variance_eq) * davenport_peak_factor(nu, duration_eq))
        peaks = np.array(peaks)
    u1, u2 = peaks
    correlation = response.covariance_displacement / (sigma_x[0] * sigma_x[1])
    return {
        "srss": float(math.hypot(u1, u2)),
        "abs": float(u1 + u2),
        "ddc": float(math.sqrt(max(u1**2 + u2**2 - 2.0 * correlation * u1 * u2, 0.0))),
        "peak_displacement": [float(u1), float(u2)],
        "displacement_correlation": float(correlation),
    }


def _check_probability(target_probability: float) -> None:
    if not (isinstance(target_probability, float | int) and 0.0 < target_probability < 1.0):
        raise CaseError("target_probability", f"must lie in (0, 1), got {target_probability!r}")


def estimate(
    case: Case, target_probability: float = DEFAULT_TARGET_PROBABILITY, linearized=None, nonstationary: str = "eq28"
) -> Estimate:
    """Expected extreme pounding force of ``case`` by both closed forms.

    Parameters
    ----------
    case : Case
    target_probability : float
        Probability of no pounding the ``required_gap`` must give [-].
    linearized : tuple of two LinearizedBuilding, optional
        Reuse a linearization (it does not depend on the gap).
    nonstationary : str
        For a modulated motion, the time-varying variances: ``"eq28"``
        (A(t)^2 sigma_inf^2, instant) or ``"exact"`` (the linearized pair's
        covariance equation, under a second).
    """
    _check_probability(target_probability)
    linearized = linearized or linearize_pair(case)
    response = response_lyapunov(case, linearized)
    crossings = _crossings(case, response, nonstationary)
    contact = case.contact
    gap = np.array([contact.gap])
    power = _exponent(contact)
    unit_peak = impact_peak_force(contact, 1.0, case.reduced_mass)
    impacts = float(crossings.intensity(gap, np.zeros(1))[0, 0])
    return Estimate(
        case=case,
        force_expected=float(unit_peak * _expected_power_of_maximum(crossings, gap, power)[0]),
        relative_velocity_expected=float(_expected_power_of_maximum(crossings, gap, 1.0)[0]),
        sigma_relative_displacement=response.sigma_relative_displacement,
        sigma_relative_velocity=response.sigma_relative_velocity,
        impacts_expected=impacts,
        pounding_probability=float(-math.expm1(-impacts)),
        required_gap=_required_gap(crossings, target_probability),
        target_probability=float(target_probability),
        upcrossing_rate=response.upcrossing_rate,
        peak_force_ratio=peak_force_ratio(contact.model, contact.restitution),
        separation_rules=_separation_rules(case, response),
        paper=paper_estimate(case, response, nonstationary),
        response=response,
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


def force_versus_gap(case: Case, gaps, linearized=None, nonstationary: str = "eq28") -> GapCurve:
    """The recommended estimate over many gaps; the linearization and the
    response statistics are computed once."""
    gaps = np.asarray(gaps, dtype=float).ravel()
    if gaps.size == 0 or np.any(gaps < 0) or not np.all(np.isfinite(gaps)):
        raise CaseError("gaps", "must be finite numbers >= 0 m")
    linearized = linearized or linearize_pair(case)
    response = response_lyapunov(case, linearized)
    crossings = _crossings(case, response, nonstationary)
    contact = case.contact
    impacts = crossings.intensity(gaps, np.zeros(1))[:, 0]
    force = impact_peak_force(contact, 1.0, case.reduced_mass) * _expected_power_of_maximum(crossings, gaps, _exponent(contact))
    return GapCurve(gaps, force, -np.expm1(-impacts), impacts, paper_estimate(case, response, nonstationary).force_expected)
