"""Rows of buildings and contacts at several floors: the case file, and the
time histories against physics and an independent integrator."""

import dataclasses
import tomllib

import numpy as np
import pytest

from pounding import simulate
from pounding.case.case import case_from_dict
from pounding.errors import CaseError
from pounding.hazard.excitation import ground_accelerations
from pounding.mechanics.contact import Contact
from pounding.mechanics.structures import BoucWen, Building, Storey
from pounding.simulation.monte_carlo import integrate

from .reference import solve_reference

ROW = """
name = "three in a row"
units = "SI"

[excitation]
spectrum = "kanai-tajimi"
G0 = 0.012
omega_g = 15.6
xi_g = 0.6
duration = 6.0

[[buildings]]
storeys = [
  { mass = 3.0e5, stiffness = 1.2e8, hysteresis = { yield_drift = 0.02, post_yield_ratio = 0.1 } },
  { mass = 3.0e5, stiffness = 1.0e8, hysteresis = { yield_drift = 0.02, post_yield_ratio = 0.1 } },
  { mass = 2.5e5, stiffness = 0.8e8, hysteresis = { yield_drift = 0.02, post_yield_ratio = 0.1 } },
]

[[buildings]]
storeys = [
  { mass = 2.0e5, stiffness = 3.0e8 },
  { mass = 2.0e5, stiffness = 2.5e8 },
]

[[buildings]]
storeys = [
  { mass = 3.0e5, stiffness = 1.0e8 },
  { mass = 3.0e5, stiffness = 0.9e8 },
  { mass = 3.0e5, stiffness = 0.8e8 },
]

[[contacts]]
between = [1, 2]
levels = [2, 2]
gap = 0.01
stiffness = 2.75e9

[[contacts]]
between = [2, 3]
levels = "aligned"
gap = 0.01
stiffness = 2.75e9
restitution = 0.5
"""


def row(**changes):
    data = tomllib.loads(ROW)
    data.update(changes)
    return case_from_dict(data)


def test_a_row_loads_with_the_aligned_floors_expanded_in_order():
    case = row()
    assert len(case.buildings) == 3
    assert [(c.between, c.levels) for c in case.contacts] == [((1, 2), (2, 2)), ((2, 3), (1, 1)), ((2, 3), (2, 2))]
    assert [c.restitution for c in case.contacts] == [0.65, 0.5, 0.5]


def test_the_single_contact_table_is_one_contact_between_buildings_1_and_2():
    from pounding import load_case

    case = load_case("section6-T2-0.4")
    assert case.contacts == (case.contact,) and case.contact.between == (1, 2)
    assert case.pair(0) is case


def test_a_pair_is_the_contacts_two_buildings_alone():
    case = row()
    pair = case.pair(2)
    assert pair.buildings == case.buildings[1:] and pair.contact.between == (1, 2) and pair.contact.levels == (2, 2)
    assert pair.reduced_mass == pytest.approx(2e5 * 3e5 / 5e5)


@pytest.mark.parametrize("contacts, key, words", [
    ([{"between": [1, 3], "levels": [1, 1], "gap": 0.01, "stiffness": 1e9}], "contacts.1.between", "not neighbours"),
    ([{"between": [2, 1], "levels": [1, 1], "gap": 0.01, "stiffness": 1e9}], "contacts.1.between", r"left building first: \[1, 2\]"),
    ([{"between": [3, 4], "levels": [1, 1], "gap": 0.01, "stiffness": 1e9}], "contacts.1.between", "does not exist"),
    ([{"between": [1, 2], "levels": [1, 1], "gap": 0.01, "stiffness": 1e9},
      {"between": [2, 3], "levels": [3, 1], "gap": 0.01, "stiffness": 1e9}], "contacts.2.levels", "building 2 has 2 storey"),
    ([{"between": [1, 2], "levels": [1, 1], "gap": 0.01, "stiffness": 1e9},
      {"between": [1, 2], "levels": "aligned", "gap": 0.02, "stiffness": 1e9}], "contacts.2.levels", "already meet in contacts.1"),
    ([{"between": [1, 2], "levels": "floors", "gap": 0.01, "stiffness": 1e9}], "contacts.1.levels", "'aligned'"),
    ([], "contacts", "at least one"),
])
def test_a_wrong_contact_is_named_by_its_key(contacts, key, words):
    with pytest.raises(CaseError, match=rf"^{key}: .*{words}"):
        row(contacts=contacts)


