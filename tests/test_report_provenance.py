"""Where a report's inputs came from: the keys changed from a preset, found in
the parsed case files whatever their unit system and spelling, and the
report's title and table that say so."""

from __future__ import annotations

import copy
import re
import tomllib

import pytest

from pounding import ArgumentError, load_case
from pounding.case.case import case_from_dict
from pounding.case.engineering import ground_motion_terms
from pounding.cli.commands import main
from pounding.presets import preset_names, preset_text
from pounding.report import CaseChange, case_changes, case_provenance, compute_snapshot, write_report
from pounding.report.case_keys import DEFAULTS, key_label
from pounding.units import STANDARD_GRAVITY

PRESET = "section5-T2-0.4"  # kgf-cm-s; one-storey buildings given by period and stiffness


def preset_data(name: str = PRESET) -> dict:
    return tomllib.loads(preset_text(name))


def as_dashboard_writes(name: str) -> dict:
    """The preset ``name`` written another way: SI, every default spelled out, a one-storey building by its
    mass and period, a multi-storey one by mass and stiffness (as the dashboard writes a case)."""
    case = load_case(name)
    spectrum, excitation = case.excitation.spectrum, case.excitation
    buildings = []
    for building in case.buildings:
        storeys = []
        for storey in building.storeys:
            law = storey.bouc_wen
            entry = {"mass": storey.mass, "bouc_wen": {"alpha": law.alpha, "A": law.A, "beta": law.beta, "gamma": law.gamma, "n": law.n}}
            entry |= {"period": float(building.periods[0])} if building.n_storeys == 1 else {"stiffness": storey.stiffness}
            storeys.append(entry)
        buildings.append({"damping_ratio": building.damping_ratio, "storeys": storeys})
    envelope = {"envelope": "none"} if excitation.envelope is None else {
        "envelope": "shinozuka-sato", "B1": excitation.envelope.B1, "B2": excitation.envelope.B2}
    c = case.contact
    return {
        "units": "SI", "name": name, "description": "another description",
        "excitation": {"spectrum": "kanai-tajimi", "G0": spectrum.G0, "omega_g": spectrum.omega_g, "xi_g": spectrum.xi_g,
                       "duration": excitation.duration, "time_step": excitation.time_step,
                       "cutoff_frequency": excitation.cutoff_frequency, "synthesis_factor": excitation.synthesis_factor, **envelope},
        "buildings": buildings,
        "contact": {"model": c.model, "gap": c.gap, "stiffness": c.stiffness, "restitution": c.restitution, "levels": list(c.levels)},
    }


def test_a_preset_modified_in_three_keys_lists_exactly_those_three():
    before = preset_data()
    after = copy.deepcopy(before)
    after["contact"]["gap"] = 5.0  # cm
    after["contact"]["restitution"] = 0.75
    after["buildings"][1]["storeys"][0]["period"] = 0.5  # the file gives period and stiffness: the mass follows, unlisted
    after["description"] = "changed too, but a description is no input"
    assert case_changes(before, after) == (
        CaseChange("buildings.2.storeys.1.period", 0.4, 0.5, "s"),
        CaseChange("contact.gap", pytest.approx(0.01), pytest.approx(0.05), "m"),
        CaseChange("contact.restitution", 0.65, 0.75, "-"),
    )
    shown = case_changes(before, after, "kgf-cm-s")
    assert [(c.key, c.before, c.after, c.unit) for c in shown][1] == ("contact.gap", 1.0, 5.0, "cm")
    provenance = case_provenance(after, PRESET, command="pounding report x.toml")
    assert provenance.modified and len(provenance.changes) == 3 and provenance.source == PRESET


@pytest.mark.parametrize("name", preset_names())
def test_an_unmodified_preset_lists_no_change_however_it_is_written(name):
    data = preset_data(name)
    assert case_changes(data, copy.deepcopy(data)) == ()
    rewritten = as_dashboard_writes(name)
    assert case_changes(data, rewritten) == () and case_changes(rewritten, data) == ()
    provenance = case_provenance(rewritten, name)
    assert not provenance.modified and provenance.changes == ()


def test_a_change_in_another_spelling_names_the_keys_either_file_gives():
    """The dashboard keeps a storey's mass when its period changes: the preset's stiffness changed with it."""
    rewritten = as_dashboard_writes(PRESET)
    rewritten["buildings"][1]["storeys"][0]["period"] = 0.5
    changes = case_changes(preset_data(), rewritten, "kgf-cm-s")
    assert [c.key for c in changes] == ["buildings.2.storeys.1.period", "buildings.2.storeys.1.stiffness"]
    stiffness = changes[1]
    assert stiffness.before == pytest.approx(9870.0) and stiffness.after == pytest.approx(9870.0 * (0.4 / 0.5) ** 2)
    assert stiffness.unit == "kgf/cm"


