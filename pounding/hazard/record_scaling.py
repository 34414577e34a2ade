"""A suite of records scaled to a design spectrum over a period range, as
engineers scale them (docs/hazard.md, K1-K5).

With Sa_i(T) the 5 %-damped pseudo-acceleration of record i (pyrotd,
:mod:`pounding.hazard.response_spectra`), Sa_t(T) the target's, and T_1 ..
T_M log-spaced over [T_a, T_b]:

- K1, the suite's mean: mean(T) = (1/N) sum_i Sa_i(T);
- K2, ``fit = "not-below"`` (the default): one factor f = r max_j Sa_t(T_j) / mean(T_j), the least for
  which the scaled mean is nowhere below r times the target (r = ``not_below``, 1 by default: ASCE 7-10
  16.1.3.1's "not less than"; ASCE 7-16 16.2.3.2's "matches or exceeds" read strictly; EN 1998-1
  3.2.3.1.2(4)'s 90 % with r = 0.9). The scaled mean touches r Sa_t at one period;
- K3, ``fit = "least-squares"``: one factor, ln f = (1/M) sum_j ln(Sa_t(T_j) / mean(T_j)), the least
  squares of the suite's log misfit;
- K4, ``fit = "each-record"``: one factor a record, ln f_i = (1/M) sum_j ln(Sa_t(T_j) / Sa_i(T_j)), the
  least squares of each record's log misfit (as the PEER NGA-West2 database scales a record to a target);
- K5, the usable band: T_a no shorter than 2 dt of the coarsest record (its Nyquist period), T_b no
  longer than any record's longest usable period, 1 / its lowest usable frequency when its source gives
  one (FEMA P695's sets), else half its duration.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pounding.errors import ArgumentError, quote
from pounding.hazard.response_spectra import pseudo_acceleration_spectrum

__all__ = ["FITS", "PERIODS_PER_DECADE", "SpectrumScaling", "scale_to_spectrum", "scaling_periods", "suite_spectra", "usable_band"]

FITS = ("not-below", "least-squares", "each-record")
"""The ways of scaling to a spectrum: one factor, the mean not below the target (K2); one factor by
least squares (K3); one factor a record by least squares (K4)."""
PERIODS_PER_DECADE = 30
"""Log-spaced periods a decade of the range (at least 12 in all)."""
NYQUIST_STEPS = 2.0
"""The shortest usable period in time steps (K5): pyrotd and an exact piecewise-linear solution agree within 4 % there."""
USABLE_DURATION_SHARE = 0.5
"""Without a lowest usable frequency, a record's longest usable period is this share of its duration (K5)."""


def usable_band(records) -> tuple[float, float]:
    """The periods [s] over which every record's Sa is usable (K5)."""
    shortest = NYQUIST_STEPS * max(record.time_step for record in records)
    longest = min(1.0 / record.metadata["lowest_usable_frequency_hz"]
                  if record.metadata.get("lowest_usable_frequency_hz") else USABLE_DURATION_SHARE * record.duration
                  for record in records)
    return shortest, longest


def scaling_periods(period_range) -> np.ndarray:
    """The log-spaced periods [s] over ``period_range`` at which the spectra are matched."""
    low, high = period_range
    count = max(12, math.ceil(PERIODS_PER_DECADE * math.log10(high / low)) + 1)
    return np.geomspace(low, high, count)


def suite_spectra(records, periods) -> np.ndarray:
    """Sa of each record at ``periods`` [m/s^2], shape (records, periods)."""
    return np.vstack([pseudo_acceleration_spectrum(record.acceleration, record.time_step, periods)[0] for record in records])


