"""Case files: the schema, the unit systems, the presets and bad input."""

import math
import textwrap
import tomllib

import numpy as np
import pytest

from pounding import ArgumentError, CaseError, load_case, preset_names, simulate
from pounding.case.case import case_from_dict
from pounding.units import KGF_CM_S, STANDARD_GRAVITY

# The schema example, in the paper's units.
PAPER_UNITS = textwrap.dedent("""
    units = "kgf-cm-s"
    [excitation]
    spectrum = "kanai-tajimi"
    G0 = 65.03
    omega_g = 27.02
    xi_g = 0.34
    duration = 10.0
    envelope = "none"
    [[buildings]]
    damping_ratio = 0.05
      [[buildings.storeys]]
      mass = 40.0
      stiffness = 1097.0
      bouc_wen = { alpha = 0.05, A = 1.0, beta = 2.0, gamma = -1.0, n = 1 }
    [[buildings]]
    damping_ratio = 0.05
      [[buildings.storeys]]
      period = 0.4
      stiffness = 9870.0
      bouc_wen = { alpha = 0.05, A = 1.0, beta = 2.0, gamma = -1.0, n = 1 }
    [contact]
    model = "jankowski"
    gap = 1.0
    stiffness = 2.0e5
    restitution = 0.65
    levels = [1, 1]
""")

g = STANDARD_GRAVITY
# The same case converted by hand: kgf = g N, cm = 0.01 m, kgf*s^2/cm = 100 g kg.
SI_UNITS = textwrap.dedent(f"""
    units = "SI"
    [excitation]
    G0 = {65.03e-4!r}
    omega_g = 27.02
    xi_g = 0.34
    duration = 10.0
    [[buildings]]
      [[buildings.storeys]]
      mass = {40.0 * 100 * g!r}
      stiffness = {1097.0 * 100 * g!r}
      bouc_wen = {{ alpha = 0.05, A = 1.0, beta = 200.0, gamma = -100.0, n = 1 }}
    [[buildings]]
      [[buildings.storeys]]
      period = 0.4
      stiffness = {9870.0 * 100 * g!r}
      bouc_wen = {{ alpha = 0.05, A = 1.0, beta = 200.0, gamma = -100.0, n = 1 }}
    [contact]
    gap = 0.01
    stiffness = {2.0e5 * g / 0.01**1.5!r}
    restitution = 0.65
""")


def test_paper_units_and_si_give_the_same_si_answer():
    paper = case_from_dict(tomllib.loads(PAPER_UNITS))
    si = case_from_dict(tomllib.loads(SI_UNITS))
    for a, b in zip(paper.buildings, si.buildings):
        np.testing.assert_allclose(a.masses, b.masses, rtol=1e-12)
        np.testing.assert_allclose(a.stiffnesses, b.stiffnesses, rtol=1e-12)
        np.testing.assert_allclose(a.storey_damping(), b.storey_damping(), rtol=1e-12)
        assert a.storeys[0].bouc_wen.beta == pytest.approx(b.storeys[0].bouc_wen.beta, rel=1e-12)
    assert paper.contact.stiffness == pytest.approx(si.contact.stiffness, rel=1e-12)
    assert paper.excitation.spectrum.G0 == pytest.approx(si.excitation.spectrum.G0, rel=1e-12)
    a = simulate(paper, records=4, seed=1)
    b = simulate(si, records=4, seed=1)
    np.testing.assert_allclose(a.force_max, b.force_max, rtol=1e-6)
    assert a.impacts_mean == b.impacts_mean


def test_period_gives_mass_and_bouc_wen_scales_with_n():
    data = tomllib.loads(PAPER_UNITS)
    data["buildings"][0]["storeys"][0]["bouc_wen"] = {"alpha": 0.05, "beta": 1.5, "gamma": -0.5, "n": 2}
    case = case_from_dict(data)
    storey = case.buildings[1].storeys[0]
    assert storey.mass == pytest.approx(storey.stiffness / (2 * math.pi / 0.4) ** 2)
    assert storey.mass == pytest.approx(40.0 * KGF_CM_S.mass, rel=2e-3)  # the notes' ~40 kgf*s^2/cm
    assert case.buildings[0].storeys[0].bouc_wen.beta == pytest.approx(1.5 * 100**2)
    assert case.buildings[0].storeys[0].bouc_wen.yield_displacement == pytest.approx(0.01)


