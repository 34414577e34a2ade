"""Rahimi & Soltani's closed form as published (Section 4, Eq. 12-30), with
the printing errors fixed as docs/errata.md says: the expected extreme
relative velocity by Davenport's peak factor (Eq. 23-24), Michaelov's
equivalent stationary process under an envelope (Eq. 26-30), and the Hertz
peak force for the separation velocity (Eq. 13-14, with delta^1.5)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pounding import defaults
from pounding.errors import ArgumentError, finite_number
from pounding.mechanics.contact import undamped_peak_force
from pounding.random_vibration.peaks import davenport_peak_factor, envelope_variance, equivalent_stationary

__all__ = ["PAPER_VARIANCE_METHODS", "PaperEstimate", "check_michaelov_n1", "paper_estimate"]

PAPER_VARIANCE_METHODS = ("eq28", "exact")
"""How the paper's method gets sigma_V(t) under an envelope: Eq. 28 or the
time-varying covariance of the linearized pair."""

_HISTORY_STEP = 0.1  # [s] time grid of sigma_V(t) for Michaelov's moments


@dataclass(frozen=True)
class PaperEstimate:
    """Rahimi & Soltani's estimate, Eq. 12-30 (Eq. 14 with delta^1.5).

    Attributes
    ----------
    force_expected : float or None
        F_e of Eq. 14 [N]; None for the ``linear`` contact law, for which
        Eq. 13-14 (Hertz) do not apply.
    relative_velocity_expected : float or None
        Expected extreme relative velocity delta_dot_e [m/s], Eq. 23 (30); None where Davenport's factor is
        not defined (see ``unavailable``).
    crossing_rate : float
        nu = sigma_V / (pi sigma_X) [1/s], Eq. 24.
    duration_effective : float
        T (stationary) or Michaelov's T_eq (Eq. 29) [s].
    peak_factor : float or None
        Davenport's factor of Eq. 23 / 30 [-]; None where it is not defined: fewer than one crossing
        expected over the duration (nu T <= 1, a strong motion shorter than a period of X).
    sigma_relative_velocity_equivalent : float or None
        sigma_eq of Eq. 29 for non-stationary motion [m/s].
    penetration_expected : float or None
        delta_e of Eq. 13 with e delta_dot_e [m].
    michaelov_n1 : float or None
        The order n1 of Eq. 29's moments for non-stationary motion [-].
    unavailable : str or None
        Why the paper's estimate is not defined for this case (then force_expected, the velocity, the peak
        factor and the penetration are None); None where it is.
    """

    force_expected: float | None
    relative_velocity_expected: float | None
    crossing_rate: float
    duration_effective: float
    peak_factor: float | None
    sigma_relative_velocity_equivalent: float | None
    penetration_expected: float | None
    michaelov_n1: float | None = None
    unavailable: str | None = None


def check_michaelov_n1(n1) -> None:
    """Raise :class:`ArgumentError` unless n1 lies in :data:`~pounding.defaults.MICHAELOV_N1_RANGE`."""
    low, high = defaults.MICHAELOV_N1_RANGE
    if not low <= finite_number("michaelov_n1", n1, error=ArgumentError) <= high:
        raise ArgumentError("michaelov_n1", f"must lie in [{low:g}, {high:g}], got {n1!r}")


def paper_estimate(pair, variance_method: str = defaults.PAPER_VARIANCE, michaelov_n1: float = defaults.MICHAELOV_N1) -> PaperEstimate:
    """The published estimator, Eq. 12-30, on a :class:`~pounding.closed_form.pair.LinearizedPair`
    (its stationary response, without the residual's).

    Parameters
    ----------
    pair : LinearizedPair
    variance_method : str
        How sigma_V(t) is found for a modulated motion: ``"eq28"``, the paper's
        A(t)^2 sigma_inf^2, or ``"exact"``, the time-varying covariance.
    michaelov_n1 : float
        Order n1 of Eq. 29's moments under an envelope, in :data:`~pounding.defaults.MICHAELOV_N1_RANGE`.
    """
    check_michaelov_n1(michaelov_n1)
    case, response = pair.case, pair.stationary_response
    sigma_v = response.sigma_relative_velocity
    rate = response.zero_crossing_rate  # Eq. 24, kept as printed (docs/errata.md, E12: the displacement's rate)
    excitation = case.excitation
    if excitation.stationary:
        duration, sigma = excitation.duration, sigma_v
        sigma_equivalent = None
    else:
        times = np.arange(0.0, excitation.duration + 1e-9, _HISTORY_STEP)
        if variance_method == "eq28":
            variance = envelope_variance(excitation.envelope, times, sigma_v**2)
        elif variance_method == "exact":
            history = pair.covariance_history(times)
            variance = history[:, 2, 2] + history[:, 3, 3] - 2 * history[:, 2, 3]
        else:
            raise ArgumentError("variance_method", f"must be one of {', '.join(PAPER_VARIANCE_METHODS)}, got {variance_method!r}")
        variance_eq, duration = equivalent_stationary(variance, times, n1=michaelov_n1)  # Eq. 29
        sigma = sigma_equivalent = math.sqrt(variance_eq)
    n1 = None if excitation.stationary else float(michaelov_n1)
    if not rate * duration > 1.0:  # Davenport's factor needs more than one crossing: the paper has no estimate here
        return PaperEstimate(None, None, float(rate), float(duration), None, sigma_equivalent, None, n1,
                             unavailable=f"Davenport's peak factor (Eq. 23) needs more than one crossing over the "
                                         f"duration; {rate * duration:.2g} are expected")
    factor = davenport_peak_factor(rate, duration)  # Eq. 23 / 30
    velocity = factor * sigma
    contact = case.contact
    if not contact.law.hertzian:
        force = penetration = None
    else:
        # Eq. 13-14: the Hertz peak for the separation velocity e * delta_dot_e (docs/errata.md, E11), with
        # delta^1.5 as Eq. 3 and 14 have it (Eq. 12's delta^2 is a misprint, docs/errata.md, E1).
        separation = contact.restitution * velocity
        force = float(undamped_peak_force(contact, separation, case.reduced_mass))
        penetration = (force / contact.stiffness) ** (2.0 / 3.0)
    return PaperEstimate(force, float(velocity), float(rate), float(duration), float(factor), sigma_equivalent, penetration, n1)
