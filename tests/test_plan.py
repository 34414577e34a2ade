"""One object says how a Monte Carlo runs (MonteCarloPlan): simulate, design_gap, sweep, fragility curves and
force spectra take it, and what it holds reaches the integrator."""

from __future__ import annotations

import dataclasses
import threading

import numpy as np
import pytest

from pounding import ArgumentError, MonteCarloPlan, Settings, design_gap, load_case, simulate, sweep
from pounding.simulation.monte_carlo import Cancelled

CASE = "section5-T2-0.4"


def test_the_options_given_one_by_one_are_the_plan():
    by_plan = simulate(CASE, MonteCarloPlan(records=6, seed=4, first_record=3))
    one_by_one = simulate(CASE, records=6, seed=4, first_record=3)
    np.testing.assert_array_equal(by_plan.force_max, one_by_one.force_max)
    assert list(by_plan.indices) == [3, 4, 5, 6, 7, 8]
    changed = simulate(CASE, MonteCarloPlan(records=6, seed=4), first_record=3)  # a plan, one field changed
    np.testing.assert_array_equal(changed.force_max, by_plan.force_max)


def test_the_plans_settings_reach_the_integrator():
    loose = simulate(CASE, MonteCarloPlan(records=3, seed=1, settings=Settings(tolerance=1e-3)))
    tight = simulate(CASE, MonteCarloPlan(records=3, seed=1, settings=Settings(tolerance=1e-8)))
    assert np.all(tight.steps > loose.steps)  # a tighter tolerance takes more steps
    np.testing.assert_allclose(tight.force_max, loose.force_max, rtol=0.05)


def test_progress_and_cancel_travel_in_the_plan():
    seen = []
    simulate(CASE, MonteCarloPlan(records=10, seed=1, progress=lambda done, total: seen.append((done, total)),
                                  settings=Settings(chunk_size=2, workers=1)))
    assert [done for done, _ in seen] == [2, 4, 6, 8, 10] and {total for _, total in seen} == {10}
    cancel = threading.Event()
    cancel.set()
    with pytest.raises(Cancelled):
        simulate(CASE, MonteCarloPlan(records=10, seed=1, cancel=cancel))


def test_the_design_gap_integrates_the_records_simulate_does():
    plan = MonteCarloPlan(records=40, seed=7)
    gap = design_gap(CASE, 0.9, plan)
    case = load_case(CASE)
    free = case.with_contact(gap=20.0)
    np.testing.assert_array_equal(gap.peaks, simulate(free, plan).relative_displacement_max)
    assert gap.gap == pytest.approx(np.sort(gap.peaks)[35])  # the 36th of 40 peaks: 90 % stay below
    assert design_gap(CASE, 0.9, plan, first_record=5).peaks.tolist() == gap.peaks.tolist()  # always from record 0


def test_a_sweep_on_the_plan_gives_simulates_numbers(tmp_path):
    plan = MonteCarloPlan(records=6, seed=2, scheduler="serial", chunk_records=4)
    table = sweep(CASE, None, plan, tmp_path / "sweep", chart=False)
    assert table["mc_force_mean_N"].iloc[0] == pytest.approx(simulate(CASE, plan).force_max_mean, rel=1e-12)


@pytest.mark.parametrize("options, field", [
    ({"records": 0}, "records"),
    ({"records": True}, "records"),
    ({"seed": -1}, "seed"),
    ({"first_record": 1.5}, "first_record"),
    ({"chunk_records": 0}, "chunk_records"),
    ({"workers": 0}, "workers"),
    ({"progress": 3}, "progress"),
    ({"cancel": "yes"}, "cancel"),
    ({"settings": {"tolerance": 1e-6}}, "settings"),
])
def test_a_bad_plan_is_refused_naming_its_field(options, field):
    with pytest.raises(ArgumentError) as error:
        MonteCarloPlan(**options)
    assert error.value.field == field


def test_an_unknown_option_is_refused_naming_it_and_the_options():
    with pytest.raises(ArgumentError) as error:
        simulate(CASE, recrods=5)
    assert error.value.field == "recrods" and "records" in error.value.message and "seed" in error.value.message
    with pytest.raises(ArgumentError) as error:
        simulate(CASE, plan={"records": 5})
    assert error.value.field == "plan"
