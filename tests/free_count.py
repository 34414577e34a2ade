"""The gap-aware force counted on the free motion (without the impacts'
damping of the motion between them), composed from the public building
blocks of :mod:`pounding.closed_form.gap_aware`: the comparison the estimator no longer
offers as an option."""

import numpy as np

from pounding.closed_form.gap_aware import Crossings, expected_force_maximum
from pounding.closed_form.impact_damping import DampedMotion


def free_force(case, crossings: Crossings, gaps, points: int = 121) -> np.ndarray:
    """E[F_max] [N] at each of ``gaps`` [m] with the largest approach counted
    on the free motion of ``crossings`` (an estimate's, or ``Crossings.of(pair)``);
    ``points``: 121 as a single estimate, 81 as a gap curve."""
    gaps = np.atleast_1d(np.asarray(gaps, dtype=float))
    free = DampedMotion.undamped(gaps.size, crossings.bandwidth)
    return expected_force_maximum(crossings, gaps, case.contact, case.reduced_mass, free, points)
