"""Expected peaks of zero-mean Gaussian processes by Vanmarcke's (1975) barrier
crossings with clumps; the expected peak ground acceleration of an excitation.

P1  Spectral moments of the one-sided PSD G: lambda_k = int_0^omega_c omega^k G(omega) d omega,
    cut at the cutoff omega_c (the records carry nothing above it; a Kanai-Tajimi
    acceleration has no finite lambda_2 without the cut).
P2  nu0 = sqrt(lambda_2 / lambda_0) / (2 pi) [1/s] (Rice's zero-upcrossing rate),
    delta = sqrt(1 - lambda_1^2 / (lambda_0 lambda_2)) (Vanmarcke's bandwidth).
P3  Crossings of the double barrier +-u at r = u / sigma(t), in clumps (Vanmarcke 1975,
    Eq. 25 there with delta_e = delta^1.2; pounding.random_vibration.peaks and pounding.random_vibration.crossing_kernels
    use the same clump factor, capped at 1)::

        nu(u, t) = 2 nu0 exp(-r^2 / 2) min(1, (1 - exp(-sqrt(pi / 2) delta^1.2 r)) / (1 - exp(-r^2 / 2))).

P4  The clumps as a Poisson process, the process at rest at t = 0::

        P(max |x| <= u) = exp(-N(u)),  N(u) = int_0^T nu(u, t) dt,
        E[max |x|] = int_0^inf (1 - exp(-N(u))) du,

    both integrals by the trapezoidal rule (u from 0 to where fewer than 1e-5 crossings
    are expected).

P5  A sampled record's peak is the largest of its samples x_k = x(k dt), not of the
    continuous process: count the crossings of the sampled sequence instead. With rho the
    correlation of consecutive samples (rho = sum_j G_j d omega cos(omega_j dt) / lambda_0),
    P(x_k < u < x_(k+1)) = 2 T(r, a), a = sqrt((1 - rho) / (1 + rho)), T Owen's function
    (the bivariate normal's Phi_2(h, h; rho) = Phi(h) - 2 T(h, a)); so the up-crossing rate
    2 nu0 exp(-r^2 / 2) / 2 of P3 becomes 2 T(r, a) / dt, the clumps kept. As dt -> 0,
    2 T(r, a) / dt -> nu0 exp(-r^2 / 2): P3. For a record cut at 25 Hz and sampled at
    200 Hz, it lowers E[PGA] by about 0.2 % (rho gives 0.5 % fewer zero crossings).
P6  Peak ground acceleration: P4-P5 (and P7 with sigma'/sigma = A'/A) with sigma(t) = A(t) sqrt(lambda_0), lambda_k summed on
    the records' own synthesis grid (Excitation.synthesis_frequencies, G = 2 S_g), i.e.
    what the records carry. E[PGA] is proportional to sqrt(G0): the intensity for a
    target PGA is G0 (PGA / E[PGA])^2.
P7  A growing sigma(t) (an oscillator building up from rest) drives its envelope a(t) up:
    given a = u, a' has the mean (sigma' / sigma) u besides its stationary scatter
    s = sigma delta 2 pi nu0 (the Cramer-Leadbetter envelope). Its up-crossing rate,
    E[a'^+ | a = u] f_a(u), is then the stationary one times::

        g(eta) = sqrt(2 pi) (phi(eta) + eta Phi(eta)),  eta = (sigma' / sigma) r / (2 pi nu0 delta),

    phi, Phi the standard normal density and distribution (g(0) = 1). The clumps of P3
    are the envelope's crossings, so P3's argument sqrt(pi / 2) delta^1.2 r is multiplied
    by g(eta): a derived term, not a fitted one. On Kanai-Tajimi records of 10 s it lifts
    the expected 5 %-damped peak at T = 2 s from 5 % to 3 % below the records' mean, at
    3 s from 11 % to 6 % below; where sigma is steady it changes nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import ndtr, owens_t

from pounding.errors import ArgumentError, CaseError, finite_number, quote
from pounding.random_vibration.peaks import VANMARCKE_DOUBLE_BARRIER

__all__ = [
    "SpectralMoments",
    "vanmarcke_expected_peak",
    "expected_peak_ground_acceleration",
    "intensity_for_peak_ground_acceleration",
    "rms_acceleration",
    "record_spectral_moments",
]

VANMARCKE_CLUMP_EXPONENT = 1.2
"""Vanmarcke's (1975) exponent of delta in P3 (his delta_e = delta^1.2; pounding.random_vibration.crossing_kernels uses it too)."""

