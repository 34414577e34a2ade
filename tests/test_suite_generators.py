"""The suites of validation/suite_generators.py have the properties of the models they claim: Boore's
(2003) omega-squared Fourier amplitude at the level of its formula and the Saragoni-Hart envelope;
Rezaeian & Der Kiureghian's (2008) filter frequency drifting as set and the gamma modulating function
as the mean square; a low-passed suite without energy above its corner; a resampled suite with the
original's spectrum; the same records from the same seed. Each expected value is computed here from
the papers' formulas, not from the module's own functions."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from validation.suite_generators import (
    BruneSource,
    DriftingFilter,
    brune_suite,
    drifting_filter_suite,
    low_passed,
    resampled,
)


def _mean_square_amplitude(records) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies [Hz] and the records' mean |A(f)|^2, A = dt FFT(a) [m/s]."""
    step = records[0].time_step
    spectra = np.array([np.abs(np.fft.rfft(r.acceleration) * step) ** 2 for r in records])
    return np.fft.rfftfreq(records[0].acceleration.size, step), spectra.mean(axis=0)


def _slope(frequency, amplitude, low, high) -> float:
    inside = (frequency >= low) & (frequency <= high)
    return float(np.polyfit(np.log10(frequency[inside]), np.log10(amplitude[inside]), 1)[0])


# Boore (2003) with M 5, R 10 km: f0 near 1 Hz, so both sides of the corner lie in the band.
SOURCE = BruneSource(magnitude=5.0, distance=10.0e3, duration=60.0)


@pytest.fixture(scope="module")
def brune_spectrum():
    frequency, mean_square = _mean_square_amplitude(brune_suite(SOURCE, 100, seed=7))
    s = SOURCE
    f = np.maximum(frequency, 1e-9)
    # The path and site filters of Boore (2003), taken out so that the source's shape is left.
    filters = np.exp(-math.pi * f * s.distance / (s.quality_factor * f**s.quality_exponent * s.shear_velocity)) * np.exp(-math.pi * s.kappa * f)
    moment = 10.0 ** (1.5 * s.magnitude + 16.05) * 1e-7  # [N m]
    corner = 4.906e6 * 3.5 * (70.0 / (moment * 1e7)) ** (1.0 / 3.0)  # Brune, beta 3.5 km/s, 70 bar [Hz]
    level = 0.55 / math.sqrt(2.0) * 2.0 * moment / (4.0 * math.pi * s.density * s.shear_velocity**3 * s.distance)
    brune = level * (2.0 * math.pi * f) ** 2 / (1.0 + (f / corner) ** 2)
    return frequency, np.sqrt(mean_square) / filters, brune, corner


def test_the_brune_suite_rises_as_omega_squared_below_the_corner(brune_spectrum):
    frequency, amplitude, _, corner = brune_spectrum
    assert corner == pytest.approx(SOURCE.corner_frequency, rel=1e-9)
    expected = 2.0 - math.log10((1 + 0.3**2) / (1 + 0.1**2)) / math.log10(3.0)  # f^2 / (1 + (f/f0)^2) from 0.1 to 0.3 f0
    assert _slope(frequency, amplitude, 0.1 * corner, 0.3 * corner) == pytest.approx(expected, abs=0.2)


def test_the_brune_suite_is_flat_above_the_corner_before_kappa(brune_spectrum):
    frequency, amplitude, _, corner = brune_spectrum
    assert abs(_slope(frequency, amplitude, 4.0 * corner, 15.0)) < 0.15


def test_the_brune_suite_has_the_level_of_boores_formula(brune_spectrum):
    frequency, amplitude, brune, corner = brune_spectrum
    band = (frequency >= 2.0 * corner) & (frequency <= 15.0)  # the low end scatters more: the 3 s window's noise
    assert np.mean(amplitude[band] ** 2 / brune[band] ** 2) == pytest.approx(1.0, abs=0.1)


def test_the_brune_records_follow_the_saragoni_hart_window():
    source = BruneSource(magnitude=6.0, distance=20.0e3)
    records = brune_suite(source, 30, seed=3)
    step = source.time_step
    power = np.convolve(np.mean([r.acceleration**2 for r in records], axis=0), np.ones(200) / 200, mode="same")
    length = 2.0 * source.ground_motion_duration
    peak = source.lead + 0.2 * length  # the window's peak at epsilon t_eta
    assert np.argmax(power) * step == pytest.approx(peak, abs=1.0)
    after = int((source.lead + length + 2.0) / step)  # eta^2 = 0.0025 of the peak at t_eta
    assert power[after] < 0.02 * power.max()
    assert power[int(0.5 * source.lead / step)] < 1e-3 * power.max()  # nothing before the noise starts


DRIFT = DriftingFilter(frequency_start=6.0, frequency_end=1.0, damping_start=0.2, damping_end=0.4)


@pytest.fixture(scope="module")
def drifting_records():
    return drifting_filter_suite(DRIFT, 40, seed=5)


