"""The served dashboard's states and uploads in headless Chromium (issues 33 and 34): a refused input shown as
refused, the Monte Carlo of uploaded records, 'recorded motions' before an upload, an uploaded case file's name,
uploads over the size limit or with a path for a name, and a Monte Carlo verdict that follows the gap."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from dashboard.inputs import CaseInputs
from dashboard.model import NO_RECORDS_YET
from dashboard.refusals import refusal
from pounding import estimate, load_case, simulate
from pounding.case.case import case_from_dict
from pounding.display_units import display
from pounding.hazard.accelerograms import Accelerogram, write_at2
from pounding.hazard.excitation import ground_accelerations
from pounding.presets import preset_text, preset_title
from pounding.report import MonteCarloPoint, monte_carlo_check
from tests.browser import CANVAS_COUNT_JS, UPDATE_TIMEOUT
from tests.test_dashboard import DEFAULT, _choose, _input, _open, _shown, _type, _wait_text

pytestmark = pytest.mark.browser

RED = "rgb(198, 40, 40)"


def _reason(page, text: str):
    """The reason shown under an input, visible, containing ``text``."""
    return page.locator(".input-refused", has_text=text).first


def _text(locator) -> str:
    """The text an element shows, its shadow root's included."""
    return locator.evaluate("""e => e.shadowRoot ? Array.from(e.shadowRoot.children).filter(c => c.tagName !== 'STYLE'
        && c.tagName !== 'LINK').map(c => c.innerText).join('') : e.innerText""").strip()


def _records(folder: Path, count: int) -> list[Path]:
    """``count`` records of the default case's excitation, as .AT2 files m0.AT2, m1.AT2..."""
    excitation = load_case(DEFAULT).excitation
    return [write_at2(folder / f"m{index}.AT2", Accelerogram(f"m{index}", excitation.time_step, record))
            for index, record in enumerate(ground_accelerations(excitation, 4, range(count)))]


def _page_text(page) -> str:
    """Every text of the page, through the shadow roots."""
    return page.evaluate("""() => { const out = []; const walk = (root) => { for (const el of root.querySelectorAll('*')) {
        if (el.shadowRoot) walk(el.shadowRoot); else if (el.children.length === 0) out.push(el.textContent); } };
        walk(document); return out.join(' '); }""")


def test_a_refused_gap_is_red_with_its_reason_and_the_headline_keeps_the_last_valid_case(dashboard):
    force = _shown(estimate(load_case(DEFAULT)).force_expected)
    _wait_text(dashboard, ".fe-recommended", force)
    gap = _input(dashboard, "gap [mm]")
    _type(dashboard, "gap [mm]", "-5")
    expected = refusal(CaseInputs(), "gap", -5.0, "SI")
    reason = _reason(dashboard, "-5 mm")
    reason.wait_for(timeout=UPDATE_TIMEOUT)
    assert _text(reason).strip() == expected and "0 mm to 20,000 mm" in expected
    assert gap.evaluate("e => getComputedStyle(e).borderTopColor") == RED and gap.input_value() == "-5"
    held = _text(dashboard.locator(".held").first)
    assert held.startswith("Not taken: Gap") and "last valid inputs" in held
    assert _text(dashboard.locator(".fe-recommended")) == force  # the last valid case, 10 mm, still shown

    _type(dashboard, "gap [mm]", "1e308")
    reason = _reason(dashboard, "1e+308 mm")
    reason.wait_for(timeout=UPDATE_TIMEOUT)
    text = _text(reason)
    assert text.startswith("Gap:") and "opposing" not in text and "array" not in text and len(text) <= 200

    dashboard.locator(".bk-tab", has_text="Monte Carlo").first.click()
    _type(dashboard, "records", "100000000000")
    reason = _reason(dashboard, "Records:")
    reason.wait_for(timeout=UPDATE_TIMEOUT)
    assert "1 to 2,000" in _text(reason)
    assert _input(dashboard, "records").input_value() != "50"  # not silently replaced by the default

    _type(dashboard, "gap [mm]", "20")  # a valid gap: plain again, and computed
    data = tomllib.loads(preset_text(DEFAULT))
    data["contact"]["gap"] = 2.0
    _wait_text(dashboard, ".fe-recommended", _shown(estimate(case_from_dict(data)).force_expected))
    assert gap.evaluate("e => getComputedStyle(e).borderTopColor") != RED
    assert _reason(dashboard, "Gap:").count() == 0 or not _reason(dashboard, "Gap:").is_visible()
    assert "Not taken: Records" in _text(dashboard.locator(".held").first)  # the records' box is still refused
    assert dashboard.errors == []


