"""Closed-form estimates of the expected extreme pounding force, without a
time-history analysis: the paper's method as published (Section 4, Eq. 12-30,
with the printing errors of docs/errata.md fixed; :mod:`pounding.closed_form.paper_method`)
and this project's gap-aware estimator (docs/theory.md, G1-G26;
:mod:`pounding.closed_form.gap_aware`), side by side, with the regime and accuracy each
estimate states (:mod:`pounding.closed_form.regimes`).

Both stand on the same statistically linearized pair (Eq. 19-21,
:class:`~pounding.closed_form.pair.LinearizedPair`) and its response at the contact
floors (Eq. 16-18, 25).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pounding import defaults
from pounding.case.case import Case, as_case
from pounding.blas import single_blas_thread
from pounding.case.engineering import engineering_terms
from pounding.closed_form.force_distribution import ForceDistribution, force_distribution, gap_for_capacity
from pounding.closed_form.gap_aware import (
    Crossings,
    expected_force_maximum,
    expected_maximum,
    gap_for_probability,
    opposing_forces,
)
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.paper_method import PaperEstimate, check_michaelov_n1, paper_estimate
from pounding.closed_form.regimes import MeasuredRange, assess, extreme_warnings, hazard_warnings, row_measured_range
from pounding.closed_form.response import ContactResponse
from pounding.closed_form.row import RowEstimate, contact_pairs, largest_force_distribution
from pounding.closed_form.separation import CodeCheck, code_checks, separation_rules
from pounding.errors import ArgumentError, check_limit, check_probability
from pounding.mechanics.contact import peak_force_ratio

__all__ = ["Estimate", "GapCurve", "estimate", "force_versus_gap", "gap_curve"]


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
        times as many, docs/accuracy.md).
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
        0 where no impact is expected (``impacts_expected`` 0: the gap lies some
        40 sigma_X or more away), since nothing is braked there.
    impacting_velocity_ratio : float
        sigma_V of the motion between impacts over the free motion's [-]: what
        the impacts before an approach leave it (:mod:`pounding.closed_form.impact_damping`);
        the force and the largest approach speed are counted on it, the pounding
        probability and the gap for the target on the free motion.
    impact_memory : float
        Share of an impact's disturbance still in the relative motion at the
        next approach [-] (0: the pair forgets an impact before the next).
    impact_dashpot : float
        The dashpot between the contact floors that damps the relative motion
        alike [N s/m].
    separation_rules : dict
        Gaps by the SRSS, ABS and DDC rules [m] from the expected peak ``|x|`` of
        each contact floor (``peak_displacement`` [m]: the linearized floor from
        rest with Vanmarcke's clumps, :func:`~pounding.random_vibration.peaks.expected_absolute_peak`)
        and their stationary correlation (``displacement_correlation`` [-]).
    paper : PaperEstimate
    response : ContactResponse
        The linearized pair's stationary response at the contact floors, the
        paper's (Eq. 16-18, 25), without the residual's response.
    warnings : tuple of str
        Where the case lies outside the range in which the estimate was found
        within 10 % of Monte Carlo: what is wrong, how large the error can be,
        what to do (docs/accuracy.md); first those of extreme inputs (records
        cut below the motion's frequencies, a soft contact, a force no building
        takes: :func:`~pounding.closed_form.regimes.extreme_warnings`).
    crossings : Crossings
        The free motion's sigma history, from which :meth:`gap_curve` counts other gaps.
    force_max_distribution : ForceDistribution
        P(F_max <= f) at the case's gap (G31): its quantiles, P(F_max > capacity).
    accuracy_regime : str
        One of :data:`~pounding.closed_form.regimes.REGIMES`: where the estimate's
        accuracy was measured alike.
    measured_accuracy : str
        How far from Monte Carlo the recommended force was measured in that
        regime (docs/accuracy.md); a range wider than 30 % either side is not
        printed without a Monte Carlo verdict (``accuracy.statement(with_verdict=True)`` prints it).
    accuracy : MeasuredRange
        The numbers behind it (:func:`~pounding.closed_form.regimes.measured_range`).
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
    warnings: tuple[str, ...]
    crossings: Crossings = field(repr=False)
    force_max_distribution: ForceDistribution = field(repr=False)
    accuracy_regime: str
    measured_accuracy: str
    accuracy: MeasuredRange | None = field(default=None, repr=False)

    def gap_curve(self, gaps) -> GapCurve:
        """This estimate at other gaps [m], reusing its response statistics."""
        return gap_curve(self.case, self.crossings, gaps, self.paper.force_expected)

    def probability_exceeding(self, capacity: float) -> float:
        """P(F_max > capacity) [-] for a capacity [N] > 0 (G31)."""
        return self.force_max_distribution.probability_exceeding(capacity)

    @property
    def contacts(self) -> tuple[Estimate]:
        """The estimate of each contact: this one (a :class:`~pounding.closed_form.row.RowEstimate` has several)."""
        return (self,)

    @property
    def code_checks(self) -> tuple[CodeCheck, ...]:
        """The design codes' separation rules against the case's gap, in the codes' words (:func:`code_checks`)."""
        return code_checks(self.separation_rules, self.case.contact.gap)

    def gap_for_capacity(self, capacity: float) -> float:
        """The smallest gap [m] at which P(F_max > capacity) stays at or below 1 - ``target_probability``
        (:func:`~pounding.closed_form.force_distribution.gap_for_capacity`): at most :attr:`required_gap`."""
        if self.crossings is None:  # buildings that move alike never pound
            return 0.0
        return gap_for_capacity(self.crossings, self.case.contact, self.case.reduced_mass, capacity,
                                self.target_probability, self.required_gap)

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
            "code_checks": [check.to_dict() for check in self.code_checks],
            "warnings": list(self.warnings),
            "accuracy_regime": self.accuracy_regime,
            "measured_accuracy": self.measured_accuracy,
            "measured_accuracy_range": None if self.accuracy is None else self.accuracy.to_dict(),
            "gap": self.case.contact.gap,
            "duration": self.case.excitation.duration,
            "paper": {
                "force_expected": paper.force_expected,
                "relative_velocity_expected": paper.relative_velocity_expected,
                "crossing_rate": paper.crossing_rate,
                "duration_effective": paper.duration_effective,
                "peak_factor": paper.peak_factor,
                "penetration_expected": paper.penetration_expected,
                "unavailable": paper.unavailable,
                "sigma_relative_displacement": self.response.sigma_relative_displacement,
                "sigma_relative_velocity": self.response.sigma_relative_velocity,
            },
            "units": {"force": "N", "length": "m", "velocity": "m/s", "rate": "1/s", "duration": "s"},
        }
        if not self.case.excitation.stationary:
            out["paper"]["sigma_relative_velocity_equivalent"] = paper.sigma_relative_velocity_equivalent
            out["paper"]["michaelov_n1"] = paper.michaelov_n1
        distribution = self.force_max_distribution
        out["force_max_quantiles"] = {key: distribution.quantile(float(key)) for key in defaults.FORCE_QUANTILES}
        out["no_impact_probability"] = distribution.no_impact_probability
        out.update(engineering_terms(self.case))
        out["units"]["acceleration"] = "m/s^2"
        return out


