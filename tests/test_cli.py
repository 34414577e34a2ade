"""The command line, run as a user runs it."""

import json
import re
import subprocess
import sys

import numpy as np
import pytest

from pounding import load_case, preset_names, simulate
from pounding.closed_form.estimator import estimate
from pounding.simulation.monte_carlo import design_gap


def run(*args, **kwargs):
    return subprocess.run([sys.executable, "-m", "pounding", *args], capture_output=True, text=True, timeout=300, **kwargs)


def test_cases_lists_every_preset():
    out = run("cases")
    assert out.returncode == 0
    for name in preset_names():
        assert name in out.stdout


def test_simulate_json_matches_the_library():
    out = run("simulate", "section5-T2-0.8", "--records", "6", "--seed", "3", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    for key in ("force_max_mean", "force_max_std_error", "force_max", "pounding_fraction", "impacts_mean"):
        assert key in data
    expected = simulate(load_case("section5-T2-0.8"), records=6, seed=3)
    np.testing.assert_allclose(data["force_max"], expected.force_max, rtol=1e-12)
    assert data["force_max_mean"] == pytest.approx(expected.force_max_mean)
    assert out.stderr == ""  # no progress bar when stderr is not a terminal
    closed_form = estimate(load_case("section5-T2-0.8"))  # the two methods side by side
    assert data["closed_form"]["force_expected"] == pytest.approx(closed_form.force_expected, rel=1e-12)
    assert data["closed_form"]["paper_force_expected"] == pytest.approx(closed_form.paper.force_expected, rel=1e-12)
    assert data["closed_form"]["accuracy_regime"] == closed_form.accuracy_regime


@pytest.mark.slow
@pytest.mark.parametrize("preset", ["section5-T2-0.4", "section5-T2-0.4-nonstationary"])
def test_estimate_json_is_the_documented_contract_in_si(preset):
    """The keys the issue and README promise, each the library's number in SI;
    a modulated case adds Eq. 29's sigma_V,eq to ``paper``."""
    out = run("estimate", preset, "--json", "--target-probability", "0.9")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    expected = estimate(load_case(preset), target_probability=0.9)
    for key in ("force_expected", "relative_velocity_expected", "sigma_relative_velocity", "sigma_relative_displacement",
                "impacts_expected", "pounding_probability", "required_gap"):
        assert data[key] == pytest.approx(getattr(expected, key), rel=1e-12), key
    for key in ("force_expected", "relative_velocity_expected", "crossing_rate", "duration_effective"):
        assert data["paper"][key] == pytest.approx(getattr(expected.paper, key), rel=1e-12), key
    assert data["units"]["force"] == "N" and data["units"]["length"] == "m"
    stationary = load_case(preset).excitation.stationary
    assert ("sigma_relative_velocity_equivalent" in data["paper"]) is not stationary
    if not stationary:
        equivalent = data["paper"]["sigma_relative_velocity_equivalent"]
        assert equivalent == pytest.approx(expected.paper.sigma_relative_velocity_equivalent, rel=1e-12)
        assert equivalent < data["sigma_relative_velocity"]  # the envelope only lowers sigma_inf


@pytest.mark.slow
def test_validate_prints_the_papers_tables_beside_both_estimators_and_its_assumptions():
    """Tables 1, 2, 5, 6 under both readings of the excitation: the paper's two
    columns as printed in it, this project's Monte Carlo and both estimators,
    each the library's number, then every assumption and what the readings gave."""
    from pounding.studies.paper_tables import ASSUMPTIONS, PAPER_TABLES, READINGS, READINGS_MEASURED

    out = run("validate", "--records", "2", "--seed", "4")
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    for table, (pattern, values) in PAPER_TABLES.items():
        for reading, suffix in READINGS.items():
            start = lines.index(f"{table}, excitation {reading}")
            for offset, (period, (exact, proposed)) in enumerate(values.items(), start=2):
                numbers = [float(x) for x in re.findall(r"\d+\.\d+", lines[start + offset])]
                assert numbers[0:2] == [1.2, period]
                assert numbers[2:4] == pytest.approx([1e3 * exact, 1e3 * proposed], abs=0.05)  # the paper's MN, in kN
                case = load_case(pattern.format(period) + suffix)
                closed_form = estimate(case)
                assert numbers[-2:] == pytest.approx([closed_form.paper.force_expected / 1e3, closed_form.force_expected / 1e3], abs=0.05)
    study = simulate(load_case("section6-T2-0.8-nonstationary"), records=2, seed=4)
    row = lines[lines.index("Table 6, excitation as printed") + 4]
    assert float(row.split("|")[1].split()[0]) == pytest.approx(study.force_max_mean / 1e3, abs=0.05)
    for assumption in ASSUMPTIONS:
        assert f"  - {assumption}" in lines
    assert READINGS_MEASURED in out.stdout


@pytest.mark.slow
def test_simulate_table_puts_the_closed_form_beside_with_its_error():
    """The printed error is the printed force over the study's mean, and the error against the ends of the
    95 % CI brackets it; the force is the library's."""
    out = run("simulate", "section5-T2-0.4", "--records", "6", "--seed", "2")
    assert out.returncode == 0, out.stderr
    study = simulate(load_case("section5-T2-0.4"), records=6, seed=2)
    line = next(line for line in out.stdout.splitlines() if line.strip().startswith("recommended"))
    force = float(re.search(r"([\d,.]+) kN", line).group(1).replace(",", ""))
    error, low, high = (float(x) for x in re.findall(r"([-+]\d+\.\d+) %", line)[:3])
    # printed in kN with 4 significant digits (315.4 kN): within half the last digit
    assert force * 1e3 == pytest.approx(estimate(load_case("section5-T2-0.4")).force_expected, abs=0.05e3)
    assert error == pytest.approx(100 * (force * 1e3 / study.force_max_mean - 1), abs=0.06)
    assert low < error < high
    assert f"accuracy      {estimate(load_case('section5-T2-0.4')).measured_accuracy}" in out.stdout


@pytest.mark.slow
def test_simulate_table_has_units():
    out = run("simulate", "section5-T2-0.8", "--records", "4")
    assert out.returncode == 0
    assert "kN" in out.stdout and "MN" not in out.stdout  # every force in kN by default (tests/test_consistency.py)
    assert "impacts per record" in out.stdout


@pytest.mark.parametrize(
    "args, words",
    [
        (("simulate", "no-such-case"), "neither a TOML file nor a preset"),
        (("simulate", "section5-T2-0.4", "--records", "0"), "--records"),
        (("simulate", "section5-T2-0.4", "--seed", "-1"), "--seed"),
        (("simulate", "section5-T2-0.4", "--tolerance", "0.5"), "--tolerance"),
        (("explode",), "invalid choice"),
        (("estimate", "section5-T2-0.4", "--target-probability", "1"), "--target-probability"),
        (("estimate", "section5-T2-0.4-nonstationary", "--michaelov-n1", "0"), "--michaelov-n1"),
        (("estimate", "nowhere.toml"), "neither a TOML file nor a preset"),
        (("report", "section5-T2-0.4", "-o", "/no/such/folder/report.html"), "--output"),
        (("report", "section5-T2-0.4"), "--output"),
        (("report", "section5-T2-0.4", "-o", "/tmp/unused-report.html", "--design-gap", "0.95"), "--design-gap"),
        (("report", "section5-T2-0.4", "-o", "/tmp/unused-report.html", "--records", "4", "--design-gap", "1.5"), "--design-gap"),
        (("sweep", "section5-T2-0.4", "--vary", "contact.gap=1:0", "-o", "/tmp/unused-sweep"), "contact.gap"),
        (("validate", "--records", "0"), "--records"),
    ],
)
def test_bad_input_exits_2_with_one_line(args, words):
    out = run(*args)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert words in out.stderr
    assert "Traceback" not in out.stderr
    assert len([line for line in lines if "error" in line]) == 1


def test_bad_case_file_names_the_field(tmp_path):
    path = tmp_path / "bad.toml"
    source = (
        'units = "SI"\n[excitation]\nG0 = 0.006\nomega_g = 27.0\nxi_g = 0.34\nduration = 5.0\n'
        "[[buildings]]\n[[buildings.storeys]]\nmass = 4e4\nstiffness = 1e6\n"
        "[[buildings]]\n[[buildings.storeys]]\nmass = 4e4\nstiffness = 1e7\n"
        "[contact]\ngap = 0.01\nstiffness = 2e9\nrestitution = 1.5\n"
    )
    path.write_text(source)
    out = run("simulate", str(path), "--records", "2")
    assert out.returncode == 2
    assert "contact.restitution" in out.stderr
    assert "[0.001, 1]" in out.stderr


def test_command_line_imports_no_plotting_library():
    code = (
        "import sys; from pounding.cli.commands import main; main(['simulate', 'section5-T2-0.4', '--records', '2', '--json']);"
        "heavy = [m for m in ('panel', 'holoviews', 'bokeh', 'matplotlib') if m in sys.modules];"
        "print('HEAVY', heavy, file=sys.stderr)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert "HEAVY []" in out.stderr


@pytest.mark.slow
def test_report_is_written_and_described(tmp_path):
    path = tmp_path / "report.html"
    out = run("report", "section5-T2-0.8", "-o", str(path), "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["report"] == str(path)
    assert data["force_expected"] > 0
    text = path.read_text()
    assert "<html" in text.lower() and "section5-T2-0.8" in text
    assert not list(tmp_path.glob(".*.tmp"))


@pytest.mark.slow
def test_report_carries_the_monte_carlo_design_gap_beside_the_closed_form(tmp_path):
    path = tmp_path / "report.html"
    out = run("report", "section5-T2-0.8", "-o", str(path), "--records", "12", "--seed", "3", "--design-gap", "0.9", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    expected = design_gap(load_case("section5-T2-0.8"), target_probability=0.9, records=12, seed=3)
    assert data["monte_carlo_design_gap"]["design_gap"] == pytest.approx(expected.gap, rel=1e-12)
    assert data["target_probability"] == 0.9  # the closed form's gap is for the same probability
    assert data["monte_carlo"]["records"] == 12
    text = path.read_text()
    assert "Monte Carlo gap for 90 % no pounding" in text and "it needs 22" in text  # 0.9^22 < 0.1 < 0.9^21


@pytest.mark.slow
def test_killed_report_leaves_no_file(tmp_path):
    """Killed while it works (here in its Monte Carlo), a report run leaves
    neither the report nor a partial file behind."""
    import signal
    import time

    path = tmp_path / "report.html"
    process = subprocess.Popen([sys.executable, "-m", "pounding", "report", "section5-T2-0.4", "-o", str(path),
                                "--records", "200000"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(6)
    assert process.poll() is None, "the run ended before it could be killed"
    process.send_signal(signal.SIGKILL)
    process.wait(timeout=30)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_help_has_examples():
    for args in (("--help",), ("simulate", "--help"), ("cases", "--help"), ("dashboard", "--help"), ("estimate", "--help"),
                 ("validate", "--help"), ("report", "--help"), ("sweep", "--help")):
        out = run(*args)
        assert out.returncode == 0
        assert "example" in out.stdout


def test_a_case_the_methods_cannot_compute_fails_in_one_line(monkeypatch, capsys):
    """A linearization that does not converge (here forced) ends the command with one line and exit 1."""
    import pounding.closed_form.estimator
    from pounding.cli.commands import main
    from pounding.errors import ConvergenceError

    def fails(*_args, **_kwargs):
        raise ConvergenceError("building 2, storey 1: the linearization did not converge (last iterate ...)")

    monkeypatch.setattr(pounding.closed_form.estimator, "estimate", fails)
    assert main(["estimate", "section5-T2-0.4"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["pounding estimate: failed: building 2, storey 1: the linearization did not converge (last iterate ...)"]
