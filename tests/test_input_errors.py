"""Honest boundaries (issue 30): a bad key of a case file is a CaseError naming the key as the file writes
it; a bad argument of a library call is an ArgumentError naming the Python argument; both are InputError
and ValueError. The command line names the option typed for an argument (``records`` -> ``--records``),
the dashboard names it in words; neither renames a case file's key."""

from __future__ import annotations

import copy
import tomllib

import pytest

import pounding
from pounding import ArgumentError, CaseError, InputError, simulate, sweep
from pounding.case.case import case_from_dict
from pounding.case.fields import build
from pounding.cli.commands import main
from pounding.cli.parser import error_line, option_for
from pounding.hazard.accelerograms import Accelerogram, write_at2
from pounding.hazard.excitation import ground_accelerations
from pounding.hazard.motion_fit import fit_excitation
from pounding.presets import preset_text

PRESET = "section5-T2-0.4"


def _raised(call) -> InputError:
    with pytest.raises(InputError) as raised:
        call()
    return raised.value


def test_the_two_kinds_are_input_errors_and_value_errors():
    for kind in (ArgumentError, CaseError):
        assert issubclass(kind, InputError) and issubclass(kind, ValueError)
        error = kind("records", "must be >= 1")
        assert (error.field, error.message, str(error)) == ("records", "must be >= 1", "records: must be >= 1")
        placed = error.under("excitation")
        assert type(placed) is kind and placed.field == "excitation.records" and placed.message == "must be >= 1"
    assert not issubclass(ArgumentError, CaseError) and not issubclass(CaseError, ArgumentError)
    assert {"InputError", "ArgumentError", "CaseError"} <= set(pounding.__all__)
    assert pounding.InputError is InputError and pounding.ArgumentError is ArgumentError


def test_a_bad_call_argument_is_an_argument_error_naming_it():
    error = _raised(lambda: simulate(PRESET, records=0))
    assert type(error) is ArgumentError and error.field == "records" and "0" in error.message
    error = _raised(lambda: simulate(PRESET, records=2, seed=-1))
    assert type(error) is ArgumentError and error.field == "seed"


@pytest.mark.parametrize("vary, words", [
    ("contact.gap=0:1:3", "not one string"),
    (["contact.gap=0:1"], "start:stop:count"),
    (["contact.gap"], "PATH=VALUES"),
    ({"buildings.3.storeys.1.period": [0.4]}, "counted from 1"),
])
def test_a_malformed_vary_is_an_argument_error_naming_vary(tmp_path, vary, words):
    error = _raised(lambda: sweep(PRESET, vary, records=2, output_dir=tmp_path / "out", scheduler="serial"))
    assert type(error) is ArgumentError and error.field == "vary" and words in error.message
    assert not (tmp_path / "out").exists()


def test_a_bad_key_of_the_case_file_is_a_case_error_naming_the_key():
    data = copy.deepcopy(tomllib.loads(preset_text(PRESET)))
    data["contact"]["gap"] = -1.0
    error = _raised(lambda: case_from_dict(data))
    assert type(error) is CaseError and error.field == "contact.gap"
    data = copy.deepcopy(tomllib.loads(preset_text(PRESET)))
    data["buildings"][1]["storeys"][0]["stiffness"] = "stiff"
    error = _raised(lambda: case_from_dict(data))
    assert type(error) is CaseError and error.field == "buildings.2.storeys.1.stiffness" and "'stiff'" in error.message


def test_a_function_given_the_case_files_values_names_the_key():
    """An argument refused by a function the loader calls came from the case file: it is its key there."""
    assert type(_raised(lambda: fit_excitation([], 100.0))) is ArgumentError
    error = _raised(lambda: build("excitation", fit_excitation, [], 100.0))
    assert type(error) is CaseError and error.field == "excitation.records"


def test_the_command_line_maps_an_argument_to_the_option_of_the_command():
    assert option_for("simulate", "records") == "--records"
    assert option_for("sweep", "vary") == "--vary" and option_for("sweep", "output_dir") == "--output"
    assert option_for("sweep", "table_format") == "--format" and option_for("report", "path") == "--output"
    assert option_for("export", "directory") == "--output" and option_for("export", "seed") == "--seed"
    assert option_for("spectrum", "period_ratio") == "--period-ratio"
    assert option_for("estimate", "vary") == "vary"  # estimate has no --vary: the name stays
    assert option_for("simulate", "case") == "case"  # the positional argument
    assert error_line("simulate", ArgumentError("records", "too many")) == "--records: too many"
    assert error_line("simulate", CaseError("records", "a key")) == "records: a key"  # a case file's key as written


