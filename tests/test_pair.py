"""The linearized pair owns what both closed forms take from it: one estimate linearizes once, builds one
state space, solves the residual's response, the covariance from rest and each contact floor's FRFs once."""

from __future__ import annotations

import collections
import functools

import numpy as np
import pytest

import pounding.closed_form.pair as pair_module
from pounding import load_case
from pounding.closed_form.estimator import estimate
from pounding.closed_form.pair import LinearizedPair

EXPENSIVE = ("linearize_pair", "pair_state_space", "residual_response", "time_varying_covariance",
             "floor_responses", "relative_displacement_psd", "impact_damping")


@pytest.mark.parametrize("name", ["section5-T2-0.4", "section6-T2-0.4-nonstationary"])
def test_one_estimate_computes_each_quantity_once(monkeypatch, name):
    counts = collections.Counter()
    for function in EXPENSIVE:
        original = getattr(pair_module, function)

        @functools.wraps(original)
        def counted(*args, _original=original, _name=function, **kwargs):
            counts[_name] += 1
            return _original(*args, **kwargs)

        monkeypatch.setattr(pair_module, function, counted)
    estimate(load_case(name))
    assert counts == {**{function: 1 for function in EXPENSIVE}, "floor_responses": 2}  # every floor's, per building


def test_a_row_linearizes_each_building_once_and_each_pair_of_buildings_once(monkeypatch):
    """Contacts of one pair of buildings share its state space and floors' FRFs; each building is linearized once."""
    import pounding.closed_form.linearization.iteration as iteration

    from .test_rows import row

    counts = collections.Counter()
    for module, function in ((pair_module, "pair_state_space"), (pair_module, "floor_responses"), (iteration, "linearize")):
        original = getattr(module, function)

        @functools.wraps(original)
        def counted(*args, _original=original, _name=function, **kwargs):
            counts[_name] += 1
            return _original(*args, **kwargs)

        monkeypatch.setattr(module, function, counted)
    case = row()  # three buildings; contacts 1-2 at one floor, 2-3 at two
    result = estimate(case)
    assert len(result.contacts) == 3
    assert counts == {"linearize": 3, "pair_state_space": 2, "floor_responses": 4}


def test_a_pair_reused_gives_the_estimate_of_its_case():
    case = load_case("section5-T2-0.4")
    pair = LinearizedPair.of(case)
    first, second, fresh = estimate(pair), estimate(pair, target_probability=0.9), estimate(case)
    assert first.force_expected == fresh.force_expected and first.required_gap == fresh.required_gap
    assert second.required_gap < first.required_gap  # a lower target asks a smaller gap, from the same pair
    assert np.array_equal(first.crossings.sigma_x, second.crossings.sigma_x)


def test_estimate_takes_a_preset_name_and_names_a_wrong_argument():
    from pounding.errors import ArgumentError

    assert estimate("section5-T2-0.4").force_expected == estimate(load_case("section5-T2-0.4")).force_expected
    for wrong in (5, None, {"contact": {}}):
        with pytest.raises(ArgumentError, match="case: must be a Case"):
            estimate(wrong)
