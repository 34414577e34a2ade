"""``pounding fragility`` and ``pounding spectrum``: their arguments, their runs and their text output.

Building the parsers imports nothing numerical; a run imports the library, and Bokeh only to write a chart.
"""

from __future__ import annotations

import argparse
import json

from pounding import defaults
from pounding.cli.arguments import (add_capacity, add_units, bounded_number, capacity_newtons, increasing_values, record_count,
                                    whole_number_type)
from pounding.cli.progress import progress_bar

__all__ = ["add_fragility", "add_spectrum", "run_fragility", "run_spectrum"]


def _common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("case", help="a preset name (see 'pounding cases') or a TOML case file")
    parser.add_argument("--records", type=record_count, default=0,
                        help="also Monte Carlo, this many records a point (default: closed form only; recorded motions: "
                        "the first records of the suite)")
    parser.add_argument("--seed", type=whole_number_type(0), default=defaults.SEED, help=f"seed of the Monte Carlo study (default {defaults.SEED})")
    add_units(parser, "--capacity (N or kgf) and of the forces printed and charted")
    parser.add_argument("--work-dir", metavar="DIR", default=None,
                        help="folder of the finished Monte Carlo chunks: rerun with it to resume (default: a temporary folder)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="Dask scheduler address; default: a local cluster on this machine's cores; 'serial': in this process")
    parser.add_argument("--workers", type=whole_number_type(1), default=None, help="worker processes of the local cluster (default: one per core)")
    parser.add_argument("-o", "--output", metavar="CHART", default=None, help="also write a self-contained HTML chart here")
    parser.add_argument("--json", action="store_true", help="print one JSON object (SI units, PGA in g)")


def add_fragility(commands) -> None:
    """The ``fragility`` subcommand."""
    parser = commands.add_parser(
        "fragility",
        help="P(F_max > capacity) against the peak ground acceleration: a fragility curve",
        description="The probability that the extreme pounding force exceeds a capacity, against the expected peak "
        "ground acceleration (the case's ground motion scaled to each; recorded motions: every record to it): the "
        "closed form at every PGA and, with --records, Monte Carlo with its 95 %% interval (on the sweep's Dask "
        "engine), each with the lognormal fragility (median PGA, dispersion beta) fitted by maximum likelihood.",
        epilog="examples:\n  pounding fragility section5-T2-0.4 --capacity 300 --pga 0.05:0.6:12\n"
        "  pounding fragility section5-T2-0.4 --capacity 300 --pga 0.05:0.6:12 --records 100 -o fragility.html\n"
        "  pounding fragility case.toml --capacity 30000 --units kgf-cm-s --pga 0.1,0.2,0.3,0.4 --json",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_capacity(parser, "", required=True)
    parser.add_argument("--pga", type=increasing_values("g"), metavar="A:B:N", required=True,
                        help="expected peak ground accelerations in g: start:stop:count or a,b,c, increasing")
    _common(parser)


def add_spectrum(commands) -> None:
    """The ``spectrum`` subcommand."""
    parser = commands.add_parser(
        "spectrum",
        help="the stochastic pounding-force spectrum: E[F_max] and its 84th percentile against building 1's period",
        description="The mean and the 84th percentile of the extreme pounding force against the fundamental period "
        "of building 1, building 2 at a fixed period or period ratio; each building made stiffer or softer (masses, "
        "yield drifts, damping ratio, gap, restitution and ground motion from the case): the closed form at every "
        "period and, with --records, Monte Carlo with 95 %% intervals (on the sweep's Dask engine).",
        epilog="examples:\n  pounding spectrum section5-T2-0.4 --period1 0.2:2:30 --period2 0.4\n"
        "  pounding spectrum section5-T2-0.4 --period1 0.3:2:12 --period-ratio 0.5 --records 100 -o spectrum.html",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--period1", type=increasing_values("s", maximum=1e3), metavar="A:B:N", required=True,
                        help="fundamental periods of building 1 [s]: start:stop:count or a,b,c, increasing")
    second = parser.add_mutually_exclusive_group(required=True)
    second.add_argument("--period-ratio", type=bounded_number(0.0, 1e3, open_low=True), metavar="R",
                        help="building 2's period is R x T1")
    second.add_argument("--period2", type=bounded_number(0.0, 1e3, open_low=True), metavar="T", help="building 2's period [s]")
    _common(parser)


def _plan(args, progress):
    """The Monte Carlo side the options ask for (none without --records)."""
    from pounding.simulation.plan import MonteCarloPlan

    if not args.records:
        return None
    return MonteCarloPlan(args.records, args.seed, args.work_dir, args.scheduler, args.workers, progress)


def _run(args, compute, chart, title: str):
    """Check the chart's target, compute, write the chart."""
    from pounding.output import check_target

    if args.output is not None:
        check_target(args.output, "--output", probe=True)
    points = len(getattr(args, "pga", None) or args.period1)
    with progress_bar(points * (args.records or 0), enabled=bool(args.records)) as progress:
        result = compute(progress)
    if args.output is not None:
        from pounding.report.curve_charts import write_chart_page

        layout, note, table = chart(result, args.units)
        write_chart_page(args.output, f"{title}: {result.case.name}", layout, note, table)
    return result


_BAND_HEADER = "  E[F_max] band of measured accuracy (regime)"


def _bands(band, accuracy, shown) -> list[str]:
    """Each point's band of measured accuracy as a column: where the Monte Carlo E[F_max] lay given the closed form's."""
    low, high = band
    return [f"  {shown.force(lo)} to {shown.force(hi) if hi < float('inf') else 'unbounded'} ({measured.regime})"
            for lo, hi, measured in zip(low, high, accuracy)]


def run_fragility(args) -> int:
    from pounding.display_units import display
    from pounding.studies.fragility import fragility_curve
    from pounding.units import STANDARD_GRAVITY

    shown = display(args.units)
    capacity = capacity_newtons(args)

    def compute(progress):
        return fragility_curve(args.case, capacity, [a * STANDARD_GRAVITY for a in args.pga], _plan(args, progress))

    from pounding.report.curve_charts import fragility_chart

    curve = _run(args, compute, fragility_chart, "Fragility of the pounding force")
    if args.json:
        print(json.dumps({**curve.to_dict(), **({"chart": args.output} if args.output else {})}))
        return 0
    mc = curve.monte_carlo
    print(f"case           {curve.case.name} (its own expected PGA {curve.reference_pga / STANDARD_GRAVITY:.3g} g)")
    print(f"capacity       {shown.force(curve.capacity)}")
    if mc is not None:
        print(f"Monte Carlo    {mc.records} records a PGA" + ("" if curve.case.recorded else f", seed {mc.seed}"))
    header = f"{'PGA [g]':>8}  {'P closed form':>13}  {'E[F_max]':>12}  {'F_84':>12}"
    print(header + ("  P Monte Carlo (95 % interval)" if mc is not None else "") + _BAND_HEADER)
    bands = _bands(curve.force_band(), curve.accuracy, shown)
    exceeding = mc.exceeding(curve.capacity) if mc is not None else None
    intervals = mc.intervals(curve.capacity) if mc is not None else None
    for index, pga in enumerate(curve.pga):
        line = (f"{pga / STANDARD_GRAVITY:8.4g}  {curve.probability[index]:13.3f}  {shown.force(curve.force_expected[index]):>12}  "
                f"{shown.force(curve.force_84[index]):>12}")
        if mc is not None:
            line += f"  {exceeding[index] / mc.records:.3f} ({intervals[index, 0]:.3f} to {intervals[index, 1]:.3f})"
        print(line + bands[index])
    for label, fit in (("closed form", curve.lognormal), ("Monte Carlo", curve.lognormal_monte_carlo)):
        if label == "Monte Carlo" and mc is None:
            continue
        if fit is None:
            print(f"lognormal fit, {label}: none (the probability is 0 or 1 at every PGA: widen the range)")
        else:
            print(f"lognormal fit, {label}: median PGA {fit.median / STANDARD_GRAVITY:.3g} g, dispersion {fit.dispersion:.3f}"
                  + ("   (at its bound: the data do not pin it)" if fit.at_bound else ""))
    if args.output:
        print(f"chart          {args.output}")
    return 0


def run_spectrum(args) -> int:
    from pounding.display_units import display
    from pounding.studies.force_spectrum import force_spectrum

    shown = display(args.units)

    def compute(progress):
        return force_spectrum(args.case, args.period1, args.period_ratio, args.period2, _plan(args, progress))

    from pounding.report.curve_charts import spectrum_chart

    spectrum = _run(args, compute, spectrum_chart, "Stochastic pounding-force spectrum")
    if args.json:
        print(json.dumps({**spectrum.to_dict(), **({"chart": args.output} if args.output else {})}))
        return 0
    mc = spectrum.monte_carlo
    second = f"T2 = {args.period_ratio:g} x T1" if args.period2 is None else f"T2 = {args.period2:g} s"
    others = len(spectrum.case.buildings) - 2
    held = ("" if not others else "; building 3 keeps its period" if others == 1
            else f"; buildings 3 to {others + 2} keep their periods")
    print(f"case           {spectrum.case.name}; {second}{held}")
    if len(spectrum.case.contacts) > 1:
        print("               the forces are the largest over all contacts")
    if mc is not None:
        print(f"Monte Carlo    {mc.records} records a period" + ("" if spectrum.case.recorded else f", seed {mc.seed}"))
    header = f"{'T1 [s]':>7}  {'T2 [s]':>7}  {'E[F_max]':>12}  {'F_84':>12}  {'P(pounding)':>11}"
    print(header + (f"  {'E[F_max] MC':>12}  {'F_84 MC':>12}" if mc is not None else "") + _BAND_HEADER)
    bands = _bands(spectrum.force_band(), spectrum.accuracy, shown)
    q84 = mc.quantile(0.84)[0] if mc is not None else None
    for index, (t1, t2) in enumerate(zip(spectrum.period1, spectrum.period2)):
        line = (f"{t1:7.4g}  {t2:7.4g}  {shown.force(spectrum.force_mean[index]):>12}  {shown.force(spectrum.force_84[index]):>12}  "
                f"{spectrum.pounding_probability[index]:11.3f}")
        if mc is not None:
            line += f"  {shown.force(mc.force_mean[index]):>12}  {shown.force(q84[index]):>12}"
        print(line + bands[index])
    if args.output:
        print(f"chart          {args.output}")
    return 0
