"""Recorded motions in a case, the PGA form of a spectrum and `pounding records`: the same records give
the same numbers whichever way they reach the integrator."""

import json
import math
import textwrap

import numpy as np
import pytest

from pounding import CaseError, design_gap, load_case, simulate
from pounding.cli.commands import main
from pounding.hazard.accelerograms import Accelerogram, read_accelerogram, write_at2
from pounding.hazard.excitation import ground_accelerations
from pounding.presets import preset_text
from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration
from pounding.units import STANDARD_GRAVITY

PRESET = "section5-T2-0.4"


def _with_excitation(table: str) -> str:
    text = preset_text(PRESET)
    start, end = text.index("[excitation]"), text.index("[[buildings]]")
    return text[:start] + textwrap.dedent(table) + "\n" + text[end:]


@pytest.fixture(scope="module")
def suite(tmp_path_factory):
    """Six synthetic records of the preset (seed 5) written as files, and a case reading them."""
    folder = tmp_path_factory.mktemp("suite")
    (folder / "motions").mkdir()
    excitation = load_case(PRESET).excitation
    records = ground_accelerations(excitation, 5, range(6))
    for index, record in enumerate(records):
        write_at2(folder / "motions" / f"m{index}.AT2", Accelerogram(f"m{index}", excitation.time_step, record))
    (folder / "case.toml").write_text(_with_excitation('[excitation]\nrecords = ["motions/*.AT2"]\n'))
    return folder, records


def test_simulating_the_files_integrates_the_records_as_synthesized(suite):
    folder, records = suite
    case = load_case(folder / "case.toml")
    assert case.recorded and [r.name for r in case.hazard.records] == [f"motions/m{i}.AT2" for i in range(6)]
    from_files = simulate(case)
    synthetic = simulate(PRESET, records=6, seed=5)
    # the files hold 8 significant digits: the forces agree to about that
    np.testing.assert_allclose(from_files.force_max, synthetic.force_max, rtol=1e-5)
    assert from_files.to_dict()["seed"] is None and len(from_files.to_dict()["record_files"]) == 6


def test_the_design_gap_of_a_suite_takes_its_records_each_once(suite):
    """Without a record count the design gap of a recorded case is that of its own records (the default 400
    synthetic records do not exist there): the 95th percentile of their free peaks, the same as the synthetic
    records they were written from give."""
    folder, _ = suite
    from_files = design_gap(load_case(folder / "case.toml"), 0.95)
    synthetic = design_gap(PRESET, 0.95, records=6, seed=5)
    assert len(from_files.peaks) == 6
    assert from_files.gap == pytest.approx(synthetic.gap, rel=1e-5)


