"""The stochastic pounding-force spectrum: the mean and the 84th percentile of
F_max against the fundamental period of building 1, building 2 at a fixed
period or a fixed period ratio, closed form (G31 at each pair of periods, F2)
and Monte Carlo on the sweep engine. docs/fragility.md, F5; the random
counterpart of Jankowski's (2006) deterministic pounding force response spectrum.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from pounding import defaults
from pounding.blas import single_blas_thread
from pounding.case.case import Case, as_case
from pounding.case.scaling import with_fundamental_periods
from pounding.closed_form.regimes import accuracy_band
from pounding.errors import ArgumentError, ConvergenceError, finite_number, quote
from pounding.simulation.plan import MonteCarloPlan
from pounding.studies.fragility import check_intensities
from pounding.studies.monte_carlo_study import MonteCarloForces, check_plan_records, monte_carlo_forces_at

__all__ = ["ForceSpectrum", "force_spectrum"]


@dataclass(frozen=True, eq=False)
class ForceSpectrum:
    """E[F_max] and its 84th percentile against building 1's fundamental period.

    Attributes
    ----------
    case : Case
        The case as given.
    period1, period2 : ndarray
        Fundamental periods of building 1 and 2 at each point [s].
    force_mean, force_84 : ndarray
        Closed-form E[F_max] (G19) and 84th percentile (G31) [N].
    pounding_probability : ndarray
        Closed-form P(at least one impact) (G31 at F = 0) [-].
    monte_carlo : MonteCarloForces or None
    accuracy : tuple of MeasuredRange
        The measured accuracy of ``force_mean`` at each period (:func:`~pounding.closed_form.regimes.measured_range`);
        its band: :meth:`force_band`.
    """

    case: Case
    period1: np.ndarray
    period2: np.ndarray
    force_mean: np.ndarray
    force_84: np.ndarray
    pounding_probability: np.ndarray
    monte_carlo: MonteCarloForces | None = None
    accuracy: tuple = ()

    def force_band(self) -> tuple[np.ndarray, np.ndarray]:
        """Where the Monte Carlo E[F_max] lay at each period given the closed form's, by the errors measured in
        each point's regime [N] (:func:`~pounding.closed_form.regimes.accuracy_band`)."""
        return accuracy_band(self.force_mean, self.accuracy)

    def to_dict(self) -> dict:
        """JSON-ready: periods in s, forces in N."""
        out = {
            "case": self.case.name,
            "period1": self.period1.tolist(),
            "period2": self.period2.tolist(),
            "force_mean": self.force_mean.tolist(),
            "force_84": self.force_84.tolist(),
            "pounding_probability": self.pounding_probability.tolist(),
            "measured_accuracy": [r.to_dict() for r in self.accuracy],
        }
        if self.monte_carlo is not None:
            mc = self.monte_carlo
            q84, q84_interval = mc.quantile(0.84)
            out.update(
                records=mc.records,
                seed=None if self.case.recorded else mc.seed,
                force_mean_monte_carlo=mc.force_mean.tolist(),
                force_mean_monte_carlo_interval=mc.force_mean_interval().tolist(),
                force_84_monte_carlo=q84.tolist(),
                force_84_monte_carlo_interval=q84_interval.tolist(),
                pounding_fraction_monte_carlo=[float(np.mean(f > 0)) for f in mc.force_max],
            )
        out["units"] = {"period": "s", "force": "N"}
        return out


def _periods_of_building_2(period1: np.ndarray, period_ratio, period2) -> np.ndarray:
    if (period_ratio is None) == (period2 is None):
        raise ArgumentError("period_ratio", "give one of period_ratio (T2 / T1) and period2 (s)")
    field = "period_ratio" if period2 is None else "period2"
    value = finite_number(field, period_ratio if period2 is None else period2, error=ArgumentError)
    if not value > 0:
        raise ArgumentError(field, f"must be > 0, got {quote(value)}")
    return period1 * value if period2 is None else np.full(period1.shape, value)


def force_spectrum(case, period1, period_ratio: float | None = None, period2: float | None = None,
                   monte_carlo: MonteCarloPlan | None = None) -> ForceSpectrum:
    """The force spectrum of ``case`` over building 1's fundamental periods ``period1`` [s].

    Building 2's period is ``period_ratio`` x T1 or ``period2`` [s] (give one). Each building is made stiffer or
    softer, its masses, yield drifts, damping ratio, the gap, the restitution and the ground motion held
    (:func:`~pounding.case.scaling.with_fundamental_periods`). ``monte_carlo``: also Monte Carlo at each period,
    at least :data:`~pounding.defaults.SPECTRUM_MIN_RECORDS` records.
    """
    from pounding.closed_form.row import force_distribution_and_accuracy

    period1 = check_intensities(period1, "period1")
    periods2 = _periods_of_building_2(period1, period_ratio, period2)
    if monte_carlo is not None:
        check_plan_records(monte_carlo, defaults.SPECTRUM_MIN_RECORDS, "for an interval of the 84th percentile")
    base = case if isinstance(case, Case) else as_case(case)
    distributions, accuracy = [], []
    with single_blas_thread():
        for t1, t2 in zip(period1, periods2):
            try:
                distribution, measured = force_distribution_and_accuracy(with_fundamental_periods(base, t1, t2))
                distributions.append(distribution)
                accuracy.append(measured)
            except ConvergenceError as error:
                raise ConvergenceError(f"at T1 = {t1:.4g} s, T2 = {t2:.4g} s: {error}") from None
    spectrum = ForceSpectrum(
        case=base, period1=period1, period2=periods2,
        force_mean=np.array([d.mean() for d in distributions]),
        force_84=np.array([d.quantile(0.84) for d in distributions]),
        pounding_probability=np.array([1.0 - d.no_impact_probability for d in distributions]), accuracy=tuple(accuracy),
    )
    if monte_carlo is None:
        return spectrum
    adjustments = [{"period1": float(t1), "period2": float(t2)} for t1, t2 in zip(period1, periods2)]
    return dataclasses.replace(spectrum, monte_carlo=monte_carlo_forces_at(monte_carlo, case, adjustments, "force spectrum"))
