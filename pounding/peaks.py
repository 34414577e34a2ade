"""Expected extremes of Gaussian responses: Davenport's peak factor (Eq. 23-24,
30, 35) and the equivalent stationary process of Michaelov et al. (2001) for
non-stationary excitation (Eq. 26-29), with the exact time-varying covariance
of the linear model as reference; and the expected largest |Y| of a response
from its time-varying sigmas with Vanmarcke's clumps (the separation rules').

Units: SI; rates in [1/s], durations in [s], variances in the response's
units squared.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from .errors import CaseError
from .linearization import StateSpace, lyapunov_covariance

__all__ = [
    "EULER_GAMMA",
    "VANMARCKE_DOUBLE_BARRIER",
    "davenport_peak_factor",
    "envelope_variance",
    "equivalent_stationary",
    "expected_absolute_peak",
    "expected_peak",
    "merged_instants",
    "michaelov_variance",
    "time_varying_covariance",
    "vanmarcke_clumps",
]

EULER_GAMMA = 0.5772156649015329
"""Euler's constant, the 'gamma = 0.5772' of Eq. 23, 30 and 35 (not the
Bouc-Wen gamma; NOTES.md point 8)."""


def davenport_peak_factor(rate, duration):
    """Davenport's (1964) expected peak factor, Eq. 23:
    sqrt(2 ln(nu T)) + 0.5772 / sqrt(2 ln(nu T)).

    The expected largest peak of a stationary Gaussian process over ``duration``
    is this factor times its standard deviation. Davenport's ``rate`` is the
    mean rate of the crossings that count: the zero-upcrossing rate
    sigma_Ydot / (2 pi sigma_Y) for the largest maximum of Y, twice that for
    the largest |Y|. (Eq. 24 uses sigma_V / (pi sigma_X), the zero-crossing
    rate of the relative *displacement*, for the peak of the relative
    *velocity*; see :class:`~pounding.response.ContactResponse`.)

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


def expected_peak(sigma, rate, duration):
    """Expected largest peak sigma * davenport_peak_factor(rate, duration)
    (Eq. 23, and Eq. 30 with the equivalent sigma and duration), in the units
    of ``sigma``."""
    return np.asarray(sigma, dtype=float) * davenport_peak_factor(rate, duration)


VANMARCKE_DOUBLE_BARRIER = math.sqrt(math.pi / 2.0)
"""Vanmarcke's (1975) constant for crossings of a double barrier, two a period
while the envelope is high: the clump factor's exponent is this times q^1.2 r."""


@njit(cache=True)
def vanmarcke_clumps(clumping: float, r: float, tail: float) -> float:
    """Vanmarcke's clump factor min(1, (1 - exp(-clumping r)) / tail), with
    tail = 1 - exp(-r^2 / 2) > 0 (the caller has it at hand, or r is 0: 1)."""
    if tail <= 0.0:
        return 1.0
    return min(1.0, -math.expm1(-clumping * r) / tail)


