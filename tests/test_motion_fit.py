"""The spectrum fitted to a suite of records (pounding.hazard.motion_fit): Arias intensity and significant duration
on analytic records; the fit on suites synthesized by pounding's own generator from known spectra."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from pounding.errors import ArgumentError, CaseError
from pounding.hazard.accelerograms import Accelerogram, G
from pounding.hazard.excitation import CloughPenzien, Excitation, KanaiTajimi, ShinozukaSato, ground_accelerations
from pounding.hazard.motion_fit import TAPER, arias_intensity, fit_excitation, significant_duration


def _suite(spectrum, records: int = 50, envelope=None, seed: int = 1) -> tuple[Excitation, list[Accelerogram]]:
    excitation = Excitation(spectrum, duration=20.0, envelope=envelope)
    rows = ground_accelerations(excitation, seed, range(records))
    return excitation, [Accelerogram(f"synthetic/{k}.AT2", excitation.time_step, row) for k, row in enumerate(rows)]


def test_arias_intensity_of_a_constant_record_grows_linearly():
    record = Accelerogram("c", 0.01, np.full(501, 2.0))
    expected = math.pi / (2 * G) * 4.0 * np.arange(501) * 0.01
    np.testing.assert_allclose(arias_intensity(record), expected, rtol=1e-12, atol=0)
    assert significant_duration(record) == pytest.approx((0.25, 4.75), rel=1e-9)
    assert significant_duration(record, 0.0, 1.0) == pytest.approx((0.0, 5.0), rel=1e-12)


def test_a_constant_amplitude_sine_lasts_90_percent_of_its_length():
    # a^2 = (1 - cos 2wt) / 2: Arias grows as t / 2 - sin(2wt) / 4w, so 5-95 % spans 0.9 L to within 1 / (w L)
    length, step, omega = 20.0, 0.002, 2 * math.pi * 5.0
    t = np.arange(int(length / step) + 1) * step
    record = Accelerogram("sine", step, 3.0 * np.sin(omega * t))
    start, end = significant_duration(record)
    assert end - start == pytest.approx(0.9 * length, abs=1.0 / omega)
    assert start == pytest.approx(0.05 * length, abs=1.0 / omega)
    total = arias_intensity(record)[-1]
    assert total == pytest.approx(math.pi / (2 * G) * 9.0 * length / 2, rel=1e-3)


def test_significant_duration_of_a_record_silent_but_for_a_burst():
    a = np.zeros(1001)
    a[400:601] = 1.0  # from 4 to 6 s at 0.01 s: 5 % of the intensity is reached at 4.1 s (trapezoid ramps at the ends)
    start, end = significant_duration(Accelerogram("burst", 0.01, a))
    assert 3.99 < start < 4.2 and 5.8 < end < 6.01 and end - start == pytest.approx(1.8, abs=0.02)


def test_significant_duration_errors():
    with pytest.raises(CaseError, match="zero throughout"):
        significant_duration(Accelerogram("quiet.AT2", 0.01, np.zeros(10)))
    with pytest.raises(ArgumentError, match="high"):
        significant_duration(Accelerogram("r", 0.01, np.ones(10)), 0.9, 0.1)


@pytest.mark.parametrize("omega_g, xi_g, seed", [(15.6, 0.6, 1), (27.02, 0.34, 2)])
def test_the_fit_recovers_a_kanai_tajimi_suite(omega_g, xi_g, seed):
    truth = KanaiTajimi(0.05, omega_g, xi_g)
    excitation, records = _suite(truth, seed=seed)
    fitted = fit_excitation(records, excitation.cutoff_frequency)
    assert type(fitted.spectrum) is KanaiTajimi  # R6: Clough-Penzien is not clearly better on Kanai-Tajimi data
    assert fitted.spectrum.G0 == pytest.approx(truth.G0, rel=0.10)
    assert fitted.spectrum.omega_g == pytest.approx(truth.omega_g, rel=0.10)
    assert fitted.spectrum.xi_g == pytest.approx(truth.xi_g, rel=0.15)
    # stationary records of 20 s: Arias grows linearly, so 5-95 % lasts about 0.9 x 20 s
    assert fitted.duration == pytest.approx(18.0, rel=0.05)
    assert "50 records" in fitted.duration_definition
    # the mean periodogram integrates to the records' variance (R3), within the band
    band = (fitted.frequencies > 2.0) & (fitted.frequencies < 100.0)
    np.testing.assert_allclose(np.median(fitted.periodogram[band] / truth.psd(fitted.frequencies[band])), 1.0, atol=0.1)


def test_the_fit_recovers_a_clough_penzien_suite_and_prefers_it():
    truth = CloughPenzien(0.05, 15.6, 0.6, omega_f=1.0, xi_f=0.9)
    excitation, records = _suite(truth, seed=3)
    fitted = fit_excitation(records, excitation.cutoff_frequency)
    assert isinstance(fitted.spectrum, CloughPenzien)
    assert fitted.misfit["clough-penzien"] < 0.9 * fitted.misfit["kanai-tajimi"]
    assert fitted.spectrum.G0 == pytest.approx(truth.G0, rel=0.10)
    assert fitted.spectrum.omega_g == pytest.approx(truth.omega_g, rel=0.10)
    band = fitted.frequencies > 1.0
    ratio = fitted.spectrum.psd(fitted.frequencies[band]) / truth.psd(fitted.frequencies[band])
    assert np.all(np.abs(np.log10(ratio)) < 0.1)  # the fitted spectrum within 26 % of the truth over the band


def _tukey(n: int) -> np.ndarray:
    window, edge = np.ones(n), int(TAPER * (n - 1) / 2)
    ramp = 0.5 * (1 - np.cos(np.pi * np.arange(edge) / edge))
    window[:edge], window[n - edge:] = ramp, ramp[::-1]
    return window


def test_a_modulated_suite_gives_the_shape_and_the_equivalent_stationary_intensity():
    envelope = ShinozukaSato()
    truth = KanaiTajimi(0.05, 15.6, 0.6)
    excitation, records = _suite(truth, envelope=envelope, seed=4)
    fitted = fit_excitation(records, excitation.cutoff_frequency)
    # the expected Arias intensity grows as the integral of A(t)^2: its 5-95 % window and the (tapered) mean of A^2 on it
    a2 = envelope(excitation.times()) ** 2
    intensity = np.r_[0.0, np.cumsum(0.5 * (a2[1:] + a2[:-1]))] / np.sum(0.5 * (a2[1:] + a2[:-1]))
    first, last = np.searchsorted(intensity, 0.05), np.searchsorted(intensity, 0.95)
    window = _tukey(last - first + 1) ** 2
    mean_a2 = np.sum(window * a2[first: last + 1]) / np.sum(window)
    assert fitted.spectrum.omega_g == pytest.approx(truth.omega_g, rel=0.10)
    assert fitted.spectrum.xi_g == pytest.approx(truth.xi_g, rel=0.15)
    assert fitted.spectrum.G0 == pytest.approx(truth.G0 * mean_a2, rel=0.10)
    assert fitted.duration == pytest.approx((last - first) * excitation.time_step, rel=0.05)


def test_records_of_different_steps_and_lengths():
    truth = KanaiTajimi(0.05, 15.6, 0.6)
    coarse = Excitation(truth, duration=30.0, time_step=0.01, cutoff_frequency=2 * math.pi * 25.0)
    fine = Excitation(truth, duration=15.0, time_step=0.004, cutoff_frequency=2 * math.pi * 25.0)
    records = [Accelerogram(f"c{k}", 0.01, row) for k, row in enumerate(ground_accelerations(coarse, 5, range(25)))]
    records += [Accelerogram(f"f{k}", 0.004, row) for k, row in enumerate(ground_accelerations(fine, 6, range(25)))]
    fitted = fit_excitation(records, 2 * math.pi * 25.0)
    assert fitted.spectrum.G0 == pytest.approx(truth.G0, rel=0.10)
    assert fitted.spectrum.omega_g == pytest.approx(truth.omega_g, rel=0.10)
    assert fitted.duration == pytest.approx(0.9 * (30.0 + 15.0) / 2, rel=0.05)


def test_scaling_the_suite_scales_g0_by_the_square():
    excitation, records = _suite(KanaiTajimi(0.05, 27.02, 0.34), records=20, seed=7)
    one = fit_excitation(records, excitation.cutoff_frequency)
    three = fit_excitation([r.scaled(3.0) for r in records], excitation.cutoff_frequency)
    assert three.spectrum.G0 == pytest.approx(9.0 * one.spectrum.G0, rel=1e-6)
    assert three.spectrum.omega_g == pytest.approx(one.spectrum.omega_g, rel=1e-6)


def test_to_dict_is_json_and_si():
    excitation, records = _suite(KanaiTajimi(0.05, 15.6, 0.6), records=10, seed=8)
    fitted = fit_excitation(records, excitation.cutoff_frequency)
    out = json.loads(json.dumps(fitted.to_dict()))
    assert out["spectrum"] in ("kanai-tajimi", "clough-penzien")
    assert out["G0"] == fitted.spectrum.G0 and out["omega_g"] == fitted.spectrum.omega_g and out["duration"] == fitted.duration
    assert ("omega_f" in out) == (out["spectrum"] == "clough-penzien")
    assert out["units"]["G0"] == "m^2/s^3" and out["units"]["omega_g"] == "rad/s" and out["units"]["duration"] == "s"
    assert not fitted.frequencies.flags.writeable and not fitted.periodogram.flags.writeable


def test_fit_errors():
    excitation, records = _suite(KanaiTajimi(0.05, 15.6, 0.6), records=2)
    for bad in ([], (), None, records[0], [records[0], "x"]):
        with pytest.raises(ArgumentError) as caught:
            fit_excitation(bad, 100.0)
        assert caught.value.field == "records"
    coarse = Accelerogram("motions/coarse.AT2", 0.02, records[0].acceleration[::4])  # Nyquist pi / 0.02 = 157 rad/s
    with pytest.raises(ArgumentError) as caught:
        fit_excitation([records[1], coarse], 160.0)
    assert caught.value.field == "cutoff_frequency" and "motions/coarse.AT2" in caught.value.message
    for cutoff in (0.0, -1.0, float("nan"), 1.0):
        with pytest.raises(ArgumentError, match="cutoff_frequency"):
            fit_excitation(records, cutoff)
    with pytest.raises(CaseError, match="zero throughout"):
        fit_excitation([Accelerogram("quiet", 0.01, np.zeros(100))], 100.0)


def test_a_cutoff_too_low_for_the_shortest_strong_motion_names_it():
    burst = Accelerogram("m/short.AT2", 0.01, np.r_[np.zeros(50), 1.0, -1.0, np.zeros(50)])  # strong motion of 0.02 s
    with pytest.raises(ArgumentError) as caught:
        fit_excitation([burst], 100.0)
    assert caught.value.field == "cutoff_frequency" and "m/short.AT2" in caught.value.message
