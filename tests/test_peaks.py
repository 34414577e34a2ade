"""Peak factors and the equivalent stationary process (Eq. 23-30)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

import pounding
from pounding.closed_form.covariance_history import time_varying_covariance
from pounding.closed_form.pair import LinearizedPair
from pounding.errors import ArgumentError, CaseError
from pounding.hazard.excitation import ShinozukaSato
from pounding.random_vibration.peaks import (
    EULER_GAMMA,
    davenport_expected_peak,
    davenport_peak_factor,
    envelope_variance,
    equivalent_stationary,
    expected_absolute_peak,
    michaelov_variance,
)


def _mean_of_extreme(crossings):
    """Mean of eta under P(max <= eta) = exp(-N exp(-eta^2 / 2)): the
    distribution whose asymptotic mean is Davenport's formula."""

    def exceedance(eta):
        return -math.expm1(-crossings * math.exp(-0.5 * eta * eta))

    return quad(exceedance, 0.0, 60.0, points=[math.sqrt(2.0 * math.log(crossings))], limit=400)[0]


@pytest.mark.parametrize("crossings, tolerance", [(1e3, 5e-3), (1e4, 3e-3), (1e6, 1.5e-3)])
def test_davenport_is_the_mean_of_the_extreme_value_distribution(crossings, tolerance):
    # Same nu T split two ways.
    factor = davenport_peak_factor(crossings / 25.0, 25.0)
    assert factor == pytest.approx(_mean_of_extreme(crossings), rel=tolerance)
    assert davenport_peak_factor(crossings, 1.0) == pytest.approx(factor, rel=1e-14)


def test_davenport_uses_eulers_constant():
    nu_t = math.exp(8.0)  # 2 ln(nu T) = 16
    assert davenport_peak_factor(nu_t, 1.0) == pytest.approx(4.0 + EULER_GAMMA / 4.0, rel=1e-14)
    assert EULER_GAMMA == pytest.approx(0.5772, abs=1e-4)
    np.testing.assert_allclose(
        davenport_peak_factor(np.array([10.0, 100.0]), 2.0),
        [davenport_peak_factor(20.0, 1.0), davenport_peak_factor(200.0, 1.0)],
    )
    assert davenport_expected_peak(0.3, nu_t, 1.0) == pytest.approx(0.3 * (4.0 + EULER_GAMMA / 4.0))


@pytest.mark.parametrize("rate, duration", [(0.05, 20.0), (0.5, 2.0), (0.0, 30.0), (1.0, -3.0)])
def test_davenport_rejects_fewer_than_one_crossing(rate, duration):
    with pytest.raises(CaseError, match="rate \\* duration > 1"):
        davenport_peak_factor(rate, duration)


def test_equivalent_stationary_of_a_constant_variance_is_itself():
    times = np.linspace(0.0, 37.5, 301)
    for n1 in (3, 4, 2.5):
        variance, duration = equivalent_stationary(np.full(times.size, 2.3e-3), times, n1)
        assert variance == pytest.approx(2.3e-3, rel=1e-13)
        assert duration == pytest.approx(37.5, rel=1e-13)


def test_equivalent_stationary_properties():
    times = np.linspace(0.0, 40.0, 4001)
    shape = ShinozukaSato()(times) ** 2
    variance, duration = equivalent_stationary(1e-4 * shape, times)
    scaled = equivalent_stationary(7.0 * 1e-4 * shape, times)
    assert scaled[0] == pytest.approx(7.0 * variance, rel=1e-12)
    assert scaled[1] == pytest.approx(duration, rel=1e-12)
    # Between the mean and the peak variance; shorter than the record.
    assert np.mean(1e-4 * shape) < variance < 1e-4
    assert 0.0 < duration < 40.0
    # A variance on for half the record: the equivalent lasts that half.
    step = np.where(times <= 20.0, 1.0, 0.0)
    assert equivalent_stationary(step, times)[1] == pytest.approx(20.0, rel=1e-3)
    with pytest.raises(ArgumentError, match="variance_of_t"):
        equivalent_stationary(np.zeros(times.size), times)
    with pytest.raises(ArgumentError, match="times"):
        equivalent_stationary(shape, times[::-1])


@pytest.mark.parametrize("bandwidth", [1.0, 0.3, 0.08])
def test_expected_absolute_peak_is_the_poisson_mean_of_vanmarcke_clumps(bandwidth):
    """A stationary record cut into instants: the same as one integral by quad
    of 1 - exp(-N(u)) with Vanmarcke's double-barrier count over the whole
    duration; at q = 1 the clumps hardly matter and it is the Poisson mean of
    the extreme of 2 nu T crossings, whose asymptote is Davenport's peak."""
    sigma, rate, duration = 0.02, 1.5, 20.0  # [m], nu [1/s], [s]
    sigma_velocity = 2 * math.pi * rate * sigma
    weights = np.full(81, duration / 80)
    weights[[0, -1]] /= 2
    peak = expected_absolute_peak(np.full(81, sigma), np.full(81, sigma_velocity), weights, bandwidth)

    def exceedance(u):
        r = u / sigma
        clumps = min(1.0, -math.expm1(-math.sqrt(math.pi / 2) * bandwidth**1.2 * r) / -math.expm1(-0.5 * r * r)) if r > 0 else 1.0
        return -math.expm1(-2 * rate * duration * math.exp(-0.5 * r * r) * clumps)

    assert peak == pytest.approx(quad(exceedance, 0.0, 10 * sigma, limit=200)[0], rel=1e-4)
    if bandwidth == 1.0:
        assert peak == pytest.approx(sigma * _mean_of_extreme(2 * rate * duration), rel=2e-3)
    else:  # narrow band: crossings come in runs, fewer independent tries, a lower peak
        assert peak < 0.97 * sigma * _mean_of_extreme(2 * rate * duration)


