"""Hostile and careless input (issue 21): every invalid input, in a case file, on the command line or
through the library, is an InputError quoting the value in the user's own units: a CaseError naming the
case file's key as written, an ArgumentError naming the library call's argument (the command line names
the option typed); numpy scalars pass where Python numbers do; the resource limits refuse at once, naming the limit;
``POUNDING_LIMITS=off`` lifts them."""

from __future__ import annotations

import copy
import dataclasses
import math
import time
import tomllib

import numpy as np
import pytest

from pounding import (
    ArgumentError,
    BoucWen,
    Building,
    CaseError,
    CloughPenzien,
    Contact,
    Excitation,
    InputError,
    Settings,
    ShinozukaSato,
    Storey,
    defaults,
    design_gap,
    integrate,
    load_case,
    simulate,
    simulate_record,
)
from pounding.case.case import as_case, case_from_dict
from pounding.cli.commands import main
from pounding.errors import check_probability
from pounding.presets import preset_text
from pounding.studies.sweeps.spec import normalized_vary

PRESET = "section5-T2-0.4"  # kgf-cm-s
BASE = tomllib.loads(preset_text(PRESET))
CASE = load_case(PRESET)


def _refused(call, field: str, *quoted: str, seconds: float = 1.0, error: type = CaseError) -> InputError:
    """``call()`` raises ``error`` (a CaseError: a key of the case file; an ArgumentError: an argument of the call)
    naming ``field``, quoting each of ``quoted``, in one short line, at once."""
    start = time.perf_counter()
    with pytest.raises(error) as raised:
        call()
    elapsed = time.perf_counter() - start
    error = raised.value
    assert isinstance(error, ValueError)
    assert error.field == field, str(error)
    for text in quoted:
        assert text in error.message, str(error)
    assert len(error.message) <= 200 and "\n" not in str(error), str(error)
    assert elapsed < seconds, f"{elapsed:.2f} s: {error}"
    return error


def _case(changes: dict | None = None, **top) -> dict:
    """The preset's parsed file, with ``changes`` {dotted path (lists counted from 1): value or KeyError}."""
    data = copy.deepcopy(BASE)
    data.update(top)
    for path, value in (changes or {}).items():
        *parents, last = path.split(".")
        node = data
        for part in parents:
            node = node[int(part) - 1] if isinstance(node, list) else node[part]
        if value is KeyError:
            del node[last]
        else:
            node[last] = value
    return data


def _storey_with_mass(**storey) -> dict:
    return _case({"buildings.1.storeys": [{"mass": 40.0, "stiffness": 1097.0, **storey}]})


# --- the examples of the issue ------------------------------------------------


def test_a_negative_gap_is_quoted_in_the_file_units_not_in_metres():
    error = _refused(lambda: case_from_dict(_case({"contact.gap": -1.0})), "contact.gap", "-1 cm")
    assert "0.01" not in error.message


def test_a_negative_stiffness_beside_a_period_is_named_not_the_mass_derived_from_it():
    _refused(lambda: case_from_dict(_case({"buildings.1.storeys.1.stiffness": -1097.0})),
             "buildings.1.storeys.1.stiffness", "-1097 kgf/cm")


def test_levels_as_one_number_is_a_case_error_not_a_type_error():
    _refused(lambda: case_from_dict(_case({"contact.levels": 5})), "contact.levels", "5")


def test_an_empty_table_is_a_case_error():
    _refused(lambda: load_case({}), "excitation", "required")


@pytest.mark.parametrize("value", [5, None, 2.5, [PRESET]])
def test_load_case_refuses_what_is_neither_a_name_a_path_nor_a_table(value):
    _refused(lambda: load_case(value), "case", type(value).__name__, error=ArgumentError)


def test_load_case_takes_the_parsed_file():
    assert load_case(copy.deepcopy(BASE)).contact == CASE.contact


# --- a table of bad values per key of the case file ----------------------------

