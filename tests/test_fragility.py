"""Fragility curves: the ground motion scaled to a PGA (F1), the closed-form curve against Monte Carlo on the
paper's Section 5 case, the lognormal fit against known curves, the Monte Carlo side on the sweep engine
(the same records as simulate, the same numbers serial or on Dask, resumable), and the command line."""

import json
import math
import textwrap

import numpy as np
import pytest

from pounding import load_case, simulate
from pounding.case.scaling import PeakGroundAcceleration
from pounding.cli.commands import main
from pounding.hazard.accelerograms import Accelerogram, write_at2
from pounding.hazard.excitation import ground_accelerations
from pounding.hazard.motion_fit import fit_excitation
from pounding.hazard.suite_spectrum import fit_suite_spectrum
from pounding.presets import preset_text
from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration
from pounding.simulation.plan import MonteCarloPlan
from pounding.studies.fragility import fit_lognormal, fragility_curve
from pounding.units import STANDARD_GRAVITY as G

SECTION5 = "section5-T2-0.4"
PGAS = np.linspace(0.05, 0.6, 12) * G


@pytest.fixture(scope="module")
def section5_curve():
    """The issue's check: capacity 0.3 MN, 0.05-0.6 g, 100 records a point."""
    return fragility_curve(SECTION5, 3.0e5, PGAS, MonteCarloPlan(100, 2, scheduler="serial"))


def test_closed_form_rises_with_pga_and_lies_within_010_of_monte_carlo(section5_curve):
    curve = section5_curve
    assert np.all(np.diff(curve.probability) >= 0) and curve.probability[0] < 0.01 and curve.probability[-1] > 0.9
    monte_carlo = curve.monte_carlo.exceeding(3.0e5) / 100
    assert np.max(np.abs(curve.probability - monte_carlo)) <= 0.10
    # the fits of both sides meet: medians within 10 %, the dispersions within 0.1
    assert curve.lognormal.median == pytest.approx(curve.lognormal_monte_carlo.median, rel=0.10)
    assert abs(curve.lognormal.dispersion - curve.lognormal_monte_carlo.dispersion) < 0.1


def test_the_monte_carlo_at_a_pga_is_simulate_of_the_scaled_case(section5_curve):
    """Record by record, the engine integrated the case scaled to that PGA, seeded as simulate seeds it."""
    scaled = PeakGroundAcceleration(load_case(SECTION5)).case_at(PGAS[6])
    direct = simulate(scaled, records=100, seed=2)
    np.testing.assert_array_equal(section5_curve.monte_carlo.force_max[6], direct.force_max)


def test_scaled_processes_have_the_expected_pga_asked():
    """G0 ~ pga^2 (G30): E[PGA] computed afresh on the scaled excitation is the target, for Kanai-Tajimi,
    a modulated case and a design spectrum's filter bank; the mean peak of 200 records is within 4 %."""
    for name in (SECTION5, "section5-T2-0.4-nonstationary"):
        scaled = PeakGroundAcceleration(load_case(name)).case_at(0.25 * G)
        assert expected_peak_ground_acceleration(scaled.excitation) == pytest.approx(0.25 * G, rel=1e-9)
    scaled = PeakGroundAcceleration(load_case(SECTION5)).case_at(0.25 * G)
    peaks = np.abs(ground_accelerations(scaled.excitation, 4, range(200))).max(axis=1)
    assert peaks.mean() == pytest.approx(0.25 * G, rel=0.04)


def test_a_design_spectrum_is_scaled_through_its_filter_bank():
    text = preset_text(SECTION5)
    start, end = text.index("[excitation]"), text.index("[[buildings]]")
    case_text = text[:start] + textwrap.dedent("""\
        [excitation]
        spectrum = "design"
        code = "ec8"
        ag = 0.2
        ground_type = "C"
        duration = 20.0
        """) + text[end:]
    import tomllib

    from pounding.case.case import case_from_dict

    case = case_from_dict(tomllib.loads(case_text))
    scaled = PeakGroundAcceleration(case).case_at(0.4 * G)
    assert expected_peak_ground_acceleration(scaled.excitation) == pytest.approx(0.4 * G, rel=1e-9)
    # the bank's shape is kept: every weight scaled alike
    ratio = np.asarray(scaled.excitation.spectrum.psd(np.array([5.0, 20.0, 60.0]))) / np.asarray(case.excitation.spectrum.psd(np.array([5.0, 20.0, 60.0])))
    assert np.ptp(ratio) < 1e-9 * ratio.mean()