def test_a_contact_table_and_a_contacts_array_are_not_both_taken():
    with pytest.raises(CaseError, match=r"^contacts: give one \[contact\] table or an array"):
        row(contact={"gap": 0.01, "stiffness": 1e9})


def test_a_row_beyond_the_limits_is_refused_naming_buildings():
    data = tomllib.loads(ROW)
    with pytest.raises(CaseError, match=r"^buildings: .*buildings in a row"):
        row(buildings=data["buildings"] * 3)
    tall = [{"storeys": [{"mass": 1e5, "stiffness": 1e8}] * 20}] * 4
    with pytest.raises(CaseError, match=r"^buildings: .*storeys in the row"):
        row(buildings=tall, contacts=data["contacts"][:1])


def test_a_case_of_several_contacts_refuses_what_takes_one():
    with pytest.raises(CaseError, match=r"^contacts: the case has 3 contacts"):
        row().contact  # noqa: B018


# --- the time histories --------------------------------------------------------


def free_mass(mass: float) -> Building:
    """A spring of 1e-3 N/m: a free mass over the impacts' second."""
    return Building((Storey(mass, 1e-3, BoucWen(alpha=1.0)),), damping_ratio=0.0)


def test_three_free_masses_pass_the_velocity_along_the_row():
    """Newton's cradle with gaps: equal masses, elastic Hertz contacts. Each impact is a separate two-body
    collision that exchanges the velocities, so the third mass leaves with the first one's velocity; momentum
    and energy are conserved throughout."""
    mass, velocity = 1e4, 0.5
    contact = dict(gap=0.05, stiffness=1e9, restitution=1.0, model="hertz")  # 100 ms apart, impacts of 28 ms
    case = dataclasses.replace(
        row(), buildings=(free_mass(mass),) * 3, name="cradle",
        contacts=(Contact(between=(1, 2), **contact), Contact(between=(2, 3), **contact)),
    )
    state = np.zeros(9)  # (d1, d2, d3, v1, v2, v3, z1, z2, z3)
    state[3] = velocity
    history = integrate(case, np.zeros(2001), 1e-3, initial_state=state)
    final = history.velocity[-1]
    np.testing.assert_allclose(final, [0.0, 0.0, velocity], atol=1e-4 * velocity)
    momentum = mass * history.velocity.sum(axis=1)
    np.testing.assert_allclose(momentum, mass * velocity, rtol=1e-6)
    assert history.summary["impacts"] == 2 and [c["impacts"] for c in history.summary["contacts"]] == [1, 1]
    peak = 1e9 * (5 * (mass / 2) * velocity**2 / (4 * 1e9)) ** 0.6  # Hertz: both impacts alike (Eq. 13)
    for contact_summary in history.summary["contacts"]:
        assert contact_summary["force_max"] == pytest.approx(peak, rel=1e-3)


def test_a_contact_out_of_reach_leaves_the_others_answer_unchanged():
    """A second contact whose gap is never closed carries no force: the first contact's peaks are those of the
    case without it, record for record."""
    case = row()
    far = dataclasses.replace(case, contacts=(case.contacts[0], dataclasses.replace(case.contacts[1], gap=5.0)))
    alone = dataclasses.replace(case, contacts=case.contacts[:1])
    both, single = simulate(far, records=4, seed=3), simulate(alone, records=4, seed=3)
    np.testing.assert_allclose(both.contacts[0].force_max, single.force_max, rtol=1e-12)
    assert single.force_max.max() > 0  # the test has teeth: the first contact pounds
    assert np.all(both.contacts[1].force_max == 0) and np.all(both.contacts[1].impacts == 0)
    np.testing.assert_array_equal(both.force_max, both.contacts[0].force_max)


@pytest.mark.slow
def test_a_row_agrees_with_solve_ivp_at_every_contact():
    """One record through scipy's DOP853 at rtol 1e-9 (tests/reference.py): each contact's impacts and peak
    force."""
    case = row()
    record = 2.0 * ground_accelerations(case.excitation, seed=1, indices=[0])[0]
    history = integrate(case, record, case.excitation.time_step)
    solution, force_at = solve_reference(case, record, case.excitation.time_step)
    assert solution.status == 0
    pounded = 0
    for c, onsets in enumerate(solution.t_events):
        summary = history.summary["contacts"][c]
        assert summary["impacts"] == len(onsets), c
        if not len(onsets):
            continue
        pounded += 1
        fine = np.concatenate([np.arange(t, t + 0.05, 2e-5) for t in onsets])
        reference = force_at(fine[fine < solution.t[-1]])[c].max()
        assert summary["force_max"] == pytest.approx(reference, rel=5e-3), c
        assert history.contact_forces[:, c].max() <= summary["force_max"] * (1 + 1e-9)
    assert pounded >= 2  # the test has teeth: two contacts pound
    assert history.summary["force_max"] == max(c["force_max"] for c in history.summary["contacts"])


