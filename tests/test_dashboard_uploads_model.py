"""The dashboard's uploads and refusals in process (issue 33): the server's own checks of an upload's name and size
(a browser is not trusted), the model's refusal of a typed number, an uploaded case file's name, the Monte Carlo of
uploaded records, and the session's files removed on close."""

from __future__ import annotations

import base64
import time

import pytest

from dashboard.model import NO_RECORDS_YET, PoundingModel
from dashboard.upload_widget import FileUpload
from pounding import load_case
from pounding.hazard.accelerograms import Accelerogram, write_at2
from pounding.hazard.excitation import ground_accelerations
from pounding.presets import preset_text

DEFAULT = "section5-T2-0.4"


def _upload(max_bytes=100, max_files=3):
    got, refused = [], []
    widget = FileUpload(got.append, refused.append, max_bytes=max_bytes, max_files=max_files)
    return widget, got, refused


def _message(name, content: bytes, index=0, total=1, batch=1):
    return {"batch": batch, "index": index, "total": total, "name": name, "size": len(content),
            "data": base64.b64encode(content).decode()}


@pytest.mark.parametrize("name", ["..", ".", "../etc/passwd", "a/b.AT2", "C:\\x\\m.AT2", "", "m\x00.AT2", "   "])
def test_a_path_for_a_file_name_is_refused_by_the_server_and_nothing_is_taken(name):
    widget, got, refused = _upload()
    widget.receive(_message(name, b"0 0\n"))
    assert got == [] and len(refused) == 1 and "not a plain file name" in refused[0] and len(refused[0]) <= 200


def test_a_file_over_the_limit_is_refused_by_the_server_even_if_the_browser_sent_it():
    widget, got, refused = _upload(max_bytes=100)
    widget.receive(_message("m.AT2", b"x" * 101))
    assert got == [] and refused == [("m.AT2 is 101 bytes, over the 100 bytes an upload may be: shorten or resample it, "
                                      "or use the command line.")]
    widget.receive({"batch": 2, "refused": [{"name": "big.AT2", "size": 30_000_000}]})  # what the browser sends instead
    assert "big.AT2 is 30 MB, over the 100 bytes" in refused[-1]


def test_a_batch_of_files_arrives_whole_or_not_at_all():
    widget, got, refused = _upload()
    widget.receive(_message("b.AT2", b"2", index=1, total=2, batch=7))
    assert got == []
    widget.receive(_message("a.AT2", b"1", index=0, total=2, batch=7))
    assert got == [{"a.AT2": b"1", "b.AT2": b"2"}] and refused == []
    widget.receive({"batch": 8, "index": 0, "total": 1, "name": "c.AT2", "data": "not base64!"})
    assert "did not arrive whole" in refused[-1]
    widget.receive("garbage")
    assert len(got) == 1


def test_the_model_refuses_a_path_for_a_record_name_and_keeps_its_records(tmp_path):
    model = PoundingModel()
    model.upload_records({"..": b"0 0\n"})
    assert "not a plain file name" in model.upload_error and model.uploaded == [] and model.ground_motion != "recorded motions"


def _records(count):
    excitation = load_case(DEFAULT).excitation
    return {f"m{i}.AT2": write_at2_bytes(f"m{i}", excitation.time_step, record)
            for i, record in enumerate(ground_accelerations(excitation, 4, range(count)))}


def write_at2_bytes(name, step, record) -> bytes:
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        return write_at2(Path(folder) / f"{name}.AT2", Accelerogram(name, step, record)).read_bytes()


def test_the_monte_carlo_of_uploaded_records_runs_on_each_of_them_and_their_files_go_on_close():
    model = PoundingModel()
    model.ground_motion = "recorded motions"
    assert model.waiting == NO_RECORDS_YET and model.result is not None and model.error == ""  # the last case stays
    model.upload_records(_records(5))
    assert model.waiting == "" and model.result.case.recorded and len(model.result.case.hazard.records) == 5
    folder = model._records_folder
    assert sorted(p.name for p in folder.iterdir()) == [f"m{i}.AT2" for i in range(5)]
    model.run_monte_carlo()
    deadline = time.monotonic() + 60
    while model.monte_carlo_job.running and time.monotonic() < deadline:
        time.sleep(0.05)
    point = model.monte_carlo_for_current_gap()
    assert model.monte_carlo_job.error == "" and point is not None and point.records == 5
    model.close()
    assert not folder.exists()


def test_a_typed_number_out_of_range_is_refused_and_the_last_case_stays():
    model = PoundingModel()
    result = model.result
    reason = model.offer(model, "gap", -5.0)
    assert reason == "Gap: -5 mm was not taken; type a value from 0 mm to 20,000 mm."
    assert model.gap == 10.0 and model.result is result and model.refused == {"gap": reason}
    assert "Gap: 1e+308 mm was not taken" in model.offer(model, "gap", 1e308)
    assert model.offer(model, "records", 10**11) == ("Records: 1e+11 was not taken; type a whole number from 1 to 2,000 "
                                                     "(the command line takes more).")
    assert model.records == 50
    assert model.offer(model.building_2, "period", 0.0).startswith("Building 2's fundamental period T2: 0 s was not taken")
    assert model.offer(model, "gap", 20.0) == "" and model.gap == 20.0 and model.result is not result
    assert set(model.refused) == {"records", "building_2.period"}
    model.preset = "section6-T2-0.4"  # a preset replaces every input: nothing refused is left
    assert model.refused == {}


def test_an_uploaded_case_file_names_the_case_until_a_preset_is_chosen():
    model = PoundingModel()
    model.load_toml(preset_text(DEFAULT), "../odd name!.toml")
    assert model.case_name() == "odd name!" and model.case_slug() == "odd-name" and model.note == "Loaded ../odd name!.toml."
    model.gap = 2 * model.gap
    assert model.case_name() == "odd name! (modified)" and model.case_slug() == "odd-name-modified"
    model.preset = "section6-T2-0.4"
    assert model.case_name() == "section6-T2-0.4" and model.note == ""



def test_the_view_shows_a_refused_number_red_until_a_value_is_taken_or_a_preset_replaces_it():
    from dashboard.view import PoundingDashboard

    page = PoundingDashboard()
    model = page.model
    field = next(f for f in page._widgets if f.key == "gap")
    field.widget.value = -5.0  # typed in the box
    assert field.widget.css_classes == ["refused"] and field.reason.visible and "-5 mm" in field.reason.object
    assert model.gap == 10.0 and field.widget.value == -5.0  # the box keeps what was typed, the model what it took
    field.widget.value = 12.0
    assert field.widget.css_classes == [] and not field.reason.visible and model.gap == 12.0
    field.widget.value = -5.0
    model.preset = "section6-T2-0.4"
    assert field.widget.css_classes == [] and field.widget.value == model.gap == load_case("section6-T2-0.4").contact.gap * 1000
