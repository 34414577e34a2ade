"""Valid but extreme cases (issue 21): each runs, or ends in one line that says why the closed form cannot
answer; absurd results are refused or warned about; the closed form is cut at the records' cutoff.

Every case is the preset ``section5-T2-0.4`` (kgf-cm-s) with one value changed, as the issue found them.
"""

import dataclasses
import json
import math
import re
import subprocess
import sys

import numpy as np
import pytest

from pounding import load_case
from pounding.cli.commands import main
from pounding.closed_form.estimator import estimate, force_versus_gap
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import CUTOFF_SHARE_LIMIT
from pounding.errors import CaseError, ConvergenceError
from pounding.presets import preset_names, preset_text

PRESET = "section5-T2-0.4"


def variant(tmp_path, *changes, duration=None, name="case"):
    """The preset's TOML with each (old, new, count) replaced (count 0: every one), written to a file."""
    text = preset_text(PRESET)
    for old, new, count in changes:
        assert old in text, old
        text = text.replace(old, new, count or -1)
    if duration is not None:
        text = text.replace("duration = 20.0", f"duration = {duration}")
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return str(path)


def run(capsys, *args):
    """``pounding *args`` in this process: an exception escaping ``main`` (a traceback) fails the test."""
    status = main(list(args))
    out = capsys.readouterr()
    return status, out.out, out.err


def one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    return lines[0]


def finite_numbers(data) -> None:
    """Every number in a JSON answer is finite."""
    if isinstance(data, dict):
        for value in data.values():
            finite_numbers(value)
    elif isinstance(data, list):
        for value in data:
            finite_numbers(value)
    elif isinstance(data, float):
        assert math.isfinite(data)


def no_long_numbers(text: str) -> None:
    """No number printed with more than 12 digits in a row (the issue's 27- and 118-digit forces)."""
    assert not re.search(r"\d{13,}", text), text


UNDAMPED = ("damping_ratio = 0.05", "damping_ratio = 0.0", 0)
ELASTIC = ("  bouc_wen = { alpha = 0.05, A = 1.0, beta = 2.0, gamma = -1.0, n = 1 }\n", "", 0)


# --- an undamped pair ------------------------------------------------------------------------------------


def test_undamped_yielding_pair_is_estimated(tmp_path, capsys):
    """damping_ratio = 0 lies in the documented [0, 1): the storeys' hysteresis damps the linearized pair,
    so the linearization starts from it instead of the undamped elastic system (no stationary response)."""
    path = variant(tmp_path, UNDAMPED)
    result = estimate(load_case(path))
    finite_numbers(result.to_dict())
    assert result.force_expected > 0.0
    # Continuous in the damping: 1e-8 gives the same answer to 1e-6.
    case = load_case(path)
    damped = dataclasses.replace(case, buildings=tuple(dataclasses.replace(b, damping_ratio=1e-8) for b in case.buildings))
    assert estimate(damped).force_expected == pytest.approx(result.force_expected, rel=1e-6)
    status, out, err = run(capsys, "estimate", path, "--json")
    assert status == 0 and err == ""
    assert json.loads(out)["force_expected"] == pytest.approx(result.force_expected, rel=1e-12)


def test_undamped_yielding_pair_simulates_beside_its_closed_form(tmp_path, capsys):
    status, out, err = run(capsys, "simulate", variant(tmp_path, UNDAMPED, duration=4.0), "--records", "2")
    assert status == 0 and err == ""
    assert "mean F_max" in out and "closed form, against this Monte Carlo" in out


def test_undamped_elastic_pair_has_no_stationary_response(tmp_path, capsys):
    path = variant(tmp_path, UNDAMPED, ELASTIC, duration=4.0)
    with pytest.raises(ConvergenceError, match="no damping and no yielding storey") as error:
        estimate(load_case(path))
    assert "\n" not in str(error.value)
    status, out, err = run(capsys, "estimate", path)
    assert status == 1 and out == ""
    assert one_line(err).startswith("pounding estimate: failed: building 1 has no damping")
    # The Monte Carlo of the same case runs and is printed, with why the closed form cannot answer.
    status, out, err = run(capsys, "simulate", path, "--records", "2")
    assert status == 0 and err == ""
    assert "mean F_max" in out
    assert re.search(r"^closed form     n/a: building 1 has no damping", out, re.MULTILINE)
    status, out, err = run(capsys, "simulate", path, "--records", "2", "--json")
    assert status == 0
    data = json.loads(out)
    assert data["force_max_mean"] > 0.0 and "no damping" in data["closed_form"]["error"]


