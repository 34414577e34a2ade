"""Reading and writing recorded accelerograms (pounding.hazard.accelerograms): files written here by hand."""

from __future__ import annotations

import numpy as np
import pytest

from pounding import defaults
from pounding.errors import ArgumentError, CaseError
from pounding.hazard.accelerograms import (
    Accelerogram,
    G,
    expand_records,
    read_accelerogram,
    read_records,
    write_at2,
    write_csv,
)

HEADER = "PEER NGA STRONG MOTION DATABASE RECORD\nIMPERIAL VALLEY 10/15/79, EL CENTRO ARRAY #9, 180\n" \
         "ACCELERATION TIME SERIES IN UNITS OF G\n"


def _write(folder, name: str, text: str):
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def _error(function, *args, **kwargs) -> CaseError:
    with pytest.raises(CaseError) as caught:
        function(*args, **kwargs)
    assert "\n" not in str(caught.value) and len(caught.value.message) < 200
    return caught.value


def test_an_nga_west2_file_with_a_short_last_line_is_read_in_m_per_s2(tmp_path):
    path = _write(tmp_path, "RSN6.AT2", HEADER + "NPTS=    7, DT=   .0100 SEC\n"
                  "  -.1000000E-01  .2000000E-01 -.3000000E-01  .4000000E-01  .5000000E-01\n  0.06 -.7E-01\n")
    record = read_accelerogram(path)
    assert record.name == str(path) and record.time_step == 0.01
    np.testing.assert_allclose(record.acceleration, G * np.array([-0.01, 0.02, -0.03, 0.04, 0.05, 0.06, -0.07]), rtol=1e-15)
    assert record.duration == pytest.approx(0.06) and record.peak == pytest.approx(0.07 * G)
    assert not record.acceleration.flags.writeable and record.acceleration.dtype == np.float64


@pytest.mark.parametrize("line", ["NPTS= 4, DT= 0.0050 SEC,", "NPTS=4,DT=.005 SEC", "npts = 4 , dt = 5.0E-03 sec",
                                  "   4    0.00500    NPTS, DT", "4 .005 NPTS, DT, SEC"])
def test_both_header_layouts_and_their_variants(tmp_path, line):
    record = read_accelerogram(_write(tmp_path, "a.at2", HEADER + line + "\n 0.1 0.2 -0.3\n 0.4\n"), name="x")
    assert record.name == "x" and record.time_step == 0.005
    np.testing.assert_allclose(record.acceleration / G, [0.1, 0.2, -0.3, 0.4])


def test_eight_values_a_line_and_glued_fortran_values(tmp_path):
    values = np.arange(1, 11) * 1e-3
    body = " ".join(f"{v:.4E}" for v in values[:8]) + "\n" + "-.1000E-01-.2000E-01\n"
    record = read_accelerogram(_write(tmp_path, "a.AT2", HEADER + "NPTS= 10, DT= 0.02 SEC\n" + body))
    np.testing.assert_allclose(record.acceleration / G, np.r_[values[:8], -0.01, -0.02])


@pytest.mark.parametrize("name, text", [
    ("a.csv", "time_s,acceleration_g\n10.0,0.1\n10.01,-0.2\n10.02,0.3\n"),
    ("a.txt", "# a comment\nTime (s)  Acc (g)\n\n0.00 0.1\n0.01\t-0.2\n# inside\n0.02   0.3\n"),
    ("a.DAT", "t;a\n0;0.1\n0.01;-0.2\n0.02;0.3\n"),
])
def test_two_column_files(tmp_path, name, text):
    record = read_accelerogram(_write(tmp_path, name, text))
    assert record.time_step == pytest.approx(0.01, rel=1e-12)
    np.testing.assert_allclose(record.acceleration, G * np.array([0.1, -0.2, 0.3]))


def _suite_record(n: int = 1003, step: float = 0.005) -> Accelerogram:
    rng = np.random.default_rng(3)
    return Accelerogram("rec", step, 2.0 * rng.standard_normal(n) * np.exp(-np.linspace(0, 3, n)))


@pytest.mark.parametrize("writer, name", [(write_at2, "out.AT2"), (write_csv, "out.csv")])
def test_write_then_read_round_trips(tmp_path, writer, name):
    record = _suite_record()
    writer(tmp_path / name, record)
    again = read_accelerogram(tmp_path / name)
    assert again.time_step == pytest.approx(record.time_step, rel=1e-12)
    assert np.max(np.abs(again.acceleration - record.acceleration)) <= 1e-7 * record.peak


