"""A verdict beside every number (issue 32): a closed-form estimate checked against a Monte Carlo study of the same
case, and the numbers the tool stands behind.

:func:`check_estimate` runs the records of the case (:func:`~pounding.simulation.monte_carlo.simulate`) and gives an
:class:`EstimateCheck`: the records' mean F_max with its 95 % interval, their fractiles of F_max, the fraction that
pounds and their gap for the estimate's target probability of no pounding; whether the closed form agrees; and the
force and gap to quote:

- **the force**: the closed form's E[F_max] where it agrees, otherwise the records' mean. It agrees when it lies in
  the 95 % interval of the mean or within ``defaults.CHECK_TOLERANCE`` (10 %) of the mean. Where no record pounded
  (mean 0) it agrees when its probability of pounding is no larger than the records allow: 0 pounding records of n
  rule out, at 95 % confidence, any probability above 1 - 0.05^(1/n) (3.0 % at n = 100).
- **the gap**: the closed form's gap for the target (G22) unless the records' own is larger (the safe side). The
  records' gap is that of :func:`~pounding.simulation.monte_carlo.design_gap`: the order statistic of the records'
  free peaks of X = x1 - x2 toward contact. Until its first contact a record moves freely, so a record that never
  touched has its free peak in the study with contact already; a record that touched has a free peak beyond the
  case's gap. The records' gap therefore comes from the study with contact alone when the order statistic falls
  among the records that never touched (pounding rare at the case's gap); otherwise the same records are run once
  more without contact.

How many records: the plan's count; a recorded suite's records, each once, when the plan names none; otherwise as many
as the precision asks: ``defaults.CHECK_FIRST_RECORDS`` (50) first, then chunks sized from the interval so far, each
record run once (``first_record``), until the 95 % interval of the mean is within ``defaults.CHECK_PRECISION`` (5 %)
of it either side, or ``defaults.CHECK_MAX_RECORDS`` (400) records. If no record pounds, the study stops at
``defaults.CHECK_UNPOUNDED_RECORDS`` (100).
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from pounding import defaults
from pounding.closed_form.estimator import Estimate
from pounding.errors import ArgumentError, described
from pounding.simulation.ground_motion import suite_size
from pounding.simulation.monte_carlo import design_gap, gap_from_peaks, simulate
from pounding.simulation.plan import MonteCarloPlan, as_plan
from pounding.simulation.result import SimulationResult, mean_interval, quantile_interval

__all__ = ["EstimateCheck", "RowCheck", "agrees", "capacity_check_sentence", "check_estimate", "check_gap_for_capacity",
           "check_row", "closed_form_agrees", "contact_check", "monte_carlo_of", "unpounded_bound"]

_SMALLEST_CHUNK = 25
"""Fewest records of a chunk after the first, where the interval asks for only a few more."""
_MARGIN = 1.1
"""The records a chunk aims at, over those the interval so far projects (its half-width falling as 1 / sqrt(n)):
enough that one more chunk usually reaches the precision."""


class _ForceAnswer:
    """The force a check stands behind: the closed form's where it agrees with the records, otherwise theirs."""

    @property
    def force_answer(self) -> float:
        """The E[F_max] the tool stands behind [N]: the closed form's where it agrees, otherwise the records' mean."""
        return self.closed_form_force if self.agrees else self.force_max_mean

    @property
    def answer_source(self) -> str:
        """Where :attr:`force_answer` comes from: "closed form" or "monte carlo"."""
        return "closed form" if self.agrees else "monte carlo"


