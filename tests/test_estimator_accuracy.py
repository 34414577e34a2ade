"""Both estimators against this project's Monte Carlo, on a representative
subset of the accuracy grid of validation/HISTORY.md (other seeds than the
documented table, so this is not a replay of it)."""

import dataclasses
import math
import re

import numpy as np
import pytest

from pounding import load_case, simulate
from pounding.closed_form.estimator import estimate
from pounding.closed_form.regimes import (
    MODERATE_GAP,
    MOVING_TOGETHER,
    NARROW_BAND_LIMIT,
    RESIDUAL_SHARE_LIMIT,
    accuracy_data,
)
from pounding.simulation.monte_carlo import design_gap
from pounding.studies.paper_tables import accuracy, accuracy_cases, mdof_case, random_case, varied_case
from tests.free_count import free_force

RECORDS = 200


def _monte_carlo(case, seed=31):
    result = simulate(case, records=RECORDS, seed=seed)
    return result.force_max_mean, result.force_max_std_error


@pytest.mark.parametrize(
    "case",
    [
        load_case("section5-T2-0.4"),
        load_case("section5-T2-0.8"),
        load_case("section6-T2-0.4"),
        load_case("section5-T2-0.4-nonstationary"),
        load_case("section6-T2-0.4-nonstationary"),
        varied_case(load_case("section5-T2-0.4"), restitution=0.4, name="e0.4"),
        varied_case(load_case("section5-T2-0.4"), gap=0.05, name="gap 5 cm"),
        varied_case(load_case("section5-T2-0.4"), g0=4.0, name="G0 x 4"),
        mdof_case(),
    ],
    ids=lambda case: case.name,
)
def test_recommended_estimate_within_ten_percent(case):
    """Where the gap is below sigma_X the recommended estimate was measured
    within 10 % on 22 of 26 grid cases; these are among them."""
    mean, error = _monte_carlo(case)
    result = estimate(case)
    assert result.sigma_relative_displacement > case.contact.gap
    assert not any("Only the largest swings close this gap" in warning for warning in result.warnings)
    assert abs(result.force_expected - mean) < 0.10 * mean + 3 * error
    if case.name.startswith(("section5", "section6")):
        # The paper's own cases (e = 0.65): its estimator was measured 10-21 % low, the
        # 20-30 % of NOTES.md's independent check less the errata fixed here.
        assert mean * 0.70 - 3 * error < result.paper.force_expected < mean * 0.97 + 3 * error


def test_elastic_pair_far_from_the_mean_within_ten_percent():
    """An exactly Gaussian relative motion at 1.5 sigma_X: the time cut counts
    the impacts (documented +2.4 %; the mirror returns it replaced gave +13.6 %)."""
    case = varied_case(load_case("section5-T2-0.4"), elastic=True, gap=0.06)
    result = simulate(case, records=600, seed=31)
    estimated = estimate(case).force_expected
    assert abs(estimated - result.force_max_mean) < 0.10 * result.force_max_mean + 3 * result.force_max_std_error


@pytest.mark.parametrize("name", ["section5-T2-0.4", "section5-T2-0.4-nonstationary"])
def test_separation_rules_rest_on_the_floors_expected_peaks(name):
    """Elastic buildings that never touch (exactly Gaussian floors): each floor's
    expected peak |x| within 5 % of the simulated mean (documented -5 % to +2 %;
    Davenport's stationary factor, used before, put it +10 % to +20 % high), and
    the three rules built from the two peaks as SRSS, ABS and DDC define them."""
    case = varied_case(load_case(name), elastic=True, gap=2.0, name="apart")
    result = simulate(case, records=300, seed=17)
    assert result.impacts.sum() == 0
    rules = estimate(case).separation_rules
    simulated = result.displacement_max.mean(axis=0)
    error = result.displacement_max.std(axis=0, ddof=1) / math.sqrt(result.n_records)
    u1, u2 = rules["peak_displacement"]
    np.testing.assert_array_less(np.abs([u1, u2] - simulated), 0.05 * simulated + 2 * error)
    rho = rules["displacement_correlation"]
    assert -1 <= rho <= 1
    assert rules["srss"] == pytest.approx(math.hypot(u1, u2), rel=1e-12)
    assert rules["abs"] == pytest.approx(u1 + u2, rel=1e-12)
    assert rules["ddc"] == pytest.approx(math.sqrt(u1**2 + u2**2 - 2 * rho * u1 * u2), rel=1e-12)


