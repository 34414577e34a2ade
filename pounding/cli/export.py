"""``pounding export``: a case for another program; ``pounding export opensees`` writes an OpenSeesPy model
(:mod:`pounding.export.opensees`). Building the parser imports no numerical library."""

from __future__ import annotations

import argparse
import json

from pounding import defaults
from pounding.cli.arguments import record_count, study_size, whole_number_type

__all__ = ["add_export", "export_command"]

_EXAMPLES = """examples:
  pounding export opensees section5-T2-0.4 --records 20 --seed 1 -o opensees/
  python opensees/model.py
  pounding simulate section5-T2-0.4 --records 20 --seed 1 --json   (the same records, for comparison)"""


def add_export(commands) -> None:
    """Add ``export`` and its ``opensees`` target to the ``pounding`` subcommands ``commands``."""
    export = commands.add_parser(
        "export",
        help="write a case as a model for another program (OpenSeesPy)",
        description="Write a case as a model another program runs: 'opensees', a standalone OpenSeesPy script.",
        epilog=_EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    targets = export.add_subparsers(dest="target", required=True, parser_class=type(export))  # bad arguments: exit 2
    opensees = targets.add_parser(
        "opensees",
        help="an OpenSeesPy script and the records 'pounding simulate' integrates",
        description="Write DIR/model.py, an OpenSeesPy model of the case (a zeroLength element per storey with the "
        "BoucWen material and the storey's dashpot, the impact material between the floors that meet), and DIR/records/, "
        "the ground accelerations 'pounding simulate CASE --records N --seed S' integrates. 'python DIR/model.py' runs "
        "each record and prints one JSON object on its last line: force_max [N] and impacts, one per record.",
        epilog=_EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    opensees.add_argument("case", help="a preset name (see 'pounding cases') or a TOML case file")
    opensees.add_argument("--records", type=record_count, default=None,
                          help=f"number of records (default {defaults.RECORDS}; a case of recorded motions: all of them)")
    opensees.add_argument("--seed", type=whole_number_type(0), default=None, help=f"seed of the study (default {defaults.SEED})")
    opensees.add_argument("-o", "--output", required=True, help="folder to write model.py and records/ to (made if missing)")
    opensees.add_argument("--json", action="store_true", help="print one JSON object naming what was written")


def export_command(args) -> int:
    """``pounding export opensees``: write the model, then say what was written and how to run it."""
    from pounding.case.case import load_case
    from pounding.export.opensees import check_exportable, export_opensees

    case = load_case(args.case)
    check_exportable(case)
    records, seed = study_size(case, args, "written")
    written = export_opensees(case, args.output, records=records, seed=seed, field="--output")
    if args.json:
        print(json.dumps({"case": case.name, "script": str(written.script), "records": [str(path) for path in written.record_files],
                          "seed": None if case.recorded else seed, "time_step": written.time_step}))
        return 0
    print(f"wrote {written.script} and {len(written.record_files)} record(s) in {written.script.parent / 'records'}")
    print(f"analysis step {written.time_step:.4g} s: {written.time_step_reason}")
    print(f"run: python {written.script}")
    return 0