@pytest.mark.parametrize("error", [np.linalg.LinAlgError("the Lyapunov equation is singular"),
                                   CaseError("excitation.G0", "out of range"), OverflowError("overflow")])
def test_simulate_prints_its_monte_carlo_whatever_the_closed_form_raises(tmp_path, capsys, monkeypatch, error):
    def failing(*args, **kwargs):
        raise error

    monkeypatch.setattr("pounding.closed_form.estimator.estimate", failing)
    path = variant(tmp_path, duration=4.0)
    status, out, err = run(capsys, "simulate", path, "--records", "2")
    assert status == 0 and err == ""
    assert "mean F_max" in out and f"closed form     n/a: {error}" in out
    status, out, err = run(capsys, "simulate", path, "--records", "2", "--design-gap", "0.9", "--json")
    assert status == 0 and json.loads(out)["closed_form_error"] == str(error)


# --- magnitudes beyond double precision --------------------------------------------------------------------


@pytest.mark.parametrize(
    "change, key",
    [
        (("  period = 1.2\n  stiffness = 1097.0", "  mass = 1e300\n  stiffness = 1097.0", 1), "error: buildings.1.storeys.1.mass"),
        # a floor of 40 kgf s^2/cm is a building's: its frequency sqrt(1e-300 / 40) is what the closed form refuses
        (("  period = 1.2\n  stiffness = 1097.0", "  mass = 40.0\n  stiffness = 1e-300", 1), "failed: buildings.1.storeys.1"),
    ],
    ids=["mass 1e300", "storey stiffness 1e-300"],
)
def test_frequencies_beyond_double_precision_end_in_one_line(tmp_path, capsys, change, key):
    """A case file's floor beyond any building (mass 1e300) is refused at load, naming the key
    (defaults.FLOOR_MASS_RANGE); a storey of 1e-300 stiffness under a building's floor, and a floor of 1e300 built in
    Python, end in the closed form's reason (the storey frequency beyond double precision) instead of a number."""
    path = variant(tmp_path, change)
    status, out, err = run(capsys, "estimate", path)
    assert status == (2 if key.startswith("error") else 1) and out == ""
    assert one_line(err).startswith(f"pounding estimate: {key}")
    case = load_case(PRESET)
    storey = dataclasses.replace(case.buildings[0].storeys[0], mass=1e300)
    building = dataclasses.replace(case.buildings[0], storeys=(storey,))
    with pytest.raises(ConvergenceError, match=re.escape("buildings.1.storeys.1")):
        estimate(dataclasses.replace(case, buildings=(building, case.buildings[1])))


@pytest.mark.parametrize("command", ["estimate", "simulate"])
def test_a_ground_filter_beyond_any_ground_motion_is_refused_in_one_line(tmp_path, capsys, command):
    """omega_g = 1e300 rad/s once overflowed in the filter (OverflowError in simulate): now refused at load,
    naming the key and the allowed range."""
    path = variant(tmp_path, ("omega_g = 27.02", "omega_g = 1e300", 1))
    with pytest.raises(CaseError, match=r"excitation\.omega_g: must be in \(0, 1e\+06\]"):
        load_case(path)
    status, out, err = run(capsys, command, path, *(["--records", "2"] if command == "simulate" else []))
    assert status == 2 and out == ""
    assert one_line(err).startswith(f"pounding {command}: error: excitation.omega_g")


def test_frequencies_beyond_double_precision_no_traceback_as_a_user_runs_it(tmp_path):
    path = variant(tmp_path, ("  period = 1.2\n  stiffness = 1097.0", "  mass = 1e300\n  stiffness = 1097.0", 1))
    out = subprocess.run([sys.executable, "-m", "pounding", "estimate", path], capture_output=True, text=True, timeout=120)
    assert out.returncode == 2
    assert "buildings.1.storeys.1.mass" in one_line(out.stderr) and "must lie in" in out.stderr


# --- absurd results -----------------------------------------------------------------------------------------


