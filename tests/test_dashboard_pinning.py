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