def test_recommended_beats_the_paper_where_the_paper_is_weakest():
    """Eq. 14's e^1.2 scaling: at e = 0.4 the paper's estimate is far low
    (documented -65 %), the recommended one is not."""
    case = varied_case(load_case("section5-T2-0.4"), restitution=0.4)
    mean, _ = _monte_carlo(case)
    result = estimate(case)
    assert result.paper.force_expected < 0.5 * mean
    assert abs(result.force_expected / mean - 1) < 0.1


def test_nearly_elastic_perfectly_plastic_frames_are_overestimated():
    """The documented high side: the Section 6 frames (alpha = 0.02), +14 % for
    T2 = 0.8 s. Their Gaussian free-motion count is right (+2 %), so the time
    cut's generous count of returns is not offset there (validation/HISTORY.md).
    Before the residual the same case was 15 % low; it must now lie on the
    safe side."""
    case = load_case("section6-T2-0.8")
    mean, error = _monte_carlo(case)
    estimated = estimate(case).force_expected
    assert mean - 3 * error < estimated < 1.20 * mean + 3 * error


@pytest.mark.parametrize("gap_over_sigma", [2.0, 2.5, 3.0])
def test_pounding_probability_against_the_simulated_fraction(gap_over_sigma):
    """Elastic pair, narrow-band relative motion: Vanmarcke's clumps make the
    Poisson count of impacts a probability of pounding."""
    base = varied_case(load_case("section5-T2-0.4"), elastic=True)
    sigma = estimate(base).sigma_relative_displacement
    case = base.with_contact(gap=gap_over_sigma * sigma)
    result = simulate(case, records=400, seed=41)
    predicted = estimate(case).pounding_probability
    fraction = result.pounding_fraction
    sampling = math.sqrt(max(fraction * (1 - fraction), 0.01) / 400)
    assert abs(predicted - fraction) < 0.05 + 3 * sampling


def test_rare_pounding_of_yielding_buildings_is_flagged():
    case = varied_case(load_case("section5-T2-0.4"), g0=0.25, gap=0.05)
    result = estimate(case)
    assert result.sigma_relative_displacement < case.contact.gap
    assert any("Only the largest swings close this gap" in warning and "pounding estimate --check" in warning for warning in result.warnings)
    assert "where the gap exceeds the RMS relative displacement" in result.measured_accuracy and _measured(result, "rare, yielding")


def _measured(result, entry: str, spectrum: str = "kanai-tajimi") -> bool:
    """Whether ``result`` states the accuracy measured for ``entry`` of
    ``pounding/data/accuracy.json`` (its span of errors and its count of cases)."""
    measured = accuracy_data()["force"][spectrum][entry]
    span = f"{100 * measured['low']:+.0f} % to {100 * measured['high']:+.0f} %"
    stated = result.accuracy.statement(with_verdict=True)
    return span in stated and f"of {measured['cases']} cases" in stated


def _share(result) -> float:
    """How much the residual's response adds to sigma_X or sigma_V, the larger."""
    return max(result.sigma_relative_displacement / result.response.sigma_relative_displacement,
               result.sigma_relative_velocity / result.response.sigma_relative_velocity) - 1.0


def _at_gap(case, gap_over_sigma):
    sigma = estimate(case).sigma_relative_displacement
    return case.with_contact(gap=gap_over_sigma * sigma)