def test_expected_absolute_peak_follows_a_build_up_and_rejects_bad_input():
    """Half the record at rest counts nothing: the peak of the other half alone."""
    sigma = np.r_[np.zeros(40), np.full(41, 0.02)]
    weights = np.full(81, 0.25)
    half = expected_absolute_peak(sigma, 5 * sigma, weights, 0.5)
    assert half == pytest.approx(expected_absolute_peak(sigma[40:], 5 * sigma[40:], weights[40:], 0.5), rel=1e-12)
    assert half < expected_absolute_peak(np.full(81, 0.02), np.full(81, 0.1), weights, 0.5)
    for kwargs, field in [({"bandwidth": 0.0}, "bandwidth"), ({"bandwidth": 1.5}, "bandwidth"),
                          ({"weights": weights[:-1]}, "weights"), ({"sigma": np.zeros(81)}, "sigma")]:
        arguments = {"sigma": sigma, "sigma_derivative": 5 * sigma, "weights": weights, "bandwidth": 0.5, **kwargs}
        with pytest.raises(ArgumentError, match=field):
            expected_absolute_peak(**arguments)


def test_envelope_variance_is_eq28():
    envelope = ShinozukaSato()
    times = np.linspace(0.0, 40.0, 81)
    np.testing.assert_allclose(envelope_variance(envelope, times, 3.0), 3.0 * envelope(times) ** 2)
    np.testing.assert_allclose(envelope_variance(None, times, 3.0), 3.0)


def test_michaelov_variance_solves_the_energy_equation():
    """Eq. 26 with C^-2 solves d s/dt = 2 xi w0 (A^2 s_inf - s), s(0) = 0."""
    envelope = ShinozukaSato()
    omega0, xi, variance_inf = 2.0 * math.pi / 1.2, 0.05, 2.0e-3
    times = np.linspace(0.0, 40.0, 41)
    solution = solve_ivp(
        lambda t, s: 2.0 * xi * omega0 * (envelope(t) ** 2 * variance_inf - s),
        (0.0, 40.0),
        [0.0],
        t_eval=times,
        rtol=1e-11,
        atol=1e-16,
    )
    np.testing.assert_allclose(michaelov_variance(envelope, times, variance_inf, omega0, xi), solution.y[0], rtol=1e-7, atol=1e-14)
    # Where xi w0 = B1, Eq. 26 divides by zero; the limit is finite and continuous.
    critical = michaelov_variance(envelope, times, variance_inf, envelope.B1 / xi, xi)
    nearby = michaelov_variance(envelope, times, variance_inf, envelope.B1 / xi * (1 + 1e-7), xi)
    np.testing.assert_allclose(critical, nearby, rtol=1e-5)


@pytest.mark.parametrize("period", [0.4, 1.2])
def test_michaelov_variance_matches_an_oscillator_under_modulated_white_noise(period):
    """Against the exact variance of a linear oscillator under Shinozuka-Sato
    modulated white noise (the setting of Eq. 26): within 1 % of the peak; the
    printed C^2 would be off by a factor C^-4 (about 250)."""
    from pounding.closed_form.covariance_history import _bedrock
    from pounding.closed_form.linearization import lyapunov_covariance

    envelope = ShinozukaSato()
    omega0, xi, S0 = 2.0 * math.pi / period, 0.05, 1.0
    matrix = np.array([[0.0, 1.0], [-(omega0**2), -2.0 * xi * omega0]])
    noise = 2.0 * math.pi * S0 * np.diag([0.0, 1.0])
    stationary = lyapunov_covariance(matrix, noise)
    variance_inf = stationary[0, 0]
    assert variance_inf == pytest.approx(math.pi * S0 / (2.0 * xi * omega0**3), rel=1e-12)
    times = np.linspace(0.0, 40.0, 2001)
    exact = _bedrock(matrix, stationary, times, envelope(times) ** 2)[:, 0, 0]
    approximate = michaelov_variance(envelope, times, variance_inf, omega0, xi)
    assert np.max(np.abs(approximate - exact)) < 0.01 * exact.max()


def _stationary_pair(preset="section5-T2-0.4-nonstationary"):
    case = pounding.load_case(preset)
    return case, LinearizedPair.of(case).state_space


