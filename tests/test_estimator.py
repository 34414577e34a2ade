"""The closed-form estimators: the paper's chain of equations, the gap-aware
quantities, and the linearized buildings against the nonlinear ones."""

import dataclasses
import math

import numpy as np
import pytest

from pounding import ArgumentError, CaseError, load_case, simulate_record
from pounding.closed_form.estimator import estimate, force_versus_gap
from pounding.closed_form.linearization import linearize_pair
from pounding.closed_form.pair import LinearizedPair
from pounding.random_vibration.crossing_kernels import approach_intensity
from pounding.random_vibration.peaks import davenport_peak_factor
from tests.free_count import free_force


def _with(case, gap=None, restitution=None):
    contact = case.contact
    if gap is not None:
        contact = dataclasses.replace(contact, gap=gap)
    if restitution is not None:
        contact = dataclasses.replace(contact, restitution=restitution)
    return dataclasses.replace(case, contacts=(contact,))


@pytest.mark.parametrize("period_2", ["0.4", "0.6", "0.8"])
def test_linearized_sigma_is_close_to_the_nonlinear_buildings(period_2):
    """Section 5 buildings without contact: the statistically linearized
    (stationary) sigma_x of each building within 15 % of the nonlinear time
    histories' once stationary (records of 120 s, the first 30 s left out)."""
    case = _with(load_case(f"section5-T2-{period_2}"), gap=10.0)
    case = dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, duration=120.0))
    statistics = LinearizedPair.of(case).floor_statistics
    mean_squares = []
    for index in range(16):
        history = simulate_record(case, seed=11, index=index)
        keep = history.time > 30.0
        time = history.time[keep]
        d = history.displacement[keep]
        mean_squares.append(np.trapezoid(d**2, time, axis=0) / (time[-1] - time[0]))
    simulated = np.sqrt(np.mean(mean_squares, axis=0))
    linearized = np.array([statistics.displacement[0][0], statistics.displacement[1][0]])
    np.testing.assert_allclose(linearized, simulated, rtol=0.15)


def test_a_motion_too_short_for_davenport_keeps_the_recommended_estimate():
    """Where nu T <= 1 Davenport's factor (Eq. 23) is undefined: the paper's estimate says so and is None,
    while the gap-aware count, which needs no peak factor, still gives the pounding probability and force."""
    case = load_case("section5-T2-0.4")
    rate = estimate(case).paper.crossing_rate
    short = dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, duration=0.8 / rate))
    result = estimate(short)
    assert result.paper.unavailable is not None and "Eq. 23" in result.paper.unavailable
    assert result.paper.force_expected is None and result.paper.peak_factor is None
    assert result.to_dict()["paper"]["unavailable"] == result.paper.unavailable
    # the recommended estimate is there, and the shorter motion pounds less than the 20 s one
    assert 0.0 < result.pounding_probability < estimate(case).pounding_probability
    assert 0.0 < result.force_expected < estimate(case).force_expected


def test_paper_chain_follows_eq23_24_and_14():
    case = load_case("section5-T2-0.4")
    result = estimate(case)
    paper = result.paper
    linearized = result.response  # the paper's sigmas: the linearized pair's, without the residual
    # Eq. 24: twice Rice's rate of the relative displacement.
    assert paper.crossing_rate == pytest.approx(linearized.sigma_relative_velocity / (np.pi * linearized.sigma_relative_displacement))
    assert paper.peak_factor == pytest.approx(davenport_peak_factor(paper.crossing_rate, 20.0))
    assert paper.relative_velocity_expected == pytest.approx(paper.peak_factor * linearized.sigma_relative_velocity)
    # Eq. 14: F = beta delta^1.5 with delta from Eq. 13 at e * delta_dot_e.
    m = case.reduced_mass
    beta = case.contact.stiffness
    delta = (5 * m * (0.65 * paper.relative_velocity_expected) ** 2 / (4 * beta)) ** 0.4
    assert paper.force_expected == pytest.approx(beta * delta**1.5, rel=1e-12)
    assert paper.penetration_expected == pytest.approx(delta, rel=1e-12)