@pytest.fixture(scope="module")
def suite(tmp_path_factory):
    """Six synthetic records of the preset with unequal peaks, as files, and a case reading them."""
    folder = tmp_path_factory.mktemp("fragility-suite")
    (folder / "motions").mkdir()
    excitation = load_case(SECTION5).excitation
    for index, record in enumerate(ground_accelerations(excitation, 6, range(6))):
        write_at2(folder / "motions" / f"m{index}.AT2", Accelerogram(f"m{index}", excitation.time_step, record * (1 + 0.2 * index)))
    text = preset_text(SECTION5)
    start, end = text.index("[excitation]"), text.index("[[buildings]]")
    (folder / "case.toml").write_text(text[:start] + '[excitation]\nrecords = ["motions/*.AT2"]\n\n' + text[end:])
    return folder


def test_recorded_motions_are_each_scaled_to_the_pga(suite):
    case = load_case(suite / "case.toml")
    scaling = PeakGroundAcceleration(case)
    scaled = scaling.case_at(0.3 * G)
    assert [r.peak for r in scaled.hazard.records] == pytest.approx([0.3 * G] * 6, rel=1e-12)
    # the shortcut (fit once, scale G0 by the square) against a fit to the records as scaled: the fit is scale-equivariant
    refit = fit_excitation(scaled.hazard.records, case.hazard.suite.requested_cutoff)
    assert scaled.hazard.fitted.spectrum.G0 == pytest.approx(refit.spectrum.G0, rel=1e-3)
    assert scaled.hazard.fitted.spectrum.omega_g == pytest.approx(refit.spectrum.omega_g, rel=1e-3)
    # and the closed form's bank (S1-S5), as it is fitted to the scaled records
    bank = fit_suite_spectrum(scaled.hazard.records, case.hazard.suite.requested_cutoff).bank
    assert scaled.excitation.spectrum == scaled.hazard.suite.bank
    assert scaled.excitation.spectrum.G0 == pytest.approx(bank.G0, rel=1e-3)
    np.testing.assert_allclose(scaled.excitation.spectrum.weights, bank.weights, rtol=1e-6, atol=1e-9)


def test_a_recorded_suite_needs_as_many_records_as_asked(suite):
    """Each record is run once at each PGA: more records than the suite holds, or fewer than an interval needs, are refused."""
    with pytest.raises(ValueError, match="at least 10"):
        fragility_curve(str(suite / "case.toml"), 2.0e5, np.array([0.2, 0.4]) * G, MonteCarloPlan(6, scheduler="serial"))
    with pytest.raises(ValueError, match="6 recorded motions"):
        fragility_curve(str(suite / "case.toml"), 2.0e5, np.array([0.2, 0.4]) * G, MonteCarloPlan(12, scheduler="serial"))


def test_lognormal_fit_recovers_a_known_curve():
    """Counts drawn from Phi(ln(a / 0.4 g) / 0.3), 200 trials at 15 PGAs: the fit lies within 4 standard errors;
    the exact probabilities as a closed-form curve give the parameters back to 1e-4."""
    rng = np.random.default_rng(11)
    pga = np.linspace(0.1, 0.9, 15) * G
    from scipy.special import ndtr

    truth = ndtr(np.log(pga / (0.4 * G)) / 0.3)
    exact = fit_lognormal(pga, truth, 1.0)
    assert exact.median == pytest.approx(0.4 * G, rel=1e-4) and exact.dispersion == pytest.approx(0.3, rel=1e-4)
    medians, dispersions = [], []
    for _ in range(40):
        fit = fit_lognormal(pga, rng.binomial(200, truth), 200)
        medians.append(fit.median / G)
        dispersions.append(fit.dispersion)
    assert abs(np.mean(medians) - 0.4) < 4 * np.std(medians) / math.sqrt(40) + 1e-3
    assert abs(np.mean(dispersions) - 0.3) < 4 * np.std(dispersions) / math.sqrt(40) + 0.01
    assert fit_lognormal(pga, np.zeros(15), 200) is None and fit_lognormal(pga, np.full(15, 200), 200) is None