BAD_VALUES = [
    # (changes, field as written, text quoted: the value in the file's units, kgf-cm-s)
    ({"contact.gap": -1.0}, "contact.gap", "-1 cm"),
    ({"contact.stiffness": -2.0e5}, "contact.stiffness", "-200000 kgf/cm^1.5"),
    ({"contact.stiffness": 1e306}, "contact.stiffness", "1e+306 kgf/cm^1.5"),
    ({"buildings.2.storeys.1.stiffness": -9870.0}, "buildings.2.storeys.1.stiffness", "-9870 kgf/cm"),
    ({"buildings.2.storeys.1.period": 1e-300}, "buildings.2.storeys.1.period", "1e-300 s"),
    ({"buildings.2.storeys.1.period": 1e300}, "buildings.2.storeys.1.period", "1e+300 s"),
    ({"excitation.G0": -65.03}, "excitation.G0", "-65.03 cm^2/s^3"),
    ({"buildings.1.storeys.1.bouc_wen": {"alpha": 0.05, "beta": 2.0, "gamma": -3.0}},
     "buildings.1.storeys.1.bouc_wen.beta", "beta = 2, gamma = -3"),
    ({"buildings.1.storeys.1.bouc_wen": {"alpha": 0.05, "beta": 2.0, "gamma": -1.0, "n": 200}},
     "buildings.1.storeys.1.bouc_wen.beta", "2 1/cm^200"),
    ({"contact.levels": 5}, "contact.levels", "5"),
    ({"buildings.1.storeys.1.period": 10**400}, "buildings.1.storeys.1.period", "huge"),
]
BAD_TOP = [
    ({"units": []}, "units", "[]"),
    ({"name": 5}, "name", "5"),
    ({"description": {}}, "description", "{}"),
    ({"x" * 300: 1}, "'" + "x" * 36 + "...", "unknown key"),
]


@pytest.mark.parametrize("changes, field, quoted", BAD_VALUES, ids=[row[1] for row in BAD_VALUES])
def test_a_bad_value_names_the_key_and_quotes_it_as_written(changes, field, quoted):
    _refused(lambda: case_from_dict(_case(changes)), field, quoted)


@pytest.mark.parametrize("top, field, quoted", BAD_TOP, ids=[row[1][:20] for row in BAD_TOP])
def test_a_bad_top_level_value_names_the_key(top, field, quoted):
    _refused(lambda: case_from_dict(_case(**top)), field, quoted)


@pytest.mark.parametrize(
    "storey, field, quoted",
    [
        ({"mass": -40.0}, "buildings.1.storeys.1.mass", "-40 kgf*s^2/cm"),
        ({"mass": 10**400}, "buildings.1.storeys.1.mass", "huge"),
        ({"damping": -5.0}, "buildings.1.storeys.1.damping", "-5 kgf*s/cm"),
    ],
)
def test_a_storey_given_by_mass_quotes_it_in_the_file_units(storey, field, quoted):
    _refused(lambda: case_from_dict(_storey_with_mass(**storey)), field, quoted)


def test_si_files_quote_si_units():
    data = _case({"contact.gap": -0.5}, units="SI")
    _refused(lambda: case_from_dict(data), "contact.gap", "-0.5 m")


# --- the dataclasses: types checked where they are built ------------------------


@pytest.mark.parametrize(
    "build, field, quoted",
    [
        (lambda: dataclasses.replace(CASE, contacts="x"), "contacts", "str 'x'"),
        (lambda: dataclasses.replace(CASE, excitation=5), "excitation", "int 5"),
        (lambda: dataclasses.replace(CASE, buildings=(CASE.buildings[0], "x")), "buildings.2", "str 'x'"),
        (lambda: dataclasses.replace(CASE, buildings=CASE.buildings[0]), "buildings", "Building"),
        (lambda: dataclasses.replace(CASE, name=None), "name", "None"),
        (lambda: dataclasses.replace(CASE, units="furlongs"), "units", "'furlongs'"),
        (lambda: dataclasses.replace(CASE.buildings[0], storeys=[1]), "storeys.1", "int 1"),
        (lambda: dataclasses.replace(CASE.buildings[0], storeys=5), "storeys", "int 5"),
        (lambda: dataclasses.replace(CASE.buildings[0].storeys[0], bouc_wen={"alpha": 1}), "bouc_wen", "dict"),
        (lambda: dataclasses.replace(CASE.excitation, spectrum="kanai-tajimi"), "spectrum", "str"),
        (lambda: dataclasses.replace(CASE.excitation, envelope=0.085), "envelope", "float"),
        (lambda: dataclasses.replace(CASE.excitation, duration=True), "duration", "True"),
        (lambda: dataclasses.replace(CASE.contact, levels=5), "levels", "5"),
        (lambda: ShinozukaSato(B1=10**400), "B1", "huge"),
    ],
)
def test_a_dataclass_given_the_wrong_type_says_so_where_it_is_built(build, field, quoted):
    _refused(build, field, quoted)


