"""The command line of ``pounding sweep``: its arguments, texts and output."""

from __future__ import annotations

import argparse
import json
import math
import sys

from pounding import defaults
from pounding.cli.arguments import add_units, record_count, whole_number_type
from pounding.cli.progress import progress_bar
from pounding.studies.sweeps.engine import SERIAL, TABLE_FORMATS, sweep
from pounding.studies.sweeps.spec import normalized_vary

DESCRIPTION = (
    "Parametric study: every combination of the --vary values, estimated in closed form and simulated by "
    "Monte Carlo with the records spread in chunks over Dask workers (a local cluster on this machine's cores, "
    "or --scheduler ADDRESS). Finished chunks are kept in the output folder: rerun the same command to resume."
)
EPILOG = """examples:
  pounding sweep section5-T2-0.4 --vary contact.gap=0.0:0.05:11 --records 300 --seed 1 -o gap-study/
  pounding sweep case.toml --vary contact.gap=0.5,1,2 --vary buildings.2.storeys.1.period=0.4,0.6,0.8 -o out/
  pounding sweep case.toml --vary excitation.G0=30:90:7 --records 2000 --scheduler tcp://10.0.0.5:8786 -o out/
--vary PATH=VALUES: PATH is a key of the case file (buildings and storeys counted from 1), in the case's
units; VALUES is start:stop:count (count values, both ends included) or a,b,c."""


def add_arguments(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Add the ``pounding sweep`` arguments to ``parser`` (the subcommand's
    parser; :data:`DESCRIPTION` and :data:`EPILOG` are its texts). Returns ``parser``."""
    parser.add_argument("case", metavar="CASE", help="a preset name (see 'pounding cases') or a TOML case file")
    parser.add_argument("--vary", action="append", default=[], metavar="PATH=VALUES",
                        help="a key of the case file and its values, in the case's units: start:stop:count or a,b,c "
                        "(repeat for more keys; every combination is run)")

    parser.add_argument("--records", type=record_count, default=defaults.SWEEP_RECORDS,
                        help=f"Monte Carlo records per point (default {defaults.SWEEP_RECORDS})")
    parser.add_argument("--seed", type=whole_number_type(0), default=defaults.SEED, help=f"seed of the study (default {defaults.SEED})")
    parser.add_argument("-o", "--output", required=True, metavar="DIR",
                        help="folder of the results and of the finished chunks (rerun with it to resume)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="Dask scheduler address (tcp://host:8786); default: a local cluster on this machine's cores; "
                        f"'{SERIAL}': in this process, without Dask")
    parser.add_argument("--workers", type=whole_number_type(1), default=None, help="worker processes of the local cluster (default: one per core)")
    parser.add_argument("--chunk-records", type=whole_number_type(1), default=defaults.CHUNK_RECORDS,
                        help=f"records per Dask task (default {defaults.CHUNK_RECORDS})")
    parser.add_argument("--format", choices=TABLE_FORMATS, default="csv", help="format of the table (default csv; parquet needs pyarrow)")
    parser.add_argument("--no-chart", action="store_true", help="do not write the design chart sweep.html")
    add_units(parser, "the forces printed (the varied keys stay in the case's units)")
    parser.add_argument("--json", action="store_true", help="print one JSON object (forces in N, lengths in m)")
    return parser


def _json_value(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if hasattr(value, "item"):  # numpy scalars
        return _json_value(value.item())
    return value


def run(args: argparse.Namespace) -> int:
    """Execute ``pounding sweep`` with the arguments of :func:`add_arguments`.

    Returns 0. Raises :class:`~pounding.errors.InputError` on bad input (the CLI prints it on one
    line and exits 2); on Ctrl-C, says how to resume and re-raises.
    """
    from pounding.simulation.plan import MonteCarloPlan

    vary = normalized_vary(args.vary)
    try:
        with progress_bar() as progress:
            plan = MonteCarloPlan(args.records, args.seed, scheduler=args.scheduler, workers=args.workers,
                                  progress=progress, chunk_records=args.chunk_records)
            table = sweep(args.case, dict(vary), plan, args.output, table_format=args.format, chart=not args.no_chart)
    except KeyboardInterrupt:
        print(f"pounding sweep: finished chunks are kept in {args.output}; rerun the same command to resume", file=sys.stderr)
        raise
    paths = [path for path, _ in vary]
    if args.json:
        rows = [{key: _json_value(value) for key, value in row.items()} for row in table.to_dict(orient="records")]
        print(json.dumps({
            "case": str(args.case), "records": args.records, "seed": args.seed, "vary": {p: list(v) for p, v in vary},
            "case_units": table.attrs["units"], "table": table.attrs["table"], "chart": table.attrs["chart"],
            "chunks_computed": table.attrs["chunks_computed"], "chunks_reused": table.attrs["chunks_reused"],
            "units": {"force": "N", "length": "m", "velocity": "m/s"}, "rows": rows,
        }))
        return 0
    print(f"{len(table)} point(s) x {args.records} records, seed {args.seed}; "
          f"{table.attrs['chunks_computed']} chunk(s) computed, {table.attrs['chunks_reused']} found done")
    from pounding.display_units import display

    shown = display(args.units)
    unit = shown.force_unit
    header = [*paths, f"F_e closed form [{unit}]", f"F_max Monte Carlo (s.e.) [{unit}]", "P closed form", "P Monte Carlo"]
    lines = []
    for row in table.to_dict(orient="records"):
        lines.append([
            *(f"{row[p]:g}" for p in paths),
            _number(row["estimate_force_N"], shown),
            f"{_number(row['mc_force_mean_N'], shown)} ({_number(row['mc_force_std_error_N'], shown)})",
            _fraction(row["estimate_pounding_probability"]),
            _fraction(row["mc_pounding_fraction"]),
        ])
    widths = [max(len(header[i]), *(len(line[i]) for line in lines)) for i in range(len(header))]
    for line in [header, *lines]:
        print("  ".join(cell.rjust(width) for cell, width in zip(line, widths)))
    print(f"forces in {unit}; varied keys in the case's units ({table.attrs['units']})")
    print(f"table  {table.attrs['table']}")
    if table.attrs["chart"]:
        print(f"chart  {table.attrs['chart']}")
    return 0


def _number(newtons: float, shown) -> str:
    """A force [N] in the display units' force unit, the number alone (the unit is in the column's header)."""
    return "n/a" if not math.isfinite(newtons) else f"{shown.from_si(newtons, force=1):.4g}"


def _fraction(value: float) -> str:
    return "n/a" if not math.isfinite(value) else f"{value:.3f}"
