"""The gap for a target probability of no pounding by Monte Carlo: a record
pounds at gap d exactly when its free relative displacement exceeds d, since
the buildings move freely until the first contact."""

import dataclasses
import json

import numpy as np
import pytest
from scipy.stats import binom

from pounding import load_case, simulate
from pounding.errors import ArgumentError
from pounding.hazard.excitation import ground_accelerations
from pounding.simulation.monte_carlo import design_gap, integrate, records_for_bound

from .test_cli import run

CASE = load_case("section5-T2-0.8")


def _at_gap(case, gap):
    return case.with_contact(gap=gap)


def test_free_peak_is_the_peak_of_the_recorded_history():
    """The kernel's peak of X = x1 - x2 is the largest value over the accepted
    steps that the full time history of the same record stores."""
    free = _at_gap(CASE, 20.0)
    record = ground_accelerations(free.excitation, 4, [0])[0]
    history = integrate(free, record, free.excitation.time_step)
    peak = np.max(history.penetration + free.contact.gap)
    assert simulate(free, records=1, seed=4).relative_displacement_max[0] == pytest.approx(peak, rel=1e-12)
    assert history.summary["relative_displacement_max"] == pytest.approx(peak, rel=1e-12)


def test_records_pound_exactly_where_their_free_peak_exceeds_the_gap():
    """Simulated with contact at the design gap and at the median peak, the
    records that pound are, one by one, those whose free peak exceeds the gap."""
    result = design_gap(CASE, target_probability=0.9, records=40, seed=5)
    for gap in (result.gap, float(np.median(result.peaks))):
        pounded = simulate(_at_gap(CASE, gap), records=40, seed=5).impacts > 0
        np.testing.assert_array_equal(pounded, result.peaks > gap)
        assert result.pounding_fraction(gap) == pytest.approx(np.mean(pounded))


def test_design_gap_is_the_smallest_peak_meeting_the_target():
    result = design_gap(CASE, target_probability=0.9, records=40, seed=5)
    assert result.pounding_fraction(result.gap) <= 0.1
    lower = np.sort(result.peaks)[np.sort(result.peaks) < result.gap]
    assert result.pounding_fraction(lower[-1]) > 0.1
    # The bound: the first order statistic that lies above the true 90 % quantile with probability 0.9.
    rank = int(binom.ppf(0.9, 40, 0.9))
    assert binom.cdf(rank, 40, 0.9) >= 0.9 > binom.cdf(rank - 1, 40, 0.9)
    assert result.upper_bound == np.sort(result.peaks)[rank] >= result.gap


def test_design_gap_is_reproducible_and_ignores_the_case_gap():
    first = design_gap(CASE, records=30, seed=2)
    second = design_gap(_at_gap(CASE, 0.0), records=30, seed=2)
    np.testing.assert_array_equal(first.peaks, second.peaks)


def test_bad_target_probability_names_the_field():
    with pytest.raises(ArgumentError, match="target_probability"):
        design_gap(CASE, target_probability=1.0, records=5)
    out = run("simulate", "section5-T2-0.4", "--design-gap", "0", "--records", "5")
    assert out.returncode == 2 and "--design-gap" in out.stderr and "Traceback" not in out.stderr


def test_command_line_gives_both_gaps_in_json():
    out = run("simulate", "section5-T2-0.8", "--design-gap", "0.9", "--records", "12", "--seed", "5", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    expected = design_gap(CASE, target_probability=0.9, records=12, seed=5)
    assert data["design_gap"] == pytest.approx(expected.gap, rel=1e-12)
    assert data["design_gap_upper_bound_90"] is None  # too few records: no bound, not an infinity JSON cannot hold
    assert data["closed_form_required_gap"] > 0


@pytest.mark.parametrize("target", [0.8, 0.95])
def test_records_for_bound_is_where_the_bound_starts(target):
    """One record fewer than ``records_for_bound`` gives no 90 % bound; that many give one."""
    fewest = records_for_bound(target)
    short = design_gap(CASE, target_probability=target, records=fewest - 1, seed=6)
    enough = design_gap(CASE, target_probability=target, records=fewest, seed=6)
    assert np.isinf(short.upper_bound) and np.isfinite(enough.upper_bound)
    assert enough.upper_bound == enough.peaks.max()  # with the fewest records, only the largest peak bounds it


def test_code_checks_state_each_rule_against_the_gap_entered():
    """EN 1998-1 4.4.2.7(3) and ASCE 7-16 Eq. 12.12-2 take the SRSS of the floors' peaks, the DDC rule their double
    difference (between |u1 - u2| and u1 + u2 for any correlation); each is met exactly from its required gap on."""
    import dataclasses
    import math

    from pounding import estimate, load_case

    case = load_case("section5-T2-0.4")
    result = estimate(case)
    u1, u2 = result.separation_rules["peak_displacement"]
    checks = {check.code: check for check in result.code_checks}
    assert set(checks) == {"EN 1998-1", "ASCE 7-16", "DDC rule"}
    assert checks["EN 1998-1"].required_gap == pytest.approx(math.hypot(u1, u2), rel=1e-12)
    assert checks["ASCE 7-16"].required_gap == pytest.approx(math.hypot(u1, u2), rel=1e-12)
    assert abs(u1 - u2) <= checks["DDC rule"].required_gap <= u1 + u2
    assert not any(check.met for check in result.code_checks)  # 1 cm against peaks of 18 cm and 2.5 cm
    for check in result.code_checks:
        for factor, met in ((0.999, False), (1.001, True)):
            wider = case.with_contact(gap=factor * check.required_gap)
            assert {c.code: c.met for c in estimate(wider).code_checks}[check.code] is met
    (entry, *_) = result.to_dict()["code_checks"]
    assert set(entry) >= {"code", "clause", "required_gap", "met"} and entry["required_gap"] == checks["EN 1998-1"].required_gap