@pytest.mark.slow
def test_serial_and_two_dask_workers_give_the_same_counts_and_a_rerun_resumes(tmp_path):
    pga = np.array([0.3, 0.45]) * G
    serial = fragility_curve(SECTION5, 3.0e5, pga, MonteCarloPlan(12, 4, tmp_path / "a", "serial"))
    dask = fragility_curve(SECTION5, 3.0e5, pga, MonteCarloPlan(12, 4, tmp_path / "b", workers=2))
    for one, other in zip(serial.monte_carlo.force_max, dask.monte_carlo.force_max):
        np.testing.assert_array_equal(one, other)
    chunks = sorted((tmp_path / "a").glob("points/*/chunk-*.json"))
    stamps = [path.stat().st_mtime_ns for path in chunks]
    again = fragility_curve(SECTION5, 3.0e5, pga, MonteCarloPlan(12, 4, tmp_path / "a", "serial"))
    assert [path.stat().st_mtime_ns for path in chunks] == stamps  # nothing recomputed
    np.testing.assert_array_equal(again.monte_carlo.force_max[1], serial.monte_carlo.force_max[1])


def test_command_line_fragility_json_and_chart(tmp_path, capsys):
    chart = tmp_path / "fragility.html"
    assert main(["fragility", SECTION5, "--capacity", "300", "--pga", "0.2:0.5:4", "--records", "10", "--scheduler", "serial",
                 "--json", "-o", str(chart)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pga"] == pytest.approx([0.2, 0.3, 0.4, 0.5])
    assert len(out["probability"]) == len(out["probability_monte_carlo"]) == len(out["probability_monte_carlo_interval"]) == 4
    assert all(low <= p <= high for p, (low, high) in zip(out["probability_monte_carlo"], out["probability_monte_carlo_interval"]))
    assert {"median_pga", "dispersion"} <= set(out["lognormal"]) and out["units"]["pga"] == "g"
    page = chart.read_text()
    assert "<script src=" not in page and "Fragility" in page and "0.3" in page


def test_command_line_fragility_in_kgf(capsys):
    """--units kgf-cm-s reads the capacity in kgf: the same curve as the capacity in kN."""
    assert main(["fragility", SECTION5, "--capacity", "30591.5", "--units", "kgf-cm-s", "--pga", "0.3,0.4", "--json"]) == 0
    in_kgf = json.loads(capsys.readouterr().out)
    assert main(["fragility", SECTION5, "--capacity", "300", "--pga", "0.3,0.4", "--json"]) == 0
    in_newtons = json.loads(capsys.readouterr().out)
    assert in_kgf["probability"] == pytest.approx(in_newtons["probability"], rel=1e-4)
    assert main(["fragility", SECTION5, "--capacity", "30591.5", "--units", "kgf-cm-s", "--pga", "0.3,0.4"]) == 0
    assert "30,592 kgf" in capsys.readouterr().out


@pytest.mark.parametrize("arguments, option", [
    (["--capacity", "0", "--pga", "0.1:0.5:5"], "--capacity"),
    (["--capacity", "-3", "--pga", "0.1:0.5:5"], "--capacity"),
    (["--capacity", "300", "--pga", "0.5:0.1:5"], "--pga"),
    (["--capacity", "300", "--pga", "0.1:0.5:1"], "--pga"),
    (["--capacity", "300", "--pga", ""], "--pga"),
    (["--capacity", "300", "--pga", "0:0.5:5"], "--pga"),
    (["--capacity", "300", "--pga", "0.3,0.2"], "--pga"),
    (["--capacity", "300", "--pga", "0.1:0.5:5", "--records", "5"], "--records"),
    (["--capacity", "300", "--pga", "0.1:0.5:5", "--records", "0"], "--records"),
])
def test_bad_fragility_input_exits_2_naming_the_argument(arguments, option, capsys):
    with pytest.raises(SystemExit) as caught:
        status = main(["fragility", SECTION5, *arguments])
        raise SystemExit(status)
    assert caught.value.code == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and option in error[0]
