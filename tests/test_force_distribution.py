"""The distribution of F_max: the closed form (G31) against Monte Carlo, and the Monte Carlo's own intervals
against their nominal coverage."""

import numpy as np
import pytest

from pounding import estimate, load_case, simulate
from pounding.cli.commands import main
from pounding.simulation.result import quantile_interval, wilson_interval


@pytest.fixture(scope="module")
def frequent_grid_errors():
    """Closed-form fractile / 500 records' fractile - 1 on every frequent-pounding case of the accuracy grid."""
    from pounding.studies.paper_tables import accuracy_cases

    errors = {}
    for case in accuracy_cases():
        closed = estimate(case)
        if closed.accuracy_regime != "frequent":
            continue
        records = simulate(case, records=500, seed=3).force_max
        errors[case.name] = [closed.force_max_distribution.quantile(p) / np.quantile(records, p) - 1 for p in (0.5, 0.84)]
    return errors


@pytest.mark.slow
def test_closed_form_fractiles_on_the_frequent_grid_cases(frequent_grid_errors):
    """The median and the 84th percentile within 10 % of 500 records' on 14 of the 16 frequent-pounding cases and within
    15 % on all: the two outside inherit the error of the mean (docs/accuracy.md, "The distribution of F_max")."""
    errors = np.array(list(frequent_grid_errors.values()))
    assert len(errors) == 16
    assert np.all(np.abs(errors) <= 0.15), frequent_grid_errors
    for column in (0, 1):
        assert np.sum(np.abs(errors[:, column]) <= 0.10) >= 14, frequent_grid_errors


def test_the_distribution_has_the_estimates_mean_and_no_impact_probability():
    """int P(F_max > f) df is G19's E[F_max]; P(F_max = 0) is close to 1 - the pounding probability of G21
    (G31 counts the impacting motion at v = 0, as G19 does; G21 the free motion the first impact meets)."""
    for name in ("section5-T2-0.4", "section6-T2-0.8-nonstationary"):
        closed = estimate(load_case(name))
        distribution = closed.force_max_distribution
        assert distribution.mean() == pytest.approx(closed.force_expected, rel=1e-3)
        assert distribution.no_impact_probability == pytest.approx(1 - closed.pounding_probability, rel=0.05, abs=1e-12)
        assert np.all(np.diff(distribution.cdf) >= 0) and distribution.cdf[-1] == pytest.approx(1.0, abs=1e-9)


def test_a_wide_gap_has_no_force_at_its_quantiles():
    case = load_case("section5-T2-0.4")
    import dataclasses

    wide = case.with_contact(gap=0.6)
    closed = estimate(wide)
    assert closed.force_max_distribution.quantile(0.5) == 0.0
    assert closed.probability_exceeding(1e3) <= closed.pounding_probability + 1e-12


def test_order_statistic_intervals_cover_the_true_quantile():
    """Exponential samples of 60: the 95 % interval of the median and of the 84th percentile covers the true
    quantile in at least 93 % of 2000 repetitions (nominal >= 95 %)."""
    rng = np.random.default_rng(7)
    for probability in (0.5, 0.84):
        truth = -np.log(1 - probability)
        covered = 0
        for _ in range(2000):
            _, low, high = quantile_interval(rng.exponential(size=60), probability)
            covered += low <= truth < high
        assert covered / 2000 >= 0.93


def test_wilson_interval_coverage():
    rng = np.random.default_rng(8)
    hits = rng.binomial(80, 0.3, size=4000)
    covered = np.mean([low <= 0.3 <= high for low, high in (wilson_interval(int(k), 80) for k in hits)])
    assert 0.93 <= covered <= 0.98


def test_capacity_must_be_positive(capsys):
    with pytest.raises(SystemExit) as caught:
        main(["estimate", "section5-T2-0.4", "--capacity", "0"])
    assert caught.value.code == 2 and "--capacity" in capsys.readouterr().err


def test_capacity_in_kgf_is_the_same_capacity_in_newtons(capsys):
    """--capacity is in the forces' display unit: kN, or kgf with --units kgf-cm-s, converted once: 30,000 kgf is
    294.1995 kN, 294,199.5 N."""
    import json

    for arguments in (["--capacity", "30000", "--units", "kgf-cm-s"], ["--capacity", "294.1995"]):
        assert main(["estimate", "section5-T2-0.4", "--json", *arguments]) == 0
        out = json.loads(capsys.readouterr().out)
        assert out["capacity"] == pytest.approx(294199.5)
        probability = out["probability_exceeding"]
    assert main(["estimate", "section5-T2-0.4", "--capacity", "30000", "--units", "kgf-cm-s"]) == 0
    text = capsys.readouterr().out
    assert "P(F_max > 30,000 kgf)" in text and f"{100 * probability:.1f} %" in text and " kN" not in text.split("paper")[0]
    assert "yield force 1097 kgf" in text  # the paper's storey: 1097 kgf/cm x its 1 cm yield drift


def test_the_gap_for_a_capacity_holds_the_records_to_the_target():
    """The gap sized to a force (issue 34): on the paper's case, where the closed form is in its home regime, 600
    records simulated at that gap exceed the capacity about as often as the target allows (5 %, within the Monte
    Carlo's noise and the closed form's measured error), while touching buildings exceed it far more often."""
    import dataclasses

    result = estimate(load_case("section5-T2-0.4"))
    capacity = 3.0e5
    gap = result.gap_for_capacity(capacity)
    assert 0.0 < gap < result.required_gap  # a force the slab takes needs less than no contact at all
    at_gap = result.case.with_contact(gap=gap)
    assert estimate(at_gap).probability_exceeding(capacity) == pytest.approx(0.05, abs=1e-3)
    fraction = simulate(at_gap, records=600, seed=3).exceedance(capacity)["probability_exceeding"]
    assert 0.025 <= fraction <= 0.10
    touching = result.case.with_contact(gap=0.0)
    assert simulate(touching, records=100, seed=3).exceedance(capacity)["probability_exceeding"] > 0.3
    # a weaker connection needs a wider gap; one stronger than any impact needs none
    assert result.gap_for_capacity(1.0e5) > gap
    assert result.gap_for_capacity(1.0e8) == 0.0
