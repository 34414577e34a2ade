"""Pin and compare in process (dashboard/pinning.py): a pinned state is kept as computed while the inputs change;
the headline's comparison, the force-against-gap overlay and the distribution's are the two estimates the library
gives for the two cases, their change is current minus pinned; Unpin gives the single state back."""

from __future__ import annotations

import dataclasses
import re

import pytest

from dashboard.headline import headline_html
from dashboard.model import PoundingModel
from dashboard.pinning import PINNED_LABEL, PinnedOverlay, overlay_distribution, pinned_html
from pounding import estimate, load_case
from pounding.display_units import display

DEFAULT = "section5-T2-0.4"


def _at_gap(gap_m: float):
    case = load_case(DEFAULT)
    return case.with_contact(gap=gap_m)


def _cells(text: str, row: str) -> list[str]:
    """The cells (pinned, current, change) of the comparison's row ``row`` (its CSS class) in the headline."""
    found = re.search(rf'<tr class="{row}"><th>[^<]*</th>(.*?)</tr>', text)
    assert found, row
    return re.findall(r"<td[^>]*>([^<]*)</td>", found.group(1))


def test_pin_keeps_the_estimate_and_a_new_gap_is_compared_with_the_librarys_numbers():
    model = PoundingModel()
    assert model.pinned is None and model.comparison() is None
    assert model.pin()
    kept = model.result
    assert model.pinned.estimate is kept and model.pinned.name == DEFAULT  # the estimate itself: nothing recomputed
    model.gap = 30.0  # mm
    assert model.result is not kept and model.pinned.estimate is kept

    pinned, current = estimate(_at_gap(0.010)), estimate(_at_gap(0.030))  # the library, directly
    force, f84, probability, gap = model.comparison()
    assert force.pinned == pytest.approx(pinned.force_expected, rel=1e-9)
    assert force.current == pytest.approx(current.force_expected, rel=1e-9)
    assert force.change == pytest.approx(current.force_expected - pinned.force_expected, rel=1e-6)
    assert force.relative_change == pytest.approx(current.force_expected / pinned.force_expected - 1, rel=1e-6)
    assert force.change < 0  # a wider gap: a smaller expected force
    assert f84.change == pytest.approx(current.force_max_distribution.quantile(0.84) - pinned.force_max_distribution.quantile(0.84), rel=1e-6)
    assert probability.change == pytest.approx(current.pounding_probability - pinned.pounding_probability, rel=1e-6, abs=1e-12)
    assert gap.current == pytest.approx(current.required_gap, rel=1e-9) and gap.pinned == pytest.approx(pinned.required_gap, rel=1e-9)

    shown = display("SI")
    text = headline_html(model.result, "SI", pinned=pinned_html(model.pinned, model.result, "SI"))
    change = force.change / 1e3
    assert _cells(text, "pin-force") == [shown.force(pinned.force_expected), shown.force(current.force_expected),
                                         f"{change:.4g} kN ({100 * force.relative_change:+.3g} %)"]
    assert ">pinned<" in text and ">current<" in text and f"Pinned: {DEFAULT}." in text


def test_the_comparison_follows_the_unit_switch():
    model = PoundingModel()
    model.pin()
    model.gap = 20.0
    model.units = "kgf-cm-s"
    force = model.comparison()[0]
    text = pinned_html(model.pinned, model.result, model.units)
    assert _cells(text, "pin-force")[2].startswith(f"{force.change / display('kgf-cm-s').force_scale:,.0f} kgf")
    assert _cells(text, "pin-gap")[0] == display("kgf-cm-s").length(model.pinned.estimate.required_gap)


def test_unpin_gives_back_the_single_state():
    model = PoundingModel()
    single = headline_html(model.result, "SI")
    model.pin()
    assert 'class="pinned"' in headline_html(model.result, "SI", pinned=pinned_html(model.pinned, model.result))
    model.unpin()
    assert model.pinned is None and model.comparison() is None and pinned_html(model.pinned, model.result) == ""
    assert headline_html(model.result, "SI", pinned=pinned_html(model.pinned, model.result)) == single


def test_nothing_is_pinned_without_a_valid_state():
    model = PoundingModel()
    model.param.update(ground_motion="design spectrum", code="ASCE 7-16", SDS=0.2, SD1=3.0, TL=8.0)  # refused by the library
    assert model.result is None and not model.pin() and model.pinned is None


def test_a_pin_outlives_a_preset_change():
    model = PoundingModel()
    model.pin()
    model.preset = "section5-T2-0.8"
    force = model.comparison()[0]
    assert force.pinned == pytest.approx(estimate(load_case(DEFAULT)).force_expected, rel=1e-9)
    assert force.current == pytest.approx(estimate(load_case("section5-T2-0.8")).force_expected, rel=1e-6)


def test_the_gap_plot_and_the_distribution_draw_the_pinned_state():
    from bokeh.plotting import figure

    from pounding.report import Figures

    model = PoundingModel()
    model.pin()
    pinned = model.pinned
    model.building_2.period = 0.6  # s: another curve (a change of the gap alone moves only the marker along the same one)
    plots = Figures()
    overlay = PinnedOverlay(plots.gap)
    item = next(i for i in plots.gap.legend[0].items if i.label.value == PINNED_LABEL)
    assert not item.visible
    overlay.fill(model.pinned, "SI")
    assert item.visible
    assert list(overlay.curve.data["force"]) == pytest.approx(pinned.snapshot.gap_curve.force_expected / 1e3)
    assert list(overlay.curve.data["gap"]) == pytest.approx(pinned.snapshot.gap_curve.gaps / 1e-3)
    assert overlay.point.data["gap"] == pytest.approx([10.0])  # the pinned state's own gap, mm
    assert max(overlay.curve.data["force"]) != pytest.approx(max(model.snapshot.gap_curve.force_expected) / 1e3)  # not the current
    overlay.fill(None)
    assert not item.visible and len(overlay.curve.data["gap"]) == 0

    plot = figure(x_range=(0, 1))
    overlay_distribution(plot, pinned, "SI")
    line = plot.renderers[-1]
    distribution = pinned.estimate.force_max_distribution
    assert list(line.data_source.data["x"][1:]) == pytest.approx(distribution.forces / 1e3)
    assert list(line.data_source.data["y"][1:]) == pytest.approx(distribution.cdf)
    assert plot.x_range.end == pytest.approx(1.05 * distribution.quantile(0.999) / 1e3)


