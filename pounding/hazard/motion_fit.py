"""A Kanai-Tajimi or Clough-Penzien spectrum fitted to a suite of recorded accelerograms.

The method (equations R1 to R6):

- R1, Arias intensity: I(t) = pi / (2 g) int_0^t a^2 dt' [m/s], by the
  trapezoid rule at the samples.
- R2, significant duration: t_5 and t_95 where I reaches 5 % and 95 % of its
  total (interpolated linearly between samples); D = t_95 - t_5 [s].
- R3, periodogram of a record's strong motion (the samples a_k from t_5 to
  t_95, tapered by a Tukey window w_k: a half cosine over TAPER / 2 = 25 % of
  them at each end, which keeps the leakage of the spectrum's peak out of its
  steep low-frequency side):
  S_i(w) = ``|dt sum_k w_k a_k exp(-i w t_k)|^2`` / (2 pi D_i mean(w_k^2)),
  two-sided [m^2/s^3], so that its integral over (-inf, inf) is the (taper-
  weighted) mean square of a over D_i.
- R4, the suite's mean: each S_i averaged within frequency bins, the bins'
  edges log-spaced (1/20 decade) but never narrower than the coarsest record's
  resolution 2 pi / D_i, from w_low = max(2 pi 0.1, 2 pi / min D_i) rad/s to the
  cutoff; then the mean over the records of each bin's average, at the bins'
  mean frequencies.
- R5, the fits: Kanai-Tajimi (G0, omega_g, xi_g; Eq. 7) and Clough-Penzien
  (adds omega_f, xi_f) minimize the weighted rms misfit
  m = sqrt(mean_j(n_j / mean(n) (log10 S_model(w_j) - log10 S_mean(w_j))^2)),
  n_j the number of periodogram values bin j averages (its log's variance
  goes as 1 / n_j), by scipy.optimize.least_squares on the logs of the parameters, from
  the mean's peak frequency and a few damping ratios; omega_g in [0.5, 200]
  rad/s, xi_g and xi_f in [0.05, 5], omega_f in [0.05, 50] rad/s (within
  pounding.hazard.excitation's bounds), G0 within 1e6 of the mean's peak level.
- R6, the choice: Clough-Penzien is kept only if its misfit m is below 0.9
  times Kanai-Tajimi's (a clearly better fit); else Kanai-Tajimi.

The fitted process is stationary and lasts the suite's mean significant
duration D (R2): the records' strong motion, as R3 measures it. For modulated
records G0 is that of the stationary process of the same (taper-weighted) mean
square over D: the true G0 times the taper-weighted mean of A(t)^2 over D.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from pounding.errors import ArgumentError, CaseError, described, finite_number, quote
from pounding.hazard.accelerograms import Accelerogram, G
from pounding.hazard.excitation import FILTER_DAMPING_MAX, FILTER_FREQUENCY_MAX, CloughPenzien, KanaiTajimi

__all__ = [
    "CP_MARGIN",
    "TAPER",
    "FittedExcitation",
    "arias_intensity",
    "fit_excitation",
    "mean_periodogram",
    "significant_duration",
    "strong_motion",
]

CP_MARGIN = 0.9
"""R6: Clough-Penzien replaces Kanai-Tajimi when its rms log10 misfit is below this times Kanai-Tajimi's."""
LOWEST_FREQUENCY = 2.0 * math.pi * 0.1
"""R4: the lowest frequency fitted [rad/s] (0.1 Hz), raised to 2 pi / D for a short strong motion."""
BINS_PER_DECADE = 20
"""R4: the bins' log spacing."""
OMEGA_G_RANGE = (0.5, min(200.0, FILTER_FREQUENCY_MAX))
XI_RANGE = (0.05, min(5.0, FILTER_DAMPING_MAX))
OMEGA_F_RANGE = (0.05, min(50.0, FILTER_FREQUENCY_MAX))
_UNITS = {"G0": "m^2/s^3", "omega_g": "rad/s", "xi_g": "-", "omega_f": "rad/s", "xi_f": "-", "duration": "s",
          "misfit": "weighted rms of log10 PSD (R5)"}


