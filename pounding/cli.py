"""The ``pounding`` command line.

Kept light: nothing on the path of ``cases``, ``simulate`` (and later
``estimate``) imports a plotting or dashboard library.
"""

from __future__ import annotations

import argparse
import json
import sys

EXIT_BAD_INPUT = 2

_EPILOG = """examples:
  pounding cases
  pounding simulate section5-T2-0.4 --records 300 --seed 1
  pounding simulate my_case.toml --records 50 --json
  pounding dashboard --port 5006
"""


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {value}")
    return value


def _non_negative_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {value}")
    return value


class _Parser(argparse.ArgumentParser):
    """Bad arguments: one line naming the argument, exit code 2."""

    def error(self, message: str):
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="pounding",
        description="Expected extreme pounding force between two adjacent buildings under random earthquakes.",
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

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
        description="Nonlinear time-history analysis of the case over N seeded synthetic records; "
        "prints the mean extreme pounding force with its standard error and 95%% confidence interval.",
        epilog="examples:\n  pounding simulate section5-T2-0.4 --records 300 --seed 1\n"
        "  pounding simulate case.toml --records 20 --json > result.json",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    simulate.add_argument("case", help="a preset name (see 'pounding cases') or a TOML case file")
    simulate.add_argument("--records", type=_positive_int, default=100, help="number of records (default 100)")
    simulate.add_argument("--seed", type=_non_negative_int, default=0, help="seed of the study (default 0)")
    simulate.add_argument("--tolerance", type=float, default=1e-6, help="relative tolerance of the integrator (default 1e-6)")
    simulate.add_argument("--json", action="store_true", help="print one JSON object (SI units) instead of a table")

    dashboard = commands.add_parser(
        "dashboard",
        help="serve the browser dashboard",
        description="Serve the dashboard (Panel) on the given port.",
        epilog="example:\n  pounding dashboard --port 5006 --show",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    dashboard.add_argument("--port", type=_non_negative_int, default=5006, help="port (default 5006; 0 picks a free one)")
    dashboard.add_argument("--show", action="store_true", help="open a browser tab")
    dashboard.add_argument("--allow-websocket-origin", action="append", default=[], help="extra allowed websocket origin (host:port)")
    return parser


def _progress_bar(total: int, enabled: bool):
    """A tqdm bar on stderr when it is a terminal; otherwise nothing."""
    if not enabled:
        return None
    from tqdm import tqdm

    return tqdm(total=total, unit="record", file=sys.stderr, dynamic_ncols=True)


def _cases(_args) -> int:
    from .presets import preset_description, preset_names

    for name in preset_names():
        print(name)
        print(f"    {preset_description(name)}")
    return 0


def _format_force(newtons: float) -> str:
    return f"{newtons / 1e6:.4f} MN" if abs(newtons) >= 1e5 else f"{newtons / 1e3:.2f} kN"


def _simulate(args) -> int:
    from .case import load_case
    from .simulation import Settings, simulate

    case = load_case(args.case)
    settings = Settings(tolerance=args.tolerance)
    bar = _progress_bar(args.records, sys.stderr.isatty())

    def progress(done: int, total: int) -> None:
        bar.update(done - bar.n)

    try:
        result = simulate(case, records=args.records, seed=args.seed, settings=settings, progress=progress if bar else None)
    finally:
        if bar is not None:
            bar.close()
    if args.json:
        print(json.dumps(result.to_dict()))
        return 0
    low, high = result.force_max_confidence_interval
    print(f"case            {case.name}")
    print(f"records         {result.n_records} x {case.excitation.duration:g} s, seed {args.seed}")
    print(f"mean F_max      {_format_force(result.force_max_mean)}  (standard error {_format_force(result.force_max_std_error)})")
    print(f"95% CI          {_format_force(low)} .. {_format_force(high)}")
    print(f"pounding        {100 * result.pounding_fraction:.1f} % of records, {result.impacts_mean:.2f} impacts per record")
    print(f"peak impact v   {result.impact_velocity_max.mean():.4f} m/s (mean over records)")
    return 0


def _dashboard(args) -> int:
    from .serve import serve_dashboard

    serve_dashboard(port=args.port, show=args.show, extra_origins=args.allow_websocket_origin)
    return 0


_COMMANDS = {"cases": _cases, "simulate": _simulate, "dashboard": _dashboard}


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``pounding`` command."""
    from .errors import CaseError

    args = _parser().parse_args(argv)
    try:
        return _COMMANDS[args.command](args)
    except CaseError as error:
        print(f"pounding {args.command}: error: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print(f"pounding {args.command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # The reader (e.g. `head`) left early; that is not an error of ours.
        sys.stderr.close()
        return 0


if __name__ == "__main__":
    sys.exit(main())
