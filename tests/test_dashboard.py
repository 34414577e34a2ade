"""The dashboard: its model in process, and the served page in headless Chromium."""

from __future__ import annotations

import math
import re
import threading
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from pounding import load_case
from pounding.case import DEFAULT_PRESET
from pounding.estimator import estimate
from pounding.report import DEFAULT_SEED, Figures, compute_snapshot, display, result_html
from pounding.simulation import Cancelled, DesignGap, design_gap
from tests.browser import CANVAS_COUNT_JS, LOAD_TIMEOUT, UPDATE_TIMEOUT

from dashboard.model import PoundingModel


def _with_period(case, building: int, period: float):
    """The case with one building's storey stiffness giving ``period`` at the same mass."""
    b = case.buildings[building - 1]
    storey = b.storeys[0]
    stiffness = storey.mass * (2 * math.pi / period) ** 2
    buildings = list(case.buildings)
    buildings[building - 1] = replace(b, storeys=(replace(storey, stiffness=stiffness),))
    return replace(case, buildings=tuple(buildings))


def _shown_force(value: float) -> str:
    return display("SI").force(value)


# --- the model, in process -----------------------------------------------------


def test_model_opens_on_the_default_preset_with_the_library_numbers():
    model = PoundingModel()
    case = load_case(DEFAULT_PRESET)
    assert model.preset == DEFAULT_PRESET and model.error == ""
    assert model.snapshot.case.buildings == case.buildings and model.snapshot.case.contact == case.contact
    assert model.snapshot.estimate.force_expected == pytest.approx(estimate(case).force_expected, rel=1e-12)
    assert model.period_1 == pytest.approx(1.2) and model.period_2 == pytest.approx(0.4)


@pytest.mark.parametrize(
    ("name", "value", "field"),
    [("gamma_1", -300.0, "buildings.1.storeys.1.bouc_wen.beta"), ("n_2", 0.5, "buildings.2.storeys.1.bouc_wen.n"), ("restitution", 0.0, "contact.restitution")],
)
def test_model_names_the_bad_input_and_drops_the_result(name, value, field):
    model = PoundingModel()
    setattr(model, name, value)
    assert model.snapshot is None
    assert field in model.error and "Invalid input" in model.error
    setattr(model, name, PoundingModel.param[name].default if name != "gamma_1" else -100.0)
    assert model.error == "" and model.snapshot is not None


def test_model_envelope_constants_drive_the_case_and_are_checked():
    model = PoundingModel()
    model.preset = "section5-T2-0.4-nonstationary"
    assert (model.B1, model.B2) == (0.085, 0.17)
    model.B1 = 0.05
    case = model.snapshot.case
    assert case.excitation.envelope.B1 == 0.05
    assert model.snapshot.estimate.force_expected == pytest.approx(estimate(case).force_expected, rel=1e-12)
    model.B1 = 0.3  # above B2: invalid
    assert model.snapshot is None and "excitation.B2" in model.error


def test_model_unit_switch_keeps_the_case():
    model = PoundingModel()
    before = model.snapshot.case
    model.units = "kgf-cm-s"
    assert model.gap == pytest.approx(1.0) and model.beta_1 == pytest.approx(2.0) and model.G0 == pytest.approx(65.03)
    after = model.snapshot.case
    assert after.contact.gap == pytest.approx(before.contact.gap)
    assert after.buildings[1].storeys[0].stiffness == pytest.approx(before.buildings[1].storeys[0].stiffness, rel=1e-9)


def test_model_unit_switches_keep_the_studies_of_typed_values():
    """Values typed by hand do not survive the round trip through the display units to the last bit: the
    studies of the case must survive it all the same, running or done."""
    model = PoundingModel(records=10)
    model.param.update(G0=0.0061234567891, gap=0.0123456789, contact_stiffness=2.7e9 / 1.000000007, period_2=0.4123456789)
    model.run_monte_carlo()
    model.run_design_gap()
    model.units = "kgf-cm-s"  # while both run (the inline schedule runs them to the end in this thread or another)
    _wait_until(lambda: not model.mc_running and not model.design_gap_running)
    point, free = model.monte_carlo_for_current_gap(), model.current_design_gap()
    assert point is not None and free is not None, (model.mc_status, model.design_gap_status)
    for units in ("SI", "kgf-cm-s", "SI"):
        model.units = units
        assert model.monte_carlo_for_current_gap() is point and model.current_design_gap() is free
    assert model.mc_points == [point]