def arias_intensity(accelerogram: Accelerogram) -> np.ndarray:
    """Cumulative Arias intensity I(t_k) = pi/(2g) int_0^t_k a^2 dt [m/s] at the samples, R1 (trapezoid)."""
    a2 = np.square(accelerogram.acceleration)
    out = np.empty(a2.size)
    out[0] = 0.0
    np.cumsum(0.5 * (a2[1:] + a2[:-1]), out=out[1:])
    return out * (math.pi / (2.0 * G) * accelerogram.time_step)


def _crossing(intensity: np.ndarray, level: float, step: float) -> float:
    """The time where the nondecreasing ``intensity`` first reaches ``level``, linear between samples."""
    k = int(np.searchsorted(intensity, level, side="left"))
    if k == 0:
        return 0.0
    k = min(k, intensity.size - 1)
    rise = intensity[k] - intensity[k - 1]
    fraction = (level - intensity[k - 1]) / rise if rise > 0 else 1.0
    return (k - 1 + min(max(fraction, 0.0), 1.0)) * step


def significant_duration(accelerogram: Accelerogram, low: float = 0.05, high: float = 0.95) -> tuple[float, float]:
    """(t_low, t_high) [s]: where the Arias intensity reaches ``low`` and ``high`` of its total, R2."""
    low, high = finite_number("low", low, error=ArgumentError), finite_number("high", high, error=ArgumentError)
    if not 0.0 <= low < high <= 1.0:
        raise ArgumentError("high", f"need 0 <= low < high <= 1, got low = {quote(low)}, high = {quote(high)}")
    intensity = arias_intensity(accelerogram)
    total = intensity[-1]
    if not (total > 0 and math.isfinite(total)):
        raise CaseError(accelerogram.name or "record", "is zero throughout (or overflows); it has no strong motion")
    step = accelerogram.time_step
    return _crossing(intensity, low * total, step), _crossing(intensity, high * total, step)


