"""Two states of a case on one page (pounding/report/comparison.py): the change is current minus pinned, in the
display units and in %; the inputs that differ are listed in those units; the page holds both states' numbers and
both curves, and needs no network."""

from __future__ import annotations

import dataclasses
import re

import pytest

from pounding import load_case
from pounding.display_units import display
from pounding.report import compute_snapshot, differences, write_comparison
from pounding.report.comparison import Difference, input_differences

DEFAULT = "section5-T2-0.4"


@pytest.fixture(scope="module")
def states():
    case = load_case(DEFAULT)
    wider = case.with_contact(gap=0.030, restitution=0.5)
    return compute_snapshot(case), compute_snapshot(wider)


def test_the_change_is_current_minus_pinned_with_its_unit_and_percent():
    shown = display("SI")
    force = Difference("expected extreme force", "force", 200e3, 150e3)
    assert force.change == -50e3 and force.relative_change == pytest.approx(-0.25)
    assert force.change_text(shown) == "-50 kN (-25 %)"
    assert Difference("gap", "length", 0.1, 0.125).change_text(shown) == "+25 mm (+25 %)"
    assert Difference("p", "probability", 0.4, 0.5).change_text(shown) == "+10 percentage points (+25 %)"
    assert Difference("f", "force", 0.0, 1e3).change_text(shown) == "+1 kN (from zero)"
    assert Difference("f", "force", 1e3, 1e3).change_text(shown) == "no change"
    assert Difference("f", "force", 2e3, 1e3).change_text(display("kgf-cm-s")).endswith("kgf (-50 %)")


def test_the_differences_are_the_two_estimates(states):
    pinned, current = states
    force, f84, probability, gap = differences(pinned.estimate, current.estimate)
    assert (force.pinned, force.current) == (pinned.estimate.force_expected, current.estimate.force_expected)
    assert f84.current == current.estimate.force_max_distribution.quantile(0.84)
    assert probability.pinned == pinned.estimate.pounding_probability
    assert (gap.pinned, gap.current) == (pinned.estimate.required_gap, current.estimate.required_gap)


def test_the_inputs_that_differ_are_listed_in_display_units(states):
    pinned, current = states
    assert input_differences(pinned.estimate, current.estimate, "SI") == [
        ("Contact, gap", "10", "30", "mm"), ("Contact, coefficient of restitution e", "0.65", "0.5", "-")]
    assert input_differences(pinned.estimate, current.estimate, "kgf-cm-s")[0] == ("Contact, gap", "1", "3", "cm")
    assert input_differences(pinned.estimate, pinned.estimate) == []


def test_the_comparison_page_holds_both_states_and_their_change(states, tmp_path):
    pinned, current = states
    path = write_comparison(tmp_path / "pair.html", pinned, current, names=("before", "after"))
    text = path.read_text()
    shown = display("SI")
    for d in differences(pinned.estimate, current.estimate):
        row = re.search(rf"<th>{re.escape(d.quantity)}</th>(.*?)</tr>", text)
        assert row, d.quantity
        assert re.findall(r"<td[^>]*>([^<]*)</td>", row.group(1)) == [
            d.value_text(d.pinned, shown), d.value_text(d.current, shown), d.change_text(shown)]
    assert "Pinned: before. Current: after." in text
    assert "<td>Contact, gap</td>" in text
    assert "<script src=" not in text and 'rel="stylesheet"' not in text  # opens offline
    visible = re.sub(r"<(script|style)\b[^>]*>.*?</\1>", "", text, flags=re.S)
    assert not re.search(r"sigma|\bEqs?\.|\(G\d+\)", visible)  # plain words: no symbol or equation label


def test_one_chart_holds_both_force_against_gap_curves(states):
    from pounding.report.comparison import _gap_chart

    pinned, current = states
    plot = _gap_chart(pinned, current, display("SI"))
    lines = {item.label.value: item.renderers[0].data_source.data for item in plot.legend[0].items}
    assert list(lines["pinned"]["y"]) == pytest.approx(pinned.gap_curve.force_expected / 1e3)
    assert list(lines["current"]["y"]) == pytest.approx(current.gap_curve.force_expected / 1e3)
    assert list(lines["current"]["x"]) == pytest.approx(current.gap_curve.gaps / 1e-3)
    dashes = {item.label.value: item.renderers[0].glyph.line_dash for item in plot.legend[0].items}
    assert dashes["pinned"] == [6] and dashes["current"] == []  # the pinned state dashed


def test_the_comparison_page_carries_each_states_monte_carlo_and_its_change(states, tmp_path):
    """Each state's check (check_estimate) travels with its snapshot: the page gives both Monte Carlo means, their
    change in the display units and in %, and whether each closed form agrees; a state without one says so."""
    from pounding.report.comparison import NO_MONTE_CARLO
    from pounding.studies.check import check_estimate

    pinned, current = states
    checks = [check_estimate(s.estimate, records=12, seed=1) for s in (pinned, current)]
    both = [dataclasses.replace(s, check=c) for s, c in zip(states, checks)]
    for units in ("SI", "kgf-cm-s"):
        text = write_comparison(tmp_path / f"pair-{units}.html", *both, units=units).read_text()
        shown = display(units)
        row = re.search(r'<tr class="monte-carlo">(.*?)</tr>', text).group(1)
        change = checks[1].force_max_mean - checks[0].force_max_mean
        assert re.findall(r"<td[^>]*>([^<]*)</td>", row) == [
            shown.force(checks[0].force_max_mean), shown.force(checks[1].force_max_mean),
            f"{'+' if change > 0 else ''}{shown.force(change)} ({100 * change / checks[0].force_max_mean:+.3g} %)"]
        assert f" {shown.force_unit} (" in re.findall(r"<td[^>]*>([^<]*)</td>", row)[2]
        verdicts = re.findall(r"<td[^>]*>([^<]*)</td>", re.search(r'<tr class="monte-carlo-verdict">(.*?)</tr>', text).group(1))
        for verdict, check in zip(verdicts, checks):
            assert verdict.startswith("agrees" if check.agrees else "does not agree") and "of 12 records" in verdict
    one = write_comparison(tmp_path / "one.html", pinned, both[1]).read_text()
    row = re.findall(r"<td[^>]*>([^<]*)</td>", re.search(r'<tr class="monte-carlo">(.*?)</tr>', one).group(1))
    assert row == ["n/a", display("SI").force(checks[1].force_max_mean), "n/a"]
    assert f'<td class="pinned">{NO_MONTE_CARLO}</td>' in one
    none = write_comparison(tmp_path / "none.html", pinned, current).read_text()
    assert 'class="monte-carlo"' not in none  # closed forms alone: no empty rows
