"""Expected extremes of Gaussian responses: Davenport's peak factor (Eq. 23-24,
30, 35) and the equivalent stationary process of Michaelov et al. (2001) for
non-stationary excitation (Eq. 26-29); and the expected largest ``|Y|`` of a
response from its time-varying sigmas with Vanmarcke's clumps (the
separation rules', docs/theory.md, G23-G24).

Units: SI; rates in [1/s], durations in [s], variances in the response's
units squared.
"""

from __future__ import annotations

import math

import numpy as np

from pounding.errors import ArgumentError, CaseError
from pounding.random_vibration.crossing_kernels import clumped_crossings, merged_instants, vanmarcke_clumps

__all__ = [
    "EULER_GAMMA",
    "VANMARCKE_DOUBLE_BARRIER",
    "davenport_peak_factor",
    "envelope_variance",
    "equivalent_stationary",
    "expected_absolute_peak",
    "davenport_expected_peak",
    "merged_instants",
    "michaelov_variance",
    "vanmarcke_clumps",
]

EULER_GAMMA = 0.5772156649015329
"""Euler's constant, the 'gamma = 0.5772' of Eq. 23, 30 and 35 (not the
Bouc-Wen gamma; docs/errata.md, E9)."""


def davenport_peak_factor(rate, duration):
    """Davenport's (1964) expected peak factor, Eq. 23:
    sqrt(2 ln(nu T)) + 0.5772 / sqrt(2 ln(nu T)).

    The expected largest peak of a stationary Gaussian process over ``duration``
    is this factor times its standard deviation. Davenport's ``rate`` is the
    mean rate of the crossings that count: the zero-upcrossing rate
    sigma_Ydot / (2 pi sigma_Y) for the largest maximum of Y, twice that for
    the largest ``|Y|``. (Eq. 24 uses sigma_V / (pi sigma_X), the zero-crossing
    rate of the relative *displacement*, for the peak of the relative
    *velocity*; see :class:`~pounding.closed_form.response.ContactResponse`.)

    Parameters
    ----------
    rate : float or array_like
        nu [1/s], > 0.
    duration : float or array_like
        T [s], > 0.

    Returns
    -------
    float or ndarray
        The peak factor [-].

    Raises
    ------
    CaseError
        If nu T <= 1: the asymptotic formula has no meaning there (fewer than
        one crossing expected; the logarithm is not positive).
    """
    product = np.asarray(rate, dtype=float) * np.asarray(duration, dtype=float)
    if not np.all(np.isfinite(product)) or np.any(product <= 1.0):
        raise CaseError(
            "excitation.duration",
            f"Davenport's peak factor needs rate * duration > 1 (more than one crossing expected), "
            f"got rate * duration = {np.array2string(product, precision=4)}",
        )
    root = np.sqrt(2.0 * np.log(product))
    factor = root + EULER_GAMMA / root
    return float(factor) if factor.ndim == 0 else factor


def davenport_expected_peak(sigma, rate, duration):
    """Expected largest peak sigma * davenport_peak_factor(rate, duration)
    (Eq. 23, and Eq. 30 with the equivalent sigma and duration), in the units
    of ``sigma``."""
    return np.asarray(sigma, dtype=float) * davenport_peak_factor(rate, duration)


VANMARCKE_DOUBLE_BARRIER = math.sqrt(math.pi / 2.0)
"""Vanmarcke's (1975) constant for crossings of a double barrier, two a period
while the envelope is high: the clump factor's exponent is this times q^1.2 r.
The gap-aware estimator counts the impacts, which cross one barrier, with it
too: chosen over the one-sided sqrt(2 pi) by looking at Monte Carlo results
(docs/theory.md, "Constants chosen by looking at Monte Carlo results")."""