def _cli(capsys, *argv) -> str:
    assert main(list(argv)) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    return err


def test_the_command_line_names_the_option_typed(tmp_path, capsys):
    err = _cli(capsys, "sweep", PRESET, "--vary", "contact.gap=0:1", "-o", str(tmp_path / "out"), "--scheduler", "serial")
    assert err.startswith("pounding sweep: error: --vary: 'contact.gap=0:1': a range is start:stop:count")
    err = _cli(capsys, "spectrum", PRESET, "--period1", "0.0001,0.0002", "--period2", "0.4")
    assert err.startswith("pounding spectrum: error: --period1: must lie in")
    (tmp_path / "file").write_text("")
    err = _cli(capsys, "sweep", PRESET, "--vary", "contact.gap=1,2", "-o", str(tmp_path / "file"), "--scheduler", "serial")
    assert err.startswith("pounding sweep: error: --output: ")
    with pytest.raises(SystemExit) as exit_code:  # refused by argparse before the library: the option named too
        main(["simulate", PRESET, "--records", "0"])
    assert exit_code.value.code == 2 and "argument --records: must be >= 1" in capsys.readouterr().err


def test_the_command_line_keeps_a_case_files_key(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(preset_text(PRESET).replace("restitution = ", "restitution = 1.5 #"))
    err = _cli(capsys, "estimate", str(path))
    assert err.startswith("pounding estimate: error: contact.restitution: ")


def test_records_beyond_a_recorded_suite_are_named_as_the_option(tmp_path, capsys):
    """The library says ``records`` (the Python argument); the command line says ``--records``."""
    (tmp_path / "motions").mkdir()
    excitation = pounding.load_case(PRESET).excitation
    for index, record in enumerate(ground_accelerations(excitation, 5, range(3))):
        write_at2(tmp_path / "motions" / f"m{index}.AT2", Accelerogram(f"m{index}", excitation.time_step, record))
    text = preset_text(PRESET)
    start, end = text.index("[excitation]"), text.index("[[buildings]]")
    (tmp_path / "case.toml").write_text(text[:start] + '[excitation]\nrecords = ["motions/*.AT2"]\n\n' + text[end:])
    case = pounding.load_case(tmp_path / "case.toml")
    error = _raised(lambda: simulate(case, records=4))
    assert type(error) is ArgumentError and error.field == "records" and "3 recorded motions" in error.message
    err = _cli(capsys, "fragility", str(tmp_path / "case.toml"), "--capacity", "100", "--pga", "0.1,0.2", "--records", "10",
               "--scheduler", "serial")
    assert err.startswith("pounding fragility: error: --records: the case has 3 recorded motions; give records at most that")


def test_the_dashboard_names_an_argument_in_words_never_as_a_flag():
    from dashboard.messages import message

    text = message(ArgumentError("target_probability", "must lie in (0, 1), got 1.5"))
    assert text == "Invalid input: target probability: must lie in (0, 1), got 1.5" and "--" not in text
    assert "(contact.gap)" in message(CaseError("contact.gap", "must be >= 0 m"))


@pytest.mark.parametrize(("edit", "field", "units_text"), [
    (lambda d: d["buildings"][0]["storeys"][0].update(stiffness=1e-300), "buildings.1.storeys.1.stiffness", "kgf*s^2/cm"),
    (lambda d: d["contact"].update(stiffness=1e-300), "contact.stiffness", "kgf/cm^1.5"),
    (lambda d: d["contact"].update(stiffness=1e300), "contact.stiffness", "kgf/cm^1.5"),
])
def test_a_floor_mass_or_contact_stiffness_beyond_any_building_is_refused_in_the_files_units(edit, field, units_text, capsys):
    """Issue 33: a storey stiffness of 1e-300 (a floor of 4e-302 kg) printed 0.00 kN beside '2.5e+121 times the
    floor weight', a contact stiffness of 1e-300 a penetration of 6e+120 sigma, both with exit 0. They are refused,
    naming the key and the range in the units the file is written in; the preset's own values are taken."""
    from pounding.presets import preset_text

    data = tomllib.loads(preset_text("section5-T2-0.4"))
    case_from_dict(copy.deepcopy(data))
    edit(data)
    with pytest.raises(CaseError) as caught:
        case_from_dict(data)
    assert caught.value.field == field and units_text in caught.value.message and "must lie in" in caught.value.message
    assert len(str(caught.value)) <= 200