def test_paper_force_ignores_the_gap_and_scales_as_e_to_the_1_2():
    case = load_case("section5-T2-0.6")
    near = estimate(_with(case, gap=0.0)).paper.force_expected
    far = estimate(_with(case, gap=0.04)).paper.force_expected
    assert near == pytest.approx(far, rel=1e-12)
    low = estimate(_with(case, restitution=0.5)).paper.force_expected
    high = estimate(_with(case, restitution=0.8)).paper.force_expected
    assert high / low == pytest.approx((0.8 / 0.5) ** 1.2, rel=1e-9)


def test_paper_equivalent_stationary_process_for_modulated_motion():
    stationary = estimate(load_case("section5-T2-0.4"))
    modulated = estimate(load_case("section5-T2-0.4-nonstationary"))
    paper = modulated.paper
    # Same buildings and spectrum: the same sigma_inf (Eq. 26-28).
    assert modulated.sigma_relative_velocity == pytest.approx(stationary.sigma_relative_velocity, rel=1e-9)
    assert paper.sigma_relative_velocity_equivalent < modulated.sigma_relative_velocity
    assert 0 < paper.duration_effective < 40.0
    exact = estimate(load_case("section5-T2-0.4-nonstationary"), paper_variance="exact").paper
    # Eq. 28's shortcut against the time-varying covariance: a few per cent.
    assert paper.force_expected == pytest.approx(exact.force_expected, rel=0.04)


def test_michaelov_order_weighs_the_strong_motion_more_as_it_grows():
    """Eq. 29 with Eq. 28's A(t)^2 sigma_inf^2 (A's peak is 1): sigma_eq grows
    with n1 towards sigma_inf, the strongest instant's; n1 = 3 is the default;
    outside its range n1 is named."""
    case = load_case("section5-T2-0.4-nonstationary")
    pair = LinearizedPair.of(case)
    sigma_inf = estimate(pair).response.sigma_relative_velocity  # the paper's, linearized
    equivalent = {n1: estimate(pair, michaelov_n1=n1).paper for n1 in (1, 3, 20)}
    sigmas = [equivalent[n1].sigma_relative_velocity_equivalent for n1 in (1, 3, 20)]
    assert sigmas[0] < sigmas[1] < sigmas[2] < sigma_inf < 1.03 * sigmas[2]
    assert equivalent[20].duration_effective < equivalent[3].duration_effective < equivalent[1].duration_effective
    default = estimate(pair).paper
    assert default.michaelov_n1 == 3 and default.force_expected == equivalent[3].force_expected
    for bad in (0.0, 25, float("nan"), "3"):
        with pytest.raises(ArgumentError, match="michaelov_n1"):
            estimate(pair, michaelov_n1=bad)


def test_paper_exact_variance_option_is_the_time_varying_covariance():
    """``paper_variance="exact"``: Eq. 29 applied to sigma_V(t) of the Lyapunov
    differential equation, here integrated by solve_ivp from rest (the
    buildings keep their stationary linearization), not Eq. 28's A^2 sigma_inf^2."""
    from scipy.integrate import solve_ivp

    from pounding.closed_form.linearization import pair_state_space
    from pounding.random_vibration.peaks import equivalent_stationary

    case = load_case("section5-T2-0.4-nonstationary")
    linearized = linearize_pair(case)
    model = pair_state_space(case, linearized)
    a, b, envelope = model.matrix, model.noise_input, case.excitation.envelope
    n = a.shape[0]

    def rhs(time, p):
        p = p.reshape(n, n)
        return (a @ p + p @ a.T + 2 * math.pi * model.G0 * envelope(time) ** 2 * np.outer(b, b)).ravel()

    times = np.arange(0.0, case.excitation.duration + 1e-9, 0.01)
    solution = solve_ivp(rhs, (0.0, times[-1]), np.zeros(n * n), t_eval=times, method="DOP853", rtol=1e-9, atol=1e-16)
    row = model.velocity[0][0] - model.velocity[1][0]  # V = v1 - v2 at the contact floors (SDOF)
    variance = np.einsum("i,ijt,j->t", row, solution.y.reshape(n, n, -1), row)
    expected = math.sqrt(equivalent_stationary(variance, times, n1=3)[0])

    exact = estimate(case, paper_variance="exact").paper
    eq28 = estimate(case).paper
    assert exact.sigma_relative_velocity_equivalent == pytest.approx(expected, rel=2e-4)
    # Eq. 28 lags nothing: 0.3 % off here (short periods, slow envelope), which the option must not be.
    assert abs(eq28.sigma_relative_velocity_equivalent / expected - 1) > 1e-3


