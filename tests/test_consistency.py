"""One product: the command line, the report and the dashboard draw the same records for the same case by default
(one seed, ``pounding.defaults.SEED``), and print their numbers in one set of display units (kN and mm unless
``--units kgf-cm-s``), the unit systems' names the same as the dashboard's unit switch."""

from __future__ import annotations

import argparse
import json
import re

import pytest

from pounding import defaults, load_case, simulate
from pounding.cli.commands import main
from pounding.cli.parser import parser
from pounding.report import compute_snapshot, with_check
from pounding.studies.check import check_estimate
from pounding.closed_form.estimator import estimate
from pounding.units import UNIT_SYSTEMS

CASE = "section5-T2-0.4"
RESEARCH_SEEDS = {"validate"}
"""Commands whose seed reproduces published measurements (the paper's tables: ``defaults.VALIDATION_SEED``)."""


def _subcommands() -> dict[str, argparse.ArgumentParser]:
    found, pending = {}, [("", parser())]
    while pending:
        prefix, command = pending.pop()
        for action in command._actions:
            if isinstance(action, argparse._SubParsersAction):
                for name, sub in action.choices.items():
                    found[f"{prefix}{name}"] = sub
                    pending.append((f"{prefix}{name} ", sub))
    return found


def _option(command: argparse.ArgumentParser, flag: str):
    return next((a for a in command._actions if flag in a.option_strings), None)


def test_every_commands_seed_defaults_to_the_one_seed():
    """A command that takes --seed defaults to defaults.SEED (None meaning it), and says so in its help."""
    seeded = {name: _option(sub, "--seed") for name, sub in _subcommands().items()}
    seeded = {name: option for name, option in seeded.items() if option is not None and name not in RESEARCH_SEEDS}
    assert {"simulate", "estimate", "report", "sweep", "fragility", "spectrum", "records", "export opensees"} <= set(seeded)
    for name, option in seeded.items():
        assert option.default in (None, defaults.SEED), name
        assert f"default {defaults.SEED}" in option.help, name


def test_the_same_case_gives_the_same_monte_carlo_mean_on_the_command_line_the_report_and_the_dashboard(capsys):
    """simulate's default seed, estimate --check's, the report's check on the same records, the dashboard's seed:
    one study, one mean (it differed when the command line's seed was 0 and the page's 1)."""
    records = 12
    assert main(["simulate", CASE, "--records", str(records), "--json"]) == 0
    command_line = json.loads(capsys.readouterr().out)
    library = simulate(load_case(CASE), records=records)
    assert command_line["seed"] == library.seed == defaults.SEED
    assert command_line["force_max_mean"] == library.force_max_mean

    assert main(["estimate", CASE, "--check", str(records), "--json"]) == 0
    checked = json.loads(capsys.readouterr().out)["check"]
    assert checked["force_max_mean"] == library.force_max_mean

    snapshot = compute_snapshot(load_case(CASE))  # what the report and the dashboard compute
    assert snapshot.seed == defaults.SEED
    report_check = check_estimate(snapshot.estimate, records=records, seed=snapshot.seed)
    assert report_check.force_max_mean == library.force_max_mean

    from dashboard.studies import Studies

    assert Studies.param.seed.default == defaults.SEED
def test_the_units_options_are_the_dashboards_unit_systems():
    """--units on every command that prints numbers, its choices the unit switch's (the library's unit systems),
    SI by default."""
    from dashboard.model import PoundingModel

    printing = {"estimate", "simulate", "report", "sweep", "fragility", "spectrum"}
    commands = _subcommands()
    for name in printing:
        option = _option(commands[name], "--units")
        assert option is not None, name
        assert tuple(option.choices) == tuple(UNIT_SYSTEMS) == tuple(PoundingModel.param.units.objects), name
        assert option.default == PoundingModel.param.units.default == "SI", name


_FORCE = re.compile(r"\d (MN|kN|N|kgf)(?![\w/*^])")
_LENGTH = re.compile(r"\d (mm|cm|m)(?![\w/*^])")
_VELOCITY = re.compile(r"\d (m/s|cm/s|mm/s)\b")
_UNITS = {"SI": ({"kN"}, {"mm"}, {"m/s"}), "kgf-cm-s": ({"kgf"}, {"cm"}, {"cm/s"})}
_COMMANDS = [
    ("estimate", CASE),
    ("estimate", CASE, "--check", "12", "--capacity", "300"),
    ("simulate", CASE, "--records", "12", "--capacity", "300"),
    ("simulate", CASE, "--records", "12", "--design-gap", "0.9"),
    ("sweep", CASE, "--vary", "contact.gap=1,2", "--records", "4", "--scheduler", "serial", "--no-chart"),
    ("fragility", CASE, "--capacity", "300", "--pga", "0.2,0.4"),
    ("spectrum", CASE, "--period1", "0.8,1.2", "--period2", "0.4"),
]


@pytest.mark.parametrize("units", list(_UNITS))
@pytest.mark.parametrize("command", _COMMANDS, ids=lambda c: " ".join(c[:1] + c[2:3]))
def test_every_printed_force_length_and_velocity_is_in_the_chosen_units(command, units, capsys, tmp_path):
    """By default every force a command prints is in kN, every length in mm and every velocity in m/s (estimate
    printed MN and cm, simulate MN beside kN); with --units kgf-cm-s in kgf, cm and cm/s. Only the text: --json
    stays SI."""
    args = [*command, "--units", units] + (["-o", str(tmp_path / "sweep")] if command[0] == "sweep" else [])
    assert main(args) == 0
    out = capsys.readouterr().out
    forces, lengths, velocities = _UNITS[units]
    found = ({m.group(1) for m in _FORCE.finditer(out)}, {m.group(1) for m in _LENGTH.finditer(out)},
             {m.group(1) for m in _VELOCITY.finditer(out)})
    assert found[0] <= forces and found[1] <= lengths and found[2] <= velocities, out
    assert found[0] or found[1] or command[0] == "sweep", out  # something was checked
    assert "docs/" not in out and ".md" not in out, out  # a wheel's user has no docs/ (simulate --design-gap pointed there)
    if command[0] == "sweep":  # its forces are a column: the unit is in the header
        assert f"forces in {next(iter(forces))}" in out