def test_model_monte_carlo_runs_and_a_change_makes_it_stale():
    model = PoundingModel()
    model.records = 10
    model.run_monte_carlo()
    deadline = time.monotonic() + 60
    while model.mc_running and time.monotonic() < deadline:
        time.sleep(0.02)
    assert not model.mc_running and model.mc_progress == 100
    point = model.monte_carlo_for_current_gap()
    assert point is not None and point.records == 10 and point.force_low <= point.force_max_mean <= point.force_high
    model.restitution = 0.6  # another case: the study is no longer shown
    assert model.monte_carlo_for_current_gap() is None and model.mc_points == []


def test_model_reports_a_failed_study(monkeypatch):
    import dashboard.model as module
    from pounding import SimulationError

    def failing(*_args, **_kwargs):
        raise SimulationError("record 3 (seed 1) failed at t = 2.0000 s: a floor displacement exceeded the runaway limit")

    monkeypatch.setattr(module, "simulate", failing)
    pending = []  # deferred, as a served session's event loop runs them: after the worker's frame is gone
    model = PoundingModel(schedule=pending.append)
    model.run_monte_carlo()
    deadline = time.monotonic() + 30
    while model.mc_running and time.monotonic() < deadline:
        while pending:
            pending.pop(0)()
        time.sleep(0.02)
    assert not model.mc_running
    assert "record 3" in model.mc_status
    assert model.monte_carlo_for_current_gap() is None


def test_model_multistorey_preset_and_contact_level():
    model = PoundingModel(preset="section6-T2-0.4")
    assert model.storeys_1 == 2 and model.error == ""
    model.level_2 = 3
    assert "contact.levels" in model.error and model.snapshot is None


# --- the Monte Carlo design gap, in process ---------------------------------------

DESIGN_GAP_RECORDS = 20


def _wait_until(done, timeout=60.0):
    deadline = time.monotonic() + timeout
    while not done() and time.monotonic() < deadline:
        time.sleep(0.02)
    assert done(), "timed out"


def _counting_design_gap(monkeypatch, gate=None):
    """Replace the model's ``design_gap`` by the library's, counting the calls and
    recording how each ended; ``gate(cancel)`` runs first in the worker thread."""
    import dashboard.model as module

    calls = []

    def counted(*args, **kwargs):
        calls.append("started")
        if gate is not None:
            gate(kwargs["cancel"])
        try:
            result = design_gap(*args, **kwargs)
        except Cancelled:
            calls[-1] = "cancelled"
            raise
        calls[-1] = "done"
        return result

    monkeypatch.setattr(module, "design_gap", counted)
    return calls


def test_model_design_gap_is_the_library_one_and_holds_at_any_gap(monkeypatch):
    calls = _counting_design_gap(monkeypatch)
    model = PoundingModel(records=DESIGN_GAP_RECORDS, seed=3)
    model.run_design_gap()
    _wait_until(lambda: not model.design_gap_running)
    result = model.current_design_gap()
    case = model.snapshot.case
    expected = design_gap(case, model.snapshot.estimate.target_probability, DESIGN_GAP_RECORDS, 3)
    assert result is model.design_gap_result and result.target_probability == 0.95
    assert (result.gap, result.upper_bound, result.seed) == (expected.gap, expected.upper_bound, 3)
    np.testing.assert_array_equal(result.peaks, expected.peaks)
    assert model.design_gap_progress == 100 and model.design_gap_status == f"Monte Carlo design gap done: {DESIGN_GAP_RECORDS} records."
    # The gap, and the unit system it is shown in, leave the free motion as it is: kept, and not run again.
    model.gap = 2 * model.gap
    model.units = "kgf-cm-s"
    assert model.snapshot.case.contact.gap == pytest.approx(2 * case.contact.gap)
    assert model.current_design_gap() is result
    model.run_design_gap()
    assert calls == ["done"] and not model.design_gap_running and model.current_design_gap() is result
    # Another record count is another study.
    model.records = DESIGN_GAP_RECORDS - 10
    model.run_design_gap()
    _wait_until(lambda: not model.design_gap_running)
    assert calls == ["done", "done"] and model.current_design_gap().n_records == DESIGN_GAP_RECORDS - 10
    # Nor does the contact law (the records' free motion never meets it)...
    model.restitution, model.contact_model = 0.6, "hertz"
    assert model.current_design_gap() is not None and model.current_design_gap().n_records == DESIGN_GAP_RECORDS - 10
    # ...but a building does: the result goes.
    model.period_2 = 0.5
    assert model.design_gap_result is None and model.current_design_gap() is None
    assert model.design_gap_status == "Monte Carlo design gap cleared: the inputs changed."


