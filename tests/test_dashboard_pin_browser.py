"""Pin and compare in the served page, headless Chromium: pin, type another gap, read both states and the change
in the headline, see the pinned curve in the plot, and export the pair as one page that holds both states."""

from __future__ import annotations

import dataclasses

import pytest

from dashboard.pinning import PINNED_LABEL
from pounding import estimate, load_case
from pounding.display_units import display
from pounding.report import differences
from tests.browser import UPDATE_TIMEOUT
from tests.test_dashboard import _type, _wait_text

pytestmark = pytest.mark.browser

DEFAULT = "section5-T2-0.4"

# Whether the force-against-gap plot's legend shows the pinned curve's entry.
PINNED_ENTRY_JS = """(label) => window.Bokeh.documents.flatMap(d => Array.from(d.all_models))
  .some(m => m.label !== undefined && m.label !== null && m.label.value === label && m.visible === true)"""


def test_pin_change_the_gap_compare_and_export_the_pair(dashboard, tmp_path):
    page, shown = dashboard, display("SI")
    case = load_case(DEFAULT)
    pinned = estimate(case)
    current = estimate(case.with_contact(gap=0.030))
    force = differences(pinned, current)[0]

    page.get_by_role("button", name="Pin this state").click()  # enabled once the plots of the state shown are in
    _wait_text(page, ".pin-force .pinned-value", shown.force(pinned.force_expected))
    _type(page, "gap [mm]", "30")
    _wait_text(page, ".pin-force .current-value", shown.force(current.force_expected))
    _wait_text(page, ".pin-force .change", force.change_text(shown))
    _wait_text(page, ".pin-force .pinned-value", shown.force(pinned.force_expected))  # the pinned state did not move
    _wait_text(page, ".fe-recommended", shown.force(current.force_expected))
    page.wait_for_function(PINNED_ENTRY_JS, arg=PINNED_LABEL, timeout=UPDATE_TIMEOUT)

    with page.expect_download(timeout=30_000) as download:
        page.get_by_role("button", name="Export comparison (HTML)").click()
    assert download.value.suggested_filename.startswith("pounding-comparison-")
    path = tmp_path / "pair.html"
    download.value.save_as(path)
    text = path.read_text()
    assert shown.force(pinned.force_expected) in text and shown.force(current.force_expected) in text
    assert force.change_text(shown) in text and "<td>Contact, gap</td>" in text

    page.get_by_role("button", name="Unpin").click()
    page.locator(".pin-force").wait_for(state="detached", timeout=UPDATE_TIMEOUT)
    assert page.errors == []