def test_written_at2_is_the_nga_west2_layout(tmp_path):
    write_at2(tmp_path / "o.AT2", Accelerogram("m", 0.01, np.ones(7) * G), title="line\none")
    lines = (tmp_path / "o.AT2").read_text().splitlines()
    assert lines[0] == "line one" and lines[2] == "ACCELERATION TIME SERIES IN UNITS OF G"
    assert lines[3].replace(" ", "") == "NPTS=7,DT=0.01SEC"
    assert len(lines) == 6 and len(lines[4].split()) == 5 and len(lines[5].split()) == 2


def test_write_csv_header(tmp_path):
    write_csv(tmp_path / "o.csv", Accelerogram("m", 0.5, [G, -2 * G]))
    assert (tmp_path / "o.csv").read_text().splitlines() == ["time_s,acceleration_g", "0,1", "0.5,-2"]


AT2_ERRORS = [
    ("NPTS= 3, DT= 0.01 SEC\n 0.1 0.2\n", "a.AT2", "2 values"),
    ("NPTS= 3, DT= 0.01 SEC\n 0.1 0.2 0.3 0.4\n", "a.AT2", "NPTS = 3"),
    ("NPTS= 3, DT= 0 SEC\n 0.1 0.2 0.3\n", "a.AT2:4", "must lie in [1e-05, 1] s"),
    ("NPTS= 3, DT= -0.01 SEC\n 0.1 0.2 0.3\n", "a.AT2:4", "must lie in [1e-05, 1] s"),
    ("NPTS= 1, DT= 0.01 SEC\n 0.1\n", "a.AT2:4", "at least 2"),
    ("3 points at 0.01 s\n 0.1 0.2 0.3\n", "a.AT2:4", "NGA-West2"),
    ("NPTS= 3, DT= 0.01 SEC\n 0.1\n 0.2 nan\n", "a.AT2:6", "not finite"),
    ("NPTS= 3, DT= 0.01 SEC\n 0.1\n 0.2 inf\n", "a.AT2:6", "not finite"),
    ("NPTS= 3, DT= 0.01 SEC\n 0.1 0.2\n x0.3\n", "a.AT2:6", "not a number"),
]


@pytest.mark.parametrize("tail, field, words", AT2_ERRORS)
def test_a_bad_at2_file_names_the_file_and_line(tmp_path, tail, field, words):
    error = _error(read_accelerogram, _write(tmp_path, "a.AT2", HEADER + tail), name="a.AT2")
    assert error.field == field and words in error.message


def test_a_short_file_and_other_units_are_refused(tmp_path):
    assert _error(read_accelerogram, _write(tmp_path, "s.AT2", "a\nb\n"), name="s.AT2").field == "s.AT2"
    text = HEADER.replace("UNITS OF G", "UNITS OF CM/S/S") + "NPTS= 2, DT= 0.01 SEC\n1 2\n"
    assert _error(read_accelerogram, _write(tmp_path, "u.AT2", text), name="u.AT2").field == "u.AT2:3"


CSV_ERRORS = [
    ("t,a\n0,0.1\n0.01,0.2\n0.02,0.2\n0.04,0.3\n0.05,0.3\n", "a.csv:5", "uniform"),
    ("t,a\n0,0.1\n0.01,0.2\n0.01,0.3\n", "a.csv:4", "increase"),
    ("t,a\n0,0.1\n0.01,0.2\n0.02,x\n", "a.csv:4", "not a number"),
    ("t,a\n0,0.1\n0.01,nan\n0.02,0.3\n", "a.csv:3", "not finite"),
    ("t,a\n0,0.1\n0.01,0.1,3\n", "a.csv:3", "columns"),
    ("t,a\n0,0.1\n", "a.csv", "at least 2"),
    ("", "a.csv", "at least 2"),
]


@pytest.mark.parametrize("text, field, words", CSV_ERRORS)
def test_a_bad_two_column_file_names_the_file_and_line(tmp_path, text, field, words):
    error = _error(read_accelerogram, _write(tmp_path, "a.csv", text), name="a.csv")
    assert error.field == field and words in error.message


def test_missing_binary_non_utf8_and_unknown_suffix(tmp_path):
    assert "no such file" in _error(read_accelerogram, tmp_path / "none.AT2", name="none.AT2").message
    (tmp_path / "b.AT2").write_bytes(HEADER.encode() + b"NPTS= 2\x00\x01")
    assert "binary" in _error(read_accelerogram, tmp_path / "b.AT2", name="b.AT2").message
    (tmp_path / "l.csv").write_bytes(b"t,a\n0,0.1\n0.01,\xe90.2\n")
    assert "UTF-8" in _error(read_accelerogram, tmp_path / "l.csv", name="l.csv").message
    _write(tmp_path, "r.xlsx", "0,1\n1,2\n")
    error = _error(read_accelerogram, tmp_path / "r.xlsx", name="r.xlsx")
    assert error.field == "r.xlsx" and ".at2" in error.message and ".csv" in error.message