def test_ground_motion_that_would_run_away_is_refused(tmp_path, capsys):
    """G0 = 6.5e7 kgf-cm-s: sigma_X of 168 m, where every simulation runs away; the estimate printed 2308 MN.
    A hundred times the paper's G0 still answers: the floors' 3 sigma (4.7 m) stay below the 10 m runaway
    limit, and Monte Carlo does not run away there."""
    path = variant(tmp_path, ("G0 = 65.03", "G0 = 6.5e7", 1))
    with pytest.raises(ConvergenceError, match="runs away"):
        estimate(load_case(path))
    with pytest.raises(ConvergenceError, match="runs away"):
        force_versus_gap(load_case(path), [0.0, 0.01])
    status, out, err = run(capsys, "estimate", path, "--json")
    assert status == 1 and out == ""
    assert "10 m at which a time history runs away" in one_line(err)
    finite_numbers(estimate(load_case(variant(tmp_path, ("G0 = 65.03", "G0 = 6503.0", 1), name="strong"))).to_dict())


def test_a_gap_nothing_reaches_brakes_no_impact(tmp_path, capsys):
    """gap = 1e30 cm: the opposing force m (sigma_V / sigma_X)^2 gap was 4e26 MN although nothing pounds."""
    path = variant(tmp_path, ("gap = 1.0", "gap = 1e30", 1))
    result = estimate(load_case(path))
    assert result.impacts_expected == 0.0 and result.pounding_probability == 0.0
    assert result.opposing_force == 0.0 and result.force_expected == 0.0
    finite_numbers(result.to_dict())
    status, out, err = run(capsys, "estimate", path)
    assert status == 0 and err == ""
    assert "force braking an impact   n/a (no impact expected at this gap)" in out
    no_long_numbers(out)


def _with_contact_stiffness(stiffness: float, duration: float | None = None):
    """The preset with a contact stiffness [SI] outside what a case file takes (defaults.CONTACT_STIFFNESS_RANGE),
    as a Python user can still build it."""
    case = load_case(PRESET)
    if duration is not None:
        case = dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, duration=duration))
    return case.with_contact(stiffness=stiffness)


def test_a_force_no_building_takes_is_warned_about(tmp_path, capsys):
    """Contact stiffness 1e300: a force of 118 digits, printed as an answer. A case file giving it is refused
    (naming the key and the range); built in Python, the estimate warns."""
    path = variant(tmp_path, ("stiffness = 2.0e5", "stiffness = 1e300", 1))
    status, out, err = run(capsys, "estimate", path)
    assert status == 2 and out == "" and one_line(err).startswith("pounding estimate: error: contact.stiffness")
    result = estimate(_with_contact_stiffness(1e300))
    assert math.isfinite(result.force_expected)
    assert any(w.startswith("The force is") and "lighter colliding floor's weight" in w for w in result.warnings)


def test_a_contact_too_soft_for_impacts_is_warned_about(tmp_path, capsys):
    """Contact stiffness 1e-300: simulate printed the closed form's error as +3398234509702533398700411060224.0 %.
    Now refused in a case file; the softest a case file takes (0.2 kgf/cm^1.5, 2e3 N/m^1.5) still penetrates
    far beyond a short shock and is warned about, by estimate and simulate."""
    assert any(w.startswith("The contact is soft") for w in estimate(_with_contact_stiffness(1e-300, 4.0)).warnings)
    path = variant(tmp_path, ("stiffness = 2.0e5", "stiffness = 0.2", 1), duration=4.0)
    result = estimate(load_case(path))
    assert any(w.startswith("The contact is soft") for w in result.warnings)
    status, out, err = run(capsys, "simulate", path, "--records", "2")
    assert status == 0 and err == ""
    assert "warning: The contact is soft" in out
    no_long_numbers(out)
    status, out, err = run(capsys, "simulate", path, "--records", "2", "--json")
    assert any(w.startswith("The contact is soft") for w in json.loads(out)["closed_form"]["warnings"])


# --- the records' cutoff -----------------------------------------------------------------------------------


def cutoff_variant(tmp_path, cutoff, duration=None):
    return variant(tmp_path, ("duration = 20.0", f"duration = 20.0\ncutoff_frequency = {cutoff}", 1),
                   duration=duration, name=f"cutoff-{cutoff}")