# --- the Monte Carlo kept with the pinned state -------------------------------------------------------------


def _wait_until(done, timeout=180.0):
    import time

    deadline = time.monotonic() + timeout
    while not done() and time.monotonic() < deadline:
        time.sleep(0.02)
    assert done(), "timed out"


@pytest.fixture
def small_checks(monkeypatch):
    """The page's automatic check on 12 records (the library's check_estimate, fewer records): quick, the same rule."""
    from dataclasses import replace

    import dashboard.studies as studies
    from dashboard.jobs import check_pool
    from pounding.studies.check import check_estimate

    check_pool().submit(lambda: None).result(timeout=120)  # no check of another test's model left running
    monkeypatch.setattr(studies, "check_estimate", lambda result, plan: check_estimate(result, replace(plan, records=12)))
    yield
    check_pool().submit(lambda: None).result(timeout=120)


def test_the_pinned_state_keeps_its_check_and_the_headline_compares_both_monte_carlo_means(small_checks):
    from pounding.report import StateMonteCarlo
    from pounding.studies.check import check_estimate

    model = PoundingModel(check=True)
    _wait_until(lambda: model.current_check() is not None)
    pinned_check = model.current_check()
    assert model.pin() and model.pinned.snapshot.check is pinned_check
    model.gap = 30.0  # mm: the page's check is cleared, then made anew for 30 mm; the pinned one stays
    assert model.pinned.snapshot.check is pinned_check
    _wait_until(lambda: model.current_check() is not None)
    current_check = model.current_check()
    assert model.pinned.snapshot.check is pinned_check and current_check is not pinned_check

    # the numbers are the library's checks of each state, on the page's seed
    assert pinned_check.force_max_mean == check_estimate(estimate(_at_gap(0.010)), records=12, seed=1).force_max_mean
    assert current_check.force_max_mean == check_estimate(estimate(_at_gap(0.030)), records=12, seed=1).force_max_mean
    text = headline_html(model.result, "SI", pinned=pinned_html(model.pinned, model.result, "SI",
                                                                StateMonteCarlo.of(model.result, current_check)))
    change = current_check.force_max_mean - pinned_check.force_max_mean
    shown = display("SI")
    assert _cells(text, "pin-monte-carlo") == [
        shown.force(pinned_check.force_max_mean), shown.force(current_check.force_max_mean),
        f"{shown.force(change)} ({100 * (change / pinned_check.force_max_mean):+.3g} %)"]
    assert change < 0 and _cells(text, "pin-monte-carlo")[2].endswith(" %)") and " kN (" in _cells(text, "pin-monte-carlo")[2]
    verdicts = _cells(text, "pin-verdict")
    for verdict, check in zip(verdicts[:2], (pinned_check, current_check)):
        assert verdict.startswith("agrees (" if check.agrees else "does not agree (") and f"of {check.records} records)" in verdict
    assert "Change: current minus pinned." in text


def test_a_check_that_ends_after_the_pin_joins_the_pinned_state(small_checks, monkeypatch):
    import dashboard.studies as studies

    monkeypatch.setattr(studies, "CHECK_DELAY", 1.0)  # s: the pin below comes first, however loaded the machine
    model = PoundingModel(check=True)
    assert model.current_check() is None and model.pin()  # pinned before its check has ended
    assert model.pinned.snapshot.check is None
    _wait_until(lambda: model.pinned.snapshot.check is not None)
    assert model.pinned.snapshot.check is model.current_check()
    assert model.pinned.estimate is model.result


def test_without_a_monte_carlo_the_comparison_is_the_closed_form_alone():
    model = PoundingModel()
    model.pin()
    model.gap = 20.0
    text = pinned_html(model.pinned, model.result, "SI")
    assert "pin-monte-carlo" not in text and "(closed form)." in text


def test_a_study_at_the_gap_counts_where_no_check_was_run_and_a_state_without_says_so():
    """The page's own Monte Carlo study (no automatic check) is kept with the pin; the current state has none: its
    cells say so and the change is n/a."""
    from pounding.report import StateMonteCarlo

    model = PoundingModel(records=10)
    model.run_monte_carlo()
    _wait_until(lambda: not model.monte_carlo_job.running and model.monte_carlo_for_current_gap() is not None)
    study = model.monte_carlo_for_current_gap()
    model.pin()
    model.gap = 20.0
    assert model.monte_carlo_for_current_gap() is None and model.pinned.snapshot.monte_carlo == (study,)
    text = pinned_html(model.pinned, model.result, "SI", StateMonteCarlo.of(model.result, None, None))
    assert _cells(text, "pin-monte-carlo") == [display("SI").force(study.force_max_mean), "n/a", "n/a"]
    pinned_verdict, current_verdict = _cells(text, "pin-verdict")[:2]
    error = model.pinned.estimate.force_expected / study.force_max_mean - 1
    assert pinned_verdict == f"not checked: {100 * abs(error):.0f} % {'under' if error < 0 else 'over'} the mean of 10 records"
    assert current_verdict == "no Monte Carlo run"
