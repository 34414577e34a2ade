"""The compiled counts of crossings and peaks: Vanmarcke's bandwidth and
clump factor, Rice's rate with the time cut, the gap-aware estimator's count
of approaches (docs/theory.md, G4-G8, G14), its required gap (G22), the separation
rules' count of a floor's peaks (G23), and the impacts' equivalent dashpot
(G10-G13).

Numba's on-disk cache of a compiled function does not notice an edit to a
compiled function it calls in another file, so these call trees live here,
in one file.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = [
    "DASHPOT_TOLERANCE",
    "U_MAX",
    "approach_intensity",
    "clumped_crossings",
    "dashpot_mismatch",
    "free_approaches",
    "jump_memory",
    "merged_instants",
    "required_gap",
    "solve_dashpots",
    "spectral_sums",
    "time_cut_rate",
    "vanmarcke_bandwidth",
    "vanmarcke_clumps",
    "with_dashpot",
]

U_MAX = 10.0
"""gap / sigma_X (and v / sigma_V) beyond which there is no impact (exp(-50))."""
DASHPOT_TOLERANCE = 1e-7
"""Tolerance on the mismatch of sigma_V^2 / sigma_V,free^2 of the impacts' dashpot [-]."""


@njit(cache=True, nogil=True)
def vanmarcke_bandwidth(lambda_0, lambda_1, lambda_2):
    """Vanmarcke's q = sqrt(1 - lambda_1^2 / (lambda_0 lambda_2)) from one-sided spectral moments [-]."""
    return math.sqrt(max(1.0 - lambda_1 * lambda_1 / (lambda_0 * lambda_2), 0.0))


@njit(cache=True, nogil=True)
def vanmarcke_clumps(clumping: float, r: float, tail: float) -> float:
    """Vanmarcke's clump factor min(1, (1 - exp(-clumping r)) / tail), with
    tail = 1 - exp(-r^2 / 2) > 0 (the caller has it at hand, or r is 0: 1)."""
    if tail <= 0.0:
        return 1.0
    return min(1.0, -math.expm1(-clumping * r) / tail)


@njit(cache=True, nogil=True)
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


@njit(cache=True, nogil=True)
def clumped_crossings(levels, sigma, rate, clumping):
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


@njit(cache=True, nogil=True)
def time_cut_rate(gap, sigma_x, sigma_v):
    """Rice's rate of upcrossings of the gap per unit of time spent below it,
    (sigma_V / (2 pi sigma_X)) exp(-u^2 / 2) / Phi(u), u = gap / sigma_X [1/s];
    0 beyond :data:`U_MAX` (G4-G5). The time cut was chosen over Zhuravlev's
    mirror returns by looking at Monte Carlo results (docs/theory.md)."""
    u = gap / sigma_x
    if u >= U_MAX:
        return 0.0
    below = 0.5 * math.erfc(-u / math.sqrt(2.0))  # P(X < gap)
    return sigma_v / (2.0 * math.pi * sigma_x) * math.exp(-0.5 * u * u) / below


@njit(cache=True, nogil=True)
def approach_intensity(gaps, velocities, sigma_x, sigma_v, weights, clumping, scale_x, scale_v):
    """Lambda(gap, v) = sum_t w_t nu_t / Phi(u_t) exp(-(u_t^2 + rho_t^2) / 2) c(r_t),
    nu_t = sigma_V(t) / (2 pi sigma_X(t)), u_t = gap / sigma_X(t), rho_t = v / sigma_V(t),
    r_t^2 = u_t^2 + rho_t^2, Phi the standard normal distribution (the time cut)
    and Vanmarcke's clump factor c(r) = min(1, (1 - exp(-clumping r)) / (1 - exp(-r^2 / 2))).
    Per gap i the sigmas are multiplied by scale_x[i], scale_v[i] and the clump
    constant is clumping[i] (the impacts' damping, :mod:`pounding.closed_form.impact_damping`)."""
    out = np.zeros((gaps.size, velocities.size))
    for i in range(gaps.size):
        for t in range(sigma_x.size):
            sx = sigma_x[t] * scale_x[i]
            sv = sigma_v[t] * scale_v[i]
            u = gaps[i] / sx
            factor = weights[t] * time_cut_rate(gaps[i], sx, sv)
            if factor == 0.0:
                continue
            level = math.exp(-0.5 * u * u)
            for j in range(velocities.size):
                rho = velocities[j] / sv
                if rho >= U_MAX:
                    continue
                speed = math.exp(-0.5 * rho * rho)
                r2 = u * u + rho * rho
                clumps = 1.0
                if r2 > 1e-18:
                    # 1 - exp(-r^2 / 2) from the two factors already at hand, but by expm1 where it is small.
                    envelope_tail = 1.0 - level * speed if r2 > 1e-2 else -math.expm1(-0.5 * r2)
                    clumps = vanmarcke_clumps(clumping[i], math.sqrt(r2), envelope_tail)
                out[i, j] += factor * speed * clumps
    return out


@njit(cache=True, nogil=True)
def required_gap(allowed, sigma_x, sigma_v, weights):
    """Bisection for Lambda(gap, 0) = allowed, Lambda(gap, 0) = sum_t w_t nu_t(gap)
    the time-cut rate summed over the history: it falls with the gap (as
    exp(-u^2 / 2) / Phi(u)), so it crosses ``allowed`` once; the gap returned
    is on the safe side of the crossing, to 1e-10 of it."""
    low, high = 0.0, U_MAX * sigma_x.max()
    if free_approaches(low, sigma_x, sigma_v, weights) <= allowed:
        return 0.0
    for _ in range(200):  # 1e-10 takes about 34 halvings; the cap ends it where rounding stops them shrinking
        if high - low <= 1e-10 * high:
            break
        middle = 0.5 * (low + high)
        if free_approaches(middle, sigma_x, sigma_v, weights) > allowed:
            low = middle
        else:
            high = middle
    return high


