"""How faithfully a process fitted to recorded motions represents them, in the
engineer's terms: its expected 5 %-damped spectrum and PGA against the records'.

S6  The records' spectrum: the 5 %-damped oscillator u'' + 2 xi w u' + w^2 u = -a(t) from rest,
    a(t) linear between samples (as the Monte Carlo integrates a record), stepped exactly
    (first-order hold: the state maps by exp(F h) and the two input integrals, from the
    matrix exponential of the augmented system), as a second-order recursive filter
    (scipy.signal.lfilter), the record followed by zeros for the longest period (its free
    vibration counts, as pyrotd's padding counts it); Sa = w^2 max ``|u|``, then the mean over the
    records, on the grid :data:`PERIODS`. Exact at any time step, where pyrotd needs 10 steps a period.
S7  The process's expected spectrum: C1-C3 (pounding.hazard.compatible_psd) with its envelope and
    duration, and its expected PGA: the largest of its samples (P5-P6).
S8  The comparison at the buildings' periods T_b: the ratios expected / records at each T_b and on
    the grid's periods from 0.5 min T_b (or 2 pi / the process's cutoff, if longer: no period beyond
    its band is compared) to 2 max T_b (log-log interpolation), and of the PGA; a
    ratio off 1 by more than :data:`FIT_TOLERANCE` warns.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["FIT_TOLERANCE", "PERIODS", "FitQuality", "SpectrumComparison", "compare_spectra", "records_mean_spectrum"]

PERIODS = tuple(float(t) for t in np.geomspace(0.05, 10.0, 47))
"""S6: the periods of the comparison [s] (20 a decade)."""
FIT_TOLERANCE = 0.10
"""S8: a ratio off 1 by more than this warns [-]."""
OSCILLATOR_DAMPING = 0.05


def _recursion(period: float, step: float, damping: float) -> tuple[np.ndarray, np.ndarray]:
    """S6: the numerator and denominator of the displacement's recursive filter for input a(t)."""
    from scipy.linalg import expm

    w = 2.0 * math.pi / period
    augmented = np.zeros((4, 4))
    augmented[:2, :2] = [[0.0, 1.0], [-w * w, -2.0 * damping * w]]
    augmented[1, 2] = -1.0  # the oscillator is driven by -a
    augmented[2, 3] = 1.0 / step  # a(t) = p + q t / h: p' = q / h
    exponential = expm(augmented * step)
    phi, constant, ramp = exponential[:2, :2], exponential[:2, 2], exponential[:2, 3]
    # s_(k+1) = phi s_k + P a_k + Q a_(k+1), P = constant - ramp, Q = ramp; u = first component
    p, q = constant - ramp, ramp
    numerator = np.array([q[0], p[0] - phi[1, 1] * q[0] + phi[0, 1] * q[1], -phi[1, 1] * p[0] + phi[0, 1] * p[1]])
    denominator = np.array([1.0, -(phi[0, 0] + phi[1, 1]), phi[0, 0] * phi[1, 1] - phi[0, 1] * phi[1, 0]])
    return numerator, denominator


def records_mean_spectrum(records, periods=PERIODS, damping: float = OSCILLATOR_DAMPING) -> np.ndarray:
    """S6: the records' mean pseudo-acceleration Sa [m/s^2] at ``periods`` [s]."""
    from scipy.signal import lfilter

    periods = np.asarray(periods, dtype=float)
    total = np.zeros(periods.size)
    groups: dict[float, list] = {}
    for record in records:
        groups.setdefault(record.time_step, []).append(record.acceleration)
    for step, rows in groups.items():
        length = max(row.size for row in rows) + math.ceil(periods.max() / step) + 1
        block = np.zeros((len(rows), length + 1))
        for i, row in enumerate(rows):
            block[i, 1: row.size + 1] = row  # a zero first: at rest before the record
        for j, period in enumerate(periods):
            numerator, denominator = _recursion(period, step, damping)
            response = lfilter(numerator, denominator, block, axis=1)
            total[j] += np.sum(np.abs(response).max(axis=1)) * (2.0 * math.pi / period) ** 2
    return total / len(records)