# --- the closed form -----------------------------------------------------------


def test_each_contacts_estimate_is_its_pairs_own():
    """Each building is linearized once for the whole row; a contact's estimate is that of its two buildings alone."""
    from pounding import estimate

    case = row()
    result = estimate(case)
    for index, contact_estimate in enumerate(result.contacts):
        alone = estimate(case.pair(index))
        assert contact_estimate.force_expected == pytest.approx(alone.force_expected, rel=1e-12)
        assert contact_estimate.required_gap == pytest.approx(alone.required_gap, rel=1e-12)
    assert result.governing == int(np.argmax([c.force_expected for c in result.contacts]))


def test_the_largest_force_of_independent_contacts_multiplies_their_distributions():
    """Two like contacts (buildings 1 and 3 alike about building 2): P(max <= f) = P(F <= f)^2, so the median of the
    largest force is the single contact's sqrt(0.5) quantile; a contact out of reach changes nothing."""
    from pounding import estimate

    data = tomllib.loads(ROW)
    data["buildings"][2] = data["buildings"][0]
    data["contacts"] = [{"between": [1, 2], "levels": [2, 2], "gap": 0.01, "stiffness": 2.75e9},
                        {"between": [2, 3], "levels": [2, 2], "gap": 0.01, "stiffness": 2.75e9}]
    both = estimate(case_from_dict(data))
    single = both.contacts[0].force_max_distribution
    assert both.contacts[1].force_expected == pytest.approx(both.contacts[0].force_expected, rel=1e-9)
    assert both.force_max_distribution.quantile(0.5) == pytest.approx(single.quantile(0.5**0.5), rel=1e-3)
    assert both.force_expected > both.contacts[0].force_expected
    data["contacts"][1]["gap"] = 3.0
    far = estimate(case_from_dict(data))
    assert far.force_expected == pytest.approx(far.contacts[0].force_expected, rel=1e-6)
    assert far.contacts[1].pounding_probability < 1e-12


def test_the_rows_largest_force_agrees_with_its_monte_carlo():
    """Measured, not tuned: the test row's largest force over all contacts against 100 records of the whole row."""
    from pounding import estimate
    from pounding.studies.check import check_row

    check = check_row(estimate(row()), records=100, seed=5)
    assert check.agrees, (check.closed_form_force, check.force_max_mean, check.force_max_confidence_interval)
    assert len(check.contacts) == 3 and all(c.records == 100 for c in check.contacts)


# --- the command line ----------------------------------------------------------


def run(*args):
    import subprocess
    import sys

    return subprocess.run([sys.executable, "-m", "pounding", *args], capture_output=True, text=True, timeout=300)


@pytest.fixture
def row_file(tmp_path):
    path = tmp_path / "row.toml"
    path.write_text(ROW)
    return path


