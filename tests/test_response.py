"""Contact-floor response of the linearized pair: Lyapunov and frequency routes."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import quad

import pounding
from pounding.closed_form.linearization import linearize_pair
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.response import ContactResponse, frequency_response, response_frequency
from pounding.hazard.excitation import CloughPenzien

DERIVED = (
    "sigma_displacement",
    "sigma_velocity",
    "sigma_acceleration",
    "covariance_displacement",
    "covariance_velocity",
    "sigma_relative_displacement",
    "sigma_relative_velocity",
    "sigma_relative_acceleration",
    "zero_crossing_rate",
    "upcrossing_rate",
    "velocity_upcrossing_rate",
)


def _clough_penzien(case):
    spectrum = case.excitation.spectrum
    cp = CloughPenzien(spectrum.G0, spectrum.omega_g, spectrum.xi_g, omega_f=1.6, xi_f=0.65)
    return dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, spectrum=cp))


@pytest.mark.parametrize("preset", ["section5-T2-0.4", "section6-T2-0.4", "section5-T2-0.8-nonstationary"])
def test_lyapunov_and_frequency_routes_agree(preset):
    pair = LinearizedPair.of(pounding.load_case(preset))
    lyapunov = pair.stationary_response
    frequency = pair.response_frequency()
    for name in DERIVED:
        np.testing.assert_allclose(getattr(frequency, name), getattr(lyapunov, name), rtol=1e-6, err_msg=name)
    scale = np.sqrt(np.outer(np.diag(lyapunov.covariance), np.diag(lyapunov.covariance)))
    np.testing.assert_allclose(frequency.covariance / scale, lyapunov.covariance / scale, atol=1e-7)


@pytest.mark.parametrize("levels", [(1, 1), (3, 2), (1, 2), (3, 1)])
def test_routes_agree_at_any_pair_of_contact_floors(levels):
    """Three storeys beside two, contact at any floor of each: the state-space
    outputs and the frequency route pick their floors by separate code, so an
    indexing slip in either fails here."""
    from pounding.studies.paper_tables import mdof_case

    case = mdof_case()
    case = case.with_contact(levels=levels)
    pair = LinearizedPair.of(case)
    lyapunov, frequency = pair.stationary_response, pair.response_frequency()
    for name in DERIVED:
        np.testing.assert_allclose(getattr(frequency, name), getattr(lyapunov, name), rtol=1e-6, err_msg=name)
    # The floor asked for, not another: each building's floors sway more the higher they are.
    lowest = LinearizedPair(case.with_contact(levels=(1, 1)), pair.buildings)
    lowest = lowest.stationary_response
    for building, level in enumerate(levels):
        if level > 1:
            assert lyapunov.sigma_displacement[building] > 1.5 * lowest.sigma_displacement[building]
        else:
            assert lyapunov.sigma_displacement[building] == pytest.approx(lowest.sigma_displacement[building], rel=1e-12)


def test_routes_agree_under_clough_penzien():
    pair = LinearizedPair.of(_clough_penzien(pounding.load_case("section6-T2-0.4")))
    lyapunov, frequency = pair.stationary_response, pair.response_frequency()
    for name in DERIVED:
        np.testing.assert_allclose(getattr(frequency, name), getattr(lyapunov, name), rtol=1e-6, err_msg=name)
    # The high-pass filter takes out low-frequency motion: less displacement than Kanai-Tajimi.
    kanai_tajimi = LinearizedPair.of(pounding.load_case("section6-T2-0.4")).stationary_response
    assert lyapunov.sigma_displacement[0] < kanai_tajimi.sigma_displacement[0]


def _eq22(omega, omega0, xi, alpha, c_e, k_e):
    """|H|^2 of Eq. 22, as printed."""
    w2 = omega**2
    denominator = w2 + k_e**2
    real = -w2 + alpha * omega0**2 + (1.0 - alpha) * omega0**2 * w2 * c_e / denominator
    imag = 2.0 * xi * omega0 * omega - (1.0 - alpha) * omega0**2 * omega * c_e * k_e / denominator
    return 1.0 / (real**2 + imag**2)


def test_one_storey_frf_is_eq22():
    case = pounding.load_case("section5-T2-0.4")
    omega = np.concatenate([[0.0], np.geomspace(0.01, 300.0, 400)])
    for linear in linearize_pair(case):
        building = linear.building
        storey = building.storeys[0]
        omega0 = math.sqrt(storey.stiffness / storey.mass)
        expected = _eq22(omega, omega0, building.damping_ratio, storey.bouc_wen.alpha, linear.c_e[0], linear.k_e[0])
        h = frequency_response(linear, omega)[:, 0]
        np.testing.assert_allclose(np.abs(h) ** 2, expected, rtol=1e-12)
        # Static limit: only the post-yield stiffness alpha k resists (the Maxwell element relaxes).
        assert h[0].real == pytest.approx(-1.0 / (storey.bouc_wen.alpha * omega0**2), rel=1e-12)


def test_frf_of_two_storeys_solves_the_equations_of_motion():
    """Check H of a two-storey building against the state-space transfer
    function of the same linearized building."""
    from pounding.closed_form.linearization import building_state_space

    case = pounding.load_case("section6-T2-0.4")
    linear = linearize_pair(case)[0]
    model = building_state_space(linear, case.excitation.spectrum)
    f = model.filter_states
    # Drive the building by a_g directly: drop the filter; a_g enters every
    # floor's acceleration as -a_g (M d'' + ... = -M 1 a_g).
    keep = np.arange(f.start)
    a = model.matrix[np.ix_(keep, keep)]
    b = -model.velocity[0][:, keep].sum(axis=0)
    omega = np.array([0.5, 3.0, 5.2, 12.0, 40.0])
    h = frequency_response(linear, omega)
    for w, row in zip(omega, h):
        state = np.linalg.solve(1j * w * np.eye(keep.size) - a, b)
        np.testing.assert_allclose(row, model.displacement[0][:, keep] @ state, rtol=1e-10)


def test_psd_of_relative_velocity_integrates_to_its_variance():
    pair = LinearizedPair.of(pounding.load_case("section6-T2-0.4"))
    expected = pair.stationary_response.sigma_relative_velocity ** 2

    def density(w):
        return float(pair.psd_relative_velocity(np.array([w]))[0])

    half = sum(
        quad(density, a, b, limit=400, epsrel=1e-10)[0]
        for a, b in ((0.0, 2.0), (2.0, 4.0), (4.0, 8.0), (8.0, 16.0), (16.0, 40.0), (40.0, np.inf))
    )
    assert 2.0 * half == pytest.approx(expected, rel=1e-6)
    omega = np.linspace(-30.0, 30.0, 7)
    psd = pair.psd_relative_velocity(omega)
    np.testing.assert_allclose(psd, psd[::-1], rtol=1e-12)  # two-sided: even in omega
    assert np.all(psd >= 0.0)


def test_identical_buildings_move_together():
    """Two identical buildings under the same ground motion: x1 = x2, so the
    relative displacement and velocity vanish (the cross terms of Eq. 16, 25
    cancel the variances)."""
    case = pounding.load_case("section5-T2-0.4")
    twins = dataclasses.replace(case, buildings=(case.buildings[0], case.buildings[0]))
    result = LinearizedPair.of(twins).stationary_response
    assert result.sigma_relative_displacement < 1e-6 * result.sigma_displacement[0]
    assert result.sigma_relative_velocity < 1e-6 * result.sigma_velocity[0]


def test_contact_response_properties_from_a_covariance():
    rng = np.random.default_rng(5)
    factor = rng.standard_normal((6, 6))
    covariance = factor @ factor.T
    result = ContactResponse((1, 1), covariance)
    x = np.array([1.0, -1.0, 0, 0, 0, 0])
    v = np.array([0, 0, 1.0, -1.0, 0, 0])
    a = np.array([0, 0, 0, 0, 1.0, -1.0])
    assert result.sigma_relative_displacement == pytest.approx(math.sqrt(x @ covariance @ x))
    assert result.sigma_relative_velocity == pytest.approx(math.sqrt(v @ covariance @ v))
    assert result.sigma_relative_acceleration == pytest.approx(math.sqrt(a @ covariance @ a))
    assert result.zero_crossing_rate == pytest.approx(2.0 * result.upcrossing_rate)
    assert result.upcrossing_rate == pytest.approx(math.sqrt(v @ covariance @ v / (x @ covariance @ x)) / (2 * math.pi))


def test_stationary_displacement_and_velocity_are_uncorrelated():
    result = LinearizedPair.of(pounding.load_case("section6-T2-0.4")).stationary_response
    assert abs(result.correlation_relative) < 1e-9
    assert abs(result.covariance[0, 2]) < 1e-9 * result.sigma_displacement[0] * result.sigma_velocity[0]


def test_floor_statistics_match_the_contact_response():
    case = pounding.load_case("section6-T2-0.4")
    pair = LinearizedPair.of(case)
    linearized = pair.buildings
    floors = pair.floor_statistics
    contact = pair.stationary_response
    level_1, level_2 = case.contact.levels
    assert floors.displacement[0][level_1 - 1] == pytest.approx(contact.sigma_displacement[0], rel=1e-12)
    assert floors.velocity[1][level_2 - 1] == pytest.approx(contact.sigma_velocity[1], rel=1e-12)
    np.testing.assert_allclose(floors.drift_velocity[0], linearized[0].sigma_drift_velocity, rtol=1e-9)
    np.testing.assert_allclose(floors.hysteretic[0], linearized[0].sigma_z, rtol=1e-9)
    assert len(floors.displacement[0]) == 2 and len(floors.displacement[1]) == 1


def test_each_route_names_its_method():
    """The response says which route gave it (``response(case, method=...)``,
    which dispatched on the name, is gone: each route is its own attribute)."""
    pair = LinearizedPair.of(pounding.load_case("section5-T2-0.4"))
    assert pair.stationary_response.method == "lyapunov"
    assert pair.response_with_residual.method == "lyapunov+residual"
    assert pair.response_frequency().method == "frequency"
    frequency = response_frequency(pair.case, pair.buildings, pair.state_space)  # the pure function, the same route
    np.testing.assert_array_equal(frequency.covariance, pair.response_frequency().covariance)
