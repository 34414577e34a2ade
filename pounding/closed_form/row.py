"""The closed form of a case of several contacts: a row of buildings, or two
buildings meeting at several floors (docs/theory.md, "Several contacts").

Outside contact the buildings move independently, so each building is
linearized once, and each contact's relative motion is that of its two
linearized buildings under the common ground motion: each contact's
:class:`~pounding.closed_form.estimator.Estimate` is that of its pair
(:meth:`~pounding.case.case.Case.pair`). What one impact does to the motion at
another contact is not in the closed form; the Monte Carlo has it, and
docs/accuracy.md measures its effect.

The largest force over all contacts, F_max = max_c F_max,c, is taken with the
contacts' extremes independent:

    P(F_max <= f) = prod_c P(F_max,c <= f)

Positively correlated extremes (the floors of one pair, which sway together)
exceed a force less often than independent ones (Slepian's inequality), so
this errs on the safe side for them; the extremes at the two sides of a
building, of opposite sign, are nearly independent over a record.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pounding import defaults
from pounding.case.case import Case
from pounding.errors import CaseError
from pounding.closed_form.force_distribution import ForceDistribution, force_distribution_of
from pounding.closed_form.linearization import linearize_row
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import CHECK_ADVICE, MeasuredRange, error_span, measured_range, row_measured_range

__all__ = ["SAFE_SIDE", "RowEstimate", "contact_pairs", "force_distribution_and_accuracy", "largest_force_distribution",
           "safe_side_statement"]


def contact_pairs(case: Case) -> tuple[LinearizedPair, ...]:
    """Each contact's two buildings as a :class:`~pounding.closed_form.pair.LinearizedPair`, in the case's order,
    each building linearized once (:func:`~pounding.closed_form.linearization.linearize_row`). :class:`CaseError`
    naming the contact where its two buildings move alike: alone they never pound, but in the case the impacts at
    the other contacts can make them, which the closed form cannot say."""
    buildings = linearize_row(case)
    first = {}  # the first pair of each two buildings: the others share its state space
    pairs = []
    for index, contact in enumerate(case.contacts):
        if contact.between in first:
            pairs.append(first[contact.between].for_contact(case.pair(index)))
        else:
            pairs.append(first.setdefault(contact.between, LinearizedPair(case.pair(index), tuple(buildings[b - 1] for b in contact.between))))
        if pairs[-1].moves_alike:
            left, right = contact.between
            raise CaseError(f"contacts.{index + 1}", f"buildings {left} and {right} move alike: alone they never pound, but "
                            "the impacts at the other contacts can make them; the closed form cannot say how hard: use simulate")
    return tuple(pairs)


def force_distribution_and_accuracy(case: Case) -> tuple[ForceDistribution, MeasuredRange]:
    """P(F_max <= f) of ``case`` at its own gaps, and the accuracy measured on cases like it, without the rest of an
    estimate: one contact's (G31, :func:`~pounding.closed_form.force_distribution.force_distribution_of`), or the
    largest over several contacts' (:func:`largest_force_distribution`). What curves over an intensity or a period
    take at each point."""
    if len(case.contacts) == 1:
        pair = LinearizedPair.of(case)
        return force_distribution_of(pair), measured_range(pair)
    distributions = [force_distribution_of(pair) for pair in contact_pairs(case)]
    return largest_force_distribution(distributions), row_measured_range(case)


def largest_force_distribution(distributions) -> ForceDistribution:
    """P(max_c F_max,c <= f) = prod_c P(F_max,c <= f), on the union of the contacts' force grids [N]."""
    forces = np.unique(np.concatenate([d.forces for d in distributions]))
    cdf = np.prod([d.probability_below(forces) for d in distributions], axis=0)
    return ForceDistribution(forces, np.maximum.accumulate(cdf))


