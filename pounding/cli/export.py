"""``pounding export``: a case for another program; ``pounding export opensees`` writes an OpenSeesPy model
(:mod:`pounding.export.opensees`). Building the parser imports no numerical library."""

from __future__ import annotations

import argparse
import json

from pounding import defaults
from pounding.cli.arguments import record_count, study_size, whole_number_type

__all__ = ["add_export", "contact_keys", "export_command"]

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
        description="Write DIR/model.py, an OpenSeesPy model of the case (every building, a zeroLength element per storey "
        "with the BoucWen material and the storey's dashpot; every contact, an impact element between the floors that meet), "
        "and DIR/records/, the ground accelerations 'pounding simulate CASE --records N --seed S' integrates. "
        "'python DIR/model.py' runs each record and prints one JSON object on its last line: force_max [N] and impacts, "
        "one per record, the largest over all contacts, and contacts: each contact's, in the case's order.",
        epilog=_EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    opensees.add_argument("case", help="a preset name (see 'pounding cases') or a TOML case file")
    opensees.add_argument("--records", type=record_count, default=None,
                          help=f"number of records (default {defaults.RECORDS}; a case of recorded motions: all of them)")
    opensees.add_argument("--seed", type=whole_number_type(0), default=None, help=f"seed of the study (default {defaults.SEED})")
    opensees.add_argument("-o", "--output", required=True, help="folder to write model.py and records/ to (made if missing)")
    opensees.add_argument("--json", action="store_true", help="print one JSON object naming what was written")


def contact_keys(source: str, case) -> tuple[str, ...]:
    """The key the case file ``source`` (a preset name or a TOML file, loaded as ``case``) gives each contact of
    ``case``, in its order: ``contact``, or ``contacts.i`` for the i-th ``[[contacts]]`` table (a table of
    ``levels = "aligned"`` gives every floor the buildings share, and each of them its key)."""
    import tomllib

    from pounding.case.case import ALIGNED, read_case_file
    from pounding.presets import preset_text

    text = preset_text(source)
    data = tomllib.loads(text) if text is not None else read_case_file(source)
    if "contacts" not in data:
        return ("contact",)
    keys = []
    for i, table in enumerate(data["contacts"], start=1):
        aligned = table.get("levels") == ALIGNED
        shared = min(case.buildings[b - 1].n_storeys for b in table.get("between", [1, 2])) if aligned else 1
        keys += [f"contacts.{i}"] * shared
    return tuple(keys)


def export_command(args) -> int:
    """``pounding export opensees``: write the model, then say what was written and how to run it."""
    from pounding.case.case import load_case
    from pounding.export.opensees import check_exportable, export_opensees

    case = load_case(args.case)
    check_exportable(case, contact_keys(args.case, case))
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
