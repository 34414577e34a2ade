"""A storey by its yield drift or yield force, and a spectrum given as a filter bank:
the engineer's forms of a case are the same case as the raw ones."""

import dataclasses
import math
import tomllib

import numpy as np
import pytest
from scipy.integrate import quad

from pounding import CaseError, estimate, simulate
from pounding.case.case import case_from_dict
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.response import response_frequency
from pounding.hazard.filter_bank import FilterBank
from pounding.mechanics.structures import BoucWen
from pounding.presets import preset_text

PRESET = "section5-T2-0.4"  # kgf-cm-s, beta = 2, gamma = -1 [1/cm], alpha = 0.05


def _data():
    return tomllib.loads(preset_text(PRESET))


def _with_hysteresis(law: dict, building: int = 0) -> dict:
    data = _data()
    storey = data["buildings"][building]["storeys"][0]
    storey.pop("bouc_wen")
    storey["hysteresis"] = law
    return data


def test_yield_drift_is_the_paper_storey_exactly():
    """beta = 2, gamma = -1 [1/cm] is a yield drift of 1 cm (Eq. 33) with beta_share 2: the same numbers."""
    raw = case_from_dict(_data())
    engineered = case_from_dict(_with_hysteresis({"yield_drift": 1.0, "post_yield_ratio": 0.05, "beta_share": 2.0}))
    assert engineered.buildings[0].storeys[0].bouc_wen == raw.buildings[0].storeys[0].bouc_wen
    a, b = estimate(raw).to_dict(), estimate(engineered).to_dict()
    assert a["force_expected"] == b["force_expected"] and a["required_gap"] == b["required_gap"]
    ra, rb = simulate(raw, records=3, seed=4), simulate(engineered, records=3, seed=4)
    np.testing.assert_array_equal(ra.force_max, rb.force_max)


def test_yield_force_is_stiffness_times_yield_drift():
    stiffness = 1097.0  # kgf/cm, building 1 of the preset
    by_drift = case_from_dict(_with_hysteresis({"yield_drift": 2.5, "post_yield_ratio": 0.1, "beta_share": 0.75}))
    by_force = case_from_dict(_with_hysteresis({"yield_force": 2.5 * stiffness, "post_yield_ratio": 0.1, "beta_share": 0.75}))
    law = by_drift.buildings[0].storeys[0].bouc_wen
    assert by_force.buildings[0].storeys[0].bouc_wen.beta == pytest.approx(law.beta, rel=1e-14)
    # A = 1, beta + gamma = 1 / (0.025 m), beta = 0.75 of it, alpha = 0.1, in SI
    assert (law.A, law.alpha, law.n) == (1.0, 0.1, 1.0)
    assert law.beta + law.gamma == pytest.approx(1 / 0.025, rel=1e-14)
    assert law.beta == pytest.approx(0.75 / 0.025, rel=1e-14)
    storey = by_drift.buildings[0].storeys[0]
    assert storey.yield_drift == pytest.approx(0.025, rel=1e-14)
    assert storey.yield_force == pytest.approx(storey.stiffness * 0.025, rel=1e-14)


def test_defaults_n_1_and_beta_share_half():
    law = BoucWen.from_yield_drift(0.01, 0.05)
    assert (law.n, law.beta, law.gamma) == (1.0, 50.0, 50.0)
    smooth = BoucWen.from_yield_drift(0.01, 0.05, n=2.0)
    assert smooth.yield_displacement == pytest.approx(0.01, rel=1e-12)


@pytest.mark.parametrize(
    "law, field",
    [
        ({"post_yield_ratio": 0.1}, "buildings.1.storeys.1.hysteresis"),
        ({"yield_drift": 1.0, "yield_force": 3.0, "post_yield_ratio": 0.1}, "buildings.1.storeys.1.hysteresis"),
        ({"yield_drift": 1.0}, "buildings.1.storeys.1.hysteresis.post_yield_ratio"),
        ({"yield_drift": 0.0, "post_yield_ratio": 0.1}, "buildings.1.storeys.1.hysteresis.yield_drift"),
        ({"yield_drift": 1.0, "post_yield_ratio": 1.0}, "buildings.1.storeys.1.hysteresis.post_yield_ratio"),
        ({"yield_drift": 1.0, "post_yield_ratio": 0.1, "beta_share": 0.4}, "buildings.1.storeys.1.hysteresis.beta_share"),
        ({"yield_drift": 1.0, "post_yield_ratio": 0.1, "n": 0.5}, "buildings.1.storeys.1.hysteresis.n"),
        ({"yield_drift": 1.0, "post_yield_ratio": 0.1, "A": 1.0}, "buildings.1.storeys.1.hysteresis.A"),
    ],
)
def test_bad_hysteresis_names_the_key(law, field):
    with pytest.raises(CaseError) as caught:
        case_from_dict(_with_hysteresis(law))
    assert caught.value.field == field


def test_bouc_wen_and_hysteresis_together_are_refused():
    data = _data()
    data["buildings"][0]["storeys"][0]["hysteresis"] = {"yield_drift": 1.0, "post_yield_ratio": 0.05}
    with pytest.raises(CaseError, match="not both"):
        case_from_dict(data)