def test_model_design_gap_running_survives_a_change_of_gap_but_not_of_the_case(monkeypatch):
    release = threading.Event()
    calls = _counting_design_gap(monkeypatch, gate=lambda _cancel: release.wait(30))
    model = PoundingModel(records=DESIGN_GAP_RECORDS)
    model.run_design_gap()
    model.gap = 0.02  # while it runs
    assert model.design_gap_running and calls in ([], ["started"])
    release.set()
    _wait_until(lambda: not model.design_gap_running)
    assert calls == ["done"]
    expected = design_gap(model.snapshot.case, 0.95, DESIGN_GAP_RECORDS, model.seed)
    assert model.current_design_gap().gap == expected.gap
    # A change of the case while it runs cancels it, and nothing of it is shown.
    release.clear()
    model.records = DESIGN_GAP_RECORDS + 10
    model.run_design_gap()
    model.period_2 = 0.45
    release.set()
    _wait_until(lambda: not model.design_gap_running)
    assert calls == ["done", "cancelled"]
    assert model.design_gap_result is None
    assert model.design_gap_status == "Monte Carlo design gap cancelled: the inputs changed while it ran."


def test_model_design_gap_cancel_stops_it(monkeypatch):
    # The first study waits for the cancel, so that it is cancelled whatever the threads' timing.
    calls = _counting_design_gap(monkeypatch, gate=lambda cancel: len(calls) > 1 or cancel.wait(30))
    model = PoundingModel(records=DESIGN_GAP_RECORDS)
    model.run_design_gap()
    assert model.design_gap_running
    model.cancel_design_gap()
    _wait_until(lambda: not model.design_gap_running)
    assert calls == ["cancelled"]
    assert model.design_gap_result is None and model.design_gap_progress == 0
    assert model.design_gap_status == "Monte Carlo design gap cancelled."
    model.run_design_gap()  # and it can run again
    _wait_until(lambda: not model.design_gap_running)
    assert calls == ["cancelled", "done"] and model.current_design_gap() is not None


def test_model_reports_a_failed_design_gap(monkeypatch):
    import dashboard.model as module
    from pounding import SimulationError

    def failing(*_args, **_kwargs):
        raise SimulationError("record 7 (seed 1) failed at t = 3.0000 s: the response became NaN or infinite")

    monkeypatch.setattr(module, "design_gap", failing)
    pending = []  # deferred, as a served session's event loop runs them
    model = PoundingModel(schedule=pending.append)
    model.run_design_gap()
    deadline = time.monotonic() + 30
    while model.design_gap_running and time.monotonic() < deadline:
        while pending:
            pending.pop(0)()
        time.sleep(0.02)
    assert not model.design_gap_running and model.current_design_gap() is None
    assert model.design_gap_status == (
        "Monte Carlo design gap failed: SimulationError: record 7 (seed 1) failed at t = 3.0000 s: the response became NaN or infinite"
    )


def _text(html: str) -> str:
    """The text of an HTML fragment, tags dropped."""
    return re.sub(r"<[^>]+>", "", html)


def test_card_and_plot_show_the_design_gap_beside_the_closed_form():
    snapshot = compute_snapshot(load_case(DEFAULT_PRESET))
    required = snapshot.estimate.required_gap
    peaks = np.linspace(0.1, 0.3, 50)
    bounded = DesignGap(gap=0.2, upper_bound=0.25, target_probability=0.95, peaks=peaks, seed=4)
    card = _text(result_html(snapshot, "kgf-cm-s", design_gap=bounded))
    assert (
        f"Monte Carlo gap for 95 % no pounding: 20 cm (90 % upper confidence bound 25 cm; free motion of 50 records, seed 4); "
        f"closed form / Monte Carlo = {required / 0.2:.3g} [-]." in card
    )
    too_few = DesignGap(gap=0.2, upper_bound=math.inf, target_probability=0.95, peaks=peaks[:20], seed=4)
    assert "200 mm (too few records for a 90 % upper confidence bound: it needs 45; free motion of 20 records" in _text(result_html(snapshot, "SI", design_gap=too_few))
    assert "Monte Carlo gap" not in _text(result_html(snapshot, "SI"))  # the static report without one: no line
    figures = Figures()
    figures.fill(snapshot, "kgf-cm-s", design_gap=bounded)
    assert list(figures.sources["design_gap"].data["gap"]) == [20.0, 20.0]
    legend = {item.label.value: item.visible for item in figures.gap.legend[0].items}
    assert legend["Monte Carlo gap for the target"] and not legend["Monte Carlo mean F_max (95 % CI)"]  # no study with contact
    figures.fill(snapshot, "kgf-cm-s")
    assert list(figures.sources["design_gap"].data["gap"]) == []
    legend = {item.label.value: item.visible for item in figures.gap.legend[0].items}
    assert not legend["Monte Carlo gap for the target"] and legend["recommended E[F_max]"]  # no empty entry in a report