@njit(cache=True, nogil=True)
def free_approaches(gap, sigma_x, sigma_v, weights):
    """Lambda(gap, 0) with every crossing counted: what the intensity kernel
    gives at v = 0 without clumps (its factor c(r) is then 1)."""
    total = 0.0
    for t in range(sigma_x.size):
        total += weights[t] * time_cut_rate(gap, sigma_x[t], sigma_v[t])
    return total


@njit(cache=True, nogil=True)
def jump_memory(rate, frequency, rates, x_modes, v_modes):
    """rho-bar: E[(omega x_J)^2 + v_J^2] at the next impact, the intervals between
    impacts exponential with ``rate`` (E[exp(s Delta)] = rate / (rate - s)), capped at 1."""
    total = 0.0
    for j in range(rates.size):
        for k in range(rates.size):
            weight = (frequency * frequency * x_modes[j] * x_modes[k] + v_modes[j] * v_modes[k]) * rate / (rate - rates[j] - rates[k])
            total += weight.real
    return min(1.0, max(0.0, total))


@njit(cache=True, nogil=True)
def spectral_sums(c, weights, psd, psd_omega, psd_omega2, feedback_re, feedback_im):
    """int G_X w^k / ``|1 + c G|^2`` for k = 0, 1, 2 (trapezoid weights)."""
    s0 = 0.0
    s1 = 0.0
    s2 = 0.0
    for i in range(weights.size):
        re = 1.0 + c * feedback_re[i]
        im = c * feedback_im[i]
        gain = weights[i] / (re * re + im * im)
        s0 += gain * psd[i]
        s1 += gain * psd_omega[i]
        s2 += gain * psd_omega2[i]
    return s0, s1, s2


@njit(cache=True, nogil=True)
def with_dashpot(c, spectra):
    """sigma_X and sigma_V ratios to the free motion's and the bandwidth of X under a dashpot c."""
    weights, psd, psd_omega, psd_omega2, feedback_re, feedback_im, free0, free2 = spectra
    s0, s1, s2 = spectral_sums(c, weights, psd, psd_omega, psd_omega2, feedback_re, feedback_im)
    return math.sqrt(s0 / free0), math.sqrt(s2 / free2), vanmarcke_bandwidth(s0, s1, s2)


@njit(cache=True, nogil=True)
def dashpot_mismatch(c, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes):
    """g(c) = sigma_V(c)^2 / sigma_V(0)^2 - R(c): the damped motion's velocity
    variance against the energy its impacts leave it, R = (1 - rho) / (1 - rho e^2);
    also the sigma ratios, the bandwidth, rho and the impact rate."""
    rates, x_modes, v_modes = modes
    ratio_x, ratio_v, bandwidth = with_dashpot(c, spectra)
    rate = time_cut_rate(gap, sigma_x * ratio_x, sigma_v * ratio_v)
    rho = jump_memory(rate, frequency, rates, x_modes, v_modes) if rate > 0.0 else 0.0
    left = (1.0 - rho) / (1.0 - rho * restitution * restitution)
    return ratio_v * ratio_v - left, ratio_x, ratio_v, bandwidth, rho, rate


@njit(cache=True, nogil=True)
def solve_dashpots(gaps, sigma_x, sigma_v, frequency, restitution, dissipation, spectra, modes, feedback_max):
    """c with g(c) = 0 for each gap (:func:`_mismatch`), by a safeguarded secant
    (Illinois) in units of the energy balance's m (1 - e^2) nu, bracketed from
    g(0) = 1 - R >= 0. Where g(0) is below 1e-12 or that unit's largest feedback
    c ``|G|`` below 1e-10, the impacts change nothing: c = 0.

    One row per gap: c, sigma_X ratio, sigma_V ratio, bandwidth, rho; c = -1
    marks a gap where no fixed point was found (raised by the caller). Each gap
    is solved on its own, so a curve's values do not depend on its other gaps."""
    out = np.zeros((gaps.size, 5))
    for k in range(gaps.size):
        gap = gaps[k]
        g_low, rx, rv, q, rho, rate = dashpot_mismatch(0.0, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes)
        scale = dissipation * rate
        c = 0.0
        if g_low > 1e-12 and scale * feedback_max > 1e-10:
            low, high = 0.0, 1.0
            g_high = dashpot_mismatch(high * scale, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes)[0]
            doublings = 0
            while g_high >= 0.0 and doublings < 60:
                low, g_low = high, g_high
                high *= 2.0
                g_high = dashpot_mismatch(high * scale, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes)[0]
                doublings += 1
            if g_high >= 0.0:
                out[k, 0] = -1.0  # flagged: no bracket
                continue
            side = 0
            converged = False
            x = low
            for _ in range(200):
                x = (low * g_high - high * g_low) / (g_high - g_low)  # g_low >= 0 > g_high
                g_x, rx, rv, q, rho, rate = dashpot_mismatch(x * scale, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes)
                if abs(g_x) <= DASHPOT_TOLERANCE or high - low <= DASHPOT_TOLERANCE * high:
                    converged = True
                    break
                if g_x > 0.0:
                    low, g_low = x, g_x
                    if side == 1:
                        g_high *= 0.5
                    side = 1
                else:
                    high, g_high = x, g_x
                    if side == -1:
                        g_low *= 0.5
                    side = -1
            if not converged:
                out[k, 0] = -1.0
                continue
            c = x * scale
        out[k, 0] = c
        out[k, 1] = rx
        out[k, 2] = rv
        out[k, 3] = q
        out[k, 4] = rho
    return out