def test_settings_are_arguments_of_a_study_not_keys_of_the_case():
    _refused(lambda: Settings(displacement_limit=math.inf), "displacement_limit", "inf", error=ArgumentError)
    _refused(lambda: Settings(workers=10**6), "workers", "1000000", error=ArgumentError)


# --- numpy scalars pass where Python numbers do, as Python numbers ---------------


def test_numpy_scalars_are_numbers():
    storey = Storey(np.float32(40.0), np.float64(1e6), BoucWen(alpha=np.float32(0.5), beta=np.int64(200), gamma=np.int8(0), n=np.int64(1)))
    assert type(storey.mass) is float and storey.mass == 40.0
    assert type(storey.bouc_wen.n) is float and type(storey.bouc_wen.beta) is float
    building = Building([storey], damping_ratio=np.float32(0.05))
    assert type(building.damping_ratio) is float and isinstance(building.storeys, tuple)
    spectrum = CloughPenzien(np.float32(0.0065), np.int64(27), np.float16(0.5), omega_f=np.float32(2.0))
    excitation = Excitation(spectrum, np.float32(20.0), ShinozukaSato(np.float32(0.085), 0.17), synthesis_factor=np.int64(2))
    assert type(excitation.duration) is float and type(excitation.synthesis_factor) is int
    assert type(spectrum.G0) is float and type(spectrum.omega_g) is float
    contact = Contact(np.float32(0.01), np.float64(2e9), levels=(np.int64(1), np.int32(1)))
    assert contact.levels == (1, 1) and all(type(level) is int for level in contact.levels)
    settings = Settings(tolerance=np.float32(1e-6), workers=np.int64(1), chunk_size=np.int16(4))
    assert type(settings.tolerance) is float and type(settings.chunk_size) is int
    assert check_probability(np.float32(0.5)) == 0.5


def test_numpy_scalars_in_a_case_table_and_a_study():
    data = _storey_with_mass(mass=np.float32(40.0))
    data["contact"]["levels"] = [np.int64(1), np.int64(1)]
    data["excitation"]["synthesis_factor"] = np.int64(1)
    case = case_from_dict(data)
    assert case.buildings[0].storeys[0].mass == pytest.approx(40.0 * 100 * 9.80665)
    result = simulate(case, records=np.int64(2), seed=np.int64(1), first_record=np.uint8(3))
    assert result.n_records == 2 and list(result.indices) == [3, 4]
    gap = design_gap(case, target_probability=np.float32(0.5), records=np.int64(4))
    assert gap.n_records == 4


# --- a preset name or a path wherever a Case is taken ----------------------------


def test_as_case(tmp_path):
    assert as_case(CASE) is CASE
    assert as_case(PRESET).contact == CASE.contact
    path = tmp_path / "mine.toml"
    path.write_text(preset_text(PRESET))
    assert as_case(path).contact == CASE.contact
    _refused(lambda: as_case(5), "case", "int 5", error=ArgumentError)
    _refused(lambda: as_case(BASE), "case", "dict", error=ArgumentError)


def test_the_studies_take_a_preset_name():
    assert simulate(PRESET, records=2).n_records == 2
    assert design_gap(PRESET, records=2).n_records == 2
    assert simulate_record(PRESET).time.size > 0
    for study in (simulate, design_gap, simulate_record):
        _refused(lambda: study(42), "case", "int 42", error=ArgumentError)


@pytest.mark.parametrize(
    "call, field, quoted",
    [
        (lambda: simulate(CASE, records=2, first_record=2**63), "first_record", "2^63"),
        (lambda: simulate(CASE, records=2, settings="fast"), "settings", "str 'fast'"),
        (lambda: simulate(CASE, records=2, progress=5), "progress", "int 5"),
        (lambda: simulate(CASE, records=2, cancel=True), "cancel", "bool True"),
        (lambda: integrate(CASE, np.full(100, np.nan), 0.005), "ground_acceleration", "finite"),
        (lambda: integrate(CASE, "shake", 0.005), "ground_acceleration", "str 'shake'"),
        (lambda: integrate(CASE, np.zeros(100), -0.005), "time_step", "-0.005"),
    ],
)
def test_a_bad_argument_of_a_study_is_named(call, field, quoted):
    _refused(call, field, quoted, error=ArgumentError)