def _pair(case) -> LinearizedPair:
    """A pair as it is; a Case, a preset name or a case file's path linearized (:func:`~pounding.case.case.as_case`)."""
    return case if isinstance(case, LinearizedPair) else LinearizedPair.of(as_case(case))


def estimate(
    case: Case | LinearizedPair,
    target_probability: float = defaults.TARGET_PROBABILITY,
    paper_variance: str = defaults.PAPER_VARIANCE,
    michaelov_n1: float = defaults.MICHAELOV_N1,
) -> Estimate | RowEstimate:
    """Expected extreme pounding force of ``case`` by both closed forms.

    A case of several contacts gives a :class:`~pounding.closed_form.row.RowEstimate`: each contact's
    estimate on its two buildings (each building linearized once) and the largest force over all contacts.

    Parameters
    ----------
    case : Case, LinearizedPair, preset name or path of a case file
        A pair reuses its linearization and response (they do not depend on the gap).
    target_probability : float
        Probability of no pounding the ``required_gap`` must give [-].
    paper_variance : str
        For the paper's method under an envelope: ``"eq28"`` (as published)
        or ``"exact"`` (see :data:`~pounding.closed_form.paper_method.PAPER_VARIANCE_METHODS`).
    michaelov_n1 : float
        For the paper's method under an envelope: the order n1 of Eq. 29's
        moments (default 3, as the paper), in :data:`~pounding.defaults.MICHAELOV_N1_RANGE`.
    """
    check_probability(target_probability)
    check_michaelov_n1(michaelov_n1)
    with single_blas_thread():
        return _estimate(case, target_probability, paper_variance, michaelov_n1)


