"""Suites of accelerograms from two published stochastic ground-motion models
that ``pounding`` does not use, for checking the fit of a recorded suite
(``validation/suite_accuracy.py``) on motions nobody tuned on.

- :func:`brune_suite`, the stochastic method of Boore (2003): a point source
  with Brune's omega-squared spectrum, geometric spreading, anelastic
  attenuation Q(f) and the kappa filter, imposed on windowed Gaussian noise
  (equations S1-S8 below);
- :func:`drifting_filter_suite`, the modulated, filtered white noise of
  Rezaeian & Der Kiureghian (2008): a filter whose frequency and damping drift
  in time, a gamma modulating function and a high-pass correction (F1-F5);
- :func:`low_passed`, :func:`resampled`: a suite through a zero-phase
  Butterworth low-pass, or resampled to another time step.

Record i of a suite is drawn from ``numpy.random.default_rng([seed, i])``, so it
does not depend on how many records are drawn. SI throughout (m, s, m/s^2).

References: D. M. Boore (2003), Simulation of ground motion using the stochastic
method, Pure Appl. Geophys. 160, 635-676; J. N. Brune (1970), J. Geophys. Res.
75, 4997-5009; J. G. Anderson & S. E. Hough (1984), Bull. Seism. Soc. Am. 74,
1969-1993; G. R. Saragoni & G. C. Hart (1974), Earthq. Eng. Struct. Dyn. 2,
249-264; S. Rezaeian & A. Der Kiureghian (2008), A stochastic ground motion
model with separable temporal and spectral nonstationarities, Earthq. Eng.
Struct. Dyn. 37, 1565-1584.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pounding.hazard.accelerograms import Accelerogram

__all__ = [
    "BruneSource",
    "DriftingFilter",
    "brune_amplitude",
    "brune_suite",
    "drifting_filter_suite",
    "gamma_modulation",
    "low_passed",
    "resampled",
    "saragoni_hart_window",
]


# --- Boore (2003): the stochastic method ---------------------------------------


@dataclass(frozen=True)
class BruneSource:
    """A point source and its path to a rock site (Boore 2003; defaults for western North America).

    magnitude: moment magnitude M; distance: hypocentral R [m]; stress_drop: Brune's delta sigma [Pa]
    (70 bar); density rho [kg/m^3] and shear_velocity beta [m/s] at the source; quality_factor Q0 and
    quality_exponent eta of Q(f) = Q0 f^eta; kappa [s]; the Saragoni-Hart window's epsilon, eta and
    f_Tgm; time_step and duration [s] of the records (noise starting at ``lead`` [s]).
    """

    magnitude: float = 6.5
    distance: float = 20.0e3
    stress_drop: float = 7.0e6
    density: float = 2800.0
    shear_velocity: float = 3500.0
    quality_factor: float = 180.0
    quality_exponent: float = 0.45
    kappa: float = 0.04
    window_epsilon: float = 0.2
    window_eta: float = 0.05
    window_length_factor: float = 2.0
    time_step: float = 0.005
    duration: float = 40.0
    lead: float = 2.0

    @property
    def moment(self) -> float:
        """S1: M0 = 10^(1.5 M + 9.05) [N m] (Boore's 10^(1.5 M + 16.05) dyne cm)."""
        return 10.0 ** (1.5 * self.magnitude + 9.05)

    @property
    def corner_frequency(self) -> float:
        """S2, Brune: f0 = 4.906e6 beta (delta sigma / M0)^(1/3) [Hz], beta in km/s, delta sigma in bar,
        M0 in dyne cm (Boore 2003)."""
        return 4.906e6 * (self.shear_velocity / 1e3) * ((self.stress_drop / 1e5) / (self.moment * 1e7)) ** (1.0 / 3.0)

    @property
    def ground_motion_duration(self) -> float:
        """S7: T_gm = 1 / f0 + 0.05 R [s] (source duration and a path duration of 0.05 s/km)."""
        return 1.0 / self.corner_frequency + 0.05 * self.distance / 1e3


def geometric_spreading(distance: float) -> float:
    """S4: Z(R) = R0 / R up to 40 km, then (R0 / 40 km) (40 km / R)^0.5; R0 = 1 km, R in m."""
    reference, bend = 1.0e3, 40.0e3
    return reference / distance if distance <= bend else reference / bend * math.sqrt(bend / distance)


def brune_amplitude(source: BruneSource, frequency) -> np.ndarray:
    """The Fourier amplitude of acceleration [m/s] at ``frequency`` [Hz], Boore (2003):

        S3: E(f) = R_theta_phi V F M0 / (4 pi rho beta^3 R0) / (1 + (f / f0)^2)   (R_theta_phi = 0.55, V = 1/sqrt 2, F = 2)
        S5: P(R, f) = Z(R) exp(-pi f R / (Q(f) beta)),   Q(f) = Q0 f^eta
        S6: Y(f) = E(f) P(R, f) exp(-pi kappa f) (2 pi f)^2

    with the site's amplification taken as 1 (rock). The (2 pi f)^2 makes displacement acceleration:
    below f0 the amplitude rises as f^2, above it is flat until kappa and Q cut it."""
    f = np.asarray(frequency, dtype=float)
    constant = 0.55 * (1.0 / math.sqrt(2.0)) * 2.0 / (4.0 * math.pi * source.density * source.shear_velocity**3 * 1.0e3)
    source_spectrum = constant * source.moment / (1.0 + (f / source.corner_frequency) ** 2)
    with np.errstate(divide="ignore"):
        quality = source.quality_factor * np.maximum(f, 1e-12) ** source.quality_exponent
    path = geometric_spreading(source.distance) * np.exp(-math.pi * f * source.distance / (quality * source.shear_velocity))
    return source_spectrum * path * np.exp(-math.pi * source.kappa * f) * (2.0 * math.pi * f) ** 2


def saragoni_hart_window(time, length: float, epsilon: float = 0.2, eta: float = 0.05) -> np.ndarray:
    """S8, Saragoni & Hart's window as Boore (2003) writes it: w = a (t / t_eta)^b exp(-c t / t_eta), with
    b = -epsilon ln(eta) / (1 + epsilon (ln(epsilon) - 1)), c = b / epsilon, a = (e / epsilon)^b: 1 at its
    peak t = epsilon t_eta, eta at t = t_eta (``length``), 0 before 0."""
    t = np.maximum(np.asarray(time, dtype=float), 0.0) / length
    b = -epsilon * math.log(eta) / (1.0 + epsilon * (math.log(epsilon) - 1.0))
    c, a = b / epsilon, (math.e / epsilon) ** b
    return a * t**b * np.exp(-c * t)


def brune_record(source: BruneSource, rng: np.random.Generator, name: str = "brune") -> Accelerogram:
    """One record by Boore's (2003) time-domain steps: Gaussian white noise over t_eta = f_Tgm T_gm,
    shaped by the window (S8) from ``lead``; its Fourier transform over the record divided by its rms
    amplitude (so the mean square amplitude spectrum is 1) and multiplied by Y(f) (S6); transformed back."""
    n = round(source.duration / source.time_step) + 1
    length = source.window_length_factor * source.ground_motion_duration
    times = np.arange(n) * source.time_step - source.lead
    inside = (times >= 0.0) & (times <= length)
    if times[-1] < length:
        raise ValueError(f"duration {source.duration} s is shorter than the lead and the window ({source.lead + length:.1f} s)")
    noise = np.zeros(n)
    noise[inside] = rng.standard_normal(int(inside.sum())) * saragoni_hart_window(times[inside], length, source.window_epsilon, source.window_eta)
    spectrum = np.fft.rfft(noise) * source.time_step
    spectrum /= math.sqrt(np.mean(np.abs(spectrum) ** 2))
    frequency = np.fft.rfftfreq(n, source.time_step)
    acceleration = np.fft.irfft(spectrum * brune_amplitude(source, frequency), n) / source.time_step
    return Accelerogram(name, source.time_step, acceleration)


def brune_suite(source: BruneSource, count: int, seed: int, name: str = "brune") -> list[Accelerogram]:
    """``count`` records of :func:`brune_record`, record i from ``default_rng([seed, i])``."""
    return [brune_record(source, np.random.default_rng([seed, i]), f"{name}-{i:03d}") for i in range(count)]


# --- Rezaeian & Der Kiureghian (2008): a filter drifting in time -----------------


@dataclass(frozen=True)
class DriftingFilter:
    """The modulated, filtered white noise of Rezaeian & Der Kiureghian (2008).

    The filter's frequency and damping go linearly from (frequency_start, damping_start) at t = 0 to
    (frequency_end, damping_end) at t = ``duration`` (frequencies in Hz); the gamma modulating function
    has shape alpha_2 (``modulation_shape``) and decay alpha_3 (``modulation_decay``, 1/s), its scale set by
    the expected Arias intensity [m/s]; the high-pass corner is ``high_pass`` [Hz] (0: none). Records of
    ``duration`` s at ``time_step`` s.
    """

    frequency_start: float = 6.0
    frequency_end: float = 1.0
    damping_start: float = 0.2
    damping_end: float = 0.4
    modulation_shape: float = 2.5
    modulation_decay: float = 0.25
    arias_intensity: float = 1.0
    high_pass: float = 0.1
    time_step: float = 0.005
    duration: float = 30.0
    memory: float = 1e-5

    def times(self) -> np.ndarray:
        return np.arange(round(self.duration / self.time_step) + 1) * self.time_step

    def frequency(self, time) -> np.ndarray:
        """F3: omega_f(tau) = omega_0 + (omega_n - omega_0) tau / t_n [rad/s], linear in time."""
        share = np.asarray(time, dtype=float) / self.duration
        return 2.0 * math.pi * (self.frequency_start + (self.frequency_end - self.frequency_start) * share)

    def damping(self, time) -> np.ndarray:
        """F3: zeta_f(tau) = zeta_0 + (zeta_n - zeta_0) tau / t_n, linear in time."""
        share = np.asarray(time, dtype=float) / self.duration
        return self.damping_start + (self.damping_end - self.damping_start) * share


def gamma_modulation(time, shape: float, decay: float, arias_intensity: float) -> np.ndarray:
    """F4: q(t) = alpha_1 t^(alpha_2 - 1) exp(-alpha_3 t), alpha_1 such that the expected Arias intensity
    pi / (2 g) int q^2 dt (the filtered noise has unit variance) is ``arias_intensity`` [m/s]:
    int_0^inf t^(2 alpha_2 - 2) exp(-2 alpha_3 t) dt = Gamma(2 alpha_2 - 1) / (2 alpha_3)^(2 alpha_2 - 1)."""
    from pounding.hazard.accelerograms import G

    integral = math.gamma(2.0 * shape - 1.0) / (2.0 * decay) ** (2.0 * shape - 1.0)
    scale = math.sqrt(arias_intensity * 2.0 * G / math.pi / integral)
    t = np.asarray(time, dtype=float)
    return scale * t ** (shape - 1.0) * np.exp(-decay * t)


def _impulse_responses(model: DriftingFilter) -> tuple[np.ndarray, np.ndarray]:
    """F1 sampled: h[j, i] = h(j dt, lambda(t_i)), the filter started at t_i seen j steps later,
    h(s, lambda) = omega_f / sqrt(1 - zeta_f^2) exp(-zeta_f omega_f s) sin(omega_f sqrt(1 - zeta_f^2) s),
    for the lags until exp(-zeta_f omega_f s) falls below ``memory``; and sigma_f(t_k)^2 / dt (F2)."""
    t = model.times()
    omega, zeta = model.frequency(t), model.damping(t)
    if not (np.all(omega > 0) and np.all((zeta > 0) & (zeta < 1))):
        raise ValueError("the filter's frequency must stay > 0 and its damping in (0, 1)")
    lags = min(t.size, math.ceil(-math.log(model.memory) / (zeta * omega).min() / model.time_step) + 1)
    damped = omega * np.sqrt(1.0 - zeta**2)
    s = np.arange(lags)[:, None] * model.time_step
    responses = omega / np.sqrt(1.0 - zeta**2) * np.exp(-zeta * omega * s) * np.sin(damped * s)
    variance = np.zeros(t.size)
    for j in range(lags):
        variance[j:] += responses[j, : t.size - j] ** 2
    return responses, variance


def _high_pass(acceleration: np.ndarray, corner: float, step: float) -> np.ndarray:
    """F5: the critically damped oscillator u'' + 2 omega_c u' + omega_c^2 u = x(t) from rest, whose u''
    is the corrected record (Rezaeian & Der Kiureghian 2008): H(s) = s^2 / (s + omega_c)^2, by the
    bilinear transform."""
    from scipy import signal

    if corner == 0:
        return acceleration
    omega_c = 2.0 * math.pi * corner
    numerator, denominator = signal.bilinear([1.0, 0.0, 0.0], [1.0, 2.0 * omega_c, omega_c**2], fs=1.0 / step)
    return signal.lfilter(numerator, denominator, acceleration, axis=-1)


def drifting_filter_suite(model: DriftingFilter, count: int, seed: int, name: str = "rdk") -> list[Accelerogram]:
    """``count`` records of Rezaeian & Der Kiureghian's (2008) model, record i from ``default_rng([seed, i])``:

        F1, F2: x(t) = q(t) (1 / sigma_f(t)) int_0^t h(t - tau, lambda(tau)) w(tau) dtau,
                sigma_f(t)^2 = int_0^t h(t - tau, lambda(tau))^2 dtau,
        discretized as x(t_k) = q(t_k) sum_i<=k s_i(t_k) u_i, s_i(t_k) = h(t_k - t_i, lambda(t_i)) /
                sqrt(sum_j<=k h(t_k - t_j, lambda(t_j))^2), u_i standard normal;

    the filtered part has unit variance, so q(t)^2 is the record's mean square (F4); then the high-pass
    of F5."""
    responses, variance = _impulse_responses(model)
    t = model.times()
    n, lags = t.size, responses.shape[0]
    with np.errstate(divide="ignore"):
        normal = np.where(variance > 0, 1.0 / np.sqrt(variance), 0.0)
    modulation = gamma_modulation(t, model.modulation_shape, model.modulation_decay, model.arias_intensity)
    noise = np.stack([np.random.default_rng([seed, i]).standard_normal(n) for i in range(count)]) if count else np.zeros((0, n))
    filtered = np.zeros_like(noise)
    for j in range(1, lags):
        filtered[:, j:] += responses[j, : n - j] * noise[:, : n - j]
    records = _high_pass(filtered * (normal * modulation), model.high_pass, model.time_step)
    return [Accelerogram(f"{name}-{i:03d}", model.time_step, records[i]) for i in range(count)]


# --- derived suites ---------------------------------------------------------------


def low_passed(records, corner: float = 10.0, order: int = 4, name: str | None = None) -> list[Accelerogram]:
    """Each record through a Butterworth low-pass of ``order`` at ``corner`` [Hz], forward and backward
    (zero phase; the gain is |H|^2 = 1 / (1 + (f / corner)^(2 order)))."""
    from scipy import signal

    out = []
    for record in records:
        sections = signal.butter(order, corner, btype="low", fs=1.0 / record.time_step, output="sos")
        label = f"{name}-{record.name.rsplit('-', 1)[-1]}" if name else record.name
        out.append(Accelerogram(label, record.time_step, signal.sosfiltfilt(sections, record.acceleration)))
    return out


def resampled(records, time_step: float, name: str | None = None) -> list[Accelerogram]:
    """Each record resampled to ``time_step`` [s] (a whole multiple or fraction of its own) by
    polyphase filtering (``scipy.signal.resample_poly``: a zero-phase anti-aliasing FIR)."""
    from fractions import Fraction

    from scipy import signal

    out = []
    for record in records:
        ratio = Fraction(record.time_step / time_step).limit_denominator(1000)
        values = signal.resample_poly(record.acceleration, ratio.numerator, ratio.denominator)
        label = f"{name}-{record.name.rsplit('-', 1)[-1]}" if name else record.name
        out.append(Accelerogram(label, time_step, values))
    return out