def test_the_measured_accuracy_stated_is_that_of_the_regime():
    """Each regime follows from the estimate's own statistics, and the accuracy
    line and warnings are those measured for it: frequent pounding (gap below
    sigma_X / 2, broad band, small residual), a moderate gap, a narrow band, a
    large residual, rare pounding of an elastic pair."""
    frequent = estimate(load_case("section5-T2-0.4"))
    assert frequent.accuracy_regime == "frequent"
    assert frequent.case.contact.gap < MODERATE_GAP * frequent.sigma_relative_displacement
    assert frequent.crossings.bandwidth >= NARROW_BAND_LIMIT and _share(frequent) <= RESIDUAL_SHARE_LIMIT
    assert _measured(frequent, "frequent")
    assert not any("pounding simulate" in w and not w.startswith("The gap for") for w in frequent.warnings)

    moderate = estimate(_at_gap(load_case("section5-T2-0.4"), 0.75))
    assert moderate.accuracy_regime == "moderate gap"
    assert _measured(moderate, "moderate gap")
    assert any("The gap is 0.5 to 1 times the RMS relative displacement" in w for w in moderate.warnings)

    narrow = estimate(varied_case(load_case("section5-T2-0.4"), elastic=True, gap=0.01))
    assert narrow.crossings.bandwidth < NARROW_BAND_LIMIT and narrow.accuracy_regime == "narrow band"
    assert _measured(narrow, "narrow band")
    assert any("sway at nearly one frequency" in w for w in narrow.warnings)

    frames = estimate(load_case("section6-T2-0.8"))
    assert _share(frames) > RESIDUAL_SHARE_LIMIT and frames.accuracy_regime == "large residual"
    assert _measured(frames, "large residual")
    assert any(f"sway {100 * _share(frames):.0f} % more than their linear equivalent" in w for w in frames.warnings)

    rare = estimate(_at_gap(varied_case(load_case("section5-T2-0.4"), elastic=True), 2.0))
    assert rare.accuracy_regime == "rare"
    assert "where the gap exceeds the RMS relative displacement" in rare.measured_accuracy and _measured(rare, "rare, elastic")
    assert rare.to_dict()["measured_accuracy"] == rare.measured_accuracy
    assert rare.to_dict()["accuracy_regime"] == "rare"


def test_no_range_wider_than_30_percent_is_printed_without_a_verdict():
    """Issue 32: an estimate without its Monte Carlo check prints no measured range wider than 30 % either side, in
    its accuracy line or its warnings; it says how often it was within 10 % instead, and the range stands beside a
    verdict (``statement(with_verdict=True)``)."""
    ranges = re.compile(r"([-+]?[\d,]+) % to ([-+]?[\d,]+) %")
    wide_seen = False
    for case in accuracy_cases():
        result = estimate(case)
        for text in (result.measured_accuracy, *result.warnings):
            for low, high in ranges.findall(text):
                assert abs(int(low.replace(",", ""))) <= 30 and abs(int(high.replace(",", ""))) <= 30, (case.name, text)
        if not result.accuracy.signable:
            wide_seen = True
            assert "check this case against Monte Carlo" in result.measured_accuracy
            assert ranges.search(result.accuracy.statement(with_verdict=True))
    assert wide_seen  # the grid holds regimes measured wider than 30 %: the rule was exercised


def test_storeys_with_another_loop_state_the_accuracy_measured_on_such_storeys():
    """A yielding storey given the engineer's way (Wen's symmetric loop, beta_share 0.5) is not what the grid measured
    (beta_share 1.5 and 2): its estimate states accuracy.json's "other loops" row of its regime (the grid's
    engineer's storeys and validation/storey_accuracy.py), the paper's loop the grid's; elastic storeys have no loop and keep the grid's."""
    from pounding.mechanics.structures import BoucWen

    paper = load_case("section5-T2-0.4")
    symmetric = dataclasses.replace(paper, buildings=tuple(
        dataclasses.replace(b, storeys=tuple(dataclasses.replace(st, bouc_wen=BoucWen.from_yield_drift(0.01, 0.05, 1.0, 0.5))
                                             for st in b.storeys)) for b in paper.buildings))
    result = estimate(symmetric)
    assert result.accuracy_regime != "rare"
    row = accuracy_data()["force"]["other loops"][result.accuracy_regime]
    assert row["cases"] > 0  # measured there: not the Kanai-Tajimi row it falls back to
    assert (result.accuracy.low, result.accuracy.high, result.accuracy.cases) == (row["low"], row["high"], row["cases"])
    assert f"on {row['within_10_percent']} of {row['cases']} cases" in result.measured_accuracy
    grid = estimate(paper).accuracy
    frequent = accuracy_data()["force"]["kanai-tajimi"]["frequent"]
    assert (grid.low, grid.high, grid.cases) == (frequent["low"], frequent["high"], frequent["cases"])
    elastic = estimate(varied_case(paper, elastic=True)).accuracy
    assert elastic.cases != row["cases"] or elastic.low != row["low"]