LEVELS = 40
"""Quadrature points in u of P4, from 0 to the level of 1e-5 expected crossings (the integrand is smooth:
40 points are within 0.02 % of 96 on the compatible spectra's oscillators)."""


def _trapezoid_weights(times: np.ndarray) -> np.ndarray:
    steps = np.diff(times)
    weights = np.zeros(times.size)
    weights[:-1] += steps / 2
    weights[1:] += steps / 2
    return weights


def _clumps(r: np.ndarray, clumping: np.ndarray) -> np.ndarray:
    """Vanmarcke's clump factor of P3, min(1, (1 - exp(-c r)) / (1 - exp(-r^2 / 2)))."""
    tail = -np.expm1(-0.5 * r * r)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(tail > 0, -np.expm1(-clumping * r) / tail, 1.0)
    return np.minimum(1.0, ratio)


def vanmarcke_expected_peak(sigma, nu0, delta, times, *, growth=None, time_step=None, sample_correlation=None,
                            clump_exponent=VANMARCKE_CLUMP_EXPONENT) -> np.ndarray:
    """Expected largest ``|x|`` over ``times`` of zero-mean Gaussian processes, P3-P4 (P5 when sampled, P7 with ``growth``).

    Parameters
    ----------
    sigma : array_like, shape (..., n)
        sigma(t) at ``times`` of each process (the last axis is time), >= 0, some > 0.
    nu0 : array_like, shape (...)
        Mean zero up-crossing rates [1/s], > 0 (P2).
    delta : array_like, shape (...)
        Vanmarcke's bandwidths, in (0, 1].
    times : array_like, shape (n,)
        Increasing instants [s], at least 2.
    growth : array_like, shape (..., n), optional
        sigma'(t) / sigma(t) [1/s] (P7); None: as if sigma were steady.
    time_step, sample_correlation : float or array_like (...), optional
        Both given: the peak of the samples every ``time_step`` [s] whose consecutive
        values correlate by ``sample_correlation`` in (-1, 1) (P5); nu0 is then unused.
    clump_exponent : float
        The exponent of delta in P3 (Vanmarcke's 1.2 by default).

    Returns
    -------
    ndarray, shape (...)
        E[max ``|x|``], in the units of ``sigma``.
    """
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size < 2 or not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0):
        raise ArgumentError("times", "must be at least 2 finite, strictly increasing instants")
    sigma = np.asarray(sigma, dtype=float)
    if sigma.shape[-1:] != times.shape or not np.all(np.isfinite(sigma)) or np.any(sigma < 0):
        raise ArgumentError("sigma", f"must be finite numbers >= 0 with {times.size} instants on its last axis")
    batch = sigma.shape[:-1]
    nu0 = np.broadcast_to(np.asarray(nu0, dtype=float), batch)
    delta = np.broadcast_to(np.asarray(delta, dtype=float), batch)
    if not (np.all(np.isfinite(nu0)) and np.all(nu0 > 0)):
        raise ArgumentError("nu0", "must be finite and > 0 1/s")
    if not (np.all(delta > 0) and np.all(delta <= 1)):
        raise ArgumentError("delta", "must lie in (0, 1]")
    peak = sigma.max(axis=-1, initial=0.0)
    if np.any(peak <= 0):
        raise ArgumentError("sigma", "is zero throughout for some process: it has no peak to expect")
    sampled = time_step is not None or sample_correlation is not None
    if sampled:
        if time_step is None or sample_correlation is None:
            raise ArgumentError("time_step", "needs sample_correlation too (P5), or neither")
        step = finite_number("time_step", time_step, error=ArgumentError)
        if not step > 0:
            raise ArgumentError("time_step", f"must be > 0 s, got {quote(step)}")
        rho = np.broadcast_to(np.asarray(sample_correlation, dtype=float), batch)
        if not (np.all(rho > -1) and np.all(rho < 1)):
            raise ArgumentError("sample_correlation", "must lie in (-1, 1)")
        slope = np.sqrt((1.0 - rho) / (1.0 + rho))
    weights = _trapezoid_weights(times)
    duration = times[-1] - times[0]
    # u up to where fewer than 1e-5 crossings are expected at the largest sigma (rate bounded by 2 nu0 or 1/dt).
    most = 2.0 * nu0 * duration if not sampled else np.full(batch, duration / step)
    top = np.maximum(6.0, np.sqrt(2.0 * np.log(1e5 * np.maximum(most, 1.0))))
    fraction = np.linspace(0.0, 1.0, LEVELS)
    levels = (top * peak)[..., None] * fraction  # (..., L)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = levels[..., :, None] / sigma[..., None, :]  # (..., L, n); inf where sigma = 0
    r = np.where(np.isfinite(r), r, 1e3)
    clumping = (VANMARCKE_DOUBLE_BARRIER * delta**clump_exponent)[..., None, None]
    if growth is not None:
        growth = np.broadcast_to(np.asarray(growth, dtype=float), sigma.shape)
        if not np.all(np.isfinite(growth)):
            raise ArgumentError("growth", "must be finite numbers [1/s], one per instant")
        eta = growth[..., None, :] * r / (2.0 * np.pi * nu0 * delta)[..., None, None]
        clumping = clumping * (np.exp(-0.5 * eta * eta) + np.sqrt(2.0 * np.pi) * eta * ndtr(eta))
    if sampled:
        rate = 4.0 * owens_t(r, slope[..., None, None]) / step
    else:
        rate = 2.0 * nu0[..., None, None] * np.exp(-0.5 * r * r)
    count = np.sum(rate * _clumps(r, clumping) * weights, axis=-1)  # N(u), (..., L)
    return np.trapezoid(-np.expm1(-count), levels, axis=-1)