@pytest.mark.parametrize("modulation", ["bedrock", "ground"])
def test_constant_envelope_tends_to_the_stationary_covariance(modulation):
    _, model = _stationary_pair()
    stationary = model.covariance()
    times = np.linspace(0.0, 80.0, 801)
    history = time_varying_covariance(model, None, times, modulation=modulation)
    scale = np.sqrt(np.outer(np.diag(stationary), np.diag(stationary)))
    np.testing.assert_allclose(history[-1] / scale, stationary / scale, atol=1e-6)
    # Buildings start at rest.
    d = model.displacement[0][0]
    assert d @ history[0] @ d == 0.0


def test_bedrock_stepping_matches_direct_integration():
    """The exact stepping for piecewise-linear A^2(t) against an adaptive
    integration of dP/dt = A P + P A^T + A(t)^2 Q."""
    case, model = _stationary_pair()
    envelope = case.excitation.envelope
    times = np.linspace(0.0, 30.0, 1201)
    stepped = time_varying_covariance(model, envelope, times, modulation="bedrock")
    A, Q, n = model.matrix, model.noise_covariance, model.size

    def rhs(t, p):
        P = p.reshape(n, n)
        return (A @ P + P @ A.T + envelope(t) ** 2 * Q).ravel()

    check = np.linspace(0.0, 30.0, 7)
    direct = solve_ivp(rhs, (0.0, 30.0), np.zeros(n * n), t_eval=check, method="DOP853", rtol=1e-10, atol=1e-16)
    direct = direct.y.T.reshape(-1, n, n)
    stationary = model.covariance()
    scale = np.sqrt(np.outer(np.diag(stationary), np.diag(stationary)))
    np.testing.assert_allclose(stepped[::200] / scale, direct / scale, atol=2e-5)


def test_ground_and_bedrock_modulation_nearly_agree_for_a_slow_envelope():
    """The envelope varies over seconds, the Kanai-Tajimi filter over about
    0.1 s: modulating before or after the filter changes little."""
    case = pounding.load_case("section5-T2-0.4-nonstationary")
    times = np.linspace(0.0, 40.0, 401)
    pair = LinearizedPair.of(case)
    ground = pair.covariance_history(times, modulation="ground")
    bedrock = pair.covariance_history(times, modulation="bedrock")
    v = np.array([0.0, 0.0, 1.0, -1.0, 0.0, 0.0])
    var_ground, var_bedrock = v @ ground @ v, v @ bedrock @ v
    assert np.max(np.abs(var_ground - var_bedrock)) < 0.02 * var_bedrock.max()


def test_eq28_equivalent_process_is_close_to_the_exact_one():
    """The paper's shortcut sigma^2(t) = A^2(t) sigma_inf^2 (Eq. 28) against the
    exact time-varying variance of the relative velocity, through Eq. 29."""
    case = pounding.load_case("section5-T2-0.4-nonstationary")
    pair = LinearizedPair.of(case)
    times = np.linspace(0.0, case.excitation.duration, 801)
    history = pair.covariance_history(times)
    v = np.array([0.0, 0.0, 1.0, -1.0, 0.0, 0.0])
    exact = equivalent_stationary(v @ history @ v, times)
    stationary = pair.stationary_response.sigma_relative_velocity ** 2
    shortcut = equivalent_stationary(envelope_variance(case.excitation.envelope, times, stationary), times)
    assert shortcut[0] == pytest.approx(exact[0], rel=0.02)
    assert shortcut[1] == pytest.approx(exact[1], rel=0.02)


@pytest.mark.parametrize("preset", ["section5-T2-0.4", "section6-T2-0.8"])
def test_switched_on_covariance_matches_direct_integration(preset):
    """A stationary motion switched on at t = 0 on buildings at rest (the
    filter already stationary): the closed form by eigenvectors, and the
    stepped one it falls back to, against solve_ivp of dP/dt = A P + P A^T + Q."""
    from pounding.closed_form.covariance_history import _stepped
    from pounding.closed_form.linearization.lyapunov import lyapunov_covariance

    _, model = _stationary_pair(preset)
    A, Q, n, f = model.matrix, model.noise_covariance, model.size, model.filter_states
    initial = np.zeros((n, n))
    initial[f, f] = lyapunov_covariance(A[f, f], Q[f, f])
    times = np.linspace(0.0, 20.0, 81)
    check = times[::10]
    direct = solve_ivp(lambda t, p: (A @ p.reshape(n, n) + p.reshape(n, n) @ A.T + Q).ravel(), (0.0, 20.0), initial.ravel(),
                       t_eval=check, method="DOP853", rtol=1e-10, atol=1e-18).y.T.reshape(-1, n, n)
    stationary = model.covariance()
    scale = np.sqrt(np.outer(np.diag(stationary), np.diag(stationary)))
    closed = time_varying_covariance(model, None, times, modulation="ground")
    stepped = _stepped(A, stationary, initial - stationary, times)
    np.testing.assert_allclose(closed[::10] / scale, direct / scale, atol=1e-6)
    np.testing.assert_allclose(stepped[::10] / scale, direct / scale, atol=1e-6)