def expected_absolute_peak(sigma, sigma_derivative, weights, bandwidth: float, points: int = 91) -> float:
    """Expected largest |Y| of a zero-mean Gaussian response over its record,
    from sigma_Y(t) and sigma_Y'(t) on a time grid with quadrature ``weights``.

    Vanmarcke's (1975) clumps of crossings of the double barrier +-u, counted
    as a Poisson process: with r_t = u / sigma_Y(t) and nu_t = sigma_Y'(t) /
    (2 pi sigma_Y(t)),

        N(u) = sum_t w_t 2 nu_t exp(-r_t^2 / 2) min(1, (1 - exp(-sqrt(pi / 2) q^1.2 r_t)) / (1 - exp(-r_t^2 / 2))),

    P(max |Y| > u) = 1 - exp(-N(u)), and E[max |Y|] = int_0^inf P du. Unlike
    Davenport's factor (Eq. 23) it follows a response building up from rest
    or under an envelope, and it takes a narrow-band response's crossings in
    runs, where Davenport's factor counts each (it puts a lightly damped
    building's peak 10-20 % high: docs/estimator.md, "The separation rules").
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
        E[max |Y|], in the units of ``sigma``.
    """
    sigma, rate_sigma, weights = (np.asarray(a, dtype=float).ravel() for a in (sigma, sigma_derivative, weights))
    if not sigma.size == rate_sigma.size == weights.size:
        raise CaseError("weights", f"sigma, sigma_derivative and weights must have one value per instant, got sizes "
                        f"{sigma.size}, {rate_sigma.size}, {weights.size}")
    for name, values in (("sigma", sigma), ("sigma_derivative", rate_sigma), ("weights", weights)):
        if not (values.size and np.isfinite(values).all() and values.min() >= 0.0):
            raise CaseError(name, "must be finite numbers >= 0, one per instant")
    if not 0.0 < bandwidth <= 1.0:
        raise CaseError("bandwidth", f"must lie in (0, 1], got {bandwidth!r}")
    moving = (sigma > 0) & (rate_sigma > 0) & (weights > 0)
    if not np.any(moving):
        raise CaseError("sigma", "the response never moves: it has no peak to expect")
    sigma, rate, weights = merged_instants(sigma[moving], rate_sigma[moving] / (np.pi * sigma[moving]), weights[moving])
    rate = weights * rate  # w_t 2 nu_t
    # Up to where fewer than 1e-4 crossings are expected even at the largest sigma.
    top = max(6.0, math.sqrt(2.0 * math.log(1e4 * max(rate.sum(), 1.0))))
    levels = np.linspace(0.0, top * sigma.max(), points)
    count = _clumped_crossings(levels, sigma, rate, VANMARCKE_DOUBLE_BARRIER * bandwidth**1.2)
    return float(np.trapezoid(-np.expm1(-count), levels))


@njit(cache=True)
def merged_instants(first, second, weights, tolerance=1e-6):
    """Consecutive instants of a time grid at which both series agree to
    ``tolerance`` (relative) taken as one, their ``weights`` summed: a
    stationary record's built-up part is then one instant. Returns the three
    arrays shortened (the first instant of each group keeps its values)."""
    keep = 0
    first, second, weights = first.copy(), second.copy(), weights.copy()
    for t in range(1, first.size):
        if abs(first[t] / first[keep] - 1.0) < tolerance and abs(second[t] / second[keep] - 1.0) < tolerance:
            weights[keep] += weights[t]
        else:
            keep += 1
            first[keep], second[keep], weights[keep] = first[t], second[t], weights[t]
    return first[: keep + 1], second[: keep + 1], weights[: keep + 1]


@njit(cache=True)
def _clumped_crossings(levels, sigma, rate, clumping):
    """N(u) of :func:`expected_absolute_peak` at each level u (``rate``: w_t 2 nu_t)."""
    count = np.zeros(levels.size)
    for i in range(levels.size):
        for t in range(sigma.size):
            r = levels[i] / sigma[t]
            if r > 12.0:  # exp(-72): nothing next to the lower levels' count
                continue
            level = math.exp(-0.5 * r * r)
            tail = 1.0 - level if r > 0.1 else -math.expm1(-0.5 * r * r)
            count[i] += rate[t] * level * vanmarcke_clumps(clumping, r, tail)
    return count