def _stated_range(text):
    """The lower and upper error [-] of a measured-accuracy text, 'Measured a % to b %'."""
    low, high = re.search(r"Measured ([-+]\d+) % to ([-+]\d+) %", text).groups()
    return int(low) / 100, int(high) / 100


@pytest.mark.slow
@pytest.mark.parametrize("regime, family, count", [("frequent", "SDOF", 4), ("moderate gap", "SDOF", 2), ("narrow band", "elastic", 2)])
def test_stated_range_holds_on_cases_drawn_afresh(regime, family, count):
    """The range stated for each regime was measured on the grid and on random
    draws (validation/out_of_sample.py, seeds 2026-2028; ``random_case``); on cases
    drawn with another seed, the first few the estimator places in that regime
    must fall within it (Monte Carlo's sampling error allowed)."""
    rng = np.random.default_rng(7)
    checked = drawn = 0
    while checked < count:
        drawn += 1
        assert drawn < 200, f"no {regime} case among 200 drawn"
        case = random_case(family, rng, drawn)
        result = estimate(case)
        if result.accuracy_regime != regime:
            continue
        low, high = _stated_range(result.accuracy.statement(with_verdict=True))
        mean, error = _monte_carlo(case)
        assert (1 + low) * mean - 3 * error < result.force_expected < (1 + high) * mean + 3 * error, case.name
        checked += 1


def test_impacts_expected_tracks_the_simulated_count_when_pounding_is_frequent():
    """The time cut doubles Rice's rate at the mean position (impacts start only
    from below the gap): the simulated count of impacts is then far above
    Rice's and near the estimate (8.7 against 10.6 for Section 5, T2 = 0.4 s)."""
    case = load_case("section5-T2-0.4")
    result = estimate(case)
    simulated = simulate(case, records=RECORDS, seed=32).impacts_mean
    rice = result.upcrossing_rate * case.excitation.duration
    assert rice < 0.6 * simulated
    assert result.impacts_expected == pytest.approx(simulated, rel=0.3)
    assert np.isfinite(result.required_gap) and result.required_gap > case.contact.gap


@pytest.mark.slow
@pytest.mark.parametrize("periods", [(1.2, 0.8), (1.2, 0.4)])
def test_required_gap_is_on_the_safe_side_for_elastic_pairs(periods):
    """At the gap given for 95 % probability of no pounding, the simulated
    fraction of records that pound is at most 5 % (within sampling error).
    Vanmarcke's clumps gave 7.7 % for the close periods 1.2 / 0.8 s."""
    case = varied_case(load_case("section5-T2-0.4"), elastic=True, periods=periods)
    result = estimate(case, target_probability=0.95)
    at_gap = case.with_contact(gap=result.required_gap)
    records = 1500
    fraction = simulate(at_gap, records=records, seed=43).pounding_fraction
    assert fraction <= 0.05 + 2.5 * math.sqrt(0.05 * 0.95 / records)


def test_peak_force_given_the_velocity_includes_the_buildings_forces():
    """Far from the mean position (an elastic pair, gap 1.5 sigma_X) the
    buildings' restoring forces brake every impact. Record by record, the
    simulated largest force against the law's peak for the record's largest
    approach velocity: with the estimator's opposing force the two agree on
    average; for free masses the law overstates the force."""
    from pounding.mechanics.contact import impact_peak_force

    case = varied_case(load_case("section5-T2-0.4"), elastic=True, gap=0.06)
    result = estimate(case)
    simulated = simulate(case, records=RECORDS, seed=33)
    pounded = simulated.impact_velocity_max > 0
    velocity, force = simulated.impact_velocity_max[pounded], simulated.force_max[pounded]
    braked = impact_peak_force(case.contact, velocity, case.reduced_mass, result.opposing_force)
    free = impact_peak_force(case.contact, velocity, case.reduced_mass)
    assert np.mean(force / braked) == pytest.approx(1.0, abs=0.02)
    assert np.mean(force / free) < 0.96


