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
from pounding.closed_form.force_distribution import ForceDistribution

__all__ = ["RowEstimate", "largest_force_distribution"]


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
    """

    case: Case
    contacts: tuple
    force_max_distribution: ForceDistribution
    target_probability: float

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
        """Each contact's warnings, each once, led by the contacts it is about (numbered from 1 in the case's order)."""
        seen = {}
        for number, estimate in enumerate(self.contacts, start=1):
            for warning in estimate.warnings:
                seen.setdefault(warning, []).append(str(number))
        return tuple(warning if len(numbers) == len(self.contacts) else
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
            "warnings": list(self.warnings),
            "duration": self.case.excitation.duration,
            "contacts": [_contact_dict(contact, estimate) for contact, estimate in zip(self.case.contacts, self.contacts)],
            "units": {"force": "N", "length": "m", "duration": "s"},
        }


def _contact_dict(contact, estimate) -> dict:
    """One contact's answer: the keys of the issue's table first, then its estimate's own (``estimate``)."""
    distribution = estimate.force_max_distribution
    return {
        "between": list(contact.between),
        "levels": list(contact.levels),
        "gap": contact.gap,
        "force_expected": estimate.force_expected,
        "force_max_quantiles": {key: distribution.quantile(float(key)) for key in defaults.FORCE_QUANTILES},
        "pounding_probability": estimate.pounding_probability,
        "required_gap": estimate.required_gap,
        "measured_accuracy": estimate.measured_accuracy,
        "estimate": estimate.to_dict(),
    }