@dataclass(frozen=True)
class FitQuality:
    """S8 at a pair's periods: ``building_periods`` [s] and their ratios; ``periods`` [s] from 0.5 min T_b to
    2 max T_b and their ratios; ``pga_ratio``; all expected / records [-]."""

    building_periods: tuple[float, ...]
    building_ratios: tuple[float, ...]
    periods: tuple[float, ...]
    ratios: tuple[float, ...]
    pga_ratio: float
    records_pga_mean: float
    pga_expected: float

    @property
    def worst(self) -> tuple[str, float]:
        """What is furthest off 1 and its ratio: ``("Sa(0.4 s)", 1.13)`` or ``("PGA", 0.8)``."""
        entries = [(f"Sa({t:.3g} s)", r) for t, r in zip(self.building_periods + self.periods,
                                                         self.building_ratios + self.ratios)]
        entries.append(("PGA", self.pga_ratio))
        return max(entries, key=lambda entry: abs(math.log(entry[1])) if entry[1] > 0 else math.inf)

    def warning(self) -> str:
        """One line (<= 200 characters) when a ratio is off 1 by more than :data:`FIT_TOLERANCE`, else ""."""
        name, ratio = self.worst
        if abs(ratio - 1.0) <= FIT_TOLERANCE:
            return ""
        span = f"{0.5 * min(self.building_periods):.2g}-{2 * max(self.building_periods):.2g} s"
        return (f"The closed form's spectrum is {100 * (ratio - 1):+.0f} % off the records' mean {name} "
                f"({span} checked): its force may be off as much or more. Check it with `pounding estimate --check`.")

    def to_dict(self) -> dict:
        return {"building_periods": list(self.building_periods), "building_ratios": list(self.building_ratios),
                "periods": list(self.periods), "ratios": list(self.ratios), "pga_ratio": self.pga_ratio,
                "records_pga_mean": self.records_pga_mean, "pga_expected": self.pga_expected,
                "tolerance": FIT_TOLERANCE, "worst": list(self.worst), "warning": self.warning(),
                "units": {"building_periods": "s", "periods": "s", "records_pga_mean": "m/s^2", "pga_expected": "m/s^2",
                          "ratios": "expected Sa (5 %) of the fitted process / records' mean Sa [-]",
                          "pga_ratio": "expected PGA / records' mean PGA [-]"}}


@dataclass(frozen=True)
class SpectrumComparison:
    """S6-S7 on :data:`PERIODS`: the records' mean Sa and the process's expected Sa [m/s^2], the PGAs [m/s^2], and
    the ``shortest`` period compared [s]: 2 pi / the process's cutoff (none is claimed beyond its band)."""

    periods: tuple[float, ...]
    records: tuple[float, ...]
    expected: tuple[float, ...]
    records_pga_mean: float
    pga_expected: float
    shortest: float = 0.0

    def scaled(self, factor: float) -> SpectrumComparison:
        """The same for records and process scaled by ``factor``."""
        return SpectrumComparison(self.periods, tuple(factor * v for v in self.records),
                                  tuple(factor * v for v in self.expected), factor * self.records_pga_mean,
                                  factor * self.pga_expected, self.shortest)

    def at(self, building_periods) -> FitQuality:
        """S8 at ``building_periods`` [s]."""
        buildings = tuple(float(t) for t in building_periods)
        grid = np.log(self.periods)
        ratio = np.log(np.asarray(self.expected) / np.asarray(self.records))

        def ratios(periods):
            return tuple(float(r) for r in np.exp(np.interp(np.log(periods), grid, ratio)))

        low, high = max(0.5 * min(buildings), self.shortest), 2.0 * max(buildings)
        inside = [t for t in self.periods if low <= t <= high]
        periods = tuple(sorted({low, high, *inside}))
        return FitQuality(buildings, ratios(buildings), periods, ratios(periods),
                          self.pga_expected / self.records_pga_mean, self.records_pga_mean, self.pga_expected)


def compare_spectra(records, excitation) -> SpectrumComparison:
    """S6-S7: ``records`` (Accelerogram) against the process ``excitation`` (an Excitation) on :data:`PERIODS`."""
    from pounding.hazard.compatible_psd import random_vibration_spectrum
    from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration

    periods = np.asarray(PERIODS)
    recorded = records_mean_spectrum(records, periods)
    expected = random_vibration_spectrum(excitation.spectrum, periods, excitation.duration, excitation.envelope,
                                         excitation.cutoff_frequency)
    pga = float(np.mean([np.abs(record.acceleration).max() for record in records]))
    return SpectrumComparison(PERIODS, tuple(float(v) for v in recorded), tuple(float(v) for v in expected), pga,
                              expected_peak_ground_acceleration(excitation), 2.0 * math.pi / excitation.cutoff_frequency)
