"""A design spectrum's compatible bank: its records' mean response spectrum (pyrotd, independent of the
code under test) against the code's spectrum."""

import math

import numpy as np
import pyrotd
import pytest

from pounding.errors import ArgumentError
from pounding.hazard.compatible_psd import compatible_spectrum, initial_psd, random_vibration_spectrum
from pounding.hazard.design_spectra import ASCE7Spectrum, Eurocode8Spectrum, TabulatedSpectrum
from pounding.hazard.excitation import Excitation, ShinozukaSato, ground_accelerations

G = 9.80665
PERIODS = np.geomspace(0.2, 2.0, 15)
RECORDS = 100
# ASCE 7-22-like multi-period spectrum (the shape of a site-specific table), in g
TABLE = TabulatedSpectrum((0.01, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 2.0, 3.0, 4.0, 5.0),
                          tuple(G * a for a in (0.5, 1.0, 1.3, 1.35, 1.3, 1.1, 0.9, 0.5, 0.32, 0.22, 0.16)))
CASES = {
    "ec8-1-C-20s": (Eurocode8Spectrum(0.3 * G, "C", 1), 20.0, None),
    "ec8-1-C-20s-envelope": (Eurocode8Spectrum(0.3 * G, "C", 1), 20.0, ShinozukaSato()),
    "ec8-2-B-10s": (Eurocode8Spectrum(0.25 * G, "B", 2), 10.0, None),
    "asce7-15s": (ASCE7Spectrum(1.0 * G, 0.6 * G, 8.0), 15.0, None),
    "asce7-20s-envelope": (ASCE7Spectrum(1.0 * G, 0.6 * G, 8.0), 20.0, ShinozukaSato()),
    "table-10s": (TABLE, 10.0, None),
    "table-20s-envelope": (TABLE, 20.0, ShinozukaSato()),
}


def records_spectrum(records, time_step, periods, damping=0.05):
    """Pseudo-acceleration spectra of the rows of ``records`` by pyrotd's frequency-domain oscillator, the
    record padded with zeros (the oscillator starts at rest) and the peak taken within the record."""
    n = records.shape[1]
    length = 1 << (2 * n - 1).bit_length()
    padded = np.zeros((records.shape[0], length))
    padded[:, :n] = records
    spectra = np.fft.rfft(padded, axis=1)
    frequencies = np.linspace(0.0, 1.0 / (2.0 * time_step), spectra.shape[1])
    out = np.empty((records.shape[0], len(periods)))
    for j, period in enumerate(periods):
        for i, spectrum in enumerate(spectra):
            response = pyrotd.calc_oscillator_resp(frequencies, spectrum, damping, 1.0 / period, osc_type="psa")
            within = int(math.ceil(n * response.size / length))
            out[i, j] = np.abs(response[:within]).max()
    return out


@pytest.mark.parametrize("name", sorted(CASES))
def test_the_records_reproduce_the_design_spectrum(name):
    target, duration, envelope = CASES[name]
    compatible = compatible_spectrum(target, duration, envelope)
    # synthesis_factor 4: with 1, records carry the PSD on lines 2 pi / (fft length) apart, about the
    # half-power band of a 5 % oscillator at 2 s, and their mean spectrum ripples +-5 % about the process's there.
    excitation = Excitation(compatible.bank, duration, envelope, synthesis_factor=4)
    records = ground_accelerations(excitation, 2024, range(RECORDS))
    ratio = records_spectrum(records, excitation.time_step, PERIODS).mean(axis=0) / target.pseudo_acceleration(PERIODS)
    assert ratio.min() >= 0.90 and ratio.max() <= 1.10, np.round(ratio, 3)


@pytest.mark.parametrize("name", sorted(CASES))
def test_the_bank_matches_the_target_and_says_so(name):
    target, duration, envelope = CASES[name]
    compatible = compatible_spectrum(target, duration, envelope)
    periods = np.asarray(compatible.periods)
    np.testing.assert_allclose(compatible.target, target.pseudo_acceleration(periods))
    again = random_vibration_spectrum(compatible.bank, periods, duration, envelope)
    np.testing.assert_allclose(again, compatible.expected, rtol=1e-9)
    assert compatible.misfit <= 0.04
    assert 2 * len(compatible.bank.frequencies) <= 32
    assert "\n" not in compatible.describe()


def test_the_starting_psd_is_within_fifteen_percent():
    # Cacciola et al.'s recursion alone (no iteration) already puts the expected spectrum near the target.
    target, duration = Eurocode8Spectrum(0.3 * G, "C", 1), 20.0
    omega = np.geomspace(2 * np.pi / 40, 2 * np.pi * 25, 480)

    class Tabulated:
        psd = staticmethod(lambda w: 0.5 * np.interp(w, omega, initial_psd(target, omega, duration)))

    periods = np.geomspace(0.1, 4.0, 12)
    ratio = random_vibration_spectrum(Tabulated, periods, duration) / target.pseudo_acceleration(periods)
    assert np.all(np.abs(ratio - 1) < 0.15), np.round(ratio, 3)


def test_a_stronger_spectrum_scales_g0_alone():
    weak = compatible_spectrum(Eurocode8Spectrum(0.1 * G, "C", 1), 20.0)
    strong = compatible_spectrum(Eurocode8Spectrum(0.3 * G, "C", 1), 20.0)
    assert strong.bank.G0 == pytest.approx(9 * weak.bank.G0, rel=1e-6)
    np.testing.assert_allclose(strong.bank.weights, weak.bank.weights, atol=1e-9)


@pytest.mark.parametrize("kwargs, field", [
    (dict(target="EC8"), "target"),
    (dict(duration=-1.0), "duration"),
    (dict(damping=1.5), "damping"),
    (dict(cutoff_frequency=50.0), "cutoff_frequency"),
    (dict(components=1), "components"),
])
def test_bad_input_names_its_field(kwargs, field):
    arguments = dict(target=ASCE7Spectrum(1.0, 0.6), duration=20.0)
    arguments.update(kwargs)
    with pytest.raises(ArgumentError) as error:
        compatible_spectrum(**arguments)
    assert error.value.field == field and len(str(error.value)) < 200
