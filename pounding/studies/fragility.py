"""Fragility curves of the pounding force: P(F_max > capacity) against the
expected peak ground acceleration, closed form (G31 at each PGA, F1) and Monte
Carlo on the sweep engine, each with the lognormal fragility engineers use,
fitted by maximum likelihood (F3-F4). docs/fragility.md.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.special import log_ndtr, ndtr, ndtri

from pounding import defaults
from pounding.blas import single_blas_thread
from pounding.case.case import Case, as_case
from pounding.case.scaling import PeakGroundAcceleration
from pounding.closed_form.regimes import accuracy_band
from pounding.closed_form.row import force_distribution_and_accuracy
from pounding.errors import ArgumentError, ConvergenceError, check_limit, finite_number, quote
from pounding.simulation.plan import MonteCarloPlan
from pounding.studies.monte_carlo_study import MonteCarloForces, check_plan_records, monte_carlo_forces_at
from pounding.units import STANDARD_GRAVITY

__all__ = ["FragilityCurve", "LognormalFragility", "check_intensities", "fit_lognormal", "fragility_curve"]

DISPERSION_RANGE = (0.01, 5.0)
"""Dispersions beta the lognormal fit may take [-]: a fit at an end says the data do not pin it (all or none exceed
but at one PGA, or a curve flat over the range)."""


@dataclass(frozen=True)
class LognormalFragility:
    """P(F_max > capacity | PGA = a) = Phi(ln(a / median) / dispersion) (F3).

    Attributes
    ----------
    median : float
        The PGA at which the probability is 1/2 [m/s^2].
    dispersion : float
        beta, the standard deviation of ln(PGA capacity) [-].
    at_bound : bool
        The fit lies at an end of :data:`DISPERSION_RANGE`: the data do not pin the dispersion.
    """

    median: float
    dispersion: float
    at_bound: bool = False

    def probability(self, pga) -> np.ndarray:
        """The fitted probability at ``pga`` [m/s^2]."""
        return ndtr(np.log(np.asarray(pga, dtype=float) / self.median) / self.dispersion)

    def to_dict(self) -> dict:
        return {"median_pga": self.median / STANDARD_GRAVITY, "dispersion": self.dispersion, "at_bound": self.at_bound}


def fit_lognormal(pga, exceeding, trials) -> LognormalFragility | None:
    """The lognormal fragility of largest likelihood (F4; Baker 2015, Eq. 11):
    max over (median, beta) of sum_j [z_j ln p_j + (n_j - z_j) ln(1 - p_j)], p_j the
    curve at ``pga`` [m/s^2], z_j of n_j exceeding (``trials``; fractions of 1 for a
    closed-form curve). None where nothing, or everything, exceeds: no curve is pinned."""
    pga = np.asarray(pga, dtype=float)
    exceeding, trials = np.asarray(exceeding, dtype=float), np.broadcast_to(np.asarray(trials, dtype=float), pga.shape)
    if exceeding.sum() <= 0.0 or (trials - exceeding).sum() <= 0.0:
        return None
    from scipy.optimize import minimize

    log_pga = np.log(pga)
    staying = trials - exceeding

    def negative_log_likelihood(theta):
        """F4 and its gradient in (ln median, beta): d ln Phi(z) / dz = phi(z) / Phi(z)."""
        z = (log_pga - theta[0]) / theta[1]
        up, down = log_ndtr(z), log_ndtr(-z)
        density = -0.5 * z * z - 0.5 * math.log(2.0 * math.pi)
        slope = -(exceeding * np.exp(density - up) - staying * np.exp(density - down))  # d(-ln L)/dz
        return -float(np.sum(exceeding * up + staying * down)), np.array([-slope.sum() / theta[1], -(slope * z).sum() / theta[1]])

    bounds = [(log_pga[0] - 10.0, log_pga[-1] + 10.0), DISPERSION_RANGE]
    best = min((minimize(negative_log_likelihood, start, jac=True, method="L-BFGS-B", bounds=bounds)
                for start in _starts(log_pga, exceeding / trials)), key=lambda result: result.fun)
    median, dispersion = math.exp(best.x[0]), float(best.x[1])
    at_bound = not DISPERSION_RANGE[0] * 1.001 < dispersion < DISPERSION_RANGE[1] * 0.999
    return LognormalFragility(median, dispersion, at_bound)


def _starts(log_pga: np.ndarray, fractions: np.ndarray) -> list[tuple[float, float]]:
    """Where F4's search starts: the probit line through the fractions strictly between 0 and 1 (two or more),
    else the first PGA whose fraction reaches 1/2 with two dispersions."""
    inside = (fractions > 0.0) & (fractions < 1.0)
    if np.count_nonzero(inside) >= 2 and np.ptp(log_pga[inside]) > 0:
        slope, intercept = np.polyfit(log_pga[inside], ndtri(fractions[inside]), 1)
        if slope > 0:
            return [(-intercept / slope, float(np.clip(1.0 / slope, *DISPERSION_RANGE)))]
    crossing = np.flatnonzero(fractions >= 0.5)
    centre = log_pga[crossing[0]] if crossing.size else log_pga[-1] + 0.5
    return [(centre, 0.2), (centre, 0.6)]


@dataclass(frozen=True, eq=False)
class FragilityCurve:
    """P(F_max > capacity) against the expected PGA, closed form and (optionally) Monte Carlo.

    Attributes
    ----------
    case : Case
        The case at its own intensity.
    capacity : float
        [N].
    pga : ndarray
        Expected peak ground accelerations [m/s^2] (recorded motions: every record's peak).
    probability : ndarray
        Closed-form P(F_max > capacity) at each PGA (G31) [-].
    force_expected, force_84 : ndarray
        Closed-form E[F_max] and 84th percentile at each PGA [N].
    reference_pga : float
        The case's own expected PGA [m/s^2].
    lognormal : LognormalFragility or None
        Fitted to the closed-form curve.
    monte_carlo : MonteCarloForces or None
    lognormal_monte_carlo : LognormalFragility or None
        Fitted to the Monte Carlo counts.
    accuracy : tuple of MeasuredRange
        The measured accuracy of ``force_expected`` at each PGA (:func:`~pounding.closed_form.regimes.measured_range`:
        the regime moves with the intensity); its band: :meth:`force_band`.
    """

    case: Case
    capacity: float
    pga: np.ndarray
    probability: np.ndarray
    force_expected: np.ndarray
    force_84: np.ndarray
    reference_pga: float
    lognormal: LognormalFragility | None
    monte_carlo: MonteCarloForces | None = None
    lognormal_monte_carlo: LognormalFragility | None = None
    accuracy: tuple = ()

    def force_band(self) -> tuple[np.ndarray, np.ndarray]:
        """Where the Monte Carlo E[F_max] lay at each PGA given the closed form's, by the errors measured in each
        point's regime [N] (:func:`~pounding.closed_form.regimes.accuracy_band`)."""
        return accuracy_band(self.force_expected, self.accuracy)

    def to_dict(self) -> dict:
        """JSON-ready: accelerations in g, forces in N."""
        fit = lambda value: None if value is None else value.to_dict()  # noqa: E731
        out = {
            "case": self.case.name,
            "capacity": self.capacity,
            "pga": (self.pga / STANDARD_GRAVITY).tolist(),
            "case_pga": self.reference_pga / STANDARD_GRAVITY,
            "probability": self.probability.tolist(),
            "force_expected": self.force_expected.tolist(),
            "force_84": self.force_84.tolist(),
            "lognormal": fit(self.lognormal),
            "measured_accuracy": [r.to_dict() for r in self.accuracy],
        }
        if self.monte_carlo is not None:
            out.update(
                records=self.monte_carlo.records,
                seed=None if self.case.recorded else self.monte_carlo.seed,
                exceeding_records=self.monte_carlo.exceeding(self.capacity).tolist(),
                probability_monte_carlo=(self.monte_carlo.exceeding(self.capacity) / self.monte_carlo.records).tolist(),
                probability_monte_carlo_interval=self.monte_carlo.intervals(self.capacity).tolist(),
                force_expected_monte_carlo=[float(np.mean(f)) for f in self.monte_carlo.force_max],
                lognormal_monte_carlo=fit(self.lognormal_monte_carlo),
            )
        out["units"] = {"pga": "g", "capacity": "N", "force": "N", "median_pga": "g"}
        return out


def check_intensities(values, field: str = "pga") -> np.ndarray:
    """Finite values > 0, strictly increasing, at least two, within :data:`~pounding.defaults.MAX_SWEEP_POINTS`."""
    try:
        values = np.array(values, dtype=float).ravel()
    except (TypeError, ValueError):
        raise ArgumentError(field, f"must be a list of numbers, got {quote(values)}") from None
    if values.size < 2:
        raise ArgumentError(field, f"needs at least 2 values, got {values.size}")
    check_limit(field, values.size, defaults.MAX_SWEEP_POINTS, "points", "give fewer values", error=ArgumentError)
    if not np.all(np.isfinite(values)) or not np.all(values > 0):
        raise ArgumentError(field, "every value must be a finite number > 0")
    if not np.all(np.diff(values) > 0):
        raise ArgumentError(field, "must increase strictly")
    return values


def fragility_curve(case, capacity: float, pga, monte_carlo: MonteCarloPlan | None = None) -> FragilityCurve:
    """P(F_max > ``capacity``) at each expected PGA, closed form and, with ``monte_carlo``, Monte Carlo.

    Parameters
    ----------
    case : preset name, path of a case file, dict (the parsed file), or Case (closed form only)
    capacity : float
        [N], > 0.
    pga : array_like
        Expected peak ground accelerations [m/s^2], > 0, increasing. The case's ground motion is scaled to each
        (:class:`~pounding.case.scaling.PeakGroundAcceleration`; recorded motions: every record to that peak).
    monte_carlo : MonteCarloPlan, optional
        Also Monte Carlo at each PGA, at least :data:`~pounding.defaults.FRAGILITY_MIN_RECORDS` records.
    """
    capacity = finite_number("capacity", capacity, error=ArgumentError)
    if not capacity > 0:
        raise ArgumentError("capacity", f"must be > 0 N, got {quote(capacity)}")
    pga = check_intensities(pga)
    if monte_carlo is not None:
        check_plan_records(monte_carlo, defaults.FRAGILITY_MIN_RECORDS, "for a useful interval")
    base = as_case(case) if not isinstance(case, Case) else case
    scaling = PeakGroundAcceleration(base)
    distributions, accuracy = [], []
    with single_blas_thread():
        for value in pga:
            try:
                distribution, measured = force_distribution_and_accuracy(scaling.case_at(value))
                distributions.append(distribution)
                accuracy.append(measured)
            except ConvergenceError as error:
                raise ConvergenceError(f"at PGA {value / STANDARD_GRAVITY:.4g} g: {error}") from None
    probability = np.array([d.probability_exceeding(capacity) for d in distributions])
    curve = FragilityCurve(
        case=base, capacity=capacity, pga=pga, probability=probability,
        force_expected=np.array([d.mean() for d in distributions]),
        force_84=np.array([d.quantile(0.84) for d in distributions]),
        reference_pga=scaling.reference, lognormal=fit_lognormal(pga, probability, 1.0), accuracy=tuple(accuracy),
    )
    if monte_carlo is None:
        return curve
    counts = monte_carlo_forces_at(monte_carlo, case, [{"pga": float(a)} for a in pga], "fragility")
    return dataclasses.replace(curve, monte_carlo=counts,
                               lognormal_monte_carlo=fit_lognormal(pga, counts.exceeding(capacity), counts.records))