def test_a_filter_bank_gives_the_frequency_domain_covariance():
    """The bank's several noises in the Lyapunov route against the integral of its PSD
    through the floors' transfer functions (response_frequency, quadrature)."""
    case = case_from_dict(_data())
    bank = FilterBank(2.0e-3, (4.0, 12.0, 35.0), (0.3, 0.5, 0.4), (0.6, 1.0, 0.2))
    case = dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, spectrum=bank))
    pair = LinearizedPair.of(case)
    lyapunov = pair.stationary_response
    frequency = response_frequency(case, pair.buildings, pair.state_space)
    assert lyapunov.sigma_relative_displacement == pytest.approx(frequency.sigma_relative_displacement, rel=1e-6)
    assert lyapunov.sigma_relative_velocity == pytest.approx(frequency.sigma_relative_velocity, rel=1e-6)
    # the bank's variance in closed form against quadrature of its PSD
    pieces = [(0.0, 10.0), (10.0, 100.0), (100.0, 1e4), (1e4, np.inf)]
    assert 2 * sum(quad(bank.psd, a, b, limit=500)[0] for a, b in pieces) == pytest.approx(bank.variance(), rel=1e-10)
    assert math.isfinite(estimate(case).force_expected)


def test_filter_bank_rejects_bad_components():
    for kwargs, field in [
        (dict(G0=1.0, frequencies=(1.0, 2.0), damping=(0.3,), weights=(1.0, 1.0)), "frequencies"),
        (dict(G0=1.0, frequencies=(0.0,), damping=(0.3,), weights=(1.0,)), "frequencies"),
        (dict(G0=1.0, frequencies=(1.0,), damping=(0.3,), weights=(0.0,)), "weights"),
        (dict(G0=-1.0, frequencies=(1.0,), damping=(0.3,), weights=(1.0,)), "G0"),
    ]:
        with pytest.raises(CaseError) as caught:
            FilterBank(**kwargs)
        assert caught.value.field == field


@pytest.mark.parametrize("drift, n", [(0.01, 160.0), (0.001, 110.0)])
def test_a_yield_drift_to_a_power_beyond_the_numbers_is_refused_naming_it(drift, n):
    """Issue 33: yield_drift^-n past the largest float (1e-2 m to the 160th: 1e320) is refused as a CaseError naming
    the yield drift, not an OverflowError traceback; the same n on a yield drift it can take is accepted."""
    with pytest.raises(CaseError, match="yield_drift.*leaves the range of numbers"):
        BoucWen.from_yield_drift(drift, 0.05, n, 0.5)
    law = BoucWen.from_yield_drift(0.5, 0.05, n, 0.5)
    assert law.yield_displacement == pytest.approx(0.5, rel=1e-12)


def test_an_elastic_perfectly_plastic_storey_is_refused_by_the_closed_form_and_simulated():
    """post_yield_ratio = 0 leaves the linearized storey without a restoring force on its drift (a zero eigenvalue):
    no stationary response exists, so the closed form must refuse, naming the storey, instead of a number; the
    time histories have no such limit and pound."""
    from pounding.errors import ConvergenceError

    case = case_from_dict(_with_hysteresis({"yield_drift": 1.0, "post_yield_ratio": 0.0}))
    with pytest.raises(ConvergenceError, match=r"building 1, storey 1 is elastic-perfectly plastic") as caught:
        estimate(case)
    assert len(str(caught.value)) <= 200
    result = simulate(case, records=4, seed=1)
    assert result.force_max_mean > 0 and math.isfinite(result.force_max_mean)
    # A small post-yield ratio has a stationary response again: the refusal is for alpha = 0 only.
    assert estimate(case_from_dict(_with_hysteresis({"yield_drift": 1.0, "post_yield_ratio": 0.02}))).force_expected > 0


def test_the_accuracy_grid_covers_the_storeys_engineers_give():
    """Issue 32's grid: every loop share (0.5, 1, 2), n (1, 2), each yield level meeting each post-yield ratio,
    post-yield 0 and elastic storeys, under Kanai-Tajimi, Clough-Penzien and a design spectrum's bank, frequent
    and rare pounding."""
    from pounding.hazard.excitation import CloughPenzien
    from pounding.hazard.filter_bank import FilterBank
    from pounding.studies.storey_grid import engineer_storey_cases

    cases = engineer_storey_cases()
    laws = {}
    for case in cases:
        law = case.buildings[0].storeys[0].bouc_wen
        spectrum = case.excitation.spectrum
        kind = "cp" if isinstance(spectrum, CloughPenzien) else ("bank" if isinstance(spectrum, FilterBank) else "kt")
        laws.setdefault(kind, []).append((law, case))
    assert set(laws) == {"kt", "cp", "bank"}
    for kind, entries in laws.items():
        yielding = [law for law, _ in entries if law.alpha < 1.0]
        shares = {round(law.beta / (law.beta + law.gamma), 6) for law in yielding}
        assert shares == {0.5, 1.0, 2.0}, kind
        assert {law.n for law in yielding} == {1.0, 2.0}
        assert {law.alpha for law in yielding} == {0.0, 0.02, 0.1, 0.2}
        assert any(law.alpha == 1.0 for law, _ in entries)
        # each yield level (drift = 1 / (beta + gamma)^(1/n)) with each positive post-yield ratio
        drifts = {(round((law.beta + law.gamma) ** (-1.0 / law.n), 9), law.alpha) for law in yielding if law.alpha > 0}
        assert len({d for d, _ in drifts}) == 3 and len(drifts) == 9, kind
        gaps = {round(case.contact.gap, 12) for _, case in entries}
        assert len(gaps) == 2
