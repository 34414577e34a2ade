"""Statistical linearization (Eq. 19-21) and the state-space model."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.linalg import solve_continuous_lyapunov
from scipy.special import erf

import pounding
from pounding.closed_form.linearization import (
    LinearizedBuilding,
    building_state_space,
    equivalent_coefficients,
    ground_filter,
    linearize,
    linearize_pair,
    lyapunov_covariance,
    state_space,
    wen_expectations,
)
from pounding.errors import ConvergenceError
from pounding.hazard.excitation import CloughPenzien, KanaiTajimi
from pounding.hazard.filter_bank import FilterBank
from pounding.mechanics.structures import BoucWen, Building, Storey


def _reference_expectations(sigma_u, sigma_z, rho, n):
    """F1..F4 by 1-D quadrature over z of the conditional expectations of the
    Bouc-Wen terms given z; udot | z is Gaussian with mean rho sigma_u z / sigma_z
    and standard deviation sigma_u sqrt(1 - rho^2)."""
    s = sigma_u * math.sqrt(1.0 - rho * rho)

    def parts(zeta):
        z = sigma_z * zeta
        mu = rho * sigma_u * zeta
        weight = math.exp(-0.5 * zeta * zeta) / math.sqrt(2.0 * math.pi)
        sign_u = erf(mu / (s * math.sqrt(2.0)))  # E[sgn(udot) | z]
        abs_u = s * math.sqrt(2.0 / math.pi) * math.exp(-0.5 * (mu / s) ** 2) + mu * sign_u  # E[|udot| | z]
        power = abs(z) ** (n - 1.0)
        return weight * np.array(
            [sign_u * power * z, power * abs(z), n * abs_u * power, n * mu * power * math.copysign(1.0, z)]
        )

    # |z|^(n-1) is not smooth at z = 0: integrate each half line.
    total = np.zeros(4)
    for a, b in ((-np.inf, 0.0), (0.0, np.inf)):
        for i in range(4):
            total[i] += quad(lambda zeta, i=i: parts(zeta)[i], a, b, epsabs=0.0, epsrel=1e-11, limit=200)[0]
    return total


@pytest.mark.parametrize("n", [1.0, 1.5, 2.0, 3.0])
@pytest.mark.parametrize("rho", [-0.8, -0.3, 0.0, 0.45, 0.97])
def test_wen_expectations_match_gaussian_quadrature(n, rho):
    sigma_u, sigma_z = 0.3, 0.02
    computed = np.array(wen_expectations(sigma_u, sigma_z, rho, n), dtype=float)
    reference = _reference_expectations(sigma_u, sigma_z, rho, n)
    # F1 and F4 vanish at rho = 0: an absolute floor far below the other terms.
    np.testing.assert_allclose(computed, reference, rtol=1e-7, atol=1e-12 * np.abs(reference).max())


def test_wen_expectations_parity_in_rho():
    """The angle l = arccos(rho) (NOTES point 5) makes F1 and F4 odd, F2 and F3
    even in rho; the printed atan form would make F1 even."""
    rho = np.array([0.2, 0.6, 0.9])
    for n in (1.0, 2.0, 2.5):
        plus = wen_expectations(0.1, 0.01, rho, n)
        minus = wen_expectations(0.1, 0.01, -rho, n)
        np.testing.assert_allclose(minus[0], -plus[0], rtol=1e-13)
        np.testing.assert_allclose(minus[1], plus[1], rtol=1e-13)
        np.testing.assert_allclose(minus[2], plus[2], rtol=1e-13)
        np.testing.assert_allclose(minus[3], -plus[3], rtol=1e-13)


@pytest.mark.parametrize("n, rho", [(1.0, 0.6), (2.0, -0.4), (1.5, 0.9)])
def test_equivalent_coefficients_minimise_mean_square_error(n, rho):
    """Monte Carlo: the least-squares fit of the Bouc-Wen rate on (udot, z)
    over Gaussian samples reproduces c_e and k_e (Eq. 19-20), and so do the
    sample means of the partial derivatives."""
    A, beta, gamma = 1.0, 150.0, -50.0
    sigma_u, sigma_z = 0.2, 0.008
    rng = np.random.default_rng(20260407)
    size = 1_000_000
    x, y = rng.standard_normal((2, size))
    z = sigma_z * x
    u = sigma_u * (rho * x + math.sqrt(1.0 - rho * rho) * y)
    abs_z_n = np.abs(z) ** n
    rate = A * u - beta * np.abs(u) * abs_z_n * np.sign(z) - gamma * u * abs_z_n
    c_e, k_e = equivalent_coefficients(A, beta, gamma, n, sigma_u, sigma_z, rho)
    fit = np.linalg.lstsq(np.stack([u, z], axis=1), rate, rcond=None)[0]
    np.testing.assert_allclose(fit, [c_e, k_e], rtol=5e-3)
    d_u = A - beta * np.sign(u) * abs_z_n * np.sign(z) - gamma * abs_z_n
    d_z = -n * np.abs(z) ** (n - 1.0) * (beta * np.abs(u) + gamma * u * np.sign(z))
    np.testing.assert_allclose([d_u.mean(), d_z.mean()], [c_e, k_e], rtol=5e-3)


@pytest.mark.parametrize("size", [2, 3, 5, 8, 11, 14])
def test_lyapunov_solver_matches_scipy(size):
    rng = np.random.default_rng(size)
    matrix = rng.standard_normal((size, size)) - 2.5 * math.sqrt(size) * np.eye(size)
    b = rng.standard_normal(size)
    noise = np.outer(b, b)
    expected = solve_continuous_lyapunov(matrix, -noise)
    np.testing.assert_allclose(lyapunov_covariance(matrix, noise), expected, rtol=1e-9, atol=1e-12 * np.abs(expected).max())


@pytest.mark.parametrize(
    "spectrum",
    [
        KanaiTajimi(0.0065, 27.02, 0.34),
        CloughPenzien(0.0065, 15.0, 0.6, omega_f=1.5, xi_f=0.7),
        FilterBank(0.002, (3.0, 11.0, 40.0), (0.2, 0.45, 0.7), (0.4, 1.0, 0.0)),
    ],
)
def test_ground_filter_reproduces_the_spectrum(spectrum):
    ground = ground_filter(spectrum)
    omega = np.array([0.0, 0.3, 1.5, 7.0, 27.0, 80.0, 400.0])
    # one transfer function per independent noise; their powers add
    transfer = np.array(
        [ground.output @ np.linalg.solve(1j * w * np.eye(ground.size) - ground.matrix, ground.noise_input) for w in omega]
    )
    power = np.sum(np.abs(transfer) ** 2, axis=1) * ground.G0
    np.testing.assert_allclose(power, spectrum.psd(omega), rtol=1e-10, atol=1e-18)


def _sdof(period=0.5, mass=2.0e4, xi=0.04, law=None):
    stiffness = mass * (2.0 * math.pi / period) ** 2
    return Building((Storey(mass, stiffness, law or BoucWen(alpha=1.0)),), damping_ratio=xi)


def test_linear_sdof_white_noise_limit():
    """alpha = 1 under a Kanai-Tajimi spectrum flat far beyond the building
    frequency: sigma_x^2 = pi S0 / (2 xi w^3), sigma_v^2 = pi S0 / (2 xi w) for
    the two-sided PSD S0 (covariance 2 pi S0 delta(tau))."""
    period, xi, S0 = 0.5, 0.04, 0.02
    building = _sdof(period, xi=xi)
    omega = 2.0 * math.pi / period
    spectrum = KanaiTajimi(S0, 3000.0 * omega, 0.6)
    linear = linearize(building, spectrum)
    assert linear.iterations == 0 and linear.c_e[0] == 1.0 and linear.k_e[0] == 0.0
    model = building_state_space(linear, spectrum)
    covariance = model.covariance()
    var_x = model.displacement[0][0] @ covariance @ model.displacement[0][0]
    var_v = model.velocity[0][0] @ covariance @ model.velocity[0][0]
    assert var_x == pytest.approx(math.pi * S0 / (2.0 * xi * omega**3), rel=1e-4)
    assert var_v == pytest.approx(math.pi * S0 / (2.0 * xi * omega), rel=1e-4)


def test_alpha_one_storeys_are_not_iterated():
    elastic = Storey(3.0e4, 4.0e7, BoucWen(alpha=1.0, A=1.0))
    yielding = Storey(3.0e4, 4.0e7, BoucWen(alpha=0.1, A=1.0, beta=150.0, gamma=-50.0, n=1.0))
    spectrum = KanaiTajimi(0.0065, 27.02, 0.34)
    linear = linearize(Building((elastic, elastic)), spectrum)
    assert linear.iterations == 0
    np.testing.assert_array_equal(linear.k_e, 0.0)
    mixed = linearize(Building((yielding, elastic)), spectrum)
    assert mixed.k_e[0] < 0.0 and mixed.k_e[1] == 0.0 and mixed.c_e[1] == 1.0
    assert mixed.n_states == 2 * 2 + 1


@pytest.mark.parametrize("preset", ["section5-T2-0.4", "section6-T2-0.4"])
def test_converged_coefficients_are_self_consistent(preset):
    """Rebuild the converged linear building through the general state-space
    assembly, take its storey statistics, and recover c_e and k_e from Eq. 20-21."""
    case = pounding.load_case(preset)
    spectrum = case.excitation.spectrum
    for linear in linearize_pair(case):
        model = building_state_space(linear, spectrum)
        covariance = model.covariance()
        velocity, z = model.drift_velocity(0), model.hysteretic[0]
        sigma_u = np.sqrt(np.einsum("ij,jk,ik->i", velocity, covariance, velocity))
        sigma_z = np.sqrt(np.einsum("ij,jk,ik->i", z, covariance, z))
        rho = np.einsum("ij,jk,ik->i", velocity, covariance, z) / (sigma_u * sigma_z)
        laws = [s.bouc_wen for s in linear.building.storeys]
        c_e, k_e = equivalent_coefficients(
            *(np.array([getattr(law, name) for law in laws]) for name in ("A", "beta", "gamma", "n")), sigma_u, sigma_z, rho
        )
        np.testing.assert_allclose(c_e, linear.c_e, rtol=1e-7)
        np.testing.assert_allclose(k_e, linear.k_e, rtol=1e-7)
        np.testing.assert_allclose(np.c_[sigma_u, sigma_z, rho], np.c_[linear.sigma_drift_velocity, linear.sigma_z, linear.rho], rtol=1e-7)
        assert np.all(linear.k_e < 0.0) and np.all(linear.c_e > 0.0)


def test_linearization_tends_to_the_elastic_system():
    """As G0 -> 0, c_e -> A and k_e -> 0, as sigma^n: by sqrt(G0) for n = 1
    (section 5) and by G0 for n = 2 (section 6)."""
    for preset, n in (("section5-T2-0.4", 1.0), ("section6-T2-0.4", 2.0)):
        case = pounding.load_case(preset)
        spectrum = case.excitation.spectrum
        for building in case.buildings:
            small, smaller = (
                linearize(building, dataclasses.replace(spectrum, G0=spectrum.G0 * factor)) for factor in (1e-8, 1e-10)
            )
            A = np.array([s.bouc_wen.A for s in building.storeys])
            omega_1 = building.mode_shapes()[0][0]
            assert np.all(np.abs(small.c_e - A) < 1e-3) and np.all(np.abs(small.k_e) < 1e-3 * omega_1)
            expected_ratio = 100.0 ** (n / 2.0)
            np.testing.assert_allclose((small.c_e - A) / (smaller.c_e - A), expected_ratio, rtol=0.02)
            np.testing.assert_allclose(small.k_e / smaller.k_e, expected_ratio, rtol=0.02)


def test_zero_excitation_returns_the_elastic_system():
    case = pounding.load_case("section5-T2-0.4")
    linear = linearize(case.buildings[0], dataclasses.replace(case.excitation.spectrum, G0=0.0))
    assert linear.iterations == 0 and linear.c_e[0] == 1.0 and linear.k_e[0] == 0.0


@pytest.mark.parametrize("factor", [1.0, 4.0 * math.pi**2, 1e4])
def test_strong_excitation_converges(factor):
    """From the paper's intensity to far beyond it (4 pi^2: the intensity the
    notes conjecture the authors used), the iteration converges."""
    case = pounding.load_case("section6-T2-0.4")
    spectrum = dataclasses.replace(case.excitation.spectrum, G0=case.excitation.spectrum.G0 * factor)
    for building in case.buildings:
        linear = linearize(building, spectrum)
        assert linear.iterations < 60
        assert np.all(np.isfinite(linear.c_e)) and np.all(linear.k_e < 0.0)


def test_plain_under_relaxation_reaches_the_same_fixed_point():
    case = pounding.load_case("section6-T2-0.4")
    spectrum = case.excitation.spectrum
    for building in case.buildings:
        mixed = linearize(building, spectrum)
        plain = linearize(building, spectrum, relaxation=0.5, memory=0)
        np.testing.assert_allclose(plain.c_e, mixed.c_e, rtol=1e-7)
        np.testing.assert_allclose(plain.k_e, mixed.k_e, rtol=1e-7)


def test_convergence_error_names_building_and_storey():
    case = pounding.load_case("section6-T2-0.4")
    with pytest.raises(ConvergenceError, match=r"building 1, storey \d") as caught:
        linearize(case.buildings[0], case.excitation.spectrum, max_iterations=2, label="building 1")
    error = caught.value
    assert error.building == "building 1" and error.storey in (1, 2)
    assert error.c_e.shape == (2,) and error.k_e.shape == (2,)
    assert "c_e = [" in str(error)


def test_pair_uses_the_stationary_spectrum_for_nonstationary_cases():
    stationary = linearize_pair(pounding.load_case("section5-T2-0.4"))
    nonstationary = linearize_pair(pounding.load_case("section5-T2-0.4-nonstationary"))
    for a, b in zip(stationary, nonstationary):
        np.testing.assert_array_equal(a.c_e, b.c_e)
        np.testing.assert_array_equal(a.k_e, b.k_e)


def test_joint_state_space_holds_both_buildings_without_interaction():
    """The pair model's block of each building equals the building's own
    model: the buildings share only the ground filter."""
    case = pounding.load_case("section6-T2-0.4")
    spectrum = case.excitation.spectrum
    first, second = linearize_pair(case)
    pair = state_space((first, second), spectrum)
    alone = building_state_space(first, spectrum)
    assert pair.size == first.n_states + second.n_states + ground_filter(spectrum).size
    n1 = first.n_states
    np.testing.assert_array_equal(pair.matrix[:n1, :n1], alone.matrix[:n1, :n1])
    np.testing.assert_array_equal(pair.matrix[:n1, n1 : n1 + second.n_states], 0.0)
    np.testing.assert_array_equal(pair.matrix[n1 : n1 + second.n_states, :n1], 0.0)
    # Each building's variances are the same alone and in the pair.
    p_pair, p_alone = pair.covariance(), alone.covariance()
    rows_pair, rows_alone = pair.displacement[0], alone.displacement[0]
    np.testing.assert_allclose(
        np.diag(rows_pair @ p_pair @ rows_pair.T), np.diag(rows_alone @ p_alone @ rows_alone.T), rtol=1e-10
    )


def test_elastic_constructor():
    building = _sdof(law=BoucWen(alpha=0.1, A=0.9, beta=120.0, gamma=-40.0))
    elastic = LinearizedBuilding.elastic(building)
    assert elastic.c_e[0] == 0.9 and elastic.k_e[0] == 0.0 and elastic.n_states == 2


def test_tall_building_uses_the_general_lyapunov_solver():
    """Four yielding storeys (14 states): beyond the dense solver's size, the
    iteration runs on scipy's solver and reaches a self-consistent point."""
    law = BoucWen(alpha=0.05, A=1.0, beta=150.0, gamma=-50.0, n=1.0)
    storeys = tuple(Storey(4.0e4, stiffness, law) for stiffness in (9.0e7, 8.0e7, 6.0e7, 4.0e7))
    building = Building(storeys, damping_ratio=0.05)
    spectrum = KanaiTajimi(0.0065 * 4.0 * math.pi**2, 27.02, 0.34)
    linear = linearize(building, spectrum)
    model = building_state_space(linear, spectrum)
    assert model.size == 14
    covariance = model.covariance()
    velocity, z = model.drift_velocity(0), model.hysteretic[0]
    sigma_u = np.sqrt(np.einsum("ij,jk,ik->i", velocity, covariance, velocity))
    sigma_z = np.sqrt(np.einsum("ij,jk,ik->i", z, covariance, z))
    rho = np.einsum("ij,jk,ik->i", velocity, covariance, z) / (sigma_u * sigma_z)
    c_e, k_e = equivalent_coefficients(1.0, 150.0, -50.0, 1.0, sigma_u, sigma_z, rho)
    np.testing.assert_allclose(c_e, linear.c_e, rtol=1e-7)
    np.testing.assert_allclose(k_e, linear.k_e, rtol=1e-7)
    assert np.all(linear.c_e < 1.0)  # yielding in every storey