@pytest.mark.parametrize("name", preset_names())
def test_every_preset_loads(name):
    case = load_case(name)
    assert case.description
    assert case.buildings[0].periods[0] == pytest.approx(1.2, rel=1e-3)
    t2 = float(name.split("T2-")[1].split("-")[0])
    assert case.buildings[1].periods[0] == pytest.approx(t2, rel=1e-3)
    assert case.excitation.stationary == ("nonstationary" not in name)
    expected_g0 = 65.03e-4 * (4 * math.pi**2 if name.endswith("G0x4pi2") else 1.0)
    assert case.excitation.spectrum.G0 == pytest.approx(expected_g0, rel=1e-6)
    # its title, for lists (the dashboard's), says what its name does, in words
    from pounding.presets import preset_title

    title = preset_title(name)
    assert case.title == title and f"T2 = {t2:g} s" in title and ("non-stationary" in title) == ("nonstationary" in name)
    assert ("G0 x 4 pi^2" in title) == name.endswith("G0x4pi2") and title.startswith(f"Section {name[7]}")


def test_every_preset_has_a_title_of_its_own():
    from pounding.presets import preset_title

    titles = [preset_title(name) for name in preset_names()]
    assert len(set(titles)) == len(titles) and all(0 < len(t) <= 80 for t in titles)


def test_presets_cover_the_paper():
    names = set(preset_names())
    for section in (5, 6):
        for t2 in ("0.4", "0.6", "0.8"):
            assert f"section{section}-T2-{t2}" in names
            assert f"section{section}-T2-{t2}-nonstationary" in names
            assert f"section{section}-T2-{t2}-G0x4pi2" in names


def _bad(path: list, value):
    data = tomllib.loads(PAPER_UNITS)
    target = data
    for key in path[:-1]:
        target = target[key]
    if value is KeyError:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    return data


@pytest.mark.parametrize(
    "path, value, field",
    [
        (["buildings", 0, "storeys", 0, "mass"], -40.0, "buildings.1.storeys.1.mass"),
        (["buildings", 1, "storeys", 0, "period"], -0.4, "buildings.2.storeys.1.period"),
        (["buildings", 1, "storeys", 0, "period"], 0.0, "buildings.2.storeys.1.period"),
        (["contact", "restitution"], 0.0, "contact.restitution"),
        (["contact", "restitution"], 1.2, "contact.restitution"),
        (["contact", "gap"], -1.0, "contact.gap"),
        (["buildings", 0, "storeys", 0, "bouc_wen", "n"], 0.5, "buildings.1.storeys.1.bouc_wen.n"),
        (["buildings", 0, "storeys", 0, "bouc_wen", "gamma"], -3.0, "buildings.1.storeys.1.bouc_wen.beta"),
        (["buildings", 0, "storeys", 0, "colour"], "red", "buildings.1.storeys.1.colour"),
        (["excitation", "spectrum"], "white", "excitation.spectrum"),
        (["excitation", "duration"], -5.0, "excitation.duration"),
        (["excitation", "xi_g"], "high", "excitation.xi_g"),
        (["excitation", "synthesis_factor"], 2.5, "excitation.synthesis_factor"),
        (["excitation", "synthesis_factor"], 0, "excitation.synthesis_factor"),
        (["contact", "levels"], [2, 1], "contact.levels"),
        (["contact", "model"], "rubber", "contact.model"),
        (["units"], "furlongs", "units"),
        (["buildings", 0, "damping_ratio"], 1.5, "buildings.1.damping_ratio"),
        (["excitation"], KeyError, "excitation"),
    ],
)
def test_bad_input_names_the_field(path, value, field):
    with pytest.raises(CaseError) as raised:
        case_from_dict(_bad(path, value))
    assert raised.value.field == field
    assert isinstance(raised.value, ValueError)
    assert field in str(raised.value)


def test_missing_building_is_named():
    data = tomllib.loads(PAPER_UNITS)
    data["buildings"] = data["buildings"][:1]
    with pytest.raises(CaseError, match=r"buildings: two or more \[\[buildings\]\] tables"):
        case_from_dict(data)


def test_multi_storey_building_takes_no_period():
    data = tomllib.loads(PAPER_UNITS)
    storey = data["buildings"][1]["storeys"][0]
    data["buildings"][1]["storeys"] = [storey, dict(storey)]
    with pytest.raises(CaseError, match=r"buildings\.2\.storeys\.1\.period"):
        case_from_dict(data)


def test_unknown_file_or_preset():
    with pytest.raises(ArgumentError, match="neither a TOML file nor a preset"):
        load_case("no-such-case")


def test_case_file_round_trip(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text(PAPER_UNITS)
    case = load_case(path)
    assert case.name == "mine"
    assert case.units == "kgf-cm-s"
    broken = tmp_path / "broken.toml"
    broken.write_text("units = ")
    with pytest.raises(CaseError, match="not valid TOML"):
        load_case(broken)


def test_synthesis_factor_is_read():
    data = tomllib.loads(PAPER_UNITS)
    default = case_from_dict(data).excitation
    data["excitation"]["synthesis_factor"] = 4
    longer = case_from_dict(data).excitation
    assert (default.synthesis_factor, longer.synthesis_factor) == (1, 4)
    assert longer.fft_length == 4 * default.fft_length
