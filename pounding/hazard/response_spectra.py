"""Response spectra of records: the 5 %-damped pseudo-acceleration of an
oscillator starting at rest, by pyrotd (MIT licence; its frequency-domain
solution of the oscillator). The records are padded with zeros, to at least
twice their length and long enough for the longest oscillator's free vibration
to die out (:data:`FREE_VIBRATION_PERIODS` periods, to about 1e-4 at 5 %
damping), so that the frequency-domain (periodic) solution does not wrap a
record's end onto its start: the oscillator then starts at rest.

Periods down to 2 time steps (the record's Nyquist period) are resolved: pyrotd
extends the Fourier spectrum so that the oscillator's response is sampled at
least 10 times a cycle, and on a FEMA P695 record sampled at 0.02 s its Sa at
2 to 5 time steps is within 4 % of the exact solution for the record taken as
piecewise linear."""

from __future__ import annotations

import math

import numpy as np

from pounding.errors import ArgumentError
from pounding.units import STANDARD_GRAVITY

__all__ = ["FREE_VIBRATION_PERIODS", "pseudo_acceleration_spectrum"]

FREE_VIBRATION_PERIODS = 30
"""Periods of the longest oscillator added after a record (with at least its own length) as zeros."""


def pseudo_acceleration_spectrum(accelerations, time_step: float, periods, damping: float = 0.05) -> np.ndarray:
    """Pseudo-spectral acceleration (2 pi / T)^2 max ``|u|`` [m/s^2] of each record (rows of
    ``accelerations`` [m/s^2], sampled every ``time_step`` [s]) at ``periods`` [s]: shape (records, periods)."""
    import pyrotd

    records = np.atleast_2d(np.asarray(accelerations, dtype=float))
    periods = np.asarray(periods, dtype=float)
    if not (np.all(np.isfinite(periods)) and np.all(periods > 0)):
        raise ArgumentError("periods", "must be finite and > 0 s")
    if np.any(periods < 2.0 * time_step * (1 - 1e-9)):  # above the record's Nyquist frequency it carries nothing
        raise ArgumentError("periods", f"must be at least 2 time steps ({2 * time_step:g} s) to be resolved by the records")
    tail = max(records.shape[1], math.ceil(FREE_VIBRATION_PERIODS * periods.max() / time_step))
    length = 1 << (records.shape[1] + tail - 1).bit_length()
    padded = np.zeros((records.shape[0], length))
    padded[:, : records.shape[1]] = records / STANDARD_GRAVITY
    frequencies = 1.0 / periods
    spectra = [pyrotd.calc_spec_accels(time_step, row, frequencies, osc_damping=damping).spec_accel for row in padded]
    return np.asarray(spectra) * STANDARD_GRAVITY