def test_recorded_motions_before_an_upload_prompt_for_records_and_keep_the_plot(dashboard):
    force = _shown(estimate(load_case(DEFAULT)).force_expected)
    _wait_text(dashboard, ".fe-recommended", force)
    _open(dashboard, "Ground motion")
    _choose(dashboard, "ground motion", "recorded motions")
    _wait_text(dashboard, ".held", NO_RECORDS_YET)
    assert _text(dashboard.locator(".fe-recommended")) == force
    assert dashboard.evaluate(f"({CANVAS_COUNT_JS})()") >= 2
    assert "Invalid input" not in _page_text(dashboard)
    assert dashboard.errors == []


def test_five_uploaded_records_run_their_own_monte_carlo(dashboard, tmp_path):
    paths = _records(tmp_path, 5)
    _open(dashboard, "Ground motion")
    _choose(dashboard, "ground motion", "recorded motions")
    dashboard.locator("input[type=file][accept*='AT2']").set_input_files([str(p) for p in paths])
    dashboard.get_by_text("Uploaded: m0.AT2, m1.AT2, m2.AT2, m3.AT2, m4.AT2").wait_for(timeout=UPDATE_TIMEOUT)
    data = tomllib.loads(preset_text(DEFAULT))
    data["excitation"] = {"records": ["*.AT2"]}
    case = case_from_dict(data, base_directory=tmp_path)
    result = estimate(case)
    _wait_text(dashboard, ".fe-recommended", _shown(result.force_expected), timeout=40_000)
    dashboard.locator(".bk-tab", has_text="Monte Carlo").first.click()
    dashboard.get_by_role("button", name="Run Monte Carlo").click()
    dashboard.locator(".mc-verdict").wait_for(timeout=60_000)
    study = MonteCarloPoint.from_result(simulate(case))  # each of the 5 records once
    assert study.records == 5
    _wait_text(dashboard, ".mc-verdict", monte_carlo_check(result, study).text)
    text = _page_text(dashboard)
    assert "Monte Carlo done: 5 records." in text and "--records" not in text and "0..49" not in text
    assert dashboard.errors == []


def test_an_uploaded_case_file_is_named_by_its_file_in_the_headline_and_the_report(dashboard, tmp_path):
    data = tomllib.loads(preset_text(DEFAULT))
    data["contact"]["gap"] = 3.0  # the file's units are the preset's (kgf, cm, s): 30 mm
    import tomli_w

    path = tmp_path / "my-house.toml"
    path.write_text(tomli_w.dumps(data))
    _open(dashboard, "Units and case file")
    dashboard.locator("input[type=file][accept='.toml']").set_input_files(str(path))
    shown = display(data["units"])  # the page takes the file's units
    _wait_text(dashboard, ".fe-recommended", shown.force(estimate(case_from_dict(data)).force_expected))
    assert _text(dashboard.locator(".headline .case-name")) == "my-house"
    dashboard.get_by_text("Loaded my-house.toml.").wait_for(timeout=UPDATE_TIMEOUT)
    with dashboard.expect_download(timeout=60_000) as download:
        dashboard.get_by_role("button", name="Export report (HTML)").click()
    assert download.value.suggested_filename == "pounding-report-my-house.html"
    download.value.save_as(tmp_path / "report.html")
    report = (tmp_path / "report.html").read_text()
    assert "<title>Pounding report: my-house</title>" in report and "Inputs: the case my-house.toml." in report
    assert f"preset {DEFAULT}" not in report
    dashboard.locator(".bk-input-group", has=dashboard.get_by_text("case (preset)")).locator("select").first.select_option(
        label=preset_title("section6-T2-0.4"))  # as a user picks it: by its title
    _wait_text(dashboard, ".fe-recommended", shown.force(estimate(load_case("section6-T2-0.4")).force_expected))
    assert dashboard.get_by_text("Loaded my-house.toml.").count() == 0
    assert _text(dashboard.locator(".headline .case-name")) == "section6-T2-0.4"
    assert dashboard.errors == []


