"""The computed state: :func:`compute_snapshot` runs the library once for a
case and keeps everything shown for it in a :class:`Snapshot` (all SI)."""

from __future__ import annotations

import dataclasses
import numbers
from dataclasses import dataclass, field

import numpy as np

from pounding import defaults
from pounding.case.case import Case
from pounding.closed_form.estimator import Estimate, GapCurve, estimate
from pounding.closed_form.linearization import equivalent_storey_force
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import accuracy_band, measured_range
from pounding.errors import ArgumentError, SimulationError
from pounding.simulation.monte_carlo import DesignGap, SimulationResult, TimeHistory, simulate, simulate_record
from pounding.simulation.plan import MonteCarloPlan, as_plan
from pounding.studies.check import EstimateCheck

DEFAULT_RECORD = 0
"""Index of that record."""
GAP_POINTS = 41
"""Gaps of the force-versus-gap curve."""
PSD_POINTS = 400
"""Frequencies of the spectra."""


# --- the computed state --------------------------------------------------------


@dataclass(frozen=True)
class MonteCarloPoint:
    """Summary of one Monte Carlo study: mean extreme force [N] with its 95 %
    confidence interval [N], pounding fraction [-], at ``gap`` [m]; and every
    record's F_max [N] (for the empirical distribution)."""

    gap: float
    records: int
    seed: int
    force_max_mean: float
    force_low: float
    force_high: float
    pounding_fraction: float
    force_max_values: tuple = ()

    @classmethod
    def from_result(cls, result: SimulationResult) -> MonteCarloPoint:
        low, high = result.force_max_confidence_interval
        return cls(
            result.case.contact.gap, result.n_records, result.seed, result.force_max_mean, low, high, result.pounding_fraction,
            tuple(float(f) for f in result.force_max),
        )

    @classmethod
    def from_check(cls, check: EstimateCheck, gap: float) -> MonteCarloPoint:
        """The study of an estimate's Monte Carlo check, at its case's ``gap`` [m] (its records' F_max not kept)."""
        low, high = check.force_max_confidence_interval
        return cls(gap, check.records, check.seed, check.force_max_mean, low, high, check.pounding_fraction)


@dataclass(frozen=True, eq=False)
class Snapshot:
    """Everything shown for one case; all SI.

    Attributes
    ----------
    case : Case
    linearized : tuple of two LinearizedBuilding
    estimate : Estimate
    gap_curve : GapCurve
    omega : ndarray
        Circular frequencies of the spectra [rad/s].
    psd_ground : ndarray
        Two-sided PSD of ground acceleration [m^2/s^3] (Eq. 7).
    psd_velocity : ndarray
        Two-sided PSD of the relative velocity at the contact floors [m^2/s].
    history : TimeHistory or None
        Record ``record`` of the study seeded ``seed``; None if it failed.
    history_error : str
        Why ``history`` is None.
    equivalent_force : tuple of two ndarray
        Restoring force of the equivalent linear storeys along the record's drifts [N].
    seed, record : int
    monte_carlo : tuple of MonteCarloPoint
        Studies of this case (at any gap) to show beside the estimates.
    design_gap : DesignGap or None
        The Monte Carlo design gap of this case for the estimate's target
        probability, to show beside the closed-form gap.
    check : EstimateCheck or None
        The estimate checked against the Monte Carlo of this case (:func:`~pounding.studies.check.check_estimate`):
        the report's verdict. None until a report is made (:func:`~.summary.with_check` runs it).
    gap_accuracy : tuple of MeasuredRange
        The measured accuracy of the recommended E[F_max] at each gap of ``gap_curve``
        (:func:`~pounding.closed_form.regimes.measured_range`): the figure's band.
    capacity : float or None
        A force the contact can take [N] (``pounding report --capacity``, the dashboard's capacity): the report
        then states P(F_max > capacity) and the gap sized to it; None: neither.
    capacity_check : dict or None
        The Monte Carlo at the gap for ``capacity`` on the records of ``check``
        (:func:`~pounding.studies.check.check_gap_for_capacity`); None until a report is made
        (:func:`~.summary.with_capacity_check` runs it).
    """

    case: Case
    linearized: tuple
    estimate: Estimate
    gap_curve: GapCurve
    omega: np.ndarray
    psd_ground: np.ndarray
    psd_velocity: np.ndarray
    history: TimeHistory | None
    history_error: str
    equivalent_force: tuple
    seed: int = defaults.SEED
    record: int = DEFAULT_RECORD
    monte_carlo: tuple = field(default=())
    design_gap: DesignGap | None = None
    check: EstimateCheck | None = None
    gap_accuracy: tuple = ()
    capacity: float | None = None
    capacity_check: dict | None = None

    def gap_band(self) -> tuple[np.ndarray, np.ndarray]:
        """Where the Monte Carlo E[F_max] lay at each gap of ``gap_curve`` given the closed form's, by the errors
        measured in each gap's regime [N] (:func:`~pounding.closed_form.regimes.accuracy_band`)."""
        return accuracy_band(self.gap_curve.force_expected, self.gap_accuracy)