@dataclass(frozen=True, eq=False)
class FittedExcitation:
    """The spectrum fitted to a suite of records, and what it was fitted to (R1 to R6).

    Parameters
    ----------
    spectrum : KanaiTajimi or CloughPenzien
        The fitted two-sided PSD (R5, R6), SI.
    duration : float
        Mean 5-95 % Arias (significant) duration of the suite [s] (R2).
    duration_definition : str
        What ``duration`` is, in words.
    frequencies : array
        The bins' mean frequencies [rad/s] (R4).
    periodogram : array
        The suite's mean two-sided periodogram of the strong motion [m^2/s^3] (R3, R4).
    misfit : dict
        Weighted rms log10 misfit m of each fit (R5): {"kanai-tajimi": ..., "clough-penzien": ...}.
    """

    spectrum: KanaiTajimi
    duration: float
    duration_definition: str
    frequencies: np.ndarray
    periodogram: np.ndarray
    misfit: dict = field(default_factory=dict)

    def __post_init__(self):
        for name in ("frequencies", "periodogram"):
            values = np.array(getattr(self, name), dtype=float)
            values.setflags(write=False)
            object.__setattr__(self, name, values)
        object.__setattr__(self, "misfit", dict(self.misfit))

    @property
    def kind(self) -> str:
        """ "clough-penzien" or "kanai-tajimi"."""
        return "clough-penzien" if isinstance(self.spectrum, CloughPenzien) else "kanai-tajimi"

    def parameters_at_bounds(self) -> dict:
        """R5's parameters that ended on a bound of their range: {name: value} (the fit wanted beyond it)."""
        ranges = {"omega_g": OMEGA_G_RANGE, "xi_g": XI_RANGE, "omega_f": OMEGA_F_RANGE, "xi_f": XI_RANGE}
        out = {}
        for name, (low, high) in ranges.items():
            value = getattr(self.spectrum, name, None)
            if value is not None and not low * (1 + 1e-6) < value < high * (1 - 1e-6):
                out[name] = float(value)
        return out

    def bound_warning(self) -> str:
        """One line (<= 200 characters) when a parameter sits on its bound (:meth:`parameters_at_bounds`), else ""."""
        bounds = self.parameters_at_bounds()
        if not bounds:
            return ""
        words = {"omega_g": ("ground frequency", " rad/s"), "xi_g": ("ground damping ratio", ""),
                 "omega_f": ("high-pass frequency", " rad/s"), "xi_f": ("high-pass damping ratio", "")}
        named = ", ".join(f"{words[name][0]} {value:.3g}{words[name][1]}" for name, value in bounds.items())
        return (f"The {self.kind.replace('-', ' ').title().replace(' ', '-')} fit to the records stops on a bound ({named}): "
                "it describes them poorly. The closed form takes the filter bank, not it.")

    def to_dict(self) -> dict:
        """JSON-ready, SI: the spectrum's name and parameters, the duration, the misfits and the units."""
        out = {"spectrum": self.kind, "G0": self.spectrum.G0, "omega_g": self.spectrum.omega_g, "xi_g": self.spectrum.xi_g}
        if isinstance(self.spectrum, CloughPenzien):
            out.update(omega_f=self.spectrum.omega_f, xi_f=self.spectrum.xi_f)
        out.update(duration=self.duration, duration_definition=self.duration_definition,
                   misfit={k: float(v) for k, v in self.misfit.items()})
        out["parameters_at_bounds"] = self.parameters_at_bounds()
        out["units"] = {k: v for k, v in _UNITS.items() if k in out}
        return out


def strong_motion(record: Accelerogram) -> tuple[np.ndarray, float]:
    """The samples from t_5 to t_95 and D = t_95 - t_5 [s], R2."""
    start, end = significant_duration(record)
    step = record.time_step
    first, last = int(math.floor(start / step)), int(math.ceil(end / step))
    return record.acceleration[first: last + 1], max(end - start, step)


TAPER = 0.5
"""R3: the fraction of the strong motion tapered (a Tukey window: a half cosine over TAPER / 2 at each end),
which keeps the peak's leakage out of the steep low-frequency side of a Clough-Penzien spectrum."""


def _taper(n: int) -> np.ndarray:
    """R3: the Tukey window w_k of ``n`` samples (1 in the middle, cosine-tapered at each end)."""
    window = np.ones(n)
    edge = int(math.floor(TAPER * (n - 1) / 2.0))
    if edge > 0:
        ramp = 0.5 * (1.0 - np.cos(np.pi * np.arange(edge) / edge))
        window[:edge] = ramp
        window[n - edge:] = ramp[::-1]
    return window


def _bin_edges(low: float, high: float, resolution: float) -> np.ndarray:
    """R4: edges log-spaced, each bin at least ``resolution`` wide."""
    ratio = 10.0 ** (1.0 / BINS_PER_DECADE)
    edges = [low]
    while edges[-1] < high:
        edges.append(max(edges[-1] * ratio, edges[-1] + resolution))
    if len(edges) > 2 and high - edges[-2] < 0.5 * (edges[-2] - edges[-3]):
        edges.pop(-2)  # no sliver of a last bin
    edges[-1] = high
    return np.asarray(edges)