def envelope_variance(envelope, times, variance_inf):
    """sigma^2(t) ~= A^2(t) sigma_inf^2, Eq. 28: the response follows the
    envelope without lag.

    Parameters
    ----------
    envelope : callable or None
        A(t) [-] (e.g. :class:`~pounding.excitation.ShinozukaSato`); None is 1.
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
    C^2 is a misprint: A(t) is normalized by C; NOTES.md point 7).

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
        raise CaseError("times", "needs at least two times, one per variance")
    if np.any(np.diff(times) <= 0.0):
        raise CaseError("times", "must increase")
    if not n1 > 0:
        raise CaseError("n1", f"must be > 0, got {n1!r}")
    if np.any(variance < 0.0) or not np.all(np.isfinite(variance)):
        raise CaseError("variance_of_t", "must be finite and >= 0")
    peak = variance.max()
    if peak == 0.0:
        raise CaseError("variance_of_t", "is zero throughout: no response")
    # Work with sigma^2 / max so high powers neither underflow nor overflow.
    ratio = variance / peak
    low, high = np.trapezoid(ratio**n1, times), np.trapezoid(ratio ** (n1 + 1), times)
    ratio_eq = high / low
    return float(peak * ratio_eq), float(low / ratio_eq**n1)


def _envelope_values(envelope, times):
    return np.ones_like(times) if envelope is None else np.asarray(envelope(times), dtype=float)


def time_varying_covariance(model: StateSpace, envelope, times, modulation: str = "bedrock", rtol: float = 1e-8, outputs=None):
    """Covariance P(t) of a linear model under modulated excitation, from rest
    (or C P(t) C^T of outputs C).

    ``modulation = "bedrock"`` (default): the white noise driving the ground
    filter is modulated, dP/dt = A P + P A^T + 2 pi G0 A(t)^2 b b^T. Stepped
    exactly for an A(t)^2 linear between the given times: with P_s the
    stationary solution (A P_s + P_s A^T + Q = 0) and R with
    A R + R A^T = P_s, a forcing (a + b tau) Q has the particular solution
    a P_s + b (tau P_s + R), and the rest decays as exp(A tau) (.) exp(A^T tau).
    Fast (a few tens of ms for a record).

    ``modulation = "ground"``: the filtered ground acceleration itself is
    modulated, as Eq. 8 and the simulated records do: the filter runs
    stationary from before the onset and only its drive of the buildings is
    scaled, dP/dt = A(t) P + P A(t)^T + Q with A(t) = A_0 + A(t) A_coupling.
    Integrated by ``scipy.integrate.solve_ivp`` (DOP853; about ten times
    slower). The two differ only while the envelope changes over the filter's
    time scale (1 / (xi_g omega_g), about 0.1 s for the paper's soil): about
    0.3 % on the relative-velocity variance of the paper's cases.

    The buildings keep their stationary linearization: the paper's approach.

    Parameters
    ----------
    model : StateSpace
        E.g. :func:`~pounding.linearization.pair_state_space`.
    envelope : callable or None
        A(t) [-]; None is 1 (a stationary motion switched on at ``times[0]``).
    times : array_like
        Increasing times [s]; the motion starts at ``times[0]`` with the
        buildings at rest.
    modulation : str
        ``"bedrock"`` or ``"ground"``.
    rtol : float
        Relative tolerance of the ``"ground"`` integration.
    outputs : ndarray, (k, n), optional
        Rows C over the state: return the outputs' covariance C P(t) C^T (for a
        stationary motion switched on, computed for the outputs alone).

    Returns
    -------
    ndarray, (n_times, n, n), or (n_times, k, k) with ``outputs``
    """
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size < 1 or np.any(np.diff(times) <= 0.0):
        raise CaseError("times", "must be a one-dimensional increasing array")
    A = model.matrix
    values = _envelope_values(envelope, times)
    rows = None if outputs is None else np.atleast_2d(np.asarray(outputs, dtype=float))
    if envelope is None and modulation == "ground":
        return _switched_on(model, times, rows)
    if modulation == "bedrock":
        history = _bedrock(A, model.covariance(), times, values**2)
    elif modulation == "ground":
        history = _ground(model, envelope, times, rtol)
    else:
        raise ValueError(f"modulation must be 'bedrock' or 'ground', got {modulation!r}")
    return history if rows is None else rows @ history @ rows.T


def _bedrock(A, stationary, times, forcing):
    # A R + R A^T = P_s: lyapunov_covariance solves A X + X A^T + Q' = 0.
    ramp = lyapunov_covariance(A, -stationary)
    out = np.zeros((times.size,) + A.shape)
    propagators = {}
    covariance = np.zeros_like(A)
    for k, h in enumerate(np.diff(times)):
        key = round(h, 12)
        if key not in propagators:
            propagators[key] = expm(A * h)
        propagator = propagators[key]
        level, slope = forcing[k], (forcing[k + 1] - forcing[k]) / h
        start = level * stationary + slope * ramp
        end = start + slope * h * stationary
        covariance = end + propagator @ (covariance - start) @ propagator.T
        out[k + 1] = covariance
    return out


def _switched_on(model: StateSpace, times, rows):
    """C P(t) C^T for a stationary ground motion acting from ``times[0]`` on
    buildings at rest (the filter already stationary): a time-invariant
    system, so P(t) = P_s + exp(A t) (P_0 - P_s) exp(A^T t).

    With A = V diag(l) V^-1 this is V (D * exp((l_i + l_j) t)) V^T with
    D = V^-1 (P_0 - P_s) V^-T: every instant at once, and only the rows C
    carried through (C V). An ill-conditioned eigenvector basis (a nearly
    defective A) falls back to stepping with one propagator per distinct step."""
    A, stationary = model.matrix, model.covariance()
    f = model.filter_states
    deviation = -stationary.copy()
    deviation[f, f] = 0.0  # the filter starts in its stationary state
    elapsed = times - times[0]
    values, vectors, inverse, condition = model.modes()
    if condition >= 1e6:
        history = _stepped(A, stationary, deviation, times)
        return history if rows is None else rows @ history @ rows.T
    modal = inverse @ deviation @ inverse.T
    decay = np.exp(np.outer(values, elapsed))  # exp(l_i t); exp((l_i + l_j) t) is a product of two
    if rows is None:  # the whole state: n^2 numbers per instant
        growth = decay.T[:, :, None] * decay.T[:, None, :]
        out = stationary + (vectors @ (modal * growth) @ vectors.T).real
        out[elapsed == 0.0] = stationary + deviation  # exactly at rest, not P_s less itself
        return out
    projected = rows @ vectors
    k, n = projected.shape
    # (C V)_ai D_ij (C V)_bj exp((l_i + l_j) t), summed over i, j as one product for every instant (k^2 n^2 numbers).
    coefficients = np.einsum("ai,ij,bj->abij", projected, modal, projected).reshape(k * k, n * n)
    growth = (decay[:, None, :] * decay[None, :, :]).reshape(n * n, elapsed.size)
    out = rows @ stationary @ rows.T + (coefficients @ growth).real.T.reshape(elapsed.size, k, k)
    out[elapsed == 0.0] = rows @ (stationary + deviation) @ rows.T
    return out


def _stepped(A, stationary, deviation, times):
    """P_s + exp(A t) deviation exp(A^T t), stepped from ``times[0]``."""
    out = np.empty((times.size,) + A.shape)
    out[0] = stationary + deviation
    steps = np.diff(times)
    uniform = steps.size > 0 and np.allclose(steps, steps[0], rtol=1e-12, atol=0.0)
    propagator = expm(A * steps[0]) if uniform else None
    for k, h in enumerate(steps):
        step_propagator = propagator if uniform else expm(A * h)
        deviation = step_propagator @ deviation @ step_propagator.T
        out[k + 1] = stationary + deviation
    return out


def _ground(model: StateSpace, envelope, times, rtol):
    n = model.size
    coupling = model.coupling
    base = model.matrix - coupling
    Q = model.noise_covariance
    initial = np.zeros((n, n))
    f = model.filter_states
    # The filter is stationary from before the onset; the buildings are at rest.
    initial[f, f] = lyapunov_covariance(model.matrix[f, f], Q[f, f])
    scale = np.sqrt(np.abs(np.diag(model.covariance())))
    atol = rtol * 1e-3 * np.outer(scale, scale).ravel()

    def rhs(t, p):
        P = p.reshape(n, n)
        a = base + float(_envelope_values(envelope, np.array([t]))[0]) * coupling
        ap = a @ P
        return (ap + ap.T + Q).ravel()

    solution = solve_ivp(rhs, (times[0], times[-1]), initial.ravel(), method="DOP853", t_eval=times, rtol=rtol, atol=atol)
    if not solution.success:
        raise RuntimeError(f"time-varying covariance: {solution.message}")
    out = solution.y.T.reshape(times.size, n, n)
    return 0.5 * (out + out.transpose(0, 2, 1))