@dataclass(frozen=True)
class SpectralMoments:
    """P1 of a one-sided PSD [m^2/s^4, m^2/s^5, m^2/s^6 for an acceleration] and the
    correlation ``rho`` of consecutive samples (P5)."""

    lambda_0: float
    lambda_1: float
    lambda_2: float
    rho: float

    @property
    def nu0(self) -> float:
        """P2 [1/s]."""
        return math.sqrt(self.lambda_2 / self.lambda_0) / (2.0 * math.pi)

    @property
    def delta(self) -> float:
        """P2 [-]."""
        return math.sqrt(max(1.0 - self.lambda_1 ** 2 / (self.lambda_0 * self.lambda_2), 1e-12))


def record_spectral_moments(excitation) -> SpectralMoments:
    """P1 of the records of ``excitation`` (a :class:`~pounding.hazard.excitation.Excitation`), summed
    on their synthesis grid up to the cutoff, and the correlation of consecutive samples."""
    omega = excitation.synthesis_frequencies()
    one_sided = 2.0 * np.asarray(excitation.spectrum.psd(omega), dtype=float) * omega[1]
    one_sided[0] = 0.0
    one_sided[omega > excitation.cutoff_frequency] = 0.0
    lambda_0 = float(np.sum(one_sided))
    if not (math.isfinite(lambda_0) and lambda_0 > 0):
        raise CaseError("excitation.spectrum", "carries no variance below the cutoff frequency")
    rho = float(np.sum(one_sided * np.cos(omega * excitation.time_step)) / lambda_0)
    return SpectralMoments(lambda_0, float(np.sum(one_sided * omega)), float(np.sum(one_sided * omega**2)), rho)


def rms_acceleration(excitation) -> float:
    """sqrt(lambda_0) [m/s^2]: the stationary records' rms (a modulated record's at A = 1)."""
    return math.sqrt(record_spectral_moments(excitation).lambda_0)


def expected_peak_ground_acceleration(excitation, sampled: bool = True) -> float:
    """E[PGA] of the records of ``excitation`` [m/s^2], P6: the largest ``|sample|`` (P5), or of
    the continuous process when ``sampled`` is False (P4)."""
    moments = record_spectral_moments(excitation)
    if excitation.envelope is None:
        times = np.array([0.0, excitation.times()[-1]])
        modulation = np.ones(2)
    else:
        times = np.linspace(0.0, excitation.times()[-1], 801)
        modulation = np.asarray(excitation.envelope(times), dtype=float)
    sigma = math.sqrt(moments.lambda_0) * modulation
    with np.errstate(divide="ignore", invalid="ignore"):
        growth = np.where(modulation > 0, np.gradient(modulation, times) / modulation, 0.0)  # A'/A, P7
    extra = {"time_step": excitation.time_step, "sample_correlation": moments.rho} if sampled else {}
    return float(vanmarcke_expected_peak(sigma, moments.nu0, moments.delta, times, growth=growth, **extra))


def intensity_for_peak_ground_acceleration(excitation, pga) -> float:
    """The G0 [m^2/s^3] for which E[PGA] of ``excitation``'s records is ``pga`` [m/s^2] (P6)."""
    pga = finite_number("pga", pga, error=ArgumentError)
    if not pga > 0:
        raise ArgumentError("pga", f"must be > 0 m/s^2, got {quote(pga)}")
    g0 = excitation.spectrum.G0
    if not g0 > 0:
        raise CaseError("excitation.spectrum.G0", "must be > 0 to be scaled to a peak ground acceleration")
    return g0 * (pga / expected_peak_ground_acceleration(excitation)) ** 2