def mean_periodogram(segments, cutoff: float, interpolated: bool = False, tapered: bool = True,
                     lowest: float = LOWEST_FREQUENCY) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """R3 and R4: the bins' mean frequencies, the records' mean periodogram on them, and
    the number of periodogram values each bin averages. ``interpolated``: each periodogram times
    sinc^4(w dt / 2 pi), the PSD of the record linear between its samples, as it is integrated (S1).
    ``tapered=False``: no window (a whole record, which starts and ends at rest, S1). The bins start at
    max(``lowest``, 2 pi / the shortest segment) [rad/s]."""
    from scipy import fft

    durations = np.array([segment[2] for segment in segments])
    low = max(lowest, 2.0 * math.pi / durations.min())
    if not cutoff > 2.0 * low:
        shortest = segments[int(np.argmin(durations))][3]
        raise ArgumentError("cutoff_frequency", f"must exceed twice the lowest fitted frequency, {2 * low:.3g} rad/s "
                                                f"(2 pi / the {durations.min():.3g} s analysed of {quote(shortest, 60)}), got {cutoff:.4g}")
    edges = _bin_edges(low, cutoff, 2.0 * math.pi / durations.min())
    bins = edges.size - 1
    power = np.zeros(bins)
    covered = np.zeros(bins)
    frequency_sum = np.zeros(bins)
    frequency_count = np.zeros(bins)
    for values, step, duration, _ in segments:
        n = fft.next_fast_len(values.size, real=True)
        omega = np.arange(n // 2 + 1) * (2.0 * math.pi / (n * step))
        window = _taper(values.size) if tapered else np.ones(values.size)
        scale = step**2 / (2.0 * math.pi * duration * np.mean(window**2))
        periodogram = np.abs(fft.rfft(values * window, n)) ** 2 * scale  # R3
        if interpolated:
            periodogram *= np.sinc(omega * step / (2.0 * math.pi)) ** 4
        index = np.searchsorted(edges, omega, side="right") - 1
        inside = (index >= 0) & (index < bins)
        index, omega, periodogram = index[inside], omega[inside], periodogram[inside]
        counts = np.bincount(index, minlength=bins)
        sums = np.bincount(index, weights=periodogram, minlength=bins)
        has = counts > 0
        power[has] += sums[has] / counts[has]
        covered += has
        frequency_sum += np.bincount(index, weights=omega, minlength=bins)
        frequency_count += counts
    keep = covered > 0
    return frequency_sum[keep] / frequency_count[keep], power[keep] / covered[keep], frequency_count[keep]


def _log_misfit(model, omega: np.ndarray, log_target: np.ndarray, weights: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        values = np.log10(model(omega))
    return weights * np.where(np.isfinite(values), values - log_target, 1e3)


def _fit(omega, log_target, weights, make, starts, lower, upper):
    """R5: the least-squares fit in log10 PSD over the log parameters; the best of ``starts``."""
    from scipy.optimize import least_squares

    lower, upper = np.log(lower), np.log(upper)

    def residuals(theta):
        return _log_misfit(make(np.exp(theta)).psd, omega, log_target, weights)

    best = None
    for start in starts:
        theta = np.clip(np.log(start), lower + 1e-9, upper - 1e-9)
        result = least_squares(residuals, theta, bounds=(lower, upper), x_scale=1.0, method="trf", xtol=1e-10)
        if best is None or result.cost < best.cost:
            best = result
    parameters = np.exp(best.x)
    return make(parameters), float(np.sqrt(np.mean(best.fun**2)))


def _kanai_tajimi(parameters) -> KanaiTajimi:
    return KanaiTajimi(float(parameters[0]), float(parameters[1]), float(parameters[2]))


def _clough_penzien(parameters) -> CloughPenzien:
    return CloughPenzien(*(float(p) for p in parameters))


def _level(omega, log_target, spectrum) -> float:
    """G0 that best matches the log levels for the shape of ``spectrum``."""
    shape = np.log10(spectrum.psd(omega) / spectrum.G0)
    return float(10.0 ** np.mean(log_target - shape))


def fit_excitation(records: Sequence[Accelerogram], cutoff_frequency: float) -> FittedExcitation:
    """The Kanai-Tajimi or Clough-Penzien spectrum and duration fitted to ``records``, R1 to R6.

    ``cutoff_frequency`` [rad/s], the highest frequency fitted, must lie below
    every record's Nyquist frequency pi / dt. Records may differ in time step and length.
    """
    if isinstance(records, Accelerogram) or not isinstance(records, Sequence) or not records:
        raise ArgumentError("records", f"must be a non-empty sequence of Accelerogram, got {described(records)}")
    for record in records:
        if not isinstance(record, Accelerogram):
            raise ArgumentError("records", f"must hold Accelerogram only, got {described(record)}")
    cutoff = finite_number("cutoff_frequency", cutoff_frequency, error=ArgumentError)
    if not cutoff > 0:
        raise ArgumentError("cutoff_frequency", f"must be a finite number > 0 rad/s, got {quote(cutoff)}")
    for record in records:
        nyquist = math.pi / record.time_step
        if not cutoff < nyquist:
            raise ArgumentError("cutoff_frequency", f"{cutoff:.4g} rad/s is not below {quote(record.name, 60)}'s Nyquist "
                                                f"frequency pi/dt = {nyquist:.4g} rad/s; lower it")
    segments = []
    for record in records:
        values, duration = strong_motion(record)
        segments.append((values, record.time_step, duration, record.name))
    omega, mean, counts = mean_periodogram(segments, cutoff)
    positive = mean > 1e-12 * mean.max()
    if np.count_nonzero(positive) < 8:
        raise ArgumentError("records", f"the suite's strong motion has power in {np.count_nonzero(positive)} frequency bins "
                                   f"below {cutoff:.4g} rad/s; at least 8 are needed to fit a spectrum")
    w, log_target = omega[positive], np.log10(mean[positive])
    weights = np.sqrt(counts[positive] / np.mean(counts[positive]))  # R5: 1 / the scatter of a bin's log mean
    peak = float(np.clip(w[np.argmax(log_target)], *OMEGA_G_RANGE))
    level = float(10.0 ** log_target.max())
    g0_range = (level * 1e-6, level * 1e6)
    starts = []
    for omega_g in {peak, float(np.clip(np.exp(np.mean(np.log(w))), *OMEGA_G_RANGE))}:
        for xi in (0.2, 0.6, 1.5):
            shape = KanaiTajimi(1.0, omega_g, xi)
            starts.append((np.clip(_level(w, log_target, shape), *g0_range), omega_g, xi))
    kanai, kt_misfit = _fit(w, log_target, weights, _kanai_tajimi, starts,
                            (g0_range[0], OMEGA_G_RANGE[0], XI_RANGE[0]), (g0_range[1], OMEGA_G_RANGE[1], XI_RANGE[1]))
    cp_starts = [(kanai.G0, kanai.omega_g, kanai.xi_g, max(omega_f, OMEGA_F_RANGE[0]), 0.6)
                 for omega_f in (w[0], min(2.0, 0.2 * kanai.omega_g), 0.3 * kanai.omega_g)]
    clough, cp_misfit = _fit(w, log_target, weights, _clough_penzien, cp_starts,
                             (g0_range[0], OMEGA_G_RANGE[0], XI_RANGE[0], OMEGA_F_RANGE[0], XI_RANGE[0]),
                             (g0_range[1], OMEGA_G_RANGE[1], XI_RANGE[1], OMEGA_F_RANGE[1], XI_RANGE[1]))
    spectrum = clough if cp_misfit < CP_MARGIN * kt_misfit else kanai  # R6
    n = len(records)
    return FittedExcitation(
        spectrum=spectrum,
        duration=float(np.mean([segment[2] for segment in segments])),
        duration_definition=f"mean 5-95 % Arias duration of the {n} records" if n > 1 else "5-95 % Arias duration of the record",
        frequencies=omega,
        periodogram=mean,
        misfit={"kanai-tajimi": kt_misfit, "clough-penzien": cp_misfit},
    )