@dataclass(frozen=True)
class RowEstimate:
    """The closed form of a case of several contacts.

    Attributes
    ----------
    case : Case
    contacts : tuple of Estimate
        Each contact's estimate on its two buildings, in the case's order.
    force_max_distribution : ForceDistribution
        P(F_max <= f) of the largest force over all contacts (:func:`largest_force_distribution`).
    target_probability : float
        Target probability of no pounding of each contact's ``required_gap`` [-].
    accuracy, contact_accuracy : MeasuredRange
        How far the largest force, and each contact's, were measured from Monte Carlo on cases of its kind
        (:func:`~pounding.closed_form.regimes.row_measured_range`): each contact's own estimate states the accuracy
        measured on two buildings with one contact, which the contacts' interaction does not have.
    """

    case: Case
    contacts: tuple
    force_max_distribution: ForceDistribution
    target_probability: float
    accuracy: MeasuredRange
    contact_accuracy: MeasuredRange

    @property
    def measured_accuracy(self) -> str:
        """How far from Monte Carlo the largest force was measured on cases of its kind, in one sentence."""
        return safe_side_statement(self.accuracy)

    @property
    def force_expected(self) -> float:
        """E[F_max] of the largest force over all contacts [N]."""
        return self.force_max_distribution.mean()

    @property
    def pounding_probability(self) -> float:
        """Probability that any contact pounds, the contacts independent [-]."""
        return float(1.0 - math.prod(1.0 - c.pounding_probability for c in self.contacts))

    @property
    def governing(self) -> int:
        """Index of the contact with the largest E[F_max] (from 0, the case's order)."""
        return int(np.argmax([c.force_expected for c in self.contacts]))

    @property
    def warnings(self) -> tuple[str, ...]:
        """Where the largest force's measured range is wide, a warning saying so; then each contact's warnings, each
        once, led by the contacts it is about (numbered from 1 in the case's order)."""
        seen = {}
        for number, estimate in enumerate(self.contacts, start=1):
            for warning in estimate.warnings:
                seen.setdefault(warning, []).append(str(number))
        own = () if self.accuracy.signable else (
            f"The largest force was measured {error_span(self.accuracy)} off Monte Carlo {self.accuracy.where}"
            f"{', on the safe side' if _safe_side(self.accuracy) else ''}. {CHECK_ADVICE}",)
        if not self.contact_accuracy.signable:  # the shielding the closed form leaves out (docs/theory.md, "Several contacts")
            own += (f"A contact beside one that pounds harder pounds less than its estimate says (up to "
                    f"{1 + self.contact_accuracy.high:.0f} times less, measured). {CHECK_ADVICE}",)
        return own + tuple(warning if len(numbers) == len(self.contacts) else
                           f"Contact{'s' if len(numbers) > 1 else ''} {', '.join(numbers)}: {warning}"
                           for warning, numbers in seen.items())

    def probability_exceeding(self, capacity: float) -> float:
        """P(F_max > capacity) at any contact [-] for a capacity [N] > 0."""
        return self.force_max_distribution.probability_exceeding(capacity)

    def to_dict(self) -> dict:
        """JSON-ready, SI units: the largest force over all contacts, the governing contact and each contact's."""
        distribution = self.force_max_distribution
        governing = self.case.contacts[self.governing]
        return {
            "case": self.case.name,
            "force_expected": self.force_expected,
            "force_max_quantiles": {key: distribution.quantile(float(key)) for key in defaults.FORCE_QUANTILES},
            "no_impact_probability": distribution.no_impact_probability,
            "pounding_probability": self.pounding_probability,
            "target_probability": self.target_probability,
            "governing_contact": {"between": list(governing.between), "levels": list(governing.levels)},
            "measured_accuracy": self.measured_accuracy,
            "measured_accuracy_range": self.accuracy.to_dict(),
            "warnings": list(self.warnings),
            "duration": self.case.excitation.duration,
            "contacts": [_contact_dict(contact, estimate, self.contact_accuracy)
                         for contact, estimate in zip(self.case.contacts, self.contacts)],
            "units": {"force": "N", "length": "m", "duration": "s"},
        }


SAFE_SIDE = -0.10
"""A measured range whose lowest error is above this [-] never lay more than 10 % below Monte Carlo: its estimates are
on the safe side, however far above, and say so."""


def _safe_side(accuracy: MeasuredRange) -> bool:
    return accuracy.low >= SAFE_SIDE


def safe_side_statement(accuracy: MeasuredRange) -> str:
    """A measured range in one sentence (:meth:`~pounding.closed_form.regimes.MeasuredRange.statement`), in full where
    it lay on the safe side: an estimate that was never more than 10 % under Monte Carlo bounds the force from above."""
    if accuracy.signable or not _safe_side(accuracy):
        return accuracy.statement()
    return (f"Measured {error_span(accuracy)} off Monte Carlo {accuracy.where} (within 10 % on "
            f"{accuracy.within_10_percent} of {accuracy.cases} cases): on the safe side, at times well above.")


def _contact_dict(contact, estimate, accuracy: MeasuredRange) -> dict:
    """One contact's answer: the keys of the issue's table first, the accuracy measured at each contact of cases of its
    kind, then its estimate on its two buildings alone (``estimate``)."""
    distribution = estimate.force_max_distribution
    return {
        "between": list(contact.between),
        "levels": list(contact.levels),
        "gap": contact.gap,
        "force_expected": estimate.force_expected,
        "force_max_quantiles": {key: distribution.quantile(float(key)) for key in defaults.FORCE_QUANTILES},
        "pounding_probability": estimate.pounding_probability,
        "required_gap": estimate.required_gap,
        "measured_accuracy": safe_side_statement(accuracy),
        "measured_accuracy_range": accuracy.to_dict(),
        "estimate": estimate.to_dict(),
    }