def expected_absolute_peak(sigma, sigma_derivative, weights, bandwidth: float, points: int = 91) -> float:
    """Expected largest ``|Y|`` of a zero-mean Gaussian response over its record,
    from sigma_Y(t) and sigma_Y'(t) on a time grid with quadrature ``weights``.

    Vanmarcke's (1975) clumps of crossings of the double barrier +-u, counted
    as a Poisson process: with r_t = u / sigma_Y(t) and nu_t = sigma_Y'(t) /
    (2 pi sigma_Y(t)),

        N(u) = sum_t w_t 2 nu_t exp(-r_t^2 / 2) min(1, (1 - exp(-sqrt(pi / 2) q^1.2 r_t)) / (1 - exp(-r_t^2 / 2))),

    P(max ``|Y|`` > u) = 1 - exp(-N(u)), and E[max ``|Y|``] = int_0^inf P du. Unlike
    Davenport's factor (Eq. 23) it follows a response building up from rest
    or under an envelope, and it takes a narrow-band response's crossings in
    runs, where Davenport's factor counts each (it puts a lightly damped
    building's peak 10-20 % high: docs/accuracy.md).
    For a stationary record and q = 1 it tends to Davenport's peak for the
    rate 2 nu. While a response builds up, Y and Y' correlate and the exact
    rate of crossings is a little higher than nu_t's; the count leaves that
    out, as the estimator's count of X does (up to 1.7 % on the peaks of the
    grid's floors built up from rest).

    Parameters
    ----------
    sigma, sigma_derivative : array_like
        sigma_Y(t) and sigma_Y'(t) at the grid's instants (Y's units and per s);
        instants where either is 0 (at rest) count nothing.
    weights : array_like
        Quadrature weights of the instants [s], >= 0, summing to the duration.
    bandwidth : float
        Vanmarcke's q of Y, in (0, 1].
    points : int
        Quadrature points in u from 0 to where fewer than 1e-4 crossings are
        expected (at least 6 max sigma_Y).

    Returns
    -------
    float
        E[max ``|Y|``], in the units of ``sigma``.
    """
    sigma, rate_sigma, weights = (np.asarray(a, dtype=float).ravel() for a in (sigma, sigma_derivative, weights))
    if not sigma.size == rate_sigma.size == weights.size:
        raise ArgumentError("weights", f"sigma, sigma_derivative and weights must have one value per instant, got sizes "
                            f"{sigma.size}, {rate_sigma.size}, {weights.size}")
    for name, values in (("sigma", sigma), ("sigma_derivative", rate_sigma), ("weights", weights)):
        if not (values.size and np.isfinite(values).all() and values.min() >= 0.0):
            raise ArgumentError(name, "must be finite numbers >= 0, one per instant")
    if not 0.0 < bandwidth <= 1.0:
        raise ArgumentError("bandwidth", f"must lie in (0, 1], got {bandwidth!r}")
    moving = (sigma > 0) & (rate_sigma > 0) & (weights > 0)
    if not np.any(moving):
        raise ArgumentError("sigma", "the response never moves: it has no peak to expect")
    sigma, rate, weights = merged_instants(sigma[moving], rate_sigma[moving] / (np.pi * sigma[moving]), weights[moving])
    rate = weights * rate  # w_t 2 nu_t
    # Up to where fewer than 1e-4 crossings are expected even at the largest sigma.
    top = max(6.0, math.sqrt(2.0 * math.log(1e4 * max(rate.sum(), 1.0))))
    levels = np.linspace(0.0, top * sigma.max(), points)
    count = clumped_crossings(levels, sigma, rate, VANMARCKE_DOUBLE_BARRIER * bandwidth**1.2)
    return float(np.trapezoid(-np.expm1(-count), levels))


def envelope_variance(envelope, times, variance_inf):
    """sigma^2(t) ~= A^2(t) sigma_inf^2, Eq. 28: the response follows the
    envelope without lag.

    Parameters
    ----------
    envelope : callable or None
        A(t) [-] (e.g. :class:`~pounding.hazard.excitation.ShinozukaSato`); None is 1.
    times : array_like
        [s].
    variance_inf : float
        Stationary variance sigma_inf^2.
    """
    times = np.asarray(times, dtype=float)
    modulation = np.ones_like(times) if envelope is None else np.asarray(envelope(times), dtype=float)
    return modulation**2 * variance_inf


