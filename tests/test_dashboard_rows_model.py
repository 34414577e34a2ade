"""Issue 35 in the dashboard's model: a row of two or three buildings and which floors meet are inputs; a case of
several contacts gives the library's RowEstimate, its check (check_row), a table of contacts with the library's
numbers in display units, each contact's force in one record; an uploaded case file of several contacts loads with
its own contacts; nothing of one contact's plots or studies breaks on it."""

from __future__ import annotations

import time
import tomllib

import pytest

from dashboard.contacts import ONE_CONTACT, contacts_html, row_headline_html
from dashboard.model import PoundingModel
from dashboard.studies import ONE_CONTACT_STUDIES
from pounding import estimate
from pounding.case.case import case_from_dict, contact_label
from pounding.closed_form.row import RowEstimate
from pounding.display_units import display
from pounding.report.contacts import RowSnapshot
from pounding.studies.check import check_row

ROW_FILE = """
name = "three in a row"
units = "SI"

[excitation]
spectrum = "kanai-tajimi"
pga = 0.3
omega_g = 15.6
xi_g = 0.6
duration = 8.0

[[buildings]]
storeys = [{ mass = 3.0e5, stiffness = 1.2e8 }, { mass = 3.0e5, stiffness = 1.2e8 }, { mass = 3.0e5, stiffness = 1.2e8 }]

[[buildings]]
storeys = [{ mass = 2.0e5, stiffness = 3.0e8 }, { mass = 2.0e5, stiffness = 3.0e8 }]

[[buildings]]
storeys = [{ mass = 3.0e5, stiffness = 1.0e8 }, { mass = 3.0e5, stiffness = 1.0e8 }, { mass = 3.0e5, stiffness = 1.0e8 }]

[[contacts]]
between = [1, 2]
levels = [2, 2]
gap = 0.01
stiffness = 2.75e9

[[contacts]]
between = [2, 3]
levels = [2, 2]
gap = 0.02
stiffness = 2.75e9
restitution = 0.5
"""
"""Three buildings, each contact with a gap and restitution of its own: no choice of the page describes them."""


def _row_model() -> PoundingModel:
    """The default preset made a row of three 2-storey buildings, aligned floors (the default)."""
    model = PoundingModel()
    model.buildings_in_row = 3
    for building in model.buildings():
        building.storeys = 2
    assert model.error == "", model.error
    return model


def test_three_buildings_at_aligned_floors_give_the_librarys_row_estimate():
    model = _row_model()
    case = model.result.case
    assert model.floors_meet == "aligned floors" and model.several_contacts
    assert [(c.between, c.levels) for c in case.contacts] == [((1, 2), (1, 1)), ((1, 2), (2, 2)), ((2, 3), (1, 1)), ((2, 3), (2, 2))]
    assert [c.gap for c in case.contacts] == pytest.approx([0.01] * 4)  # the gap applies to every contact
    library = estimate(model.build_case(), target_probability=model.target_probability)
    assert isinstance(model.result, RowEstimate) and model.result.force_expected == pytest.approx(library.force_expected, rel=1e-9)
    assert model.case_file()["contacts"][0]["levels"] == "aligned"  # the library expands the shorthand


def test_the_roof_of_the_lower_building_and_one_floor_each():
    model = _row_model()
    model.building_2.storeys = 1
    model.floors_meet = "roof of the lower building"
    assert [(c.between, c.levels) for c in model.result.case.contacts] == [((1, 2), (1, 1)), ((2, 3), (1, 1))]
    model.building_2.storeys = 2
    model.floors_meet = "one floor each"
    model.building_1.contact_floor, model.building_3.contact_floor = 2, 1
    assert [(c.between, c.levels) for c in model.result.case.contacts] == [((1, 2), (2, 1)), ((2, 3), (1, 1))]
    model.buildings_in_row = 2  # back to a pair: one contact, the third building's inputs no longer apply
    assert not model.several_contacts and model.result.case.contact.levels == (2, 1)
    assert not any("building 3" in label for label, *_ in model.changes())


def test_the_headline_names_the_governing_contact_and_the_largest_force():
    model = _row_model()
    result = model.result
    text = row_headline_html(result, "SI", name=model.case_name())
    assert f"governing: <span class=\"governing-contact\">{contact_label(result.case.contacts[result.governing])}</span>" in text
    assert f'<span class="value fe-recommended">{display("SI").force(result.force_expected)}</span>' in text
    assert "Traceback" not in text and all(len(w) <= 200 for w in result.warnings)


