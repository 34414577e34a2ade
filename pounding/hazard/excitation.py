"""Ground motion: Kanai-Tajimi / Clough-Penzien spectra, the Shinozuka-Sato
envelope, and seeded Gaussian records by the spectral representation method.

All spectra are *two-sided* power spectral densities of ground acceleration,
[m^2/s^3], as in Eq. 7 of Rahimi & Soltani (2016): the variance of the
acceleration is the integral of S_g over (-inf, inf).
"""

from __future__ import annotations

import itertools
import math
import numbers
from dataclasses import dataclass

import numpy as np

from pounding import defaults
from pounding.errors import (
    CaseError,
    check_limit,
    described,
    finite_number,
    finite_numbers,
    quote,
    whole_number,
)
from pounding.hazard.filter_bank import FilterBank

__all__ = [
    "CloughPenzien",
    "Excitation",
    "FilterBank",
    "KanaiTajimi",
    "ShinozukaSato",
    "TabulatedEnvelope",
    "ground_acceleration",
    "ground_accelerations",
    "check_samples",
    "record_rng",
]


FILTER_FREQUENCY_MAX = 1e6
"""Largest filter frequency omega_g, omega_f [rad/s] (160 kHz: far above any ground motion; a wide filter stands for white noise)."""
FILTER_DAMPING_MAX = 100.0
"""Largest filter damping ratio xi_g, xi_f [-] (beyond, the filter is flat over every building's frequencies)."""


def _positive(instance, field: str, maximum: float = math.inf) -> None:
    """Check ``instance.field`` is a finite number > 0 (and <= ``maximum``) and store it as a float."""
    value = finite_number(field, getattr(instance, field))
    if not 0 < value <= maximum:
        bound = f"in (0, {maximum:g}]" if math.isfinite(maximum) else "a finite number > 0"
        raise CaseError(field, f"must be {bound}, got {quote(value)}")
    object.__setattr__(instance, field, value)


def _non_negative(instance, field: str) -> None:
    """Check ``instance.field`` is a finite number >= 0 and store it as a float."""
    value = finite_number(field, getattr(instance, field))
    if not value >= 0:
        raise CaseError(field, f"must be a finite number >= 0, got {quote(value)}")
    object.__setattr__(instance, field, value)


@dataclass(frozen=True)
class KanaiTajimi:
    """Kanai-Tajimi spectrum, Eq. 7.

    Parameters
    ----------
    G0 : float
        Bedrock white-noise intensity [m^2/s^3] (two-sided).
    omega_g : float
        Ground (filter) frequency [rad/s].
    xi_g : float
        Ground damping ratio [-]. (The text after Eq. 7 swaps the two names:
        omega_g = 27.02 rad/s, xi_g = 0.34; docs/errata.md, E3.)
    """

    G0: float
    omega_g: float
    xi_g: float

    def __post_init__(self):
        _non_negative(self, "G0")
        _positive(self, "omega_g", FILTER_FREQUENCY_MAX)
        _positive(self, "xi_g", FILTER_DAMPING_MAX)

    def filter_response(self, omega):
        """``|H_g(omega)|^2`` of the soil filter (the fraction in Eq. 7) [-]."""
        w2 = np.square(omega)
        wg2 = self.omega_g**2
        four_xi2_wg2 = 4.0 * self.xi_g**2 * wg2
        return (wg2**2 + four_xi2_wg2 * w2) / ((wg2 - w2) ** 2 + four_xi2_wg2 * w2)

    def psd(self, omega):
        """Two-sided PSD of ground acceleration S_g(omega) [m^2/s^3], Eq. 7."""
        return self.G0 * self.filter_response(omega)

    def variance(self) -> float:
        """Variance of ground acceleration [m^2/s^4]: the integral of Eq. 7 over all omega."""
        return math.pi * self.G0 * self.omega_g * (1.0 + 4.0 * self.xi_g**2) / (2.0 * self.xi_g)


@dataclass(frozen=True)
class CloughPenzien(KanaiTajimi):
    """Clough-Penzien spectrum: Kanai-Tajimi times a high-pass filter that
    removes the (unphysical) finite displacement variance at low frequency.

    Parameters
    ----------
    omega_f : float
        High-pass corner frequency [rad/s].
    xi_f : float
        High-pass damping ratio [-].
    """

    omega_f: float = 2.0
    xi_f: float = 0.6

    def __post_init__(self):
        super().__post_init__()
        _positive(self, "omega_f", FILTER_FREQUENCY_MAX)
        _positive(self, "xi_f", FILTER_DAMPING_MAX)

    def psd(self, omega):
        w2 = np.square(omega)
        wf2 = self.omega_f**2
        high_pass = w2**2 / ((wf2 - w2) ** 2 + 4.0 * self.xi_f**2 * wf2 * w2)
        return super().psd(omega) * high_pass

    def variance(self) -> float:
        from scipy.integrate import quad

        value, _ = quad(self.psd, 0.0, np.inf, limit=200)
        return 2.0 * value