def test_a_yield_drift_is_compared_as_its_bouc_wen_law():
    before = preset_data()
    after = copy.deepcopy(before)
    # beta = 2, gamma = -1 /cm: beta + gamma = 1 / (1 cm), beta share 2; the same law by its yield drift
    same = {"yield_drift": 1.0, "post_yield_ratio": 0.05, "n": 1, "beta_share": 2.0}
    after["buildings"][0]["storeys"][0].pop("bouc_wen")
    after["buildings"][0]["storeys"][0]["hysteresis"] = same
    assert case_changes(before, after) == ()
    after["buildings"][0]["storeys"][0]["hysteresis"] = {**same, "yield_drift": 2.0}
    changes = {c.key: (c.before, c.after, c.unit) for c in case_changes(before, after, "kgf-cm-s")}
    assert changes == {"buildings.1.storeys.1.bouc_wen.beta": (2.0, pytest.approx(1.0), "1/cm"),
                       "buildings.1.storeys.1.bouc_wen.gamma": (-1.0, pytest.approx(-0.5), "1/cm")}


def test_a_pga_is_compared_as_its_g0():
    before = preset_data()
    pga = ground_motion_terms(load_case(PRESET))["pga_expected"] / STANDARD_GRAVITY
    after = copy.deepcopy(before)
    del after["excitation"]["G0"]
    after["excitation"]["pga"] = pga
    assert case_changes(before, after) == ()
    after["excitation"]["pga"] = 2 * pga  # G0 scales with the PGA squared
    (change,) = case_changes(before, after, "kgf-cm-s")
    assert change.key == "excitation.G0" and change.after == pytest.approx(4 * 65.03, rel=1e-6) and change.unit == "cm^2/s^3"


_PLACES = {  # where each group of defaults lives in a case file
    "excitation": ("excitation",), "process": ("excitation",), "shinozuka-sato": ("excitation",),
    "clough-penzien": ("excitation",), "design": ("excitation",), "ec8": ("excitation",),
    "building": ("buildings", 0), "bouc_wen": ("buildings", 0, "storeys", 0, "bouc_wen"),
    "hysteresis": ("buildings", 0, "storeys", 0, "hysteresis"), "contact": ("contact",),
}


def _at(data, path):
    for part in path:
        data = data[part]
    return data


@pytest.mark.parametrize("form", list(DEFAULTS))
def test_each_default_is_the_parsers(form):
    """A key left out and the same key written at DEFAULTS' value give the same case."""
    data = preset_data("section6-T2-0.4-nonstationary" if form == "shinozuka-sato" else PRESET)
    storey = data["buildings"][0]["storeys"][0]
    if form == "clough-penzien":
        data["excitation"]["spectrum"] = "clough-penzien"
    elif form == "hysteresis":
        storey.pop("bouc_wen")
        storey["hysteresis"] = {"yield_drift": 1.0, "post_yield_ratio": 0.02}
    elif form in ("design", "ec8"):
        code = {"code": "ec8", "ag": 0.2, "ground_type": "B"}
        data["excitation"] = {"spectrum": "design", "duration": 10.0, **code}
    for key in DEFAULTS[form]:
        _at(data, _PLACES[form]).pop(key, None)
    written = copy.deepcopy(data)
    _at(written, _PLACES[form]).update(copy.deepcopy(DEFAULTS[form]))
    assert _numbers(case_from_dict(data)) == _numbers(case_from_dict(written)), form


def _numbers(case) -> str:
    """The case's physics as text (its numbers to 12 digits), for comparison."""
    return re.sub(r"\d\.\d{12,}", lambda m: f"{float(m.group()):.12g}", repr((case.excitation, case.buildings, case.contact)))


def test_an_unknown_preset_is_named():
    with pytest.raises(ArgumentError, match="preset"):
        case_provenance(preset_data(), "no-such-preset")


def test_key_labels_read_as_words():
    assert key_label("buildings.2.storeys.1.period") == "building 2, storey 1: period T"
    assert key_label("contact.gap") == "contact: gap"
    assert key_label("excitation.G0") == "excitation: G0 (Kanai-Tajimi intensity)"


# --- the report -------------------------------------------------------------------------------------