def test_estimate_json_has_every_contact_in_the_cases_order(row_file):
    import json

    from pounding import estimate

    out = run("estimate", str(row_file), "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    expected = estimate(row())
    assert data["force_expected"] == pytest.approx(expected.force_expected, rel=1e-12)
    assert [(c["between"], c["levels"]) for c in data["contacts"]] == [([1, 2], [2, 2]), ([2, 3], [1, 1]), ([2, 3], [2, 2])]
    for contact, mine in zip(data["contacts"], expected.contacts):
        for key in ("force_expected", "pounding_probability", "required_gap"):
            assert contact[key] == pytest.approx(getattr(mine, key), rel=1e-12)
        assert set(contact["force_max_quantiles"]) == {"0.5", "0.84", "0.95"}


def test_simulate_json_has_every_contacts_peaks_and_the_largest_on_top(row_file):
    import json

    out = run("simulate", str(row_file), "--records", "4", "--seed", "2", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    forces = np.array([c["force_max"] for c in data["contacts"]])
    np.testing.assert_array_equal(data["force_max"], forces.max(axis=0))
    expected = simulate(row(), records=4, seed=2)
    for contact, peaks in zip(data["contacts"], expected.contacts):
        np.testing.assert_allclose(contact["force_max"], peaks.force_max, rtol=1e-12)
        assert contact["force_max_mean"] == pytest.approx(peaks.force_max.mean())
        assert set(contact) >= {"between", "levels", "force_max_confidence_interval", "pounding_fraction", "impacts_mean"}


def test_a_bad_contact_exits_2_with_one_line_naming_its_key(tmp_path):
    data = ROW.replace('levels = "aligned"', "levels = [3, 2]")
    path = tmp_path / "bad.toml"
    path.write_text(data)
    out = run("estimate", str(path))
    assert out.returncode == 2
    assert out.stderr.strip().count("\n") == 0 and "contacts.2.levels" in out.stderr and "building 2 has 2 storey" in out.stderr


def test_a_cases_kind_and_its_measured_accuracy():
    """Each grid case is classified as the kind it was built as, and an estimate states that kind's measured range."""
    import json
    from pathlib import Path

    from pounding import estimate
    from pounding.closed_form.regimes import row_kind
    from pounding.studies.row_grid import row_cases

    for case in row_cases()[::4]:
        assert case.name.startswith(row_kind(case) + ":"), case.name
    result = estimate(row())
    measured = json.loads((Path(__file__).parents[1] / "pounding" / "data" / "accuracy.json").read_text())
    entry = measured["force"]["several contacts"]["three in a row"]
    assert (result.accuracy.low, result.accuracy.high, result.accuracy.cases) == (entry["low"], entry["high"], entry["cases"])
    assert "rows of three buildings" in result.measured_accuracy
    assert all(len(w) <= 200 for w in result.warnings)
    assert result.to_dict()["contacts"][0]["measured_accuracy"].startswith("Measured")


def test_fragility_spectrum_and_sweeps_take_a_case_of_several_contacts():
    """Curves over an intensity or a period, and a sweep's point, give the row's largest force as estimate does."""
    from pounding import estimate
    from pounding.case.scaling import PeakGroundAcceleration, with_fundamental_periods
    from pounding.studies.force_spectrum import force_spectrum
    from pounding.studies.fragility import fragility_curve
    from pounding.studies.sweeps.work import point_estimate

    case = row()
    pga = np.array([1.0, 3.0])
    curve = fragility_curve(case, 2.0e6, pga)
    for value, probability in zip(pga, curve.probability):
        at = estimate(PeakGroundAcceleration(case).case_at(value))
        assert probability == pytest.approx(at.probability_exceeding(2.0e6), rel=1e-9)
        assert len(at.contacts) == 3
    assert curve.accuracy[0].regime == "three in a row"
    spectrum = force_spectrum(case, [0.4, 0.6], period_ratio=0.7)
    at = estimate(with_fundamental_periods(case, 0.6, 0.42))
    assert spectrum.force_mean[1] == pytest.approx(at.force_expected, rel=1e-9)
    point = point_estimate(tomllib.loads(ROW))
    whole = estimate(case)
    assert point["force"] == pytest.approx(whole.force_expected, rel=1e-12) and point["paper_force"] is None
    assert point["required_gap"] == pytest.approx(max(c.required_gap for c in whole.contacts), rel=1e-12)


def test_each_contacts_design_gap_is_its_free_pairs():
    """Without contact the buildings move independently: each contact's gap for the target, from one free run of the
    whole row, is that of its two buildings alone (the same records; the integrator's steps differ, hence 1e-3)."""
    from pounding.simulation.monte_carlo import design_gap, design_gaps

    case = row()
    gaps = design_gaps(case, 0.9, records=12, seed=4)
    assert len(gaps) == 3
    for index, gap in enumerate(gaps):
        alone = design_gap(case.pair(index), 0.9, records=12, seed=4)
        np.testing.assert_allclose(gap.peaks, alone.peaks, rtol=1e-3)
    with pytest.raises(CaseError, match="^contacts: "):
        design_gap(case, 0.9, records=2)


def test_neighbours_that_move_alike_are_refused_by_the_closed_form_naming_the_contact():
    """Identical neighbours never pound alone, but in a row the other contacts' impacts can make them pound: the
    closed form cannot say how hard, and says so (the Monte Carlo of the row does: they pound)."""
    from pounding import estimate
    from pounding.studies.fragility import fragility_curve

    data = tomllib.loads(ROW)
    data["buildings"][1] = data["buildings"][0]
    case = case_from_dict(data)
    for attempt in (lambda: estimate(case), lambda: fragility_curve(case, 1e6, [1.0, 2.0])):
        with pytest.raises(CaseError, match=r"^contacts\.1: buildings 1 and 2 move alike.*use simulate"):
            attempt()
    assert simulate(case, records=4, seed=1).contacts[0].impacts.sum() > 0  # the interaction the closed form lacks