# --- the served page, in Chromium ------------------------------------------------


def _handle(page, label: str):
    """The noUiSlider handle of the slider whose label starts with ``label``."""
    return page.locator(".bk-input-group", has=page.get_by_text(label, exact=False)).locator(".noUi-handle").first


def _wait_text(page, selector: str, text: str, timeout=UPDATE_TIMEOUT):
    page.wait_for_function(
        """([selector, text]) => { const find = (root) => { const el = root.querySelector(selector); if (el) return el;
             for (const e of root.querySelectorAll('*')) { if (e.shadowRoot) { const f = find(e.shadowRoot); if (f) return f; } } return null; };
             const deep = (el) => el.shadowRoot ? deep(el.shadowRoot) : Array.from(el.childNodes).map(
               (c) => c.nodeType === 3 ? c.textContent : (c.nodeType === 1 && !['STYLE', 'SCRIPT', 'LINK'].includes(c.tagName) ? deep(c) : '')).join('');
             const el = find(document); return el !== null && deep(el).trim() === text; }""",
        arg=[selector, text],
        timeout=timeout,
    )


@pytest.mark.browser
def test_page_loads_without_errors_and_shows_the_default_case(dashboard):
    expected = estimate(load_case(DEFAULT_PRESET))
    assert dashboard.locator(".fe-recommended").inner_text() == _shown_force(expected.force_expected)
    assert dashboard.locator(".fe-paper").inner_text() == _shown_force(expected.paper.force_expected)
    # F_e against the gap and the open tab's two spectra (two canvases a plot).
    dashboard.wait_for_function(f"() => ({CANVAS_COUNT_JS})() === 6", timeout=LOAD_TIMEOUT)
    assert dashboard.errors == []


# The largest value of ``column`` in the page's Bokeh data sources that have a ``key`` column.
SOURCE_MAX_JS = """([key, column]) => { let best = null; for (const doc of window.Bokeh.documents) { for (const m of doc.all_models) {
  const d = m.data; const get = (name) => d == null ? undefined : (d instanceof Map ? d.get(name) : d[name]);
  if (get(key) != null && get(column) != null) { for (const v of get(column)) { if (best === null || v > best) best = v; } } } }
  return best; }"""


@pytest.mark.browser
def test_plot_tabs_draw_their_plots_when_opened(dashboard):
    """Only the open tab is in the page: opening another one draws its plots,
    with the data of the current inputs (changed while the tab was closed)."""
    dashboard.wait_for_function(f"() => ({CANVAS_COUNT_JS})() === 6", timeout=LOAD_TIMEOUT)
    _handle(dashboard, "period T2").focus()
    dashboard.keyboard.press("ArrowRight")  # 0.40 -> 0.45 s
    changed = compute_snapshot(_with_period(load_case(DEFAULT_PRESET), 2, 0.45))
    _wait_text(dashboard, ".fe-recommended", _shown_force(changed.estimate.force_expected))
    for tab, canvases in [("Pounding force history", 4), ("Hysteresis loops", 6), ("Spectra", 6)]:
        dashboard.locator(".bk-tab", has_text=tab).click()
        dashboard.wait_for_function(f"() => ({CANVAS_COUNT_JS})() === {canvases}", timeout=UPDATE_TIMEOUT)
        if tab == "Pounding force history":  # the record of T2 = 0.45 s, not of the first page
            peak = changed.history.contact_force.max() / 1e3  # [kN], as plotted
            # The plots are refilled REDRAW_DELAY_MS after the card: under load the tab may open on the
            # previous record first, so wait for the refill (a dashboard that never refills times out here).
            dashboard.wait_for_function(
                f"() => {{ const v = ({SOURCE_MAX_JS})(['time', 'force']); return v !== null && Math.abs(v - {float(peak)!r}) <= 1e-9 * {float(peak)!r}; }}",
                timeout=UPDATE_TIMEOUT,
            )
            assert dashboard.evaluate(f"({SOURCE_MAX_JS})(['time', 'force'])") == pytest.approx(peak, rel=1e-9)
    assert dashboard.errors == []


