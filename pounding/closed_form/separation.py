"""The separation rules beside the design gap (docs/theory.md, G23-G25): SRSS,
ABS and DDC combinations of each contact floor's expected peak ``|x|``, the
linearized floor's sigmas from rest with Vanmarcke's clumps. The floors'
sigmas are the linearized ones, without the residual's response: chosen by
looking at Monte Carlo results, where with it the peaks went higher still
above the simulated ones (docs/theory.md)."""

from __future__ import annotations

import math

import numpy as np

from pounding.random_vibration.peaks import expected_absolute_peak

__all__ = ["separation_rules"]


def separation_rules(pair) -> dict:
    """SRSS, ABS and DDC gaps [m] of a :class:`~pounding.closed_form.pair.LinearizedPair`
    from the expected peak ``|displacement|`` of each contact floor
    (``peak_displacement`` [m], :func:`~pounding.random_vibration.peaks.expected_absolute_peak`
    on the covariance history from rest) and their stationary correlation
    (``displacement_correlation`` [-], used by DDC)."""
    weights, history = pair.history_from_rest
    # history's outputs are x1, x2, v1, v2, ...; at rest a variance may round to just below 0.
    sigmas = np.sqrt(np.maximum(np.diagonal(history, axis1=1, axis2=2), 0.0))
    u1, u2 = (expected_absolute_peak(sigmas[:, floor], sigmas[:, 2 + floor], weights, q)
              for floor, q in enumerate(pair.floor_bandwidths))
    correlation = pair.stationary_response.correlation_displacement
    return {
        "srss": float(math.hypot(u1, u2)),
        "abs": float(u1 + u2),
        "ddc": float(math.sqrt(max(u1**2 + u2**2 - 2.0 * correlation * u1 * u2, 0.0))),
        "peak_displacement": [float(u1), float(u2)],
        "displacement_correlation": float(correlation),
    }