def test_the_table_has_a_row_a_contact_with_the_librarys_numbers_and_the_check_per_contact():
    model = _row_model()
    result = model.result
    check = check_row(result, records=20, seed=3)
    text = contacts_html(result, "SI", check)
    shown = display("SI")
    assert text.count('<tr class="contact') == len(result.case.contacts)
    for number, (contact, one, mine) in enumerate(zip(result.case.contacts, result.contacts, check.contacts), start=1):
        row = text.split(f'data-contact="{number}">')[1].split("</tr>")[0]
        assert f'<td class="buildings">{contact.between[0]}-{contact.between[1]}</td>' in row
        assert f'<td class="force-expected">{shown.force(one.force_expected)}</td>' in row
        assert f'<td class="f84">{shown.force(one.force_max_distribution.quantile(0.84))}</td>' in row
        assert f'<td class="required-gap">{shown.length(one.required_gap)}</td>' in row
        assert f'<td class="mc-mean">{shown.force(mine.force_max_mean)}</td>' in row
    assert f'<tr class="contact governing" data-contact="{result.governing + 1}">' in text


def test_the_automatic_check_of_several_contacts_is_check_row():
    from dashboard.jobs import check_pool

    check_pool().submit(lambda: None).result(timeout=120)  # no check of another test's model left running
    model = PoundingModel(check=True)
    model.buildings_in_row = 3
    assert model.error == ""
    deadline = time.monotonic() + 120
    while model.current_check() is None and not model.check_error() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert model.check_error() == ""
    found = model.current_check()
    assert found is not None and len(found.contacts) == len(model.result.case.contacts)
    library = check_row(model.result, seed=model.seed)
    assert found.force_max_mean == pytest.approx(library.force_max_mean, rel=1e-12)


def test_the_snapshot_has_each_contacts_force_and_one_contact_studies_say_so():
    model = _row_model()
    snapshot = model.snapshot
    assert isinstance(snapshot, RowSnapshot) and snapshot.history.contact_forces.shape[1] == len(model.result.case.contacts)
    model.run_monte_carlo()
    model.run_design_gap()
    assert model.monte_carlo_job.status == ONE_CONTACT_STUDIES == model.design_gap_job.status
    assert model.monte_carlo_for_current_gap() is None and not model.can_pin()


def test_an_uploaded_file_of_several_contacts_keeps_its_own_and_a_changed_gap_applies_to_every_contact():
    model = PoundingModel()
    model.load_toml(ROW_FILE, "row.toml")
    assert model.error == "" and model.floors_meet == "as in the case file" and model.buildings_in_row == 3
    library = estimate(case_from_dict(tomllib.loads(ROW_FILE)), target_probability=model.target_probability)
    assert model.result.force_expected == pytest.approx(library.force_expected, rel=1e-6)
    assert [c.gap for c in model.result.case.contacts] == pytest.approx([0.01, 0.02])
    assert [c.restitution for c in model.result.case.contacts] == pytest.approx([0.65, 0.5])
    model.gap = 30.0  # mm: now every contact's; each keeps its own restitution
    assert [c.gap for c in model.result.case.contacts] == pytest.approx([0.03, 0.03])
    assert [c.restitution for c in model.result.case.contacts] == pytest.approx([0.65, 0.5])
    model.units = "kgf-cm-s"  # the file's contacts are kept in SI: a unit switch changes nothing
    assert [c.gap for c in model.result.case.contacts] == pytest.approx([0.03, 0.03])


def test_the_tabs_that_take_one_contact_say_so_and_the_others_work(tmp_path):
    import panel as pn

    from dashboard.tabs import _BUILDERS
    from dashboard.view import PoundingDashboard

    view = PoundingDashboard(model=_row_model())
    m = view.model
    capacity = display("SI").to_si(m.capacity, force=1)
    built = {kind: build(view, m.snapshot, "SI", capacity) for kind, build in _BUILDERS.items()}
    assert isinstance(built["distribution"], pn.pane.Markdown) and built["distribution"].object == ONE_CONTACT["distribution"]
    assert isinstance(built["fragility"], pn.Column)
    view._redraw()
    labels = view.contact_history.source.data["label"]
    assert labels == [f"{n}: {contact_label(c)}" for n, c in enumerate(m.result.case.contacts, start=1)]
    assert view.figures.sources["gap"].data["gap"] == [] or len(view.figures.sources["gap"].data["gap"]) == 0
    report = view._export()
    text = open(report).read()
    assert "Governing" in text and text.count('<tr class="contact') == len(m.result.case.contacts)