@pytest.mark.browser
def test_changing_T2_and_restitution_changes_F_e_to_the_library_value(dashboard):
    case = load_case(DEFAULT_PRESET)
    _handle(dashboard, "period T2").focus()
    dashboard.keyboard.press("ArrowRight")  # 0.40 -> 0.45 s
    changed = _with_period(case, 2, 0.45)
    _wait_text(dashboard, ".fe-recommended", _shown_force(estimate(changed).force_expected))
    _handle(dashboard, "restitution").focus()
    dashboard.keyboard.press("ArrowLeft")  # 0.65 -> 0.60
    changed = replace(changed, contact=replace(changed.contact, restitution=0.6))
    result = estimate(changed)
    _wait_text(dashboard, ".fe-recommended", _shown_force(result.force_expected))
    _wait_text(dashboard, ".fe-paper", _shown_force(result.paper.force_expected))
    assert dashboard.errors == []


@pytest.mark.browser
def test_short_simulation_runs_to_completion_with_progress(dashboard):
    dashboard.get_by_role("button", name="Run Monte Carlo").click()
    _wait_text(dashboard, ".mc-status", "Monte Carlo done: 50 records.", timeout=60_000)
    progress = dashboard.locator("progress").first
    assert progress.get_attribute("value") == "100"
    mean = dashboard.locator(".mc-mean").inner_text()
    assert mean.endswith("kN")
    assert dashboard.errors == []


@pytest.mark.browser
def test_design_gap_button_shows_the_library_gap(dashboard):
    records = _handle(dashboard, "records")
    records.focus()
    for _ in range(3):
        dashboard.keyboard.press("ArrowLeft")  # 50 -> 20 records
    dashboard.get_by_role("button", name="Monte Carlo design gap").click()
    _wait_text(dashboard, ".design-gap-status", f"Monte Carlo design gap done: {DESIGN_GAP_RECORDS} records.", timeout=60_000)
    case = load_case(DEFAULT_PRESET)
    expected = design_gap(case, 0.95, DESIGN_GAP_RECORDS, DEFAULT_SEED)
    _wait_text(dashboard, ".mc-design-gap", display("SI").length(expected.gap))
    _wait_text(dashboard, ".mc-design-gap-bound", f"too few records for a 90 % upper confidence bound: it needs {expected.records_for_bound}")
    _wait_text(dashboard, ".design-gap-ratio", f"{estimate(case).required_gap / expected.gap:.3g}")
    assert dashboard.errors == []


@pytest.mark.browser
def test_export_downloads_a_report_that_loads_offline(dashboard, browser, tmp_path: Path):
    shown = dashboard.locator(".fe-recommended").inner_text()
    with dashboard.expect_download(timeout=60_000) as download:
        dashboard.get_by_role("button", name="Export report (HTML)").click()
    path = tmp_path / "report.html"
    download.value.save_as(path)
    page = browser.new_page()
    log: list[str] = []
    page.on("console", lambda m: log.append(m.text) if m.type == "error" else None)
    page.route("**/*", lambda r: r.continue_() if r.request.url.startswith("file:") else (log.append(r.request.url), r.abort()))
    page.goto(path.as_uri())
    page.wait_for_function(f"() => ({CANVAS_COUNT_JS})() >= 12", timeout=LOAD_TIMEOUT)  # six plots, two canvases each
    assert page.locator(".fe-recommended").inner_text() == shown
    assert log == []
    page.close()


@pytest.mark.browser
def test_bad_value_shows_the_message_and_no_stale_number(dashboard):
    gamma = dashboard.locator(".bk-input-group", has=dashboard.get_by_text("Bouc-Wen gamma", exact=False)).locator("input").first
    gamma.fill("-300")
    gamma.press("Enter")
    dashboard.get_by_text("beta + gamma must be > 0", exact=False).first.wait_for(timeout=UPDATE_TIMEOUT)
    assert dashboard.get_by_text("building 1, Bouc-Wen beta", exact=False).count() >= 1
    assert dashboard.locator(".fe-recommended").count() == 0