def _estimate(case, target_probability: float, paper_variance: str, michaelov_n1: float) -> Estimate | RowEstimate:
    """:func:`estimate` on checked options."""
    if not isinstance(case, LinearizedPair) and len(as_case(case).contacts) > 1:
        return _row_estimate(as_case(case), target_probability, paper_variance, michaelov_n1)
    pair = _pair(case)
    case = pair.case
    crossings = Crossings.of(pair)
    response = pair.response_with_residual
    contact = case.contact
    gap = np.array([contact.gap])
    impacts = float(crossings.intensity(gap, np.zeros(1))[0, 0])  # G21: Lambda(gap, 0)
    required_gap = gap_for_probability(crossings, target_probability)
    impacting = crossings.damped(gap)
    (velocity,) = expected_maximum(crossings, gap, lambda v: v, 1.0, impacting)
    distribution = force_distribution(crossings, contact.gap, contact, case.reduced_mass, impacting)
    force = distribution.mean()  # G19: E[F_max] on G31's own grid
    paper = paper_estimate(pair, paper_variance, michaelov_n1)
    sigma_x = response.sigma_relative_displacement
    assessment = assess(pair, contact.gap, sigma_x, required_gap, target_probability)
    # Where nothing is expected to pound (a gap ~40 sigma_X or more), no impact is braked: its f0 would be m w^2 d.
    opposing = float(opposing_forces(crossings, gap, case.reduced_mass)[0]) if impacts > 0.0 else 0.0
    return Estimate(
        case=case,
        force_expected=force,
        relative_velocity_expected=float(velocity),
        sigma_relative_displacement=response.sigma_relative_displacement,
        sigma_relative_velocity=response.sigma_relative_velocity,
        impacts_expected=impacts,
        pounding_probability=float(-math.expm1(-impacts)),
        required_gap=required_gap,
        target_probability=float(target_probability),
        upcrossing_rate=response.upcrossing_rate,
        peak_force_ratio=peak_force_ratio(contact.model, contact.restitution),
        opposing_force=opposing,
        impacting_velocity_ratio=float(impacting.ratio_velocity[0]),
        impact_memory=float(impacting.memory[0]),
        impact_dashpot=float(impacting.dashpot[0]),
        separation_rules=separation_rules(pair),
        paper=paper,
        response=pair.stationary_response,
        warnings=(hazard_warnings(case) + extreme_warnings(pair, force, paper.force_expected, float(velocity), sigma_x)
                  + assessment.warnings),
        crossings=crossings,
        force_max_distribution=distribution,
        accuracy_regime=assessment.regime,
        measured_accuracy=assessment.measured_accuracy,
        accuracy=assessment.accuracy,
    )


def _row_estimate(case: Case, target_probability: float, paper_variance: str, michaelov_n1: float) -> RowEstimate:
    """Each contact's estimate on its pair of buildings, each building linearized once."""
    contacts = tuple(_estimate(pair, target_probability, paper_variance, michaelov_n1) for pair in contact_pairs(case))
    distribution = largest_force_distribution([c.force_max_distribution for c in contacts])
    return RowEstimate(case, contacts, distribution, float(target_probability), row_measured_range(case),
                       row_measured_range(case, each_contact=True))


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


def gap_curve(case: Case, crossings: Crossings, gaps, paper_force: float | None) -> GapCurve:
    """The recommended estimate at each of ``gaps`` [m] from the free motion's ``crossings``."""
    gaps = np.asarray(gaps, dtype=float).ravel()
    if gaps.size == 0 or np.any(gaps < 0) or not np.all(np.isfinite(gaps)):
        raise ArgumentError("gaps", "must be finite numbers >= 0 m")
    check_limit("gaps", gaps.size, defaults.MAX_GAPS, "gaps", "estimate fewer gaps at a time", error=ArgumentError)
    impacts = crossings.intensity(gaps, np.zeros(1))[:, 0]
    # A curve for plots and design charts: 81 points in v^p (1e-4) keep 100 gaps within 10 ms.
    force = expected_force_maximum(crossings, gaps, case.contact, case.reduced_mass, crossings.damped(gaps), 81)
    return GapCurve(gaps, force, -np.expm1(-impacts), impacts, paper_force)


def force_versus_gap(case: Case | LinearizedPair, gaps) -> GapCurve:
    """The recommended estimate over many gaps [m]; the linearization and the
    response statistics are computed once (see also :meth:`Estimate.gap_curve`)."""
    pair = _pair(case)
    return gap_curve(pair.case, Crossings.of(pair), gaps, paper_estimate(pair).force_expected)