def test_the_closed_form_takes_the_fitted_spectrum(suite, capsys):
    folder, _ = suite
    assert main(["estimate", str(folder / "case.toml"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    fitted = out["fitted_excitation"]
    assert fitted["spectrum"] in ("kanai-tajimi", "clough-penzien")
    assert "Arias" in fitted["duration_definition"] and 0.8 * 20 < fitted["duration"] < 20
    assert out["record_files"][0] == "motions/m0.AT2"
    # six stationary records of the preset: omega_g of the preset's soil comes back roughly
    assert fitted["omega_g"] == pytest.approx(27.02, rel=0.25)


def test_simulate_says_records_and_seed_do_not_apply(suite, capsys):
    folder, _ = suite
    assert main(["simulate", str(folder / "case.toml"), "--records", "3", "--json"]) == 0
    captured = capsys.readouterr()
    assert "do not apply" in captured.err and len(json.loads(captured.out)["force_max"]) == 6


def test_pounding_records_writes_what_simulate_integrates(tmp_path, capsys):
    assert main(["records", PRESET, "--records", "3", "--seed", "7", "-o", str(tmp_path / "out")]) == 0
    files = sorted((tmp_path / "out").glob("*.AT2"))
    assert [f.name for f in files] == ["record-0.AT2", "record-1.AT2", "record-2.AT2"]
    excitation = load_case(PRESET).excitation
    expected = ground_accelerations(excitation, 7, range(3))
    for file, record in zip(files, expected):
        read = read_accelerogram(file)
        assert read.time_step == excitation.time_step
        np.testing.assert_allclose(read.acceleration, record, atol=1e-7 * np.abs(record).max())
    assert main(["records", PRESET, "--records", "2", "-o", str(tmp_path / "csv"), "--format", "csv"]) == 0
    assert len(list((tmp_path / "csv").glob("*.csv"))) == 2


def test_an_interrupted_records_run_leaves_a_marker_saying_the_set_is_partial(tmp_path, monkeypatch):
    """Issue 33: an interrupted `pounding records` left complete files and nothing to say the set was partial; its
    INCOMPLETE.txt stays behind until the last record is written, and a full run leaves none."""
    import pounding.hazard.accelerograms as accelerograms

    from pounding.cli.hazard import INCOMPLETE_MARKER

    assert main(["records", PRESET, "--records", "3", "-o", str(tmp_path / "whole")]) == 0
    assert not (tmp_path / "whole" / INCOMPLETE_MARKER).exists() and len(list((tmp_path / "whole").glob("*.AT2"))) == 3
    original, calls = accelerograms.write_at2, []

    def interrupted(*args, **kwargs):
        calls.append(1)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return original(*args, **kwargs)

    monkeypatch.setattr(accelerograms, "write_at2", interrupted)
    assert main(["records", PRESET, "--records", "3", "-o", str(tmp_path / "part")]) == 130  # Ctrl-C's exit status
    assert len(list((tmp_path / "part").glob("*.AT2"))) == 2
    assert "stopped early" in (tmp_path / "part" / INCOMPLETE_MARKER).read_text()


def test_records_bad_arguments_exit_2(capsys, tmp_path):
    assert main(["records", PRESET, "-o", str(tmp_path)]) == 2
    assert "--records" in capsys.readouterr().err
    with pytest.raises(SystemExit) as caught:  # argparse: a count below 1
        main(["records", PRESET, "--records", "0", "-o", str(tmp_path)])
    assert caught.value.code == 2 and "--records" in capsys.readouterr().err
    (tmp_path / "file").write_text("")
    assert main(["records", PRESET, "--records", "1", "-o", str(tmp_path / "file")]) == 2
    assert "--output" in capsys.readouterr().err


@pytest.mark.parametrize(
    "table, field",
    [
        ('[excitation]\nrecords = ["nothing/*.AT2"]\n', "excitation.records.nothing/*.AT2"),
        ('[excitation]\nrecords = []\n', "excitation.records"),
        ('[excitation]\nrecords = ["motions/*.AT2"]\nscale = 2\npga = 0.3\n', "excitation.pga"),
        ('[excitation]\nrecords = ["motions/*.AT2"]\nduration = 20\n', "excitation.duration"),
    ],
)
def test_bad_record_keys_name_the_key(suite, table, field):
    folder, _ = suite
    path = folder / "bad.toml"
    path.write_text(_with_excitation(table))
    with pytest.raises(CaseError) as caught:
        load_case(path)
    assert caught.value.field == field


@pytest.mark.slow
def test_a_record_shorter_than_five_periods_is_refused(tmp_path):
    short = Accelerogram("short", 0.005, np.sin(np.arange(1000) * 0.05))  # 5 s against T1 = 1.2 s
    write_at2(tmp_path / "short.AT2", short)
    (tmp_path / "case.toml").write_text(_with_excitation('[excitation]\nrecords = ["short.AT2"]\n'))
    with pytest.raises(CaseError) as caught:
        load_case(tmp_path / "case.toml")
    assert caught.value.field == "short.AT2" and "5 times" in caught.value.message


def test_scaling_each_record_to_a_pga(suite):
    folder, records = suite
    path = folder / "pga.toml"
    path.write_text(_with_excitation('[excitation]\nrecords = ["motions/*.AT2"]\npga = 0.25\n'))
    case = load_case(path)
    for record in case.hazard.records:
        assert record.peak == pytest.approx(0.25 * STANDARD_GRAVITY, rel=1e-12)


@pytest.mark.parametrize("envelope", ["", 'envelope = "shinozuka-sato"\n'])
def test_the_pga_form_gives_records_of_that_mean_peak(tmp_path, envelope):
    """G0 chosen for an expected PGA of 0.3 g: the mean peak of 200 records is within 3 % of it."""
    path = tmp_path / "case.toml"
    path.write_text(_with_excitation(f'[excitation]\nspectrum = "kanai-tajimi"\npga = 0.3\nomega_g = 27.02\nxi_g = 0.34\n'
                                     f'duration = 20.0\n{envelope}'))
    excitation = load_case(path).excitation
    assert expected_peak_ground_acceleration(excitation) == pytest.approx(0.3 * STANDARD_GRAVITY, rel=1e-9)
    peaks = np.abs(ground_accelerations(excitation, 11, range(200))).max(axis=1)
    assert peaks.mean() == pytest.approx(0.3 * STANDARD_GRAVITY, rel=0.03)
    assert math.isfinite(excitation.spectrum.G0)


def test_pga_and_g0_together_are_refused(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(_with_excitation('[excitation]\nG0 = 65.03\npga = 0.3\nomega_g = 27.02\nxi_g = 0.34\nduration = 20.0\n'))
    with pytest.raises(CaseError) as caught:
        load_case(path)
    assert caught.value.field == "excitation" and "G0 and pga" in caught.value.message


def test_a_bad_record_file_exits_2_naming_file_and_line(tmp_path, capsys):
    (tmp_path / "bad.AT2").write_text("PEER\nEVENT\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    4, DT= .0050 SEC\n"
                                      "0.1 0.2 nan 0.4\n")
    (tmp_path / "case.toml").write_text(_with_excitation('[excitation]\nrecords = ["bad.AT2"]\n'))
    assert main(["simulate", str(tmp_path / "case.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "bad.AT2:5" in err


@pytest.mark.parametrize("step", ["1e-300", "5.0"])
def test_a_time_step_no_record_has_is_refused_naming_the_file_and_line(tmp_path, capsys, step):
    """Issue 33: DT = 1e-300 was blamed on cutoff_frequency; a step outside [1e-5, 1] s is refused naming the DT line."""
    (tmp_path / "odd.AT2").write_text(f"PEER\nEVENT\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    4, DT= {step} SEC\n"
                                      "0.1 0.2 0.3 0.4\n")
    (tmp_path / "case.toml").write_text(_with_excitation('[excitation]\nrecords = ["odd.AT2"]\n'))
    assert main(["estimate", str(tmp_path / "case.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "odd.AT2:4" in err and "time step DT must lie in [1e-05, 1] s" in err


@pytest.mark.parametrize("kind", ["folder", "pipe", "device"])
def test_a_record_that_is_no_file_says_what_it_is(tmp_path, kind):
    """Issue 33: a folder, a FIFO or a link to /dev/zero given as a record was "no such file"."""
    import os

    path = tmp_path / "odd.AT2"
    {"folder": lambda: path.mkdir(), "pipe": lambda: os.mkfifo(path), "device": lambda: path.symlink_to("/dev/zero")}[kind]()
    (tmp_path / "case.toml").write_text(_with_excitation('[excitation]\nrecords = ["odd.AT2"]\n'))
    with pytest.raises(CaseError, match=f"odd.AT2: is a {kind}, not a file"):
        load_case(tmp_path / "case.toml")


@pytest.mark.slow
def test_the_report_shows_the_periodogram_and_the_fitted_spectrum(suite, tmp_path):
    from pounding.report import write_report

    folder, _ = suite
    text = write_report(tmp_path / "recorded.html", load_case(folder / "case.toml")).read_text()
    assert "mean periodogram and the fitted" in text and "6 recorded motions" in text and "storey 1: yield drift" in text


def test_a_recorded_case_states_the_accuracy_measured_on_recorded_suites(suite):
    """The closed form of a recorded suite was measured against the records themselves (generated suites and FEMA
    P695's far-field set): a recorded case states that row of its regime, not the Kanai-Tajimi grid's, which was
    measured on the very process the records now only approximate."""
    from pounding import estimate
    from pounding.closed_form.regimes import accuracy_data

    folder, _ = suite
    recorded = estimate(load_case(folder / "case.toml"))
    table = accuracy_data()["force"]["recorded suites"]
    label = "rare, yielding" if recorded.accuracy_regime == "rare" else recorded.accuracy_regime
    row = table[label]
    assert row["cases"] > 0, "measured there: not the Kanai-Tajimi row it would fall back to"
    assert (recorded.accuracy.low, recorded.accuracy.high, recorded.accuracy.cases) == (row["low"], row["high"], row["cases"])
    assert "recorded suites" in recorded.measured_accuracy
    synthetic = estimate(load_case(PRESET)).accuracy  # the same buildings under the process: the grid's row
    assert "recorded suites" not in synthetic.where


@pytest.mark.parametrize(("count", "size"), [(3930, 199_000_000), (2_000_000, 100_000)])
def test_an_at2_file_whose_size_cannot_hold_its_npts_is_refused_from_its_header(tmp_path, count, size):
    """Issue 33: a 199 MB record with a wrong NPTS was read and parsed whole (18 s, 1.85 GB) before it was refused;
    the header and the file's size tell it at once, naming the NPTS line."""
    path = tmp_path / "wrong.AT2"
    with path.open("wb") as stream:
        stream.write(f"PEER\nEVENT\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= {count:7d}, DT= .00500 SEC\n".encode())
        stream.write(b"  .1234567E-02" * 5 + b"\n")
        stream.truncate(size)  # the rest sparse: as large on the disk as in the listing, never written
    with pytest.raises(CaseError) as caught:
        read_accelerogram(path)
    assert caught.value.field == f"{path}:4" and f"NPTS = {count}" in caught.value.message
    assert ("more than" if size > count else "fewer than") in caught.value.message


def test_an_at2_file_of_the_size_its_npts_needs_is_read(tmp_path):
    """The check against the size passes a long record written as the NGA files are (100,000 values, 1.4 MB)."""
    values = np.random.default_rng(0).normal(0.0, 0.05, 100_000)
    path = write_at2(tmp_path / "long.AT2", Accelerogram("long", 0.005, values * STANDARD_GRAVITY))
    assert path.stat().st_size > 65_536
    assert read_accelerogram(path).acceleration.size == 100_000
