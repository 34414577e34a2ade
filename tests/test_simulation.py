"""The time-history engine ("exact method") against theory, an independent
integrator, and itself at a tighter tolerance."""

import dataclasses
import math

import numpy as np
import pytest
from scipy import integrate as scipy_integrate

import pounding
from pounding import BoucWen, Settings, SimulationError, integrate, load_case, simulate, simulate_record
from pounding.hazard.excitation import ground_accelerations

from .conftest import KANAI_TAJIMI_SI, make_case, one_storey
from .reference import solve_reference


def _shorter(case, duration):
    return dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, duration=duration))


@pytest.mark.slow
def test_linear_buildings_match_random_vibration_theory():
    """alpha = 1 and a gap out of reach: the sample variances of displacement and
    velocity, and of the relative motion (cross terms), equal the integrals of
    |H|^2 S_g over the generated band."""
    periods = (1.2, 0.4)
    case = make_case([one_storey(t) for t in periods], gap=1.0, duration=160.0)
    per_record = []
    for index in range(64):
        history = simulate_record(case, seed=5, index=index)
        assert history.summary["impacts"] == 0
        keep = history.time > 20.0  # past the start-up transient
        time = history.time[keep]

        def variance(x):
            return scipy_integrate.trapezoid(x[keep] ** 2, time) / (time[-1] - time[0])

        d, v = history.displacement, history.velocity
        per_record.append([variance(d[:, 0]), variance(d[:, 1]), variance(v[:, 0]), variance(v[:, 1]),
                           variance(d[:, 0] - d[:, 1]), variance(v[:, 0] - v[:, 1])])
    per_record = np.array(per_record)
    measured = per_record.mean(axis=0)
    standard_error = per_record.std(axis=0, ddof=1) / math.sqrt(len(per_record))

    def transfer(omega, period, xi=0.05):
        natural = 2 * np.pi / period
        return -1.0 / (natural**2 - omega**2 + 2j * xi * natural * omega)

    def band_integral(function):
        points = [2 * np.pi / t for t in periods] + [KANAI_TAJIMI_SI.omega_g]
        value, _ = scipy_integrate.quad(lambda w: function(w) * KANAI_TAJIMI_SI.psd(w), 0.0,
                                        case.excitation.cutoff_frequency, points=points, limit=1000)
        return 2 * value

    h1 = lambda w: transfer(w, periods[0])  # noqa: E731
    h2 = lambda w: transfer(w, periods[1])  # noqa: E731
    theory = np.array([
        band_integral(lambda w: abs(h1(w)) ** 2),
        band_integral(lambda w: abs(h2(w)) ** 2),
        band_integral(lambda w: w**2 * abs(h1(w)) ** 2),
        band_integral(lambda w: w**2 * abs(h2(w)) ** 2),
        band_integral(lambda w: abs(h1(w) - h2(w)) ** 2),
        band_integral(lambda w: w**2 * abs(h1(w) - h2(w)) ** 2),
    ])
    assert np.all(np.abs(measured - theory) < 3.5 * standard_error + 0.005 * theory), (measured / theory - 1, standard_error / theory)
    assert np.all(standard_error / theory < 0.03)  # the test has teeth


@pytest.mark.slow
@pytest.mark.parametrize("preset, amplify", [("section5-T2-0.4", 1.0), ("section6-T2-0.4", 3.0)])
def test_one_record_agrees_with_solve_ivp(preset, amplify):
    """The same record through scipy's DOP853 at rtol 1e-9 on the equations
    written in storey drifts (tests/reference.py)."""
    case = _shorter(load_case(preset), 8.0)
    record = amplify * ground_accelerations(case.excitation, seed=0, indices=[0])[0]
    history = integrate(case, record, case.excitation.time_step)
    solution, force_at = solve_reference(case, record, case.excitation.time_step)
    assert solution.status == 0
    onsets = solution.t_events[0]
    assert history.summary["impacts"] == len(onsets) >= 3
    # Peak force: the reference's dense output on a 20 us grid over the impacts.
    fine = np.concatenate([np.arange(t, t + 0.1, 2e-5) for t in onsets])
    reference_force_max = force_at(fine[fine < solution.t[-1]])[0].max()
    assert history.summary["force_max"] == pytest.approx(reference_force_max, rel=5e-3)
    # Approach velocity at the onsets (the kernel locates them itself).
    rates = []
    for y in solution.y_events[0]:
        n = y.size // 3
        sizes = case.buildings[0].n_storeys
        level_1, level_2 = case.contact.levels
        rates.append(sum(y[n : n + level_1]) - sum(y[n + sizes : n + sizes + level_2]))
    assert history.summary["impact_velocity_max"] == pytest.approx(max(rates), rel=1e-3)


def test_halving_the_tolerance_keeps_the_answer():
    case = load_case("section5-T2-0.4")
    loose = simulate(case, records=16, seed=2, settings=Settings(tolerance=1e-6))
    tight = simulate(case, records=16, seed=2, settings=Settings(tolerance=5e-7))
    assert loose.force_max_mean == pytest.approx(tight.force_max_mean, rel=1e-3)
    np.testing.assert_allclose(loose.force_max, tight.force_max, rtol=5e-3)
    np.testing.assert_array_equal(loose.impacts, tight.impacts)
    assert tight.steps.mean() > loose.steps.mean()