# --- case files: any encoding, binary, oversized, malformed ----------------------


def test_a_binary_file_is_a_case_error_not_a_unicode_error(tmp_path):
    path = tmp_path / "image.toml"
    path.write_bytes(bytes(range(256)) * 8)
    _refused(lambda: load_case(path), str(path), "UTF-8")


def test_a_latin_1_file_is_refused_naming_the_byte(tmp_path):
    path = tmp_path / "latin.toml"
    path.write_bytes(preset_text(PRESET).replace("Rahimi", "Rahimí").encode("latin-1"))
    _refused(lambda: load_case(path), str(path), "0xed", "UTF-8")


@pytest.mark.parametrize("encoding", ["utf-8-sig", "utf-16", "utf-32"])
def test_a_file_with_a_byte_order_mark_loads(tmp_path, encoding):
    path = tmp_path / "marked.toml"
    path.write_bytes(preset_text(PRESET).encode(encoding))
    assert load_case(path).contact == CASE.contact


def test_a_path_too_long_is_neither_a_file_nor_a_preset():
    _refused(lambda: load_case("x" * 5000), "case", "neither a TOML file nor a preset", error=ArgumentError)


def test_a_deeply_nested_file_is_a_case_error(tmp_path):
    path = tmp_path / "deep.toml"
    path.write_text("a = " + "[" * 100_000 + "]" * 100_000)
    _refused(lambda: load_case(path), str(path), "not valid TOML")


def test_an_oversized_file_is_refused_before_it_is_read(tmp_path):
    path = tmp_path / "huge.toml"
    with path.open("wb") as file:
        file.truncate(50 * defaults.MAX_CASE_FILE_BYTES)  # sparse: 50 MB of zeros
    _refused(lambda: load_case(path), str(path), "1,000,000", defaults.LIMITS_VARIABLE)


# --- the resource limits: refused at once, the limit named ------------------------


@pytest.mark.parametrize(
    "changes, field, limit",
    [
        ({"excitation.duration": 1e9}, "excitation.duration", "2,097,152"),
        ({"excitation.time_step": 1e-9}, "excitation.time_step", "2,097,152"),
        ({"excitation.duration": 1e300, "excitation.time_step": 1e-300}, "excitation.duration", "2,097,152"),
        ({"excitation.duration": 10_000.0, "excitation.synthesis_factor": 16}, "excitation.synthesis_factor", "16,777,216"),
    ],
)
def test_a_record_too_long_is_refused_before_it_is_drawn(changes, field, limit):
    _refused(lambda: case_from_dict(_case(changes)), field, limit, "samples")


def _tall(storeys: int) -> dict:
    storey = {"mass": 40.0, "stiffness": 1097.0}
    return _case({"buildings.1.storeys": [dict(storey) for _ in range(storeys)]})


def test_storeys_per_building_are_limited():
    _refused(lambda: case_from_dict(_tall(21)), "buildings.1.storeys", "21 storeys", "limit of 20")
    million = _tall(10**6)
    _refused(lambda: case_from_dict(million), "buildings.1.storeys", "1,000,000 storeys")
    _refused(lambda: Building([Storey(1e4, 1e6)] * 21), "storeys", "limit of 20")
    assert case_from_dict(_tall(20)).buildings[0].n_storeys == 20


def test_records_are_limited():
    _refused(lambda: simulate(CASE, records=100_000_000_000), "records", "1,000,000", defaults.LIMITS_VARIABLE, error=ArgumentError)
    _refused(lambda: design_gap(CASE, records=10**7), "records", "1,000,000", error=ArgumentError)