def test_the_samples_limit_is_checked_from_the_header(tmp_path, monkeypatch):
    path = _write(tmp_path, "big.AT2", HEADER + f"NPTS= {defaults.MAX_SAMPLES_PER_RECORD + 1}, DT= 0.01 SEC\n0.1\n")
    assert _error(read_accelerogram, path, name="big.AT2").field == "big.AT2:4"
    monkeypatch.setenv(defaults.LIMITS_VARIABLE, "off")  # lifted: the count is then checked against the values
    assert "has 1 values" in _error(read_accelerogram, path, name="big.AT2").message


def test_the_file_size_limit(tmp_path, monkeypatch):
    monkeypatch.setattr(defaults, "MAX_RECORD_FILE_BYTES", 100)
    path = _write(tmp_path, "a.csv", "t,a\n" + "".join(f"{k * 0.01:.2f},0.1\n" for k in range(40)))
    assert "bytes" in _error(read_accelerogram, path, name="a.csv").message
    monkeypatch.setenv(defaults.LIMITS_VARIABLE, "off")
    assert read_accelerogram(path).acceleration.size == 40


def _suite(tmp_path):
    for name in ["m/b.AT2", "m/a.AT2", "m/deep/c.at2", "other/d.csv"]:
        record = Accelerogram(name, 0.01, np.array([0.1, -0.4, 0.2]) * G * (1 + len(name)))
        (write_csv if name.endswith("csv") else write_at2)(_parent(tmp_path / name), record)


def _parent(path):
    path.parent.mkdir(parents=True, exist_ok=True)
    return path


def test_globs_expand_sorted_and_de_duplicated(tmp_path):
    _suite(tmp_path)
    paths = expand_records(["m/**/*.[aA][tT]2", "m/a.AT2", "./m/b.AT2", "other/*.csv"], tmp_path)
    assert [p.relative_to(tmp_path).as_posix() for p in paths] == ["m/a.AT2", "m/b.AT2", "m/deep/c.at2", "other/d.csv"]
    absolute = expand_records([str(tmp_path / "m" / "*.AT2")], "/nowhere")
    assert [p.name for p in absolute] == ["a.AT2", "b.AT2"]


def test_bad_patterns(tmp_path):
    _suite(tmp_path)
    error = _error(expand_records, ["m/*.AT2", "m/*.v2"], tmp_path, field="excitation.records")
    assert error.field == "excitation.records.m/*.v2" and "no file" in error.message
    assert "no such file" in _error(expand_records, ["m/x.AT2"], tmp_path).message
    assert _error(expand_records, ["m"], tmp_path).field.endswith(".m")  # a folder is not a record
    for bad in ([], "m/*.AT2", [3], None):
        assert _error(expand_records, bad, tmp_path, field="f").field == "f"


def test_read_records_names_scale_and_pga(tmp_path):
    _suite(tmp_path)
    records = read_records(["m/*.AT2", "other/d.csv"], tmp_path)
    assert [r.name for r in records] == ["m/a.AT2", "m/b.AT2", "other/d.csv"]
    scaled = read_records(["m/*.AT2", "other/d.csv"], tmp_path, scale=2.5)
    for one, two in zip(records, scaled):
        np.testing.assert_allclose(two.acceleration, 2.5 * one.acceleration)
    to_pga = read_records(["m/*.AT2", "other/d.csv"], tmp_path, pga=3.0)
    assert [r.peak for r in to_pga] == pytest.approx([3.0] * 3)
    np.testing.assert_allclose(to_pga[0].acceleration, np.array([0.1, -0.4, 0.2]) * 3.0 / 0.4)


def test_scale_and_pga_errors(tmp_path):
    _suite(tmp_path)
    assert _error(read_records, ["m/a.AT2"], tmp_path, scale=2, pga=3).field == "excitation.pga"
    assert _error(read_records, ["m/a.AT2"], tmp_path, scale=-1).field == "excitation.scale"
    assert _error(read_records, ["m/a.AT2"], tmp_path, pga=float("nan")).field == "excitation.pga"
    write_at2(tmp_path / "zero.AT2", Accelerogram("z", 0.01, np.zeros(4)))
    error = _error(read_records, ["zero.AT2"], tmp_path, pga=3.0)
    assert error.field == "zero.AT2" and "zero" in error.message


def test_accelerogram_checks_its_data():
    record = Accelerogram("r", 0.01, [1, 2, -3])
    assert record.scaled(2.0).peak == 6.0 and record.peak == 3.0
    for step, values in ((0.0, [1, 2]), (0.01, [1.0]), (0.01, [[1, 2], [3, 4]]), (0.01, [1, np.nan]), (float("inf"), [1, 2])):
        with pytest.raises(CaseError):
            Accelerogram("r", step, values)
    with pytest.raises(ArgumentError, match="factor"):
        record.scaled(0)