def test_same_seed_same_numbers_whatever_the_workers_and_chunks():
    case = _shorter(load_case("section5-T2-0.6-nonstationary"), 25.0)
    one = simulate(case, records=12, seed=9, settings=Settings(workers=1, chunk_size=12))
    two = simulate(case, records=12, seed=9, settings=Settings(workers=2, chunk_size=5))
    np.testing.assert_array_equal(one.force_max, two.force_max)
    np.testing.assert_array_equal(one.impacts, two.impacts)
    tail = simulate(case, records=4, seed=9, first_record=8)
    np.testing.assert_array_equal(one.force_max[8:], tail.force_max)
    other = simulate(case, records=12, seed=10)
    assert not np.array_equal(one.force_max, other.force_max)


def test_simulate_and_simulate_record_see_the_same_record():
    case = _shorter(load_case("section5-T2-0.4"), 10.0)
    batch = simulate(case, records=3, seed=4)
    history = simulate_record(case, seed=4, index=2)
    assert history.summary["force_max"] == pytest.approx(batch.force_max[2], rel=1e-12)
    assert history.summary["impacts"] == batch.impacts[2]


def test_summary_statistics():
    case = _shorter(load_case("section5-T2-0.8"), 10.0)
    result = simulate(case, records=20, seed=1)
    assert result.force_max_mean == pytest.approx(result.force_max.mean())
    assert result.force_max_std_error == pytest.approx(result.force_max.std(ddof=1) / math.sqrt(20))
    low, high = result.force_max_confidence_interval
    assert low < result.force_max_mean < high
    assert (high - low) / 2 == pytest.approx(2.093 * result.force_max_std_error, rel=1e-3)  # t(0.975, 19)
    assert result.pounding_fraction == pytest.approx(np.mean(result.impacts > 0))
    assert np.all(result.force_max[result.impacts == 0] == 0)
    data = result.to_dict()
    assert data["force_max"] == result.force_max.tolist()


def test_the_interval_of_the_mean_force_never_goes_below_zero():
    """Issue 33: with few pounding records among many that do not, mean - t s.e. falls below 0; a force is never
    negative, so the interval is cut at 0 there and keeps its Student-t upper end."""
    base = _shorter(load_case("section5-T2-0.4"), 10.0)
    case = base.with_contact(gap=0.15)
    result = simulate(case, records=30, seed=3)
    assert 0 < result.pounding_fraction < 0.3  # a few pound
    half = 2.045 * result.force_max_std_error  # t(0.975, 29)
    assert result.force_max_mean - half < 0  # the uncut interval would go below zero
    low, high = result.force_max_confidence_interval
    assert low == 0.0 and high == pytest.approx(result.force_max_mean + half, rel=1e-3)
    assert result.to_dict()["force_max_ci95"][0] == 0.0


def test_wider_gap_means_less_pounding():
    case = _shorter(load_case("section5-T2-0.4"), 10.0)
    fractions = []
    for gap in (0.0, 0.01, 0.03, 1.0):
        widened = case.with_contact(gap=gap)
        fractions.append(simulate(widened, records=16, seed=3).impacts_mean)
    assert fractions[0] > fractions[1] > fractions[2] >= fractions[3] == 0


def test_progress_is_reported_to_the_end():
    case = _shorter(load_case("section5-T2-0.4"), 5.0)
    calls = []
    simulate(case, records=10, seed=0, settings=Settings(chunk_size=3), progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (10, 10)
    assert [done for done, _ in calls] == sorted(done for done, _ in calls)


def test_cancel_stops_the_study():
    import threading

    case = _shorter(load_case("section5-T2-0.4"), 5.0)
    cancel = threading.Event()
    cancel.set()
    with pytest.raises(pounding.simulation.monte_carlo.Cancelled):
        simulate(case, records=10, seed=0, cancel=cancel)


def test_runaway_record_raises_naming_record_seed_and_time():
    case = _shorter(load_case("section5-T2-0.4"), 10.0)
    with pytest.raises(SimulationError, match=r"record 0 \(seed 3\) failed at t = \d+\.\d+ s: .*runaway"):
        simulate(case, records=4, seed=3, settings=Settings(displacement_limit=1e-3))


def test_unstable_building_is_reported_not_averaged():
    # alpha = 0 and a Bouc-Wen law with no hardening leaves nothing to hold the
    # storey once it yields; strong shaking walks it away.
    soft = BoucWen(alpha=0.0, A=1.0, beta=300.0, gamma=-100.0, n=1.0)
    case = make_case([one_storey(1.0, bouc_wen=soft), one_storey(0.5)],
                     spectrum=dataclasses.replace(KANAI_TAJIMI_SI, G0=0.5), gap=0.5, duration=30.0)
    with pytest.raises(SimulationError, match="record"):
        simulate(case, records=4, seed=0, settings=Settings(displacement_limit=0.5))