@pytest.mark.parametrize("window", [(3.0, 6.0), (8.0, 11.0), (12.0, 16.0)])
def test_the_drifting_filter_crosses_zero_at_its_frequency_of_the_time(drifting_records, window):
    """A displacement-type filter of white noise crosses zero 2 f_f times a second (lambda_2 / lambda_0 =
    omega_f^2), f_f going from 6 Hz at 0 to 1 Hz at 30 s."""
    step = DRIFT.time_step
    first, last = int(window[0] / step), int(window[1] / step)
    crossings = np.mean([np.count_nonzero(np.diff(np.signbit(r.acceleration[first:last]))) for r in drifting_records])
    middle = 0.5 * (window[0] + window[1])
    expected = 2.0 * (6.0 + (1.0 - 6.0) * middle / 30.0)
    assert crossings / (window[1] - window[0]) == pytest.approx(expected, rel=0.12)


def test_the_drifting_filter_has_the_gamma_modulation_as_its_mean_square(drifting_records):
    """The filtered noise has unit variance, so E[x^2] = q(t)^2 = (alpha_1 t^(alpha_2 - 1) e^(-alpha_3 t))^2,
    alpha_1 from the expected Arias intensity pi / (2 g) int q^2 dt."""
    t = DRIFT.times()
    shape = t ** (2 * (DRIFT.modulation_shape - 1)) * np.exp(-2 * DRIFT.modulation_decay * t)
    arias = np.sum(shape) * DRIFT.time_step * math.pi / (2 * 9.80665)
    expected = DRIFT.arias_intensity / arias * shape
    mean_square = np.mean([r.acceleration**2 for r in drifting_records], axis=0)
    for start in (3.0, 6.0, 9.0, 12.0, 15.0):
        window = slice(int(start / DRIFT.time_step), int((start + 2.0) / DRIFT.time_step))
        assert np.mean(mean_square[window]) / np.mean(expected[window]) == pytest.approx(1.0, abs=0.2)


def test_the_drifting_filter_records_are_high_passed(drifting_records):
    """Rezaeian & Der Kiureghian's correction, the critically damped oscillator at f_c = 0.1 Hz: the
    records' Fourier amplitude is that of the same records without it times |H|, |H|^2 = (f^2 / (f^2 + f_c^2))^2."""
    import dataclasses

    uncorrected = drifting_filter_suite(dataclasses.replace(DRIFT, high_pass=0.0), 40, seed=5)
    frequency, corrected = _mean_square_amplitude(drifting_records)
    _, raw = _mean_square_amplitude(uncorrected)
    for k in (1, 2, 3, 6):  # 0.033 Hz to 0.2 Hz
        f = frequency[k]
        assert corrected[k] / raw[k] == pytest.approx((f**2 / (f**2 + 0.1**2)) ** 2, rel=0.3)


def _share_above(records, frequency: float) -> float:
    f, mean_square = _mean_square_amplitude(records)
    return float(mean_square[f > frequency].sum() / mean_square.sum())


def test_the_low_passed_suite_has_no_energy_above_its_corner():
    records = brune_suite(BruneSource(magnitude=5.5, distance=10.0e3), 10, seed=2)
    filtered = low_passed(records, 10.0)
    assert _share_above(records, 12.5) > 0.05  # the raw suite has some to take out
    assert _share_above(filtered, 12.5) < 0.01
    assert _share_above(filtered, 20.0) < 1e-4
    f, raw = _mean_square_amplitude(records)
    _, cut = _mean_square_amplitude(filtered)
    below = (f > 0.5) & (f < 5.0)
    assert np.mean(cut[below] / raw[below]) == pytest.approx(1.0, abs=0.02)  # zero phase, flat pass band


def test_the_resampled_suite_keeps_the_spectrum_below_its_nyquist(drifting_records):
    coarse = resampled(drifting_records[:10], 0.02)
    assert all(r.time_step == 0.02 for r in coarse)
    assert coarse[0].duration == pytest.approx(drifting_records[0].duration, abs=0.02)
    f, fine = _mean_square_amplitude(drifting_records[:10])
    g, rough = _mean_square_amplitude(coarse)
    band = (g > 0.3) & (g < 15.0)
    assert np.mean(rough[band] / np.interp(g[band], f, fine)) == pytest.approx(1.0, abs=0.05)


@pytest.mark.parametrize("make", [lambda n, seed: brune_suite(BruneSource(magnitude=5.5, distance=10.0e3), n, seed),
                                  lambda n, seed: drifting_filter_suite(DriftingFilter(duration=12.0), n, seed)])
def test_a_seed_gives_the_same_records_and_record_i_does_not_depend_on_the_count(make):
    first, again, more, other = make(2, 11), make(2, 11), make(3, 11), make(2, 12)
    for a, b, c in zip(first, again, more):
        assert np.array_equal(a.acceleration, b.acceleration) and np.array_equal(a.acceleration, c.acceleration)
    assert not np.allclose(first[0].acceleration, other[0].acceleration)
    assert not np.allclose(first[0].acceleration, first[1].acceleration)


def test_the_suite_accuracy_script_writes_its_rows_as_json(tmp_path, capsys):
    from validation import suite_accuracy

    output = tmp_path / "suites.json"
    suite_accuracy.main(records=2, suites=["RDK weak drift"], pairs=["section5-T2-0.4"], json_path=output)
    assert "| RDK weak drift | section5-T2-0.4 |" in capsys.readouterr().out
    document = json.loads(output.read_text())
    assert document["records"] == 2 and document["suites"][0]["records"] == 2
    (row,) = document["cases"]
    assert set(row) >= {"monte_carlo", "closed_form", "pounding_fraction", "pounding_probability", "fitted_process_monte_carlo"}