def _clough_penzien(case):
    from pounding.hazard.excitation import CloughPenzien

    s = case.excitation.spectrum
    spectrum = CloughPenzien(s.G0, s.omega_g, s.xi_g, omega_f=2.0, xi_f=0.6)
    return dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, spectrum=spectrum))


def test_plastic_drift_without_low_frequency_motion_is_flagged_and_real():
    """With a Clough-Penzien spectrum the linearized yielding pair drifts only
    through the linearization's residual; the simulated one drifts further and
    pounds at the gap the estimate gives for 95 % no pounding more often than
    5 % (documented 10.6 % with 1,000 records). The estimate says so."""
    case = _clough_penzien(load_case("section5-T2-0.8"))
    result = estimate(case, target_probability=0.95)
    assert any("drift" in warning and "pounding estimate --check" in warning for warning in result.warnings)
    assert "Clough-Penzien" in result.measured_accuracy
    at_gap = case.with_contact(gap=result.required_gap)
    records = 400
    fraction = simulate(at_gap, records=records, seed=44).pounding_fraction
    assert fraction > 0.05 + 2 * math.sqrt(0.05 * 0.95 / records)


def test_elastic_pairs_get_no_drift_warning():
    case = _clough_penzien(varied_case(load_case("section5-T2-0.4"), elastic=True))
    result = estimate(case)
    assert not any("drift" in warning for warning in result.warnings)
    assert "Clough-Penzien" in result.measured_accuracy


def test_narrow_band_pairs_are_flagged_where_vanmarcke_over_clumps():
    """Close periods (1.2 / 0.8 s, bandwidth q = 0.21): the clump factor counts
    too few independent approaches far from the mean (documented -26 % at
    1.5 sigma_X), so the estimate must carry the narrow-band warning; the
    broad-band Section 5 pair must not."""
    base = varied_case(load_case("section5-T2-0.4"), elastic=True, periods=(1.2, 0.8))
    sigma = estimate(base).sigma_relative_displacement
    case = base.with_contact(gap=1.5 * sigma)
    result = estimate(case)
    assert result.crossings.bandwidth < 0.3
    assert any("sway at nearly one frequency" in warning and "pounding estimate --check" in warning for warning in result.warnings)
    mean, error = _monte_carlo(case)
    assert result.force_expected < 0.9 * mean - error
    assert not any("sway at nearly one frequency" in warning for warning in estimate(load_case("section5-T2-0.4")).warnings)


def test_accuracy_rows_carry_the_regime_and_no_relative_error_without_pounding():
    """``validate --grid``'s rows: a case where no record pounds has no relative error (not a division by
    zero), and each row states the regime its estimate gives."""
    wide = varied_case(load_case("section5-T2-0.4"), gap=1.0, name="wide gap")  # far beyond any record's peak
    near = load_case("section5-T2-0.4")
    rows = accuracy([wide, near], records=2, seed=1)
    assert rows[0].monte_carlo == 0.0 and rows[0].recommended_error is None and rows[0].paper_error is None
    assert rows[1].monte_carlo > 0.0 and rows[1].recommended_error is not None
    assert [row.accuracy_regime for row in rows] == ["rare", "frequent"]


def test_accuracy_rows_say_where_the_closed_form_refuses():
    """The grid's elastic-perfectly plastic storeys: the row keeps the Monte Carlo and the reason, with no estimate
    and no error (not a crash of the whole grid, not a number the closed form does not have)."""
    from pounding.studies.storey_grid import engineer_storey_cases

    plastic = next(case for case in engineer_storey_cases() if "post-yield 0," in case.name)
    (row,) = accuracy([plastic], records=2, seed=1)
    assert row.refused and "elastic-perfectly plastic" in row.refused and row.accuracy_regime == "refused"
    assert row.recommended is None and row.recommended_error is None and row.monte_carlo > 0.0


