"""One product: the command line, the report and the dashboard draw the same records for the same case by default
(one seed, ``pounding.defaults.SEED``), and print their numbers in one set of display units (kN and mm unless
``--units kgf-cm-s``), the unit systems' names the same as the dashboard's unit switch."""

from __future__ import annotations

import argparse
import json

import pytest

from pounding import defaults, load_case, simulate
from pounding.cli.commands import main
from pounding.cli.parser import parser
from pounding.report import compute_snapshot, with_check
from pounding.studies.check import check_estimate
from pounding.closed_form.estimator import estimate

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