def _visible(text: str) -> str:
    body = re.sub(r"<(script|style)\b[^>]*>.*?</\1>", "", text, flags=re.S)
    return re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", body))


@pytest.mark.slow
def test_the_report_of_a_modified_preset_says_so_and_lists_the_changes(tmp_path):
    after = preset_data()
    after["contact"]["gap"] = 5.0
    after["contact"]["restitution"] = 0.75
    after["excitation"]["duration"] = 30.0
    provenance = case_provenance(after, PRESET, command="pounding dashboard (Export report)", units="kgf-cm-s")
    snapshot = compute_snapshot(case_from_dict(after, name=PRESET))
    text = _visible(write_report(tmp_path / "r.html", snapshot, "kgf-cm-s", provenance=provenance).read_text())
    assert f"Pounding report: modified from preset {PRESET}" in text
    assert "modified in 3 key(s)" in text and "The preset's description (before the changes)" in text
    table = text[text.index("Changed from the preset"):text.index("parameter value unit")]
    for key, before, after_value, unit in (("contact.gap", "1", "5", "cm"), ("contact.restitution", "0.65", "0.75", "-"),
                                           ("excitation.duration", "20", "30", "s")):
        assert re.search(rf"{re.escape(key)} {before} {after_value} {re.escape(unit)}", table), key
    assert table.count(" preset this report ") == 1 and len(re.findall(r"(?:contact|excitation|buildings)\.[\w.]+", table)) == 3
    assert "pounding dashboard (Export report)" in text


@pytest.mark.slow
def test_the_report_of_an_unmodified_preset_says_no_modification(tmp_path):
    snapshot = compute_snapshot(load_case(PRESET))
    text = _visible(write_report(tmp_path / "r.html", snapshot, provenance=case_provenance(as_dashboard_writes(PRESET), PRESET)).read_text())
    assert f"Pounding report: {PRESET} " in text and "with no modification" in text
    assert "modified from" not in text and "Changed from the preset" not in text
    # Without a provenance, a case named after a preset is checked against it: the same numbers are the preset ...
    assert "with no modification" in _visible(write_report(tmp_path / "s.html", snapshot).read_text())
    # ... and other numbers are not, though the changes cannot be listed.
    changed = case_from_dict({**preset_data(), "contact": {**preset_data()["contact"], "gap": 3.0}}, name=PRESET)
    text = _visible(write_report(tmp_path / "t.html", compute_snapshot(changed)).read_text())
    assert f"modified from preset {PRESET}" in text and "the changes are not listed" in text


@pytest.mark.slow
def test_pounding_report_names_its_source_and_command(tmp_path, capsys):
    case_file = tmp_path / "mine.toml"  # as saved from the dashboard: named after its preset
    case_file.write_text(preset_text(PRESET).replace("restitution = 0.65", "restitution = 0.7"))
    assert main(["report", str(case_file), "-o", str(tmp_path / "r.html")]) == 0
    text = _visible((tmp_path / "r.html").read_text())
    assert f"mine.toml, modified from preset {PRESET}" in text and re.search(r"contact\.restitution 0\.65 0\.7 -", text)
    assert f"pounding report {case_file} -o {tmp_path / 'r.html'} --units SI" in text
    assert main(["report", PRESET, "-o", str(tmp_path / "p.html"), "--units", "kgf-cm-s"]) == 0
    text = _visible((tmp_path / "p.html").read_text())
    assert "with no modification" in text and f"pounding report {PRESET} -o" in text


@pytest.mark.slow
def test_the_changes_of_an_si_case_are_in_the_reports_mm_and_kn_without_e_notation(tmp_path):
    """Issue 34: the 'changed from the preset' table of an SI report was in m and N/m with e-notation while the rest
    of the report is in mm and kN: lengths and forces now in mm and kN, large numbers grouped, never 2.75e+09."""
    after = preset_data()
    after["contact"]["gap"] = 5.0  # cm in the preset's kgf-cm-s
    after["contact"]["stiffness"] = 2.0e6  # kgf/cm^1.5
    provenance = case_provenance(after, PRESET, units="SI")
    snapshot = compute_snapshot(case_from_dict(after, name=PRESET))
    text = _visible(write_report(tmp_path / "r.html", snapshot, "SI", provenance=provenance).read_text())
    table = text[text.index("Changed from the preset"):text.index("parameter value unit")]
    assert re.search(r"contact\.gap 10 50 mm", table), table
    assert not re.search(r"\de[+-]\d", table), table
    assert re.search(r"contact\.stiffness [\d,]+ [\d,]+ N/m\^1\.5", table), table