@dataclass(frozen=True)
class ShinozukaSato:
    """Shinozuka-Sato envelope A(t) = (exp(-B1 t) - exp(-B2 t)) / C, Eq. 9,
    normalized so that its maximum is 1.

    Parameters
    ----------
    B1, B2 : float
        Decay constants [1/s], 0 < B1 < B2.
    """

    B1: float = 0.085
    B2: float = 0.17

    def __post_init__(self):
        _positive(self, "B1")
        _positive(self, "B2")
        if not self.B2 > self.B1:
            raise CaseError("B2", f"must be greater than B1 = {self.B1}, got {self.B2}")

    @property
    def peak_time(self) -> float:
        """Time of the envelope's maximum [s]."""
        return math.log(self.B2 / self.B1) / (self.B2 - self.B1)

    @property
    def normalization(self) -> float:
        """C of Eq. 9: the maximum of exp(-B1 t) - exp(-B2 t) [-]."""
        t = self.peak_time
        return math.exp(-self.B1 * t) - math.exp(-self.B2 * t)

    def __call__(self, t):
        """A(t) [-], Eq. 9."""
        t = np.asarray(t, dtype=float)
        return (np.exp(-self.B1 * t) - np.exp(-self.B2 * t)) / self.normalization


@dataclass(frozen=True)
class TabulatedEnvelope:
    """An envelope A(t) [-] given at instants [s], linear between them and held beyond
    (a recorded suite's mean intensity in time, docs/hazard.md S4).

    Parameters
    ----------
    times : tuple of float
        Increasing instants [s], at least two.
    values : tuple of float
        A(t) at them [-], >= 0, not all zero.
    """

    times: tuple[float, ...]
    values: tuple[float, ...]

    def __post_init__(self):
        times, values = finite_numbers("times", self.times), finite_numbers("values", self.values)
        if len(times) < 2 or len(values) != len(times) or any(b <= a for a, b in itertools.pairwise(times)):
            raise CaseError("times", "must be at least two increasing instants, one value each")
        if not (min(values) >= 0 and max(values) > 0):
            raise CaseError("values", "must be >= 0 and not all zero")
        object.__setattr__(self, "times", times)
        object.__setattr__(self, "values", values)

    def __call__(self, t):
        """A(t) [-]."""
        return np.interp(np.asarray(t, dtype=float), self.times, self.values)