def test_records_that_carry_nothing_have_no_estimate(tmp_path, capsys):
    """cutoff_frequency = 0.001 rad/s lies below the records' lowest frequency: no record pounds (none moves),
    where the estimate gave a pounding probability of 100 %."""
    path = cutoff_variant(tmp_path, 0.001, duration=4.0)
    with pytest.raises(CaseError, match="excitation.cutoff_frequency") as error:
        estimate(load_case(path))
    assert "records carry no ground motion" in str(error.value)
    status, out, err = run(capsys, "estimate", path)
    assert status == 2 and out == ""
    assert one_line(err).startswith("pounding estimate: error: excitation.cutoff_frequency")
    status, out, err = run(capsys, "simulate", path, "--records", "2")
    assert status == 0 and err == ""
    assert "0.0 % of records" in out and "closed form     n/a: excitation.cutoff_frequency" in out


def test_a_cutoff_below_the_motion_cuts_the_estimate_and_warns(tmp_path):
    """10 rad/s, below omega_g = 27 rad/s and building 2's 15.7 rad/s: 24 % of sigma_V^2 lies above. Monte
    Carlo (300 records, seed 11) gave 275.6 kN, against 320.3 kN at the default cutoff; the estimate, which
    ignored the cutoff (315.4 kN, +14 %), is now cut there (263.0 kN, -4.6 %) and says so. At 60 rad/s (2e-6
    of sigma_V^2 above) nothing printed changes, and there is no warning."""
    default, cut = estimate(load_case(PRESET)), estimate(load_case(cutoff_variant(tmp_path, 10)))
    assert cut.force_expected == pytest.approx(263.0e3, rel=0.01)
    assert cut.sigma_relative_velocity < 0.9 * default.sigma_relative_velocity
    (warning,) = [w for w in cut.warnings if w.startswith("The records stop at 10 rad/s")]
    assert "24 % of the relative velocity's power" in warning and len(warning) <= 200
    high = estimate(load_case(cutoff_variant(tmp_path, 60)))
    assert high.force_expected == pytest.approx(default.force_expected, rel=1e-5)
    for result in (default, high):
        assert not [w for w in result.warnings if w.startswith("The records stop")]


def test_the_default_cutoff_leaves_the_presets_untouched_and_a_low_one_does_not():
    """The records' default cutoff (2 pi 25 Hz) removes under 1e-5 of every variance the closed form uses on
    every preset: the estimate is not cut there, so its numbers are exactly the uncut ones, and it gives no
    cutoff warning; the same presets with the records cut at 10 rad/s are cut."""
    for name in preset_names():
        case = load_case(name)
        pair = LinearizedPair.of(case)
        full = pair.state_space.covariance()
        assert pair.stationary_response.method == "lyapunov", name  # the Lyapunov covariance, uncut
        np.testing.assert_array_equal(pair.stationary_response.covariance, pair.contact_outputs @ full @ pair.contact_outputs.T)
        low = LinearizedPair(dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, cutoff_frequency=10.0)),
                             pair.buildings)
        # 0.015 % (the yielded G0 x 4 pi^2 pairs) to 32 % of sigma_V^2 lies above 10 rad/s
        assert low.stationary_response.sigma_relative_velocity < pair.stationary_response.sigma_relative_velocity, name
        assert pair.cutoff_shares[5] < CUTOFF_SHARE_LIMIT, name  # no cutoff warning


def test_a_cutoff_below_the_buildings_still_answers_in_finite_numbers(tmp_path, capsys):
    """0.5 rad/s: one frequency of the synthesis grid is left; the estimate answers (finite) and warns."""
    status, out, err = run(capsys, "estimate", cutoff_variant(tmp_path, 0.5), "--json")
    assert status == 0 and err == ""
    data = json.loads(out)
    finite_numbers(data)
    assert data["warnings"][0].startswith("The records stop at 0.5 rad/s")


# --- every new warning is short ----------------------------------------------------------------------------


def test_every_extreme_warning_is_at_most_200_characters(tmp_path):
    cases = [load_case(cutoff_variant(tmp_path, 0.503)), _with_contact_stiffness(1e300), _with_contact_stiffness(1e-300)]
    for case in cases:
        warnings = estimate(case).warnings
        assert warnings
        for warning in warnings:
            assert len(warning) <= 200, warning
            assert "\n" not in warning