@dataclass(frozen=True)
class EstimateCheck(_ForceAnswer):
    """A closed-form estimate against a Monte Carlo study of the same case (:func:`check_estimate`).

    Attributes
    ----------
    records : int
        Records of the study.
    seed : int or None
        Seed of the synthetic records; None for a recorded suite.
    force_max_mean : float
        The records' mean F_max [N] (0 counted for a record without impact).
    force_max_confidence_interval : tuple of float
        95 % interval of that mean (Student t) [N]; (-inf, inf) from one record.
    force_max_quantiles : dict
        The records' fractiles of F_max [N], keyed as ``defaults.FORCE_QUANTILES``.
    pounding_fraction : float
        Fraction of the records that pounded [-].
    required_gap : float
        The records' gap for ``target_probability`` of no pounding [m] (:func:`~pounding.simulation.monte_carlo.design_gap`).
    agrees : bool
        Whether the closed form's E[F_max] agrees with the records (the module's docstring says when).
    closed_form_force : float
        The closed form's E[F_max] [N].
    closed_form_gap : float
        The closed form's gap for ``target_probability`` of no pounding (G22) [m].
    closed_form_pounding_probability : float
        The closed form's probability of pounding (G21) [-].
    target_probability : float
        Probability of no pounding both gaps are for [-].
    closed_form_quantiles : dict
        The closed form's fractiles of F_max (G31) [N], keyed as ``force_max_quantiles``.
    """

    records: int
    seed: int | None
    force_max_mean: float
    force_max_confidence_interval: tuple[float, float]
    force_max_quantiles: dict
    pounding_fraction: float
    required_gap: float
    agrees: bool
    closed_form_force: float
    closed_form_gap: float
    closed_form_pounding_probability: float
    target_probability: float
    closed_form_quantiles: dict = dataclasses.field(default_factory=dict)

    @property
    def gap_answer(self) -> float:
        """The gap for the target the tool stands behind [m]: the larger of the closed form's and the records'."""
        return max(self.closed_form_gap, self.required_gap)

    @property
    def gap_source(self) -> str:
        """Where :attr:`gap_answer` comes from: "closed form" or "monte carlo"."""
        return "monte carlo" if self.required_gap > self.closed_form_gap else "closed form"

    @property
    def quantiles_source(self) -> str:
        """Where the fractiles of F_max the tool stands behind come from: the closed form's where its E[F_max] agrees
        and none of its upper fractiles (84 %, 95 %) lies more than ``defaults.CHECK_TOLERANCE`` below the records';
        otherwise the records' ("monte carlo"): a suite whose spread is wider than the closed form's distribution
        has its upper fractiles under-estimated, on the unsafe side."""
        if not self.agrees or not self.closed_form_quantiles:
            return "monte carlo"
        low = 1.0 - defaults.CHECK_TOLERANCE
        upper = [key for key in self.force_max_quantiles if float(key) > 0.5]
        short = any(self.closed_form_quantiles[key] < low * self.force_max_quantiles[key] for key in upper)
        return "monte carlo" if short else "closed form"

    @property
    def quantiles_answer(self) -> dict:
        """The fractiles of F_max the tool stands behind [N], keyed as ``force_max_quantiles``."""
        source = self.force_max_quantiles if self.quantiles_source == "monte carlo" else self.closed_form_quantiles
        return dict(source)

    def fractile_sentence(self, force: Callable[[float], str]) -> str:
        """Where the records' fractiles stand instead of the closed form's, one sentence saying so with them (units
        by ``force``, as :meth:`sentences`); "" where the closed form's stand."""
        if self.quantiles_source == "closed form" or not self.force_max_quantiles:
            return ""
        values = ", ".join(f"{100 * float(key):g} %: {force(value)}" for key, value in self.force_max_quantiles.items())
        why = "" if not self.agrees else " (the closed form's upper fractiles are lower: the records spread wider)"
        return f"Fractiles of F_max from the records{why}: {values}."

    @property
    def error(self) -> float:
        """The closed form's E[F_max] over the records' mean, minus 1 [-]; nan where no record pounded."""
        return self.closed_form_force / self.force_max_mean - 1.0 if self.force_max_mean > 0.0 else math.nan

    def to_dict(self) -> dict:
        """JSON-ready, SI units (``estimate --json``'s ``check``): the study and the verdict."""
        low, high = self.force_max_confidence_interval
        return {
            "records": self.records,
            "seed": self.seed,
            "force_max_mean": self.force_max_mean,
            "force_max_confidence_interval": [_finite_or_none(low), _finite_or_none(high)],
            "force_max_quantiles": dict(self.force_max_quantiles),
            "pounding_fraction": self.pounding_fraction,
            "required_gap": self.required_gap,
            "target_probability": self.target_probability,
            "agrees": self.agrees,
            "units": {"force": "N", "length": "m"},
        }

    def answers(self) -> dict:
        """JSON-ready, SI units (``estimate --json``'s top level): the force and the gap the tool stands behind, and
        where each comes from."""
        return {"force_answer": self.force_answer, "answer_source": self.answer_source,
                "gap_answer": self.gap_answer, "gap_source": self.gap_source,
                "quantiles_answer": self.quantiles_answer, "quantiles_source": self.quantiles_source}

    def sentences(self, force: Callable[[float], str], length: Callable[[float], str]) -> tuple[str, str]:
        """The verdict in two sentences, the force's and the gap's, every number with its unit: ``force`` and
        ``length`` turn a force [N] and a length [m] into text (``Display.force``, ``Display.length``)."""
        plural = "s" if self.records > 1 else ""
        study = (f"{self.records} recorded motion{plural}" if self.seed is None
                 else f"{self.records} record{plural}, seed {self.seed}")
        low, high = self.force_max_confidence_interval
        verdict = "agrees" if self.agrees else f"does not agree: {force(self.force_max_mean)} stands"
        if self.force_max_mean == 0.0:
            found = f"no record pounded (so pounding under {100 * unpounded_bound(self.records):.1f} %, 95 % confidence)"
            closed = f"the closed form's pounding probability, {100 * self.closed_form_pounding_probability:.1f} %, {verdict}"
        else:
            interval = f"95 % interval {force(low)} to {force(high)}" if math.isfinite(high - low) else "one record: no interval"
            found = f"{force(self.force_max_mean)} ({interval})"
            side = "under" if self.error < 0 else "over"
            closed = f"the closed form's {force(self.closed_form_force)} is {100 * abs(self.error):.0f} % {side} it and {verdict}"
        gap = (f"the closed form's {length(self.closed_form_gap)} covers it" if self.gap_source == "closed form"
               else f"the closed form's {length(self.closed_form_gap)} falls short: {length(self.required_gap)} stands")
        force_sentence = f"Monte Carlo check ({study}): {found}; {closed}."
        gap_sentence = (f"Monte Carlo gap for {100 * self.target_probability:g} % no pounding, same records: "
                        f"{length(self.required_gap)}; {gap}.")
        return force_sentence, gap_sentence


