"""Issue 35 in headless Chromium, the dashboard served by ``pounding dashboard``: an uploaded case file of three
buildings shows the governing contact in the headline, the table of contacts with one row a contact and the
library's numbers (computed here, in display units), and one line a contact in the record's force history."""

from __future__ import annotations

import sys
import tomllib

import pytest

from pounding import estimate
from pounding.case.case import case_from_dict, contact_label
from pounding.display_units import display
from tests.browser import LOAD_TIMEOUT, UPDATE_TIMEOUT, offline
from tests.test_dashboard_cleanup import _start
from tests.test_dashboard_rows_model import ROW_FILE

pytestmark = pytest.mark.browser

LINES_JS = """() => { for (const doc of Bokeh.documents) for (const m of doc.all_models) {
  const data = m.data; if (data === undefined || data === null || typeof data !== 'object') continue;
  const get = (key) => data instanceof Map ? data.get(key) : data[key];
  const labels = get('label'), colours = get('colour');
  if (labels !== undefined && colours !== undefined && labels.length > 0) return labels.length; }
  return -1; }"""
"""How many lines the force history of each contact draws (its source: one row a line, with a label and a colour)."""


def test_a_row_of_three_shows_the_governing_contact_the_table_and_each_contacts_force(browser, tmp_path):
    process, url, log = _start([sys.executable, "-m", "pounding", "dashboard", "--port", "0"], tmp_path)
    try:
        context = browser.new_context(viewport={"width": 1500, "height": 1100})
        page = context.new_page()
        errors: list[str] = []
        page.on("pageerror", lambda e: errors.append(f"page error: {e}"))
        offline(page, errors)
        page.goto(url)
        page.locator(".fe-recommended").wait_for(timeout=LOAD_TIMEOUT)
        path = tmp_path / "row.toml"
        path.write_text(ROW_FILE)
        page.locator(".card-header", has_text="Units and case file").first.click()
        page.locator("input[type=file][accept='.toml']").set_input_files(str(path))

        result = estimate(case_from_dict(tomllib.loads(ROW_FILE)))
        shown = display("SI")
        governing = contact_label(result.case.contacts[result.governing])
        page.locator(".governing-contact", has_text=governing).wait_for(timeout=UPDATE_TIMEOUT)
        force = page.locator(".headline .fe-recommended").first.inner_text()
        assert force == shown.force(result.force_expected)
        rows = page.locator("table.contacts tr.contact")
        rows.first.wait_for(timeout=UPDATE_TIMEOUT)
        assert rows.count() == len(result.case.contacts) == 2
        for index, (contact, one) in enumerate(zip(result.case.contacts, result.contacts)):
            row = rows.nth(index)
            assert row.locator(".buildings").inner_text() == f"{contact.between[0]}-{contact.between[1]}"
            assert row.locator(".floors").inner_text() == f"{contact.levels[0]}/{contact.levels[1]}"
            assert row.locator(".gap").inner_text() == shown.length(contact.gap)
            assert row.locator(".force-expected").inner_text() == shown.force(one.force_expected)
            assert row.locator(".f84").inner_text() == shown.force(one.force_max_distribution.quantile(0.84))
            assert row.locator(".pounding-probability").inner_text() == f"{100 * one.pounding_probability:.3g} %"
            assert row.locator(".required-gap").inner_text() == shown.length(one.required_gap)

        page.locator(".bk-tab", has_text="Force history").click()
        page.wait_for_function(f"() => ({LINES_JS})() === {len(result.case.contacts)}", timeout=UPDATE_TIMEOUT)
        page.locator(".bk-tab", has_text="Distribution of F_max").click()
        page.get_by_text("drawn for a case of one contact").first.wait_for(timeout=UPDATE_TIMEOUT)
        assert not errors, errors
        assert not any("Traceback" in line for line in log), "".join(log)
        context.close()
    finally:
        process.terminate()
        process.wait(timeout=20)