@pytest.mark.slow
def test_design_gap_statement_follows_whether_the_floors_move_together():
    """The closed-form gap for 95 % was measured safe for one-storey yielding pairs whose contact floors move
    less together (correlation of x1, x2 below MOVING_TOGETHER: at most 0.072 of records pounding, mean 0.035) and
    unsafe for those that move together (mean 0.070). On pairs drawn with another seed, five of each: the first
    stay within sampling of 0.05 (3 standard errors of 400 records), the second pound more often, and only they
    carry the note."""
    rng = np.random.default_rng(7)
    fractions = {True: [], False: []}
    drawn = 0
    while min(len(v) for v in fractions.values()) < 5:
        drawn += 1
        assert drawn < 200
        case = random_case("SDOF", rng, drawn)
        result = estimate(case)
        together = result.response.correlation_displacement >= MOVING_TOGETHER
        if len(fractions[together]) == 5:
            continue
        fractions[together].append(design_gap(case, 0.95, records=400, seed=9).pounding_fraction(result.required_gap))
        noted = [w for w in result.warnings if "the floors move together" in w]
        assert len(noted) == int(together), case.name
        # The gap for 95 % is flagged only where it was measured unsafe: for pairs whose floors move together.
        assert any(w.startswith("The gap for 95 % lies in the motion's tail") for w in result.warnings) == together, case.name
    assert max(fractions[False]) <= 0.05 + 3 * math.sqrt(0.05 * 0.95 / 400), fractions[False]
    assert np.mean(fractions[True]) > np.mean(fractions[False]) + 0.02, fractions


def _elastic_pair(periods, g0, restitution, gap=0.0):
    return varied_case(load_case("section5-T2-0.4"), elastic=True, periods=periods, g0=g0, restitution=restitution, gap=gap,
                       name=f"elastic {periods[0]}/{periods[1]} s G0x{g0} e {restitution} gap {gap} m")


def test_impacts_damp_a_pair_that_remembers_them_and_the_force_can_grow_with_the_gap():
    """Elastic buildings of 0.61 and 0.48 s, e = 0.42 (drawn with seed 1, not
    from the draws the model was chosen on): near the mean position the impacts,
    about every half period, take energy the lightly damped pair remembers.
    Monte Carlo's force grows with the gap there (fewer impacts damp the motion
    less: 1.69 MN at gap 0, 1.83 MN at 1.66 cm in validation/HISTORY.md, 400
    records). The estimate must be within 10 % at both gaps and grow between
    them; counted on the free motion it was 73 % high at gap 0 and fell with
    the gap."""
    estimates, means = [], []
    for gap in (0.0, 0.0166):
        case = _elastic_pair((0.61, 0.48), 5.86, 0.42, gap)
        result = estimate(case)
        mean, error = _monte_carlo(case)
        assert abs(result.force_expected / mean - 1) < 0.10 + 2 * error / mean, case.name
        assert result.impacting_velocity_ratio < 0.9
        assert free_force(case, result.crossings, case.contact.gap)[0] > 1.25 * mean  # the free count misses it
        estimates.append(result.force_expected)
        means.append(mean)
    assert estimates[1] > estimates[0] and means[1] > means[0]


def test_close_periods_near_the_mean_within_ten_percent():
    """0.42 and 0.31 s elastic buildings (bandwidth of X 0.16) at 1.7 cm, a third of
    sigma_X: the free count put the force 31 % above Monte Carlo (validation/HISTORY.md,
    draw 2027, one of the draws the model was chosen on; another Monte Carlo seed
    here); the damped count must be within 10 %."""
    case = _elastic_pair((0.42, 0.31), 17.92, 0.54, 0.017)
    result = estimate(case)
    assert result.crossings.bandwidth < 0.3 and result.impact_memory > 0.3
    mean, error = _monte_carlo(case)
    assert abs(result.force_expected / mean - 1) < 0.10 + 2 * error / mean