@dataclass(frozen=True, eq=False)
class SpectrumScaling:
    """How a suite was scaled to a design spectrum.

    Attributes
    ----------
    description : str
        The target in words (the design spectrum's ``describe()``).
    fit : str
        One of :data:`FITS`.
    not_below : float
        r of K2 (1 unless given).
    period_range : tuple of float
        [T_a, T_b] [s].
    range_source : str
        Where the range came from, in words.
    periods, target : array
        The matching periods [s] and the target's Sa there [m/s^2].
    spectra : array
        Each record's Sa as read, before scaling [m/s^2], shape (records, periods).
    factors : array
        Each record's factor (all equal unless ``fit = "each-record"``).
    """

    description: str
    fit: str
    not_below: float
    period_range: tuple[float, float]
    range_source: str
    periods: np.ndarray
    target: np.ndarray
    spectra: np.ndarray
    factors: np.ndarray

    @property
    def scaled_mean(self) -> np.ndarray:
        """The scaled suite's mean Sa at :attr:`periods` [m/s^2]."""
        return (self.factors[:, None] * self.spectra).mean(axis=0)

    def text(self) -> str:
        """The scaling in words, for the ground-motion line."""
        low, high = self.period_range
        if self.fit == "each-record":
            how = (f"each record by its own factor ({self.factors.min():.3g} to {self.factors.max():.3g}), "
                   f"least squares in log Sa against {self.description}")
        elif self.fit == "least-squares":
            how = f"the suite x {self.factors[0]:.4g}, its mean Sa fitted to {self.description} by least squares in log Sa"
        else:
            share = "" if self.not_below == 1 else f"{self.not_below:g} x "
            how = f"the suite x {self.factors[0]:.4g}, its mean Sa nowhere below {share}{self.description}"
        return f"{how}, over {low:.3g} to {high:.3g} s ({self.range_source})"

    def to_dict(self) -> dict:
        """JSON-ready (SI)."""
        return {"target": self.description, "fit": self.fit, "not_below": self.not_below,
                "period_range": list(self.period_range), "range_source": self.range_source,
                "factors": self.factors.tolist(), "periods": self.periods.tolist(), "target_sa": self.target.tolist(),
                "scaled_mean_sa": self.scaled_mean.tolist(),
                "units": {"period_range": "s", "periods": "s", "target_sa": "m/s^2", "scaled_mean_sa": "m/s^2"}}


def _factors(spectra: np.ndarray, target: np.ndarray, fit: str, not_below: float) -> np.ndarray:
    count = spectra.shape[0]
    if fit == "each-record":
        return np.exp(np.mean(np.log(target[None, :] / spectra), axis=1))  # K4
    mean = spectra.mean(axis=0)  # K1
    factor = not_below * np.max(target / mean) if fit == "not-below" else np.exp(np.mean(np.log(target / mean)))  # K2, K3
    return np.full(count, factor)


def scale_to_spectrum(records, target, period_range, fit: str = "not-below", not_below: float = 1.0,
                      range_source: str = "as given"):
    """``records`` scaled to the design spectrum ``target`` (``pseudo_acceleration(periods)`` [m/s^2]) over
    ``period_range`` [s] by ``fit`` (:data:`FITS`), and the :class:`SpectrumScaling` that says how.

    Raises :class:`ArgumentError` naming ``periods`` when the range leaves the records' usable band (K5),
    ``fit`` or ``not_below`` when they are unknown or out of range."""
    if fit not in FITS:
        raise ArgumentError("fit", f"unknown fit {quote(fit)}; allowed: {', '.join(FITS)}")
    if not (isinstance(not_below, (int, float)) and 0.5 <= not_below <= 2.0):
        raise ArgumentError("not_below", f"must be a share of the target in [0.5, 2], got {quote(not_below)}")
    low, high = (float(value) for value in period_range)
    if not (0 < low < high and math.isfinite(high)):
        raise ArgumentError("periods", f"must be two periods 0 < T_a < T_b [s], got {quote(list(period_range))}")
    shortest, longest = usable_band(records)
    if low < shortest * (1 - 1e-9) or high > longest * (1 + 1e-9):
        raise ArgumentError("periods", f"{low:.3g} to {high:.3g} s leaves the records' usable band, {shortest:.3g} to "
                            f"{longest:.3g} s (from 2 time steps to the longest usable period); give periods within it or drop records")
    periods = scaling_periods((low, high))
    target_values = np.asarray(target.pseudo_acceleration(periods), dtype=float)
    spectra = suite_spectra(records, periods)
    if not np.all(spectra > 0):
        raise ArgumentError("records", "a record's spectrum is zero over the range; it cannot be scaled to a spectrum")
    factors = _factors(spectra, target_values, fit, float(not_below))
    scaled = tuple(record.scaled(float(factor)) for record, factor in zip(records, factors))
    return scaled, SpectrumScaling(target.describe(), fit, float(not_below), (low, high), range_source, periods,
                                   target_values, spectra, factors)

