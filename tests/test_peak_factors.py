"""Expected peaks (pounding.random_vibration.peak_factors) against Monte Carlo records and Davenport's asymptote."""

import math

import numpy as np
import pytest

from pounding import load_case
from pounding.errors import ArgumentError
from pounding.hazard.excitation import CloughPenzien, Excitation, ShinozukaSato, ground_accelerations
from pounding.random_vibration.peak_factors import (
    expected_peak_ground_acceleration,
    intensity_for_peak_ground_acceleration,
    rms_acceleration,
    vanmarcke_expected_peak,
)
from pounding.random_vibration.peaks import davenport_peak_factor

RECORDS = 200


def _mean_pga(excitation, seed=3):
    return float(np.abs(ground_accelerations(excitation, seed, range(RECORDS))).max(axis=1).mean())


@pytest.mark.parametrize("excitation", [
    load_case("section5-T2-0.4").excitation,  # the paper's Kanai-Tajimi: G0 from the preset, 27.02 rad/s, 0.34, 20 s
    Excitation(CloughPenzien(G0=0.01, omega_g=15.0, xi_g=0.6, omega_f=1.5, xi_f=0.6), 20.0),
    load_case("section5-T2-0.4-nonstationary").excitation,  # Shinozuka-Sato, 40 s
], ids=["kanai-tajimi", "clough-penzien", "kanai-tajimi-modulated"])
def test_expected_pga_is_the_records_mean_pga(excitation):
    records = _mean_pga(excitation)
    assert expected_peak_ground_acceleration(excitation) == pytest.approx(records, rel=0.03)


def test_a_short_strong_motion_is_within_five_percent():
    # A Shinozuka-Sato envelope peaking at 3 s: some 40 zero crossings in the strong motion; the Poisson
    # count of P4 is then about 2.5 % low on 1000 records (0.5 % standard error).
    excitation = Excitation(load_case("section5-T2-0.4").excitation.spectrum, 10.0, ShinozukaSato(0.2, 0.5))
    assert expected_peak_ground_acceleration(excitation) == pytest.approx(_mean_pga(excitation), rel=0.05)


def test_intensity_for_a_target_pga_gives_records_of_that_pga():
    excitation = load_case("section5-T2-0.4").excitation
    g0 = intensity_for_peak_ground_acceleration(excitation, 3.0)
    scaled = Excitation(type(excitation.spectrum)(g0, excitation.spectrum.omega_g, excitation.spectrum.xi_g),
                        excitation.duration)
    assert _mean_pga(scaled, seed=8) == pytest.approx(3.0, rel=0.03)


def test_rms_is_the_records_rms():
    excitation = load_case("section5-T2-0.4").excitation
    records = ground_accelerations(excitation, 5, range(100))
    assert rms_acceleration(excitation) == pytest.approx(math.sqrt(np.mean(records**2)), rel=0.02)
    assert rms_acceleration(excitation) == pytest.approx(math.sqrt(excitation.represented_variance()), rel=1e-9)


def test_a_broad_band_stationary_peak_tends_to_davenports():
    # delta = 1: hardly any clumps at the levels of the peak; many crossings: Davenport's asymptote for rate 2 nu0.
    nu0, duration = 50.0, 2000.0
    peak = vanmarcke_expected_peak(np.ones(2), nu0, 1.0, [0.0, duration])
    assert peak == pytest.approx(davenport_peak_factor(2 * nu0, duration), rel=0.005)


def test_the_sampled_peak_tends_to_the_continuous_one_and_lies_below_it():
    nu0, duration = 5.0, 20.0
    continuous = vanmarcke_expected_peak(np.ones(2), nu0, 0.6, [0.0, duration])
    for step, tolerance in ((1e-4, 2e-3), (5e-3, 0.02)):
        rho = math.cos(2 * math.pi * nu0 * step)  # a narrow band at nu0: rho(dt) = cos(omega dt)
        sampled = vanmarcke_expected_peak(np.ones(2), nu0, 0.6, [0.0, duration], time_step=step, sample_correlation=rho)
        assert sampled < continuous
        assert sampled == pytest.approx(continuous, rel=tolerance)


def test_vectorized_over_processes():
    sigma = np.array([[1.0, 1.0], [2.0, 2.0], [1.0, 1.0]])
    peaks = vanmarcke_expected_peak(sigma, [5.0, 5.0, 1.0], [0.5, 0.5, 0.5], [0.0, 10.0])
    assert peaks[1] == pytest.approx(2 * peaks[0])
    assert peaks[2] < peaks[0]  # fewer crossings, lower peak


@pytest.mark.parametrize("kwargs, field", [
    (dict(sigma=np.zeros(2)), "sigma"),
    (dict(sigma=np.array([1.0, np.nan])), "sigma"),
    (dict(nu0=0.0), "nu0"),
    (dict(delta=1.5), "delta"),
    (dict(times=[0.0, 0.0]), "times"),
    (dict(time_step=0.01), "time_step"),
    (dict(time_step=0.01, sample_correlation=1.0), "sample_correlation"),
])
def test_bad_input_names_its_field(kwargs, field):
    arguments = dict(sigma=np.ones(2), nu0=1.0, delta=0.5, times=[0.0, 10.0])
    arguments.update(kwargs)
    sigma, nu0, delta, times = (arguments.pop(k) for k in ("sigma", "nu0", "delta", "times"))
    with pytest.raises(ArgumentError) as error:
        vanmarcke_expected_peak(sigma, nu0, delta, times, **arguments)
    assert error.value.field == field and len(str(error.value)) < 200


def test_pga_target_must_be_positive():
    with pytest.raises(ArgumentError, match="pga"):
        intensity_for_peak_ground_acceleration(load_case("section5-T2-0.4").excitation, -1.0)