@dataclass(frozen=True)
class Excitation:
    """A random ground motion: a stationary Gaussian process with a given
    spectrum, optionally modulated by an envelope (Eq. 8).

    Parameters
    ----------
    spectrum : KanaiTajimi, CloughPenzien or FilterBank
        Two-sided PSD of the stationary ground acceleration.
    duration : float
        Record length [s].
    envelope : ShinozukaSato, TabulatedEnvelope or None
        Deterministic modulating function; None for a stationary record.
    time_step : float
        Sampling interval of the records [s]. Between samples the acceleration
        is interpolated linearly, as a recorded accelerogram would be.
    cutoff_frequency : float
        Highest frequency represented in the records [rad/s]; must lie below
        the Nyquist frequency pi / time_step.
    synthesis_factor : int
        The synthesis FFT spans this many times the shortest power of two of
        samples that holds the record, and the record is its start. 1 (the
        default) gives records periodic over about their duration, which carry
        nothing below about pi / duration [rad/s]; a larger factor represents
        the spectrum down to lower frequencies (a convergence check: see
        docs/accuracy.md). 1 to 64.
    """

    spectrum: KanaiTajimi | FilterBank
    duration: float
    envelope: ShinozukaSato | TabulatedEnvelope | None = None
    time_step: float = 0.005
    cutoff_frequency: float = 2.0 * math.pi * 25.0
    synthesis_factor: int = 1

    def __post_init__(self):
        factor = self.synthesis_factor
        if not (isinstance(factor, numbers.Integral) and not isinstance(factor, bool) and 1 <= factor <= 64):
            raise CaseError("synthesis_factor", f"must be an integer from 1 to 64, got {quote(factor)}")
        object.__setattr__(self, "synthesis_factor", whole_number("synthesis_factor", factor))
        if not isinstance(self.spectrum, (KanaiTajimi, FilterBank)):
            raise CaseError("spectrum", f"must be a KanaiTajimi, CloughPenzien or FilterBank, got {described(self.spectrum)}")
        if self.envelope is not None and not isinstance(self.envelope, (ShinozukaSato, TabulatedEnvelope)):
            raise CaseError("envelope", f"must be a ShinozukaSato, TabulatedEnvelope or None, got {described(self.envelope)}")
        _positive(self, "duration")
        _positive(self, "time_step")
        _positive(self, "cutoff_frequency")
        if self.time_step > self.duration / 10:
            raise CaseError("time_step", f"must be at most duration/10 = {self.duration / 10:g} s, got {self.time_step:g}")
        nyquist = math.pi / self.time_step
        if self.cutoff_frequency >= nyquist:
            raise CaseError(
                "cutoff_frequency",
                f"must be below the Nyquist frequency pi/time_step = {nyquist:.4g} rad/s, got {self.cutoff_frequency:.4g}",
            )
        check_samples(self.duration, self.time_step, self.synthesis_factor)

    @property
    def stationary(self) -> bool:
        return self.envelope is None

    @property
    def n_samples(self) -> int:
        """Number of samples of one record, t = 0, dt, ..., >= duration."""
        return int(math.ceil(self.duration / self.time_step - 1e-9)) + 1

    @property
    def fft_length(self) -> int:
        """Length of the synthesis FFT: ``synthesis_factor`` times a power of
        two >= n_samples, so the synthesis period 2 pi / d_omega is at least
        ``synthesis_factor`` times the record's duration."""
        return self.synthesis_factor * (1 << (self.n_samples - 1).bit_length())

    def times(self) -> np.ndarray:
        """Sample times [s]."""
        return np.arange(self.n_samples) * self.time_step

    def synthesis_frequencies(self) -> np.ndarray:
        """Frequencies omega_j = j d_omega of the one-sided synthesis grid [rad/s]."""
        m = self.fft_length
        return np.arange(m // 2 + 1) * (2.0 * math.pi / (m * self.time_step))

    def represented_variance(self) -> float:
        """Variance of the stationary records as generated [m^2/s^4]: the sum
        of the one-sided PSD over the synthesis grid up to the cutoff.
        Tends to ``spectrum.variance()`` as the cutoff grows."""
        return float(np.sum(_one_sided_weights(self)))

    def envelope_values(self) -> np.ndarray:
        """A(t) at the sample times (ones when stationary)."""
        if self.envelope is None:
            return np.ones(self.n_samples)
        return self.envelope(self.times())


def check_samples(duration: float, time_step: float, synthesis_factor: int = 1) -> None:
    """:class:`CaseError` when a record of ``duration`` sampled every ``time_step``
    [s] would exceed :data:`~pounding.defaults.MAX_SAMPLES_PER_RECORD` samples or
    its synthesis :data:`~pounding.defaults.MAX_SYNTHESIS_SAMPLES`; counted
    before anything is allocated. Names ``duration`` when the record is too long
    even at the default time step, else ``time_step``."""
    samples = duration / time_step + 1.0  # a float: 1e300 / 1e-300 is inf, not an error
    default_step = Excitation.__dataclass_fields__["time_step"].default
    field = "duration" if duration / default_step >= defaults.MAX_SAMPLES_PER_RECORD else "time_step"
    check_limit(field, samples, defaults.MAX_SAMPLES_PER_RECORD,
                f"samples per record ({duration:g} s / {time_step:g} s)", "shorten duration or lengthen time_step")
    # the FFT of synthesis_factor times the power of two >= the samples
    power = 2.0 ** math.ceil(math.log2(max(samples - 1.0, 1.0)))
    check_limit("synthesis_factor", synthesis_factor * power, defaults.MAX_SYNTHESIS_SAMPLES,
                f"synthesis samples ({synthesis_factor} x {power:,.0f})", "lower synthesis_factor")


def _one_sided_weights(excitation: Excitation) -> np.ndarray:
    """G(omega_j) d_omega with G = 2 S_g the one-sided PSD; zero at omega = 0
    and above the cutoff."""
    omega = excitation.synthesis_frequencies()
    d_omega = omega[1]
    weights = 2.0 * excitation.spectrum.psd(omega) * d_omega
    weights[0] = 0.0
    weights[omega > excitation.cutoff_frequency] = 0.0
    return weights


def record_rng(seed: int, index: int) -> np.random.Generator:
    """The random generator of record ``index`` of a study seeded ``seed``.

    Records are seeded one by one (``SeedSequence(seed, spawn_key=(index,))``,
    the ``index``-th child of ``SeedSequence(seed)``), so a record's motion does
    not depend on how many records are drawn or how they are split into chunks.
    """
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(index,)))


def ground_acceleration(excitation: Excitation, rng: np.random.Generator) -> np.ndarray:
    """One record of ground acceleration [m/s^2] at ``excitation.times()``.

    Spectral representation with Gaussian complex amplitudes: x(t) = Re sum_j
    sqrt(G_j d_omega) (a_j - i b_j) exp(i omega_j t), a_j, b_j ~ N(0, 1), which is
    exactly Gaussian and stationary with variance sum_j G_j d_omega; then
    multiplied by the envelope (Eq. 8).
    """
    weights = _one_sided_weights(excitation)
    m = excitation.fft_length
    amplitudes = np.sqrt(weights) * (rng.standard_normal(weights.size) - 1j * rng.standard_normal(weights.size))
    # irfft(c)[k] = (2/m) Re sum_j c_j exp(2 pi i j k / m) when c_0 = c_{m/2} = 0.
    record = np.fft.irfft(amplitudes, n=m)[: excitation.n_samples] * (m / 2)
    if excitation.envelope is not None:
        record *= excitation.envelope_values()
    return record


def ground_accelerations(excitation: Excitation, seed: int, indices) -> np.ndarray:
    """Records ``indices`` of the study seeded ``seed``, one per row [m/s^2]."""
    indices = np.asarray(indices, dtype=np.int64).ravel()
    out = np.empty((indices.size, excitation.n_samples))
    for row, index in enumerate(indices):
        out[row] = ground_acceleration(excitation, record_rng(seed, int(index)))
    return out