def test_equivalent_storey_force_integrates_the_linear_law_along_a_drift_history():
    """Against solve_ivp on zdot = c_e udot + k_e z (Eq. 19), the drift linear
    between uneven samples: q = alpha k u + (1 - alpha) k z at every sample."""
    from scipy.integrate import solve_ivp

    from pounding.closed_form.linearization import equivalent_storey_force

    case = pounding.load_case("section5-T2-0.4")
    building = linearize_pair(case)[0]
    assert building.hysteretic[0]
    rng = np.random.default_rng(3)
    time = np.sort(np.concatenate([[0.0, 6.0], rng.uniform(0.0, 6.0, 400)]))
    drift = 0.05 * np.sin(2.1 * time) * (1 + 0.3 * np.cos(0.7 * time))
    rate = np.diff(drift) / np.diff(time)
    c_e, k_e = building.c_e[0], building.k_e[0]
    z = [0.0]
    for i in range(time.size - 1):  # one solve per piece: the drift rate jumps at the samples
        piece = solve_ivp(lambda t, y, s=rate[i]: c_e * s + k_e * y, (time[i], time[i + 1]), [z[-1]], rtol=1e-12, atol=1e-15)
        z.append(piece.y[0, -1])
    storey = building.building.storeys[0]
    alpha = storey.bouc_wen.alpha
    expected = alpha * storey.stiffness * drift + (1 - alpha) * storey.stiffness * np.array(z)
    force = equivalent_storey_force(building, time, drift[:, None])[:, 0]
    assert np.max(np.abs(force - expected)) < 1e-8 * np.max(np.abs(expected))
