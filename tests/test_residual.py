"""The linearization residual as an input (pounding.closed_form.linearization.residual):
each step against an independent computation."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.linalg import expm

from pounding import load_case
from pounding.closed_form.linearization.residual import (
    residual_chaos,
    residual_correlation,
    residual_response,
)
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.response import contact_output_matrix
from pounding.simulation.monte_carlo import simulate_record
from pounding.studies.paper_tables import varied_case
from validation.residual_sampled import residual_response_sampled


def _bouc_wen_rate(law, velocity, z):
    return law.A * velocity - law.beta * np.abs(velocity) * np.abs(z) ** (law.n - 1) * z - law.gamma * velocity * np.abs(z) ** law.n


@pytest.fixture(scope="module")
def pair():
    linearized = LinearizedPair.of(load_case("section5-T2-0.8"))
    return linearized.case, linearized.buildings, linearized.state_space


def _storey_statistics(model, linearized, building, storey):
    rows = np.array([model.drift_velocity(building)[storey], model.hysteretic[building][storey]])
    return rows, rows @ model.covariance() @ rows.T


def test_residual_is_orthogonal_to_the_linear_law_and_its_chaos_carries_its_variance(pair):
    """Sampled Gaussian (u', z): Eq. 20's c_e, k_e are the mean-square best
    linear law (the residual is uncorrelated with u' and z), and the chaoses
    kept carry most of the sampled E[r^2], which the quadrature reproduces."""
    _, linearized, model = pair
    rng = np.random.default_rng(0)
    for building in (0, 1):
        lb = linearized[building]
        law = lb.building.storeys[0].bouc_wen
        _, covariance = _storey_statistics(model, linearized, building, 0)
        velocity, z = np.linalg.cholesky(covariance) @ rng.standard_normal((2, 2_000_000))
        r = _bouc_wen_rate(law, velocity, z) - lb.c_e[0] * velocity - lb.k_e[0] * z
        assert abs(np.corrcoef(r, velocity)[0, 1]) < 0.01 and abs(np.corrcoef(r, z)[0, 1]) < 0.01
        _, chaos, variance = residual_chaos(law, lb.c_e[0], lb.k_e[0], covariance)
        assert variance == pytest.approx(np.mean(r * r), rel=0.01)
        kept = sum(
            math.factorial(p) ** 2 * sum(t[a] ** 2 / (math.factorial(a) * math.factorial(p - a)) for a in range(p + 1))
            for p, t in zip((3, 5), chaos)
        )
        assert 0.85 * variance < kept <= 1.001 * variance


@pytest.mark.slow
def test_residual_correlation_against_sampling_at_lags(pair):
    """E[r_j(t) r_k(t + tau)] by the diagram formula against a sample of the
    four jointly Gaussian variables (u'_j, z_j)(t), (u'_k, z_k)(t + tau) with
    the covariance P exp(A^T tau) of the linearized pair."""
    _, linearized, model = pair
    storeys, lags, correlation = residual_correlation(model, linearized)
    covariance = model.covariance()
    rng = np.random.default_rng(1)
    for lag_index in (0, int(0.2 / lags[1]), int(0.5 / lags[1])):
        tau = lags[lag_index]
        for j, k in ((0, 0), (0, 1), (1, 0)):
            rows_j, rows_k = storeys[j].rows, storeys[k].rows
            cross = rows_j @ covariance @ expm(model.matrix.T * tau) @ rows_k.T  # E[y_j(t) y_k(t + tau)^T]
            joint = np.block([[rows_j @ covariance @ rows_j.T, cross], [cross.T, rows_k @ covariance @ rows_k.T]])
            values, vectors = np.linalg.eigh(joint)  # singular at lag 0 for j = k
            sample = (vectors * np.sqrt(np.clip(values, 0.0, None))) @ rng.standard_normal((4, 1_000_000))
            residuals = []
            for storey, (velocity, z) in ((storeys[j], sample[:2]), (storeys[k], sample[2:])):
                lb = linearized[storey.building]
                law = lb.building.storeys[storey.storey].bouc_wen
                residuals.append(_bouc_wen_rate(law, velocity, z) - lb.c_e[storey.storey] * velocity - lb.k_e[storey.storey] * z)
            product = residuals[0] * residuals[1]
            # The chaoses left out (order 7 and up) carry (1 - captured) of each variance;
            # by Cauchy-Schwarz their correlation is at most the geometric mean of the two.
            left_out = math.sqrt((1 - storeys[j].captured) * storeys[j].variance * (1 - storeys[k].captured) * storeys[k].variance)
            sampling = 4 * product.std() / math.sqrt(product.size)
            assert abs(correlation[lag_index, k, j] - product.mean()) < left_out + sampling


def test_residual_response_against_a_monte_carlo_of_the_linear_pair(pair):
    """The closed form (chaos, diagram formula, FFT, modal frequency response)
    against the time stepping of the linearized pair with the residual
    evaluated along its own sampled motion and fed into the z equations."""
    case, linearized, model = pair
    rows = contact_output_matrix(tuple(level - 1 for level in case.contact.levels), model)
    outputs = np.array([rows[0] - rows[1], rows[2] - rows[3]])
    closed_form = np.diag(residual_response(model, linearized, outputs))
    sampled = residual_response_sampled(model, linearized, outputs, trajectories=600, duration=14.0)
    assert np.sqrt(closed_form) == pytest.approx(np.sqrt(sampled), rel=0.06)


def test_elastic_pairs_have_no_residual():
    pair = LinearizedPair.of(varied_case(load_case("section5-T2-0.4"), elastic=True))
    linear = pair.stationary_response
    corrected = pair.response_with_residual
    np.testing.assert_array_equal(corrected.covariance, linear.covariance)


def test_residual_vanishes_with_the_amplitude():
    """Far below yield the Bouc-Wen law is linear: the residual's share of
    sigma_X falls with the intensity (for n = 1 only in proportion to the
    amplitude, so it is still 3 % at 1e-4 G0) and vanishes in the limit."""
    base = load_case("section5-T2-0.8")
    shares = []
    for factor in (1e-2, 1e-4, 1e-6, 1e-8):
        pair = LinearizedPair.of(varied_case(base, g0=factor))
        shares.append(pair.response_with_residual.sigma_relative_displacement / pair.stationary_response.sigma_relative_displacement - 1.0)
    assert shares == sorted(shares, reverse=True)
    assert shares[0] > 0.1 and shares[-1] < 1e-4


def test_residual_brings_sigma_x_of_weakly_yielding_buildings_to_the_simulation():
    """At a hundredth of the paper's intensity the Section 5 pair (n = 1) still
    yields a little and drifts; the linearization misses 16 % of the simulated
    sigma_X (records keeping the spectrum's low end, without contact), the
    residual's response brings it within 6 % (documented in validation/HISTORY.md)."""
    case = varied_case(load_case("section5-T2-0.8"), g0=0.01)
    case = dataclasses.replace(
        case,
        excitation=dataclasses.replace(case.excitation, synthesis_factor=8, duration=40.0),
        contacts=(dataclasses.replace(case.contact, gap=10.0),),
    )
    first, second = case.contact.levels[0] - 1, case.buildings[0].n_storeys + case.contact.levels[1] - 1
    squares = []
    for index in range(100):
        history = simulate_record(case, 3, index)
        settled = history.time > 10.0
        squares.append(np.mean((history.displacement[settled, first] - history.displacement[settled, second]) ** 2))
    simulated = math.sqrt(np.mean(squares))
    pair = LinearizedPair.of(case)
    linear = pair.stationary_response.sigma_relative_displacement
    corrected = pair.response_with_residual.sigma_relative_displacement
    assert linear < 0.9 * simulated
    assert abs(corrected / simulated - 1.0) < 0.08


def test_residual_adds_variance_and_decoheres_the_frames():
    """Section 6, T2 = 0.8 s: the residuals of the two frames are independent
    of the ground motion and only partly of each other, so the corrected
    frames' velocities are less coherent (documented: 0.85 linearized, 0.80
    simulated)."""
    case = load_case("section6-T2-0.8")
    pair = LinearizedPair.of(case)
    linear, corrected = pair.stationary_response, pair.response_with_residual
    assert np.all(np.diag(corrected.covariance) >= np.diag(linear.covariance))

    def coherence(response):
        c = response.covariance
        return c[2, 3] / math.sqrt(c[2, 2] * c[3, 3])

    assert coherence(corrected) < coherence(linear) - 0.03
    assert corrected.method == "lyapunov+residual"