def test_a_record_over_the_size_limit_or_named_like_a_path_is_refused_and_the_session_goes_on(dashboard, tmp_path):
    limit = dashboard.locator(".upload-limit").first
    assert "up to 5 MB each" in _text(limit)  # stated on the page
    _open(dashboard, "Ground motion")
    _choose(dashboard, "ground motion", "recorded motions")
    upload = dashboard.locator("input[type=file][accept*='AT2']")
    big = tmp_path / "big.AT2"
    with big.open("wb") as stream:  # 30 MB: whole, it would pass the websocket's 20 MB and close the session
        stream.truncate(30_000_000)
    upload.set_input_files(str(big))
    refused = dashboard.locator(".upload-refused", has_text="big.AT2").first
    refused.wait_for(timeout=UPDATE_TIMEOUT)
    assert _text(refused) == "big.AT2 is 30 MB, over the 5 MB an upload may be: shorten or resample it, or use the command line."
    upload.set_input_files([{"name": "..", "mimeType": "text/plain", "buffer": b"NPTS= 2, DT= 0.01 SEC\n0 0\n"}])
    named = dashboard.locator(".upload-refused", has_text="plain file name").first
    named.wait_for(timeout=UPDATE_TIMEOUT)
    assert "'..'" in _text(named)
    _choose(dashboard, "ground motion", "Kanai-Tajimi")  # the session is alive: a new input is computed
    _type(dashboard, "gap [mm]", "20")
    data = tomllib.loads(preset_text(DEFAULT))
    data["contact"]["gap"] = 2.0
    _wait_text(dashboard, ".fe-recommended", _shown(estimate(case_from_dict(data)).force_expected))
    assert dashboard.errors == []


def test_a_monte_carlo_verdict_is_shown_at_its_own_gap_only(dashboard):
    """Issue 34: after a study at 10 mm, the verdict goes at 30 mm and comes back at 10 mm."""
    case = load_case(DEFAULT)
    _wait_text(dashboard, ".fe-recommended", _shown(estimate(case).force_expected))
    dashboard.locator(".bk-tab", has_text="Monte Carlo").first.click()
    _type(dashboard, "records", "10")
    dashboard.get_by_role("button", name="Run Monte Carlo").click()
    verdict = monte_carlo_check(estimate(case), MonteCarloPoint.from_result(simulate(case, records=10, seed=1))).text
    _wait_text(dashboard, ".mc-verdict", verdict, timeout=60_000)
    _type(dashboard, "gap [mm]", "30")
    data = tomllib.loads(preset_text(DEFAULT))
    data["contact"]["gap"] = 3.0
    _wait_text(dashboard, ".fe-recommended", _shown(estimate(case_from_dict(data)).force_expected))
    assert dashboard.locator(".mc-verdict").count() == 0
    _type(dashboard, "gap [mm]", "10")
    _wait_text(dashboard, ".fe-recommended", _shown(estimate(case).force_expected))
    _wait_text(dashboard, ".mc-verdict", verdict)
    assert dashboard.errors == []