def test_required_gap_gives_the_target_probability():
    """Every crossing of the free motion counted (no clumps): exp(-Lambda) is
    the target there, and the best-estimate probability (clumps) no larger."""
    case = load_case("section5-T2-0.8")
    result = estimate(case, target_probability=0.9)
    free = result.crossings  # every crossing counted: the intensity kernel without clumps (clump constant inf)
    crossings = approach_intensity(np.array([result.required_gap]), np.zeros(1), free.sigma_x, free.sigma_v, free.weights,
                                   np.full(1, np.inf), np.ones(1), np.ones(1))[0, 0]
    assert 0.9 <= math.exp(-crossings) <= 0.9 + 1e-7  # the bisection ends on the safe side
    at_gap = estimate(_with(case, gap=result.required_gap), target_probability=0.9)
    assert at_gap.pounding_probability <= 0.1 + 1e-9
    stricter = estimate(case, target_probability=0.99)
    assert stricter.required_gap > result.required_gap > case.contact.gap


@pytest.mark.parametrize("name", ["section5-T2-0.4", "section6-T2-0.8"])
def test_expected_approaches_are_continuous_at_zero_gap(name):
    """At the onset the buildings are at rest and their variances are rounding
    noise; their ratio is no crossing rate. Counted, it added a few % to the
    approaches at exactly zero gap and nothing a micrometre away."""
    case = load_case(name)
    at_zero = estimate(_with(case, gap=0.0))
    nearby = estimate(_with(case, gap=1e-6 * at_zero.sigma_relative_displacement))
    assert at_zero.impacts_expected == pytest.approx(nearby.impacts_expected, rel=1e-4)


def test_force_and_probability_fall_with_the_gap():
    case = load_case("section5-T2-0.4-nonstationary")
    gaps = np.linspace(0.0, 0.3, 61)
    curve = force_versus_gap(case, gaps)
    assert np.all(np.diff(curve.force_expected) < 0)
    assert np.all(np.diff(curve.pounding_probability) <= 0)
    assert curve.pounding_probability[-1] < 0.01
    single = estimate(_with(case, gap=gaps[10]))
    assert curve.force_expected[10] == pytest.approx(single.force_expected, rel=1e-3)
    assert curve.pounding_probability[10] == pytest.approx(single.pounding_probability, rel=1e-9)


@pytest.mark.parametrize("value", [0.0, 1.0, -0.2, 1.5])
def test_bad_target_probability_is_named(value):
    with pytest.raises(ArgumentError, match="target_probability"):
        estimate(load_case("section5-T2-0.4"), target_probability=value)


def test_bad_gaps_are_named():
    with pytest.raises(ArgumentError, match="gaps"):
        force_versus_gap(load_case("section5-T2-0.4"), [0.01, -0.01])