def _finite_or_none(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def unpounded_bound(records: int) -> float:
    """The largest probability of pounding that 0 pounding records of ``records`` leave, at 95 % confidence:
    1 - 0.05^(1/records) [-] (about 3 / records)."""
    return 1.0 - 0.05 ** (1.0 / records)


def check_estimate(estimate: Estimate, plan: MonteCarloPlan | int | None = None, **options) -> EstimateCheck:
    """Check a closed-form estimate against a Monte Carlo study of its case.

    Parameters
    ----------
    estimate : Estimate
        :func:`~pounding.closed_form.estimator.estimate`'s result; its case is simulated, its
        ``target_probability`` is the target of both gaps.
    plan : MonteCarloPlan, or int, optional
        How the study runs (a number: its records). ``records`` None (the default): a recorded suite's records,
        each once, or as many synthetic records as the precision asks (the module's docstring). The study starts
        at record 0 whatever ``first_record`` says; ``progress(done, total)`` counts the records run with and
        without contact, ``total`` growing as the study does.
    **options
        Fields of the plan given one by one: ``check_estimate(result, records=200, seed=1)``.

    Returns
    -------
    EstimateCheck
    """
    if not isinstance(estimate, Estimate):
        raise ArgumentError("estimate", f"must be an Estimate (pounding.estimate's result), got {described(estimate)}")
    if isinstance(plan, numbers.Integral) and not isinstance(plan, bool):
        if "records" in options:
            raise ArgumentError("records", "is given twice: as the plan and by name")
        plan, options = None, {"records": plan, **options}
    plan = as_plan(plan, options)
    case = estimate.case
    counted = _Progress(plan.progress)
    result = monte_carlo_of(case, plan, counted)

    def free_peaks() -> np.ndarray:
        counted.planned = 2 * result.n_records
        return design_gap(case, estimate.target_probability,
                          dataclasses.replace(plan, records=result.n_records, progress=counted.at(result.n_records))).peaks

    check = contact_check(estimate, result, result, free_peaks)
    counted.finish()
    return check


@dataclass(frozen=True)
class RowCheck(_ForceAnswer):
    """A case of several contacts against one Monte Carlo study of the whole case (:func:`check_row`): every contact
    acts in the same time histories.

    Attributes
    ----------
    records, seed, force_max_mean, force_max_confidence_interval, force_max_quantiles, pounding_fraction, agrees
        As :class:`EstimateCheck`'s, for the largest force over all contacts and a pounding at any contact.
    closed_form_force : float
        The closed form's E[F_max] of the largest force over all contacts [N].
    contacts : tuple of EstimateCheck
        Each contact's check, in the case's order.
    """

    records: int
    seed: int | None
    force_max_mean: float
    force_max_confidence_interval: tuple[float, float]
    force_max_quantiles: dict
    pounding_fraction: float
    agrees: bool
    closed_form_force: float
    contacts: tuple[EstimateCheck, ...]

    def to_dict(self) -> dict:
        """JSON-ready, SI units: the study, the verdict over all contacts, and each contact's (``contacts``)."""
        low, high = self.force_max_confidence_interval
        return {
            "records": self.records, "seed": self.seed, "force_max_mean": self.force_max_mean,
            "force_max_confidence_interval": [_finite_or_none(low), _finite_or_none(high)],
            "force_max_quantiles": dict(self.force_max_quantiles), "pounding_fraction": self.pounding_fraction,
            "agrees": self.agrees, "force_answer": self.force_answer, "answer_source": self.answer_source,
            "contacts": [{**c.to_dict(), **c.answers()} for c in self.contacts], "units": {"force": "N", "length": "m"},
        }


def check_row(estimate, plan: MonteCarloPlan | None = None, **options) -> RowCheck:
    """Check the closed form of a case of several contacts (a :class:`~pounding.closed_form.row.RowEstimate`) against
    one Monte Carlo study of the whole case: the largest force over all contacts, and each contact's force and gap
    as :func:`check_estimate` checks them. ``plan`` and ``**options`` as :func:`check_estimate`'s."""
    plan = as_plan(plan, options)
    case = estimate.case
    counted = _Progress(plan.progress)
    result = monte_carlo_of(case, plan, counted)
    free = []

    def free_peaks(index: int):
        def peaks() -> np.ndarray:
            if not free:  # every contact's free peaks from one run of the records without contact
                counted.planned = 2 * result.n_records
                apart = dataclasses.replace(case, contacts=tuple(
                    dataclasses.replace(c, gap=2.0 * plan.settings.displacement_limit) for c in case.contacts))
                free.append(simulate(apart, dataclasses.replace(plan, records=result.n_records, first_record=0,
                                                                progress=counted.at(result.n_records))))
            return free[0].contacts[index].relative_displacement_max
        return peaks

    contacts = tuple(contact_check(e, result.contacts[i], result, free_peaks(i)) for i, e in enumerate(estimate.contacts))
    counted.finish()
    return RowCheck(
        records=result.n_records, seed=None if case.recorded else result.seed, force_max_mean=result.force_max_mean,
        force_max_confidence_interval=tuple(float(v) for v in result.force_max_confidence_interval),
        force_max_quantiles={key: result.force_max_quantile(float(key))[0] for key in defaults.FORCE_QUANTILES},
        pounding_fraction=result.pounding_fraction, agrees=agrees(estimate, result.force_max),
        closed_form_force=estimate.force_expected, contacts=contacts,
    )


def monte_carlo_of(case, plan: MonteCarloPlan, counted: _Progress) -> SimulationResult:
    """The check's study of ``case``: the plan's records, a recorded suite's each once, or as many as the precision
    asks (the module's docstring), from record 0."""
    if plan.records is not None or suite_size(case):
        return simulate(case, dataclasses.replace(plan, first_record=0, progress=counted.at(0)))
    return _adaptive(case, plan, counted)


def contact_check(estimate: Estimate, peaks, result: SimulationResult, free_peaks: Callable[[], np.ndarray]) -> EstimateCheck:
    """The check of one contact's ``estimate`` against its per-record ``peaks`` (``force_max``, ``impacts``,
    ``relative_displacement_max``: a :class:`SimulationResult` of one contact, or a
    :class:`~pounding.simulation.result.ContactPeaks`) in the study ``result``; ``free_peaks()`` gives the same
    records' free peaks at the contact, run without contact, where the records' gap needs them."""
    target = estimate.target_probability
    # a record that never touched moved freely throughout; one that touched only here has its free peak beyond the
    # gap; where another contact's impacts moved a record, its free peak here is unknown: the records run again apart
    elsewhere = np.any(result.impacts > peaks.impacts)
    gap = gap_from_peaks(np.where(result.impacts == 0, peaks.relative_displacement_max, np.inf), target)
    if elsewhere or not math.isfinite(gap):
        gap = gap_from_peaks(free_peaks(), target)
    force_max = peaks.force_max
    return EstimateCheck(
        records=result.n_records,
        seed=None if result.case.recorded else result.seed,
        force_max_mean=float(np.mean(force_max)),
        force_max_confidence_interval=tuple(float(v) for v in mean_interval(force_max)),
        force_max_quantiles={key: quantile_interval(force_max, float(key))[0] for key in defaults.FORCE_QUANTILES},
        pounding_fraction=float(np.mean(peaks.impacts > 0)),
        required_gap=gap,
        agrees=agrees(estimate, force_max),
        closed_form_force=estimate.force_expected,
        closed_form_gap=estimate.required_gap,
        closed_form_pounding_probability=estimate.pounding_probability,
        target_probability=target,
        closed_form_quantiles={key: float(estimate.force_max_distribution.quantile(float(key)))
                               for key in defaults.FORCE_QUANTILES},
    )


def agrees(estimate, force_max: np.ndarray) -> bool:
    """Whether the closed form's E[F_max] and probability of pounding (an :class:`Estimate`'s, or a
    :class:`~pounding.closed_form.row.RowEstimate`'s) agree with the records' per-record F_max [N]:
    :func:`closed_form_agrees` of their mean and its 95 % interval."""
    force_max = np.asarray(force_max, dtype=float)
    return closed_form_agrees(estimate, float(np.mean(force_max)), mean_interval(force_max), force_max.size)


def closed_form_agrees(estimate, mean: float, interval: tuple[float, float], records: int) -> bool:
    """Whether the closed form's E[F_max] agrees with a Monte Carlo study of its case: the one rule of every verdict
    (the module's docstring).

    Parameters
    ----------
    estimate : Estimate or RowEstimate
        The closed form: its ``force_expected`` [N], and its ``pounding_probability`` [-] where no record pounded.
    mean : float
        The records' mean F_max [N] (0 where none pounded).
    interval : tuple of float
        The 95 % interval of that mean [N]; not finite from one record.
    records : int
        How many records the study ran.

    Returns
    -------
    bool
        Inside the interval or within ``defaults.CHECK_TOLERANCE`` of the mean; where the mean is 0, a probability
        of pounding no larger than :func:`unpounded_bound` of ``records``.
    """
    force = estimate.force_expected
    if mean == 0.0:
        return bool(estimate.pounding_probability <= unpounded_bound(records))
    low, high = interval
    return bool(low <= force <= high and math.isfinite(high - low)) or abs(force / mean - 1.0) <= defaults.CHECK_TOLERANCE


class _Progress:
    """The caller's ``progress(done, total)`` over the study's parts: each part reports its own records, offset by
    those before it; ``planned`` is the total as the study knows it so far."""

    def __init__(self, report):
        self.report, self.done, self.planned = report, 0, 0

    def at(self, offset: int):
        if self.report is None:
            return None

        def progress(done: int, total: int) -> None:
            self.done = offset + done
            self.planned = max(self.planned, offset + total)
            self.report(self.done, self.planned)

        return progress

    def finish(self) -> None:
        if self.report is not None and self.planned != self.done:
            self.planned = self.done
            self.report(self.done, self.done)


def _adaptive(case, plan: MonteCarloPlan, counted: _Progress) -> SimulationResult:
    """Synthetic records in chunks, each record once, until the precision or the count of the module's docstring."""
    parts: list[SimulationResult] = []
    size = defaults.CHECK_FIRST_RECORDS
    while size:
        done = sum(part.n_records for part in parts)
        counted.planned = max(counted.planned, done + size)
        parts.append(simulate(case, dataclasses.replace(plan, records=size, first_record=done, progress=counted.at(done))))
        result = SimulationResult.joined(parts)
        size = _next_chunk(result)
    return result


def _next_chunk(result: SimulationResult) -> int:
    """Records of the next chunk; 0 when the study is done."""
    records, mean = result.n_records, result.force_max_mean
    room = defaults.CHECK_MAX_RECORDS - records
    if room <= 0:
        return 0
    if mean == 0.0:
        return max(0, min(defaults.CHECK_UNPOUNDED_RECORDS - records, room))
    low, high = result.force_max_confidence_interval
    ratio = (high - low) / 2.0 / (defaults.CHECK_PRECISION * mean)
    if ratio <= 1.0:
        return 0
    wanted = math.ceil(_MARGIN * records * ratio**2)
    return min(room, max(wanted - records, _SMALLEST_CHUNK))


def check_gap_for_capacity(estimate: Estimate, capacity: float, check: EstimateCheck,
                           progress: Callable[[int, int], None] | None = None) -> dict:
    """The Monte Carlo at the closed form's gap for a ``capacity`` [N] (:meth:`Estimate.gap_for_capacity`), on the
    records of ``check`` (its count and seed; a recorded suite's own records, each once): the gap [m], the records,
    the fraction whose F_max exceeds the capacity with its 95 % Wilson interval, and ``holds``: whether that interval
    reaches down to the target 1 - ``estimate.target_probability``. ``progress(done, total)`` counts its records."""
    gap = estimate.gap_for_capacity(capacity)
    case = estimate.case
    at_gap = case.with_contact(gap=gap)
    study = (simulate(at_gap, progress=progress) if case.recorded
             else simulate(at_gap, records=check.records, seed=check.seed, progress=progress))
    exceedance = study.exceedance(capacity)
    holds = exceedance["probability_exceeding_interval"][0] <= 1.0 - estimate.target_probability
    return {"gap": gap, "records": study.n_records, **exceedance, "holds": bool(holds)}


def capacity_check_sentence(at_gap: dict, capacity: float, target_probability: float, force: Callable[[float], str],
                            length: Callable[[float], str]) -> str:
    """:func:`check_gap_for_capacity`'s answer ``at_gap`` in one sentence, every number with its unit (``force`` and
    ``length`` as in :meth:`EstimateCheck.sentences`): how many records exceed the ``capacity`` [N] at the gap for
    it, and whether the target 1 - ``target_probability`` holds there."""
    low, high = at_gap["probability_exceeding_interval"]
    verdict = "holds" if at_gap["holds"] else "does not hold: widen the gap"
    return (f"At the gap for {force(capacity)}, {length(at_gap['gap'])}: {100 * at_gap['probability_exceeding']:.1f} % "
            f"of {at_gap['records']} records exceed it (95 % interval {100 * low:.1f} % to {100 * high:.1f} %); "
            f"the target of {100 * (1 - target_probability):g} % {verdict}.")