def _widest_gap(case: Case, result: Estimate) -> float:
    """The force-against-gap curve's widest gap [m]: past the required gap and twice the case's gap."""
    return max(1.25 * result.required_gap, 2.0 * case.contact.gap, 1e-3)


def gap_grid(case: Case, result: Estimate, points: int = GAP_POINTS) -> np.ndarray:
    """Gaps [m] from 0 past the required gap and twice the case's gap, with the case's gap among them."""
    return np.unique(np.append(np.linspace(0.0, _widest_gap(case, result), points), case.contact.gap))


def curve_gaps(case: Case, result: Estimate, count: int) -> np.ndarray:
    """``count`` gaps [m] evenly across the force-against-gap curve, 0 excluded: where :func:`gap_points` may put
    Monte Carlo points."""
    if count < 1:
        raise ArgumentError("count", f"must be at least 1, got {count}")
    return np.linspace(0.0, _widest_gap(case, result), count + 1)[1:]


def gap_points(case: Case, gaps, plan: MonteCarloPlan | int | None = None, **options) -> tuple[MonteCarloPoint, ...]:
    """Monte Carlo points of the force-against-gap curve: :func:`~pounding.simulation.monte_carlo.simulate` of
    ``case`` with its gap set to each of ``gaps`` [m], by ``plan`` (a number: its records; fields by name as
    ``simulate`` takes them), the same records (seed) at every gap. ``progress(done, total)`` counts over all gaps."""
    if isinstance(plan, numbers.Integral) and not isinstance(plan, bool):
        plan, options = None, {"records": plan, **options}
    plan = as_plan(plan, options)
    gaps = [float(g) for g in np.asarray(gaps, dtype=float).ravel()]
    report, points = plan.progress, []
    for index, gap in enumerate(gaps):
        at_gap = case.with_contact(gap=gap)
        progress = None if report is None else _offset(report, index, len(gaps))
        points.append(MonteCarloPoint.from_result(simulate(at_gap, dataclasses.replace(plan, progress=progress))))
    return tuple(points)


def _offset(report, index: int, count: int):
    """``progress(done, total)`` of the study at the ``index``-th of ``count`` gaps, as a count over them all."""
    return lambda done, total: report(index * total + done, count * total)


def compute_snapshot(
    case: Case,
    seed: int = defaults.SEED,
    record: int = DEFAULT_RECORD,
    target_probability: float = defaults.TARGET_PROBABILITY,
    monte_carlo: tuple = (),
    pair: LinearizedPair | None = None,
    result: Estimate | None = None,
) -> Snapshot:
    """Run the library once for ``case``: the linearization is computed once and shared.

    ``pair`` and ``result``: the case's linearized pair and its estimate at ``target_probability``, when
    already made (the dashboard shows the estimate first); made here otherwise.

    Raises whatever the library raises for an impossible case (``CaseError``,
    ``ConvergenceError``); a failed record is kept in ``history_error``.
    """
    pair = LinearizedPair.of(case) if pair is None else pair
    linearized = pair.buildings
    result = estimate(pair, target_probability) if result is None else result
    curve = result.gap_curve(gap_grid(case, result))
    sigma_x = result.sigma_relative_displacement
    accuracy = tuple(measured_range(pair, gap, sigma_x) for gap in curve.gaps)
    omega = np.geomspace(0.3, case.excitation.cutoff_frequency, PSD_POINTS)
    psd_ground = np.asarray(case.excitation.spectrum.psd(omega), dtype=float)
    psd_velocity = pair.psd_relative_velocity(omega)
    history, history_error, equivalent = None, "", ()
    try:
        history = simulate_record(case, seed, record)
    except SimulationError as error:
        history_error = str(error)
    if history is not None:
        equivalent = tuple(
            equivalent_storey_force(lin, history.time, history.drift[:, [history.floor(b, j + 1) for j in range(lin.building.n_storeys)]])
            for b, lin in enumerate(linearized, start=1)
        )
    return Snapshot(
        case, linearized, result, curve, omega, psd_ground, psd_velocity, history, history_error, equivalent, seed, record,
        tuple(monte_carlo), gap_accuracy=accuracy,
    )