@pytest.mark.slow
def test_every_number_is_finite_and_in_range_over_the_claimed_ranges_and_beyond():
    """100 cases drawn from the ranges the estimator claims (every kind of pair,
    stationary and modulated), each also pushed beyond them, to gap 0 and 50 cm
    and restitution 0.05 and 0.99: no NaN or infinity, probabilities in [0, 1],
    forces >= 0, a positive gap for the target, and (in the ranges) the
    probability never rising with the gap. The force may rise with a small gap
    (fewer impacts damp the motion less; Monte Carlo shows it, see
    test_estimator_accuracy.py), but at most once, then falls: a rise and a
    fall and a rise again would be the model's wiggle, not physics. The
    impacts only take energy out: never above the free count."""
    from pounding.studies.paper_tables import random_cases

    for case in random_cases(1):
        result = estimate(case)
        numbers = [v for v in result.to_dict().values() if isinstance(v, float)]
        numbers += [v for v in result.to_dict()["paper"].values() if isinstance(v, float)]
        assert all(math.isfinite(v) for v in numbers), case.name
        assert 0.0 <= result.pounding_probability <= 1.0 and result.force_expected >= 0.0 and result.required_gap > 0.0, case.name
        gaps = np.linspace(0.0, 3.0 * result.required_gap, 30)
        curve = result.gap_curve(gaps)
        force = curve.force_expected
        assert np.all(np.isfinite(force)) and np.all(force >= 0.0), case.name
        assert np.all(np.diff(curve.pounding_probability) <= 1e-12), case.name
        free = free_force(case, result.crossings, gaps, 81)  # the free count, as a gap curve counts
        assert np.all(force <= free * (1.0 + 1e-9)), case.name
        steps = np.diff(force)
        signs = np.sign(steps[np.abs(steps) > 1e-6 * force.max()])  # above the fixed point's tolerance
        assert np.all(np.diff(signs) <= 0), case.name  # +...+ then -...-: one rise at most, then the fall
        for gap in (0.0, 0.5):
            for restitution in (0.05, 0.99):
                extreme = estimate(_with(case, gap=gap, restitution=restitution))
                assert all(math.isfinite(v) for v in (extreme.force_expected, extreme.pounding_probability, extreme.required_gap))
                assert extreme.force_expected >= 0.0 and 0.0 <= extreme.pounding_probability <= 1.0, (case.name, gap, restitution)
                assert extreme.required_gap > 0.0, (case.name, gap, restitution)


def test_no_relative_motion_is_named_not_divided_by():
    """Identical buildings never approach each other under one ground motion, and
    without ground motion nothing moves: both are named, not a ZeroDivisionError."""
    from pounding.studies.paper_tables import varied_case

    base = load_case("section5-T2-0.4")
    for twins in (
        varied_case(base, elastic=True, periods=(0.5, 0.5)),
        varied_case(base, periods=(0.4, 0.4)),  # yielding
        dataclasses.replace(load_case("section6-T2-0.4"), buildings=(load_case("section6-T2-0.4").buildings[0],) * 2),  # two storeys
    ):
        with pytest.raises(CaseError, match="^buildings: the two buildings move alike"):
            estimate(twins)
    with pytest.raises(CaseError, match="^excitation.G0: must be > 0"):
        force_versus_gap(varied_case(base, g0=0.0), [0.0, 0.01])
    assert estimate(varied_case(base, elastic=True, periods=(0.5, 0.51))).force_expected > 0.0  # nearly alike is fine


@pytest.mark.slow
def test_every_warning_and_accuracy_statement_is_short():
    """Each warning and the measured accuracy are one or two short sentences,
    at most 200 characters: on every preset, on each at a moderate and at a
    rare gap (the linearization reused: it does not depend on the gap), and on
    a yielding pair under a Clough-Penzien spectrum; between them every kind
    of warning is met."""
    from pounding import preset_names
    from pounding.hazard.excitation import CloughPenzien

    kinds = {"The buildings sway at nearly one frequency", "Storeys near elastic-perfectly plastic", "The gap is 0.5 to 1 times",
             "Only the largest swings close this gap", "The gap for 95 %", "A building yields and the spectrum"}
    seen = set()
    for name in preset_names():
        pair = LinearizedPair.of(load_case(name))
        results = [estimate(pair)]
        sigma = results[0].sigma_relative_displacement
        results += [estimate(LinearizedPair(_with(pair.case, gap=u * sigma), pair.buildings)) for u in (0.75, 1.5)]
        for result in results:
            assert len(result.measured_accuracy) <= 200, (name, result.measured_accuracy)
            for warning in result.warnings:
                assert len(warning) <= 200, (name, warning)
                seen.update(kind for kind in kinds if warning.startswith(kind))
    case = load_case("section5-T2-0.8")
    s = case.excitation.spectrum
    spectrum = CloughPenzien(s.G0, s.omega_g, s.xi_g, omega_f=2.0, xi_f=0.6)
    result = estimate(dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, spectrum=spectrum)))
    assert len(result.measured_accuracy) <= 200 and all(len(w) <= 200 for w in result.warnings), result.warnings
    seen.update(kind for kind in kinds for w in result.warnings if w.startswith(kind))
    assert seen == kinds
