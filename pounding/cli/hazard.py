"""Command-line pieces about the ground motion and the storeys: the lines
``estimate`` prints in an engineer's terms, and ``pounding records``."""

from __future__ import annotations

import json

from pounding.units import STANDARD_GRAVITY

__all__ = ["engineering_lines", "records_command"]


def _g(acceleration: float) -> str:
    return f"{acceleration / STANDARD_GRAVITY:.3f} g"


def _length(metres: float | None) -> str:
    return "elastic" if metres is None else f"{100 * metres:.3f} cm"


def _force(newtons: float | None) -> str:
    if newtons is None:
        return "elastic"
    return f"{newtons / 1e6:.4f} MN" if abs(newtons) >= 1e5 else f"{newtons / 1e3:.2f} kN"


def _spectrum_text(fitted: dict) -> str:
    text = f"{fitted['spectrum']}: G0 = {fitted['G0']:.4g} m^2/s^3, omega_g = {fitted['omega_g']:.3g} rad/s, xi_g = {fitted['xi_g']:.3g}"
    if fitted["spectrum"] == "clough-penzien":
        text += f", omega_f = {fitted['omega_f']:.3g} rad/s, xi_f = {fitted['xi_f']:.3g}"
    return text


def engineering_lines(terms: dict, force_text=None) -> list[str]:
    """The ground motion and the storeys, from ``Estimate.to_dict()`` (its :func:`~pounding.case.engineering.engineering_terms`);
    ``force_text`` prints a force [N] (default kN or MN)."""
    force_text = force_text or _force
    motion = terms["ground_motion"]
    lines = []
    if "fitted_excitation" in terms:
        fitted = terms["fitted_excitation"]
        lines.append(f"ground motion               {len(terms['record_files'])} recorded motions ({terms['record_scaling']}); "
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
            lines.append(f"  {where:25s} elastic, stiffness {storey['stiffness']:.4g} N/m")
        else:
            lines.append(f"  {where:25s} yield drift {_length(storey['yield_drift'])}, yield force {force_text(storey['yield_force'])}, "
                         f"post-yield ratio {storey['post_yield_ratio']:.3g}")
    return lines


def records_command(args) -> int:
    """``pounding records``: write the records ``simulate`` integrates, one file per record."""
    from pounding import defaults
    from pounding.case.case import load_case
    from pounding.errors import ArgumentError
    from pounding.hazard.accelerograms import Accelerogram, write_at2, write_csv
    from pounding.output import check_folder
    from pounding.simulation.ground_motion import check_suite_range, ground_motion_batches, suite_size
    from pounding.simulation.system import check_records

    case = load_case(args.case)
    size = suite_size(case)
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
    for index in range(records):
        _, accelerations, time_step = next(ground_motion_batches(case, seed, [index]))
        name = f"record-{index:0{width}d}.{suffix}"
        record = Accelerogram(name, time_step, accelerations[0])
        source = case.hazard.records[index].name if size else f"record {index} of seed {seed}"
        if args.format == "at2":
            write_at2(directory / name, record, title=f"pounding: case {case.name}, {source}")
        else:
            write_csv(directory / name, record)
        written.append(name)
    if args.json:
        print(json.dumps({"case": case.name, "seed": None if size else seed, "directory": str(directory), "files": written}))
    else:
        print(f"wrote {len(written)} records ({args.format}, acceleration in g) to {directory}")
    return 0