def test_what_a_thread_holds_is_limited():
    long = case_from_dict(_case({"excitation.duration": 10_000.0}))
    _refused(lambda: simulate(long, records=100, settings=Settings(chunk_size=100)), "chunk_size", "16,777,216", error=ArgumentError)
    storeys = [{"mass": 40.0, "stiffness": 1097.0}] * 20
    tall = case_from_dict(_case({"buildings.1.storeys": storeys, "buildings.2.storeys": storeys, "excitation.duration": 10_000.0}))
    _refused(lambda: simulate_record(tall), "excitation.duration", "history values", "134,217,728")
    _refused(lambda: integrate(CASE, np.zeros(defaults.MAX_SAMPLES_PER_RECORD + 1), 0.005), "ground_acceleration", "2,097,152",
             error=ArgumentError)


def test_sweep_points_are_limited():
    _refused(lambda: normalized_vary(["contact.gap=0:5:100000000"]), "vary", "100,000,000", "10,000", error=ArgumentError)
    _refused(lambda: normalized_vary(["contact.gap=0:5:200", "contact.restitution=0.1:0.9:200"]), "vary", "40,000 sweep points",
             error=ArgumentError)
    _refused(lambda: normalized_vary({"contact.gap": range(20_000)}), "vary", "10,000", error=ArgumentError)
    assert len(normalized_vary({"contact.gap": [np.float32(0.5), np.int64(1)]})[0][1]) == 2


def test_the_limits_are_lifted_knowingly(monkeypatch):
    monkeypatch.setenv(defaults.LIMITS_VARIABLE, "off")
    assert Building([Storey(1e4, 1e6)] * 21).n_storeys == 21
    assert case_from_dict(_case({"excitation.duration": 1e9})).excitation.duration == 1e9  # nothing allocated yet
    assert len(normalized_vary(["contact.gap=0:5:20000"])[0][1]) == 20_000
    _refused(lambda: case_from_dict(_case({"excitation.duration": 1e300, "excitation.time_step": 1e-300})),
             "excitation.duration", "inf samples")  # beyond any machine


# --- the command line: the option as typed ---------------------------------------


@pytest.mark.parametrize(
    "argv, words",
    [
        (["simulate", PRESET, "--tolerance", "nan"], "argument --tolerance"),
        (["simulate", PRESET, "--records", "100000000000"], "argument --records: 100,000,000,000 records exceed the limit of 1,000,000"),
        (["estimate", PRESET, "--target-probability", "nan"], "argument --target-probability"),
        (["estimate", PRESET, "--michaelov-n1", "inf"], "argument --michaelov-n1"),
        (["validate", "--records", "100000000000"], "argument --records"),
    ],
)
def test_a_bad_option_is_named_as_typed(argv, words, capsys):
    start = time.perf_counter()
    with pytest.raises(SystemExit) as raised:
        main(argv)
    assert raised.value.code == 2
    assert time.perf_counter() - start < 1.0
    error = capsys.readouterr().err
    assert words in error and len(error.strip().splitlines()) == 1


@pytest.mark.parametrize(
    "argv, words",
    [
        (["sweep", PRESET, "--vary", "contact.gap=0:5:100000000", "-o", "{tmp}"], "--vary: 100,000,000 values"),
        (["estimate", "{tmp}/binary.toml"], "not a UTF-8 text file"),
        (["estimate", "{tmp}/tall.toml"], "buildings.1.storeys: 21 storeys exceed the limit of 20"),
        (["simulate", "{tmp}/long.toml"], "excitation.duration: 200,000,000,001 samples per record"),
    ],
)
def test_a_bad_case_or_sweep_exits_2_with_one_line(argv, words, tmp_path, capsys):
    (tmp_path / "binary.toml").write_bytes(bytes(range(256)))
    storey = "[[buildings.storeys]]\nmass = 4e4\nstiffness = 1e6\n"
    (tmp_path / "tall.toml").write_text('[excitation]\nG0 = 0.0065\nomega_g = 27.0\nxi_g = 0.34\nduration = 20.0\n'
                                        f'[[buildings]]\n{storey * 21}[[buildings]]\n{storey}[contact]\ngap = 0.01\nstiffness = 1e9\n')
    (tmp_path / "long.toml").write_text(preset_text(PRESET).replace("duration = 20.0", "duration = 1e9"))
    start = time.perf_counter()
    code = main([arg.format(tmp=tmp_path) for arg in argv])
    assert code == 2 and time.perf_counter() - start < 1.0
    error = capsys.readouterr().err
    assert words in error and len(error.strip().splitlines()) == 1
    assert not (tmp_path / "sweep.csv").exists()