def michaelov_variance(envelope, times, variance_inf, omega0, xi):
    """Michaelov et al.'s variance of an oscillator's response under the
    Shinozuka-Sato modulation, Eq. 26-27, with the prefactor C^-2 (the printed
    C^2 is a misprint: A(t) is normalized by C; docs/errata.md, E8).

    Each term is 2 xi omega0 int_0^t exp(-2 xi omega0 (t - s)) exp(-2 B s) ds,
    so the result solves d sigma^2/dt = 2 xi omega0 (A^2(t) sigma_inf^2 - sigma^2)
    from rest; the coefficients xi / (xi - B / omega0) of Eq. 26 appear on
    integrating. The form used here also holds where xi omega0 = B (Eq. 26
    divides by zero there).

    Parameters
    ----------
    envelope : ShinozukaSato
        Provides B1, B2 [1/s] and the normalization C.
    times : array_like
        Times from the onset [s], >= 0.
    variance_inf : float
        Stationary variance sigma_inf^2 of the response.
    omega0 : float
        Natural frequency of the oscillator [rad/s].
    xi : float
        Its damping ratio [-].

    Returns
    -------
    ndarray
        sigma^2(t).
    """
    t = np.asarray(times, dtype=float)
    decay = 2.0 * xi * omega0

    def term(rate):
        # decay * exp(-rate t) * int_0^t exp(-(decay - rate) u) du, stable for any sign of decay - rate.
        excess = decay - rate
        if excess == 0.0:
            integral = t
        else:
            integral = -np.expm1(-excess * t) / excess
        return decay * np.exp(-rate * t) * integral

    B1, B2 = envelope.B1, envelope.B2
    bracket = term(2.0 * B1) + term(2.0 * B2) - 2.0 * term(B1 + B2)
    return variance_inf * bracket / envelope.normalization**2


def equivalent_stationary(variance_of_t, times, n1: float = 3):
    """Michaelov et al.'s (2001) equivalent stationary process, Eq. 29.

    With I(n) = int sigma^(2 n)(t) dt over ``times`` (trapezoidal rule),
    sigma_eq^2 = I(n1 + 1) / I(n1) and T_eq = I(n1) / sigma_eq^(2 n1): a
    stationary process of variance sigma_eq^2 lasting T_eq has about the same
    extreme-value distribution as the non-stationary one (Eq. 30).

    Parameters
    ----------
    variance_of_t : array_like
        sigma^2(t) at ``times``, >= 0.
    times : array_like
        Increasing times [s].
    n1 : float
        Order of the moments; 3 or 4 usually within 10 % (paper).

    Returns
    -------
    variance_eq : float
        sigma_eq^2.
    duration_eq : float
        T_eq [s].
    """
    variance = np.asarray(variance_of_t, dtype=float)
    times = np.asarray(times, dtype=float)
    if variance.shape != times.shape or times.ndim != 1 or times.size < 2:
        raise ArgumentError("times", "needs at least two times, one per variance")
    if np.any(np.diff(times) <= 0.0):
        raise ArgumentError("times", "must increase")
    if not n1 > 0:
        raise ArgumentError("n1", f"must be > 0, got {n1!r}")
    if np.any(variance < 0.0) or not np.all(np.isfinite(variance)):
        raise ArgumentError("variance_of_t", "must be finite and >= 0")
    peak = variance.max()
    if peak == 0.0:
        raise ArgumentError("variance_of_t", "is zero throughout: no response")
    # Work with sigma^2 / max so high powers neither underflow nor overflow.
    ratio = variance / peak
    low, high = np.trapezoid(ratio**n1, times), np.trapezoid(ratio ** (n1 + 1), times)
    ratio_eq = high / low
    return float(peak * ratio_eq), float(low / ratio_eq**n1)
