"""The ``pounding`` command line.

Kept light: nothing on the path of ``cases``, ``simulate`` (and later
``estimate``) imports a plotting or dashboard library.
"""

from __future__ import annotations

import json
import math
import sys
import warnings
from functools import partial

from pounding import defaults
from pounding.cli.arguments import capacity_newtons, study_size
from pounding.cli.parser import EXIT_BAD_INPUT, parser
from pounding.cli.progress import progress_bar


def _cases(_args) -> int:
    from pounding.presets import preset_description, preset_names, preset_title

    for name in preset_names():
        print(f"{name}: {preset_title(name)}")
        print(f"    {preset_description(name)}")
    return 0


def _shown(args):
    """The display units of ``--units`` (pounding.display_units): kN, mm and m/s by default, kgf, cm and cm/s with
    ``kgf-cm-s``; every number a command prints goes through them, once."""
    from pounding.display_units import display

    return display(args.units)


def _simulate(args) -> int:
    from pounding.case.case import load_case
    from pounding.closed_form.estimator import estimate
    from pounding.errors import ConvergenceError, check_probability
    from pounding.simulation.monte_carlo import MonteCarloPlan, Settings, design_gap, design_gaps, simulate

    if args.design_gap is not None:
        check_probability(args.design_gap, "--design-gap")
    case = load_case(args.case)
    capacity = capacity_newtons(args)
    records, seed = study_size(case, args)
    several = len(case.contacts) > 1
    study = simulate if args.design_gap is None else partial(design_gaps if several else design_gap,
                                                             target_probability=args.design_gap)
    with progress_bar(records) as progress:
        result = study(case, plan=MonteCarloPlan(records, seed, settings=Settings(tolerance=args.tolerance), progress=progress))
    try:  # a few ms beside seconds of simulation: the two methods side by side
        closed_form, failure = estimate(case, target_probability=args.design_gap or defaults.TARGET_PROBABILITY), None
    except (ConvergenceError, ValueError, ArithmeticError) as error:  # InputError, LinAlgError, overflow: the MC stands
        closed_form, failure = None, " ".join(str(error).split()) or type(error).__name__  # one line: why not
    shown = _shown(args)
    force_text = shown.force
    error_text = lambda f, r: f"{100 * (f / r - 1):+.1f} %" if abs(f / r - 1) <= 1e4 else f"{f / r:.3g} times"
    if args.design_gap is not None and several:
        from pounding.cli.rows import print_design_gaps

        return print_design_gaps(case, result, closed_form, failure, args.json, _shown(args))
    if args.design_gap is not None:
        return _print_design_gap(case, result, closed_form, failure, args)
    if args.json:
        if closed_form is None:
            beside = {"error": failure}
        else:
            beside = closed_form.to_dict() if len(case.contacts) > 1 else _closed_form_dict(closed_form, capacity)
        out = {**result.to_dict(), "closed_form": beside}
        if capacity is not None:
            out.update(capacity=capacity, **result.exceedance(capacity))
        print(json.dumps(out))
        return 0
    low, high = result.force_max_confidence_interval
    print(f"case            {case.name}")
    print(f"records         {_records_text(case, result.n_records, seed)}")
    if math.isfinite(result.force_max_std_error):
        print(f"mean F_max      {force_text(result.force_max_mean)}  (standard error {force_text(result.force_max_std_error)})")
        print(f"95% CI          {force_text(low)} .. {force_text(high)}")
    else:
        print(f"mean F_max      {force_text(result.force_max_mean)}  (one record: no standard error; run 2 or more)")
    print("F_max fractiles " + ", ".join(f"{100 * float(key):g} %: {force_text(result.force_max_quantile(float(key))[0])}"
                                         for key in defaults.FORCE_QUANTILES))
    if capacity is not None:
        exceeding = result.exceedance(capacity)
        low_p, high_p = exceeding["probability_exceeding_interval"]
        print(f"P(F_max > {force_text(capacity)})  {100 * exceeding['probability_exceeding']:.1f} % of records "
              f"(95 % interval {100 * low_p:.1f} to {100 * high_p:.1f} %)")
    print(f"pounding        {100 * result.pounding_fraction:.1f} % of records, {result.impacts_mean:.2f} impacts per record")
    print(f"peak impact v   {shown.velocity(float(result.impact_velocity_max.mean()))} (mean over records)")
    if len(case.contacts) > 1:
        from pounding.cli.rows import row_simulation_lines

        print("(the force, pounding and impacts above are over all contacts: the largest force, any contact)")
        for line in row_simulation_lines(result, closed_form, shown):
            print(line)
        if closed_form is None:
            print(f"closed form     n/a: {failure}")
        return 0
    if closed_form is None:
        print(f"closed form     n/a: {failure}")
        return 0
    print("closed form, against this Monte Carlo")
    for label, force in (("recommended", closed_form.force_expected), ("paper", closed_form.paper.force_expected)):
        if force is None:
            print(f"  {label:12s}  n/a (the paper's formula holds for the Hertz-type laws only)")
        elif result.force_max_mean > 0.0:
            # The mean's 95 % interval read as a range of the closed form's error.
            print(f"  {label:12s}  {force_text(force)}   {error_text(force, result.force_max_mean)}"
                  + (f"   ({error_text(force, high)} to {error_text(force, low)} against the ends of the Monte Carlo's 95 % CI)"
                     if low > 0.0 else ""))
        else:
            print(f"  {label:12s}  {force_text(force)}   (no record pounded)")
    print(f"  pounding      {100 * closed_form.pounding_probability:.1f} % probability   (simulated: {100 * result.pounding_fraction:.1f} % of records)")
    print(f"  accuracy      {closed_form.measured_accuracy}")
    for warning in closed_form.warnings:
        print(f"  warning: {warning}")
    return 0


def _records_text(case, count: int, seed: int) -> str:
    if case.recorded:
        return f"{count} recorded motions ({case.hazard.scaling}), each over its own length"
    return f"{count} x {case.excitation.duration:g} s, seed {seed}"


def _closed_form_dict(closed_form, capacity: float | None = None) -> dict:
    """The closed form's numbers printed beside a Monte Carlo study (SI), with its warnings."""
    keys = ("force_expected", "pounding_probability", "impacts_expected", "accuracy_regime", "measured_accuracy")
    distribution = closed_form.force_max_distribution
    out = {**{key: getattr(closed_form, key) for key in keys}, "paper_force_expected": closed_form.paper.force_expected,
           "force_max_quantiles": {key: distribution.quantile(float(key)) for key in defaults.FORCE_QUANTILES},
           "warnings": list(closed_form.warnings)}
    if capacity is not None:
        out["probability_exceeding"] = closed_form.probability_exceeding(capacity)
    return out


_GAP_ACCURACY = ("the closed form's, for comparison: on some of the pairs measured against records it was too small; "
                 "the gap above is the records' own")
"""What the closed-form gap beside a Monte Carlo design gap is worth, said where it is printed (a wheel has no docs/)."""


def _print_design_gap(case, result, closed_form, failure, args) -> int:
    required = None if closed_form is None else closed_form.required_gap
    if args.json:
        failed = {} if failure is None else {"closed_form_error": failure}
        print(json.dumps({"case": case.name, **result.to_dict(), "closed_form_required_gap": required, **failed}))
        return 0
    print(f"case            {case.name}")
    length = _shown(args).length
    print(f"records         {_records_text(case, result.n_records, result.seed)} (free motion: the case's gap is not used)")
    bound = length(result.upper_bound) if math.isfinite(result.upper_bound) else f"n/a: it needs {result.records_for_bound} records"
    print(f"gap for {100 * result.target_probability:g} % no pounding   {length(result.gap)}   (90 % confidence bound {bound})")
    if closed_form is None:
        print(f"closed form     n/a: {failure}")
    else:
        print(f"closed form     {length(required)}   ({_GAP_ACCURACY})")
    return 0


def _estimate(args) -> int:
    from pounding.case.case import load_case
    from pounding.case.engineering import engineering_terms
    from pounding.cli.hazard import engineering_lines
    from pounding.closed_form.estimator import estimate

    if args.seed is not None and args.check is None:
        from pounding.errors import ArgumentError

        raise ArgumentError("seed", "is the seed of the Monte Carlo check: give it with --check")
    case = load_case(args.case)
    capacity = capacity_newtons(args)
    result = estimate(case, target_probability=args.target_probability, paper_variance=args.paper_variance,
                      michaelov_n1=args.michaelov_n1)
    check = None if args.check is None else _check(case, result, args)
    if len(case.contacts) > 1:
        return _estimate_row(case, result, check, capacity, args)
    at_capacity_gap, gap_for_capacity = None, None
    if check is not None and capacity is not None:
        from pounding.studies.check import check_gap_for_capacity

        at_capacity_gap = check_gap_for_capacity(result, capacity, check)  # the gap with its Monte Carlo
        gap_for_capacity = at_capacity_gap["gap"]
    elif capacity is not None:
        gap_for_capacity = result.gap_for_capacity(capacity)
    if args.json:
        out = result.to_dict()
        if capacity is not None:
            out["capacity"] = capacity
            out["probability_exceeding"] = result.probability_exceeding(capacity)
            out["gap_for_capacity"] = gap_for_capacity
        if check is not None:
            out.update(check=check.to_dict(), **check.answers())
        if at_capacity_gap is not None:
            out["gap_for_capacity_check"] = at_capacity_gap
        print(json.dumps(out))
        return 0
    paper = result.paper
    rules = result.separation_rules
    shown = _shown(args)
    force_text, length, velocity = shown.force, shown.length, shown.velocity
    print(f"case                        {case.name} ({'stationary' if case.excitation.stationary else 'non-stationary'}, {case.excitation.duration:.4g} s)")
    print(f"gap                         {length(case.contact.gap)}")
    for code in result.code_checks:
        print(f"  {code.title:<26s}{'met' if code.met else 'not met'}: {length(code.required_gap)} required ({code.short_rule})")
    linearized = result.response
    for line in engineering_lines(engineering_terms(case), shown):
        print(line)
    print(f"RMS relative displacement   {length(result.sigma_relative_displacement)}   "
          f"(linearized {length(linearized.sigma_relative_displacement)}, plus the yielding the linearization leaves out)")
    print(f"RMS relative velocity       {velocity(result.sigma_relative_velocity)}   "
          f"(linearized {velocity(linearized.sigma_relative_velocity)})")
    print("recommended (gap-aware)")
    print(f"  expected extreme force    {force_text(result.force_expected)}")
    print(f"  expected peak impact v    {velocity(result.relative_velocity_expected)}")
    quantiles = result.force_max_distribution
    print(f"  F_max fractiles           50 %: {force_text(quantiles.quantile(0.5))}, 84 %: {force_text(quantiles.quantile(0.84))}, "
          f"95 %: {force_text(quantiles.quantile(0.95))}")
    if capacity is not None:
        print(f"  P(F_max > {force_text(capacity)})  {100 * result.probability_exceeding(capacity):.1f} %")
    print(f"  expected impacts          {result.impacts_expected:.2f}   (approaches from below the gap; rebounds not counted)")
    print("  force braking an impact   " + (f"{force_text(result.opposing_force)}   (the buildings' own, at the gap)"
                                              if result.impacts_expected > 0.0 else "n/a (no impact expected at this gap)"))
    dashpot = f"{shown.from_si(result.impact_dashpot, force=1, length=-1, time=1):.4g} {shown.label(force=1, length=-1, time=1)}"
    print(f"  impacts' damping          {100 * (1 - result.impacting_velocity_ratio):.1f} % off the RMS relative velocity before "
          f"an approach, as a dashpot of {dashpot} between the floors")
    print(f"  pounding probability      {100 * result.pounding_probability:.1f} %")
    print(f"  gap for {100 * result.target_probability:g} % no pounding  {length(result.required_gap)}"
          f"   (SRSS {length(rules['srss'])}, ABS {length(rules['abs'])}, DDC {length(rules['ddc'])})")
    if capacity is not None:
        exceed = f"{100 * (1 - result.target_probability):g} %"
        print(f"  gap for P(F_max > {force_text(capacity)}) <= {exceed}   {length(gap_for_capacity)}   (a force the contact "
              f"can take, instead of no contact at all)")
    accuracy = result.measured_accuracy if check is None else result.accuracy.statement(with_verdict=True)
    print(f"  accuracy                  {accuracy}")
    print("paper (Rahimi & Soltani 2016)")
    if paper.unavailable is not None:
        print(f"  expected extreme force    n/a ({paper.unavailable})")
    elif paper.force_expected is None:
        print("  expected extreme force    n/a (the paper's formula holds for the Hertz-type laws only)")
    else:
        print(f"  expected extreme force    {force_text(paper.force_expected)}")
    if paper.relative_velocity_expected is not None:
        print(f"  expected extreme velocity {velocity(paper.relative_velocity_expected)}   (peak factor {paper.peak_factor:.3f})")
    print(f"  crossing rate             {paper.crossing_rate:.4f} 1/s, effective duration {paper.duration_effective:.2f} s")
    if paper.michaelov_n1 is not None:
        print(f"  equivalent RMS velocity   {velocity(paper.sigma_relative_velocity_equivalent)}   "
              f"(stationary equivalent of order {paper.michaelov_n1:g}, variance in time by {args.paper_variance})")
    for warning in result.warnings:
        print(f"warning: {warning}")
    if check is not None:
        for line in (*check.sentences(force_text, length), check.fractile_sentence(force_text)):
            if line:
                print(line)
    if at_capacity_gap is not None:
        from pounding.studies.check import capacity_check_sentence

        print(capacity_check_sentence(at_capacity_gap, capacity, result.target_probability, force_text, length))
    return 0


def _estimate_row(case, result, check, capacity, args) -> int:
    """``estimate`` on a case of several contacts: the largest force over all contacts, then each contact's."""
    from pounding.cli.rows import row_estimate_lines

    if args.json:
        out = result.to_dict()
        if capacity is not None:
            out.update(capacity=capacity, probability_exceeding=result.probability_exceeding(capacity))
            for contact, estimate in zip(out["contacts"], result.contacts):
                contact["gap_for_capacity"] = estimate.gap_for_capacity(capacity)
        if check is not None:
            out["check"] = check.to_dict()
        print(json.dumps(out))
        return 0
    for line in row_estimate_lines(case, result, _shown(args), capacity, check):
        print(line)
    return 0


def _check(case, result, args):
    """``estimate --check [N]``: the Monte Carlo of the same case (:func:`~pounding.studies.check.check_estimate`), its
    progress drawn; a recorded suite runs each of its records once, whatever N and ``--seed`` say (a note says so)."""
    from pounding.cli.parser import ADAPTIVE
    from pounding.simulation.plan import MonteCarloPlan
    from pounding.studies.check import check_estimate, check_row

    records = None if args.check == ADAPTIVE else args.check
    if case.recorded and (records is not None or args.seed is not None):
        print(f"pounding estimate: note: N and --seed of --check do not apply to recorded motions: each of the "
              f"{len(case.hazard.records)} is integrated once", file=sys.stderr)
        records = None
    seed = defaults.SEED if args.seed is None else args.seed
    check = check_row if len(case.contacts) > 1 else check_estimate
    with progress_bar() as progress:
        return check(result, MonteCarloPlan(records, seed, progress=progress))


def _validate(args) -> int:
    from pounding.cli.validate import validate_command

    return validate_command(args)


def _dashboard(args) -> int:
    from pounding.cli.serve import serve_dashboard

    return 0 if serve_dashboard(port=args.port, show=args.show, extra_origins=args.allow_websocket_origin) == 0 else 1


def _report(args) -> int:
    from dataclasses import replace
    from pathlib import Path

    from pounding.case.case import load_case
    from pounding.errors import ArgumentError, check_probability
    from pounding.output import check_target
    from pounding.simulation.monte_carlo import MonteCarloPlan, design_gap, simulate

    if args.design_gap is not None:
        check_probability(args.design_gap, "--design-gap")
        if not args.records:
            raise ArgumentError("--design-gap", "needs records: give --records N (N >= 1)")
    if args.gap_points and not args.records:
        raise ArgumentError("--gap-points", "needs records: give --records N (N >= 1), the records at each gap")
    case = load_case(args.case)
    check_target(args.output, "--output", probe=True)  # before any work: "", a device, a folder, read-only are refused
    path = Path(args.output)
    if len(case.contacts) > 1:  # several contacts: every contact listed
        from pounding.cli.rows import row_report

        return row_report(args, case, path, progress_bar, _report_provenance(args))
    # The plotting libraries load here only: every other command stays fast.
    from pounding.report import (
        MonteCarloPoint,
        compute_snapshot,
        curve_gaps,
        gap_points,
        with_capacity_check,
        with_check,
        write_report,
    )

    # The estimate first (milliseconds): if it cannot be made, no simulation is wasted.
    snapshot = compute_snapshot(case, target_probability=args.design_gap or defaults.TARGET_PROBABILITY)

    def run(study, total=None):
        with progress_bar(total or args.records) as progress:
            return study(case, plan=MonteCarloPlan(args.records, args.seed, progress=progress))

    monte_carlo = (MonteCarloPoint.from_result(run(simulate)),) if args.records else ()
    if args.gap_points:
        gaps = curve_gaps(case, snapshot.estimate, args.gap_points)
        monte_carlo += run(partial(gap_points, gaps=gaps), args.gap_points * args.records)
    free = run(partial(design_gap, target_probability=args.design_gap)) if args.design_gap is not None else None
    snapshot = replace(snapshot, monte_carlo=monte_carlo, design_gap=free, capacity=capacity_newtons(args))
    with progress_bar() as progress:  # the verdict: on --records' records, else as many as its precision asks
        snapshot = with_check(snapshot, progress)
    if snapshot.capacity is not None:
        with progress_bar() as progress:  # the gap for --capacity, on the check's records
            snapshot = with_capacity_check(snapshot, progress)
    write_report(path, snapshot, units=args.units, field="--output", provenance=_report_provenance(args))
    if args.json:
        figures = snapshot.estimate.to_dict()
        if monte_carlo:
            figures["monte_carlo"] = dict(monte_carlo[0].__dict__)
        if args.gap_points:
            figures["monte_carlo_gap_points"] = [dict(point.__dict__) for point in monte_carlo[1:]]
        if free is not None:
            figures["monte_carlo_design_gap"] = free.to_dict()
        figures.update(check=snapshot.check.to_dict(), **snapshot.check.answers())
        if snapshot.capacity is not None:  # as estimate --capacity --check gives them
            figures.update(capacity=snapshot.capacity, probability_exceeding=snapshot.estimate.probability_exceeding(snapshot.capacity),
                           gap_for_capacity=snapshot.capacity_check["gap"], gap_for_capacity_check=snapshot.capacity_check)
        print(json.dumps({"report": str(path), **figures}))
    else:
        print(f"wrote {path} ({path.stat().st_size / 1e6:.1f} MB)")
    return 0


def _report_provenance(args):
    """Where ``pounding report``'s case came from, and the command (every option written out) that made it.
    A case file whose ``name`` is a preset's is reported as that preset, modified or not."""
    import shlex

    from pounding.case.case import read_case_file
    from pounding.presets import preset_text
    from pounding.report import ReportProvenance, case_provenance

    command = shlex.join(["pounding", "report", args.case, "-o", args.output, "--units", args.units]
                         + (["--records", str(args.records), "--seed", str(args.seed)] if args.records else [])
                         + (["--gap-points", str(args.gap_points)] if args.gap_points else [])
                         + (["--design-gap", f"{args.design_gap:g}"] if args.design_gap is not None else [])
                         + (["--capacity", f"{args.capacity:.12g}"] if args.capacity is not None else []))
    if preset_text(args.case) is not None:
        return ReportProvenance(args.case, args.case, (), command)
    data = read_case_file(args.case)
    name = data.get("name")
    if isinstance(name, str) and preset_text(name) is not None:
        return case_provenance(data, name, source=args.case, command=command, units=args.units)
    return ReportProvenance(args.case, None, (), command)


def _fragility(args) -> int:
    from pounding.cli.curves import run_fragility

    return run_fragility(args)


def _spectrum(args) -> int:
    from pounding.cli.curves import run_spectrum

    return run_spectrum(args)


def _records(args) -> int:
    from pounding.cli.hazard import records_command

    return records_command(args)


def _export(args) -> int:
    from pounding.cli.export import export_command

    return export_command(args)


def _sweep(args) -> int:
    from pounding.cli import sweep

    return sweep.run(args)


_COMMANDS = {
    "cases": _cases,
    "estimate": _estimate,
    "simulate": _simulate,
    "validate": _validate,
    "sweep": _sweep,
    "report": _report,
    "records": _records,
    "fragility": _fragility,
    "spectrum": _spectrum,
    "export": _export,
    "dashboard": _dashboard,
}


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``pounding`` command."""

    args = parser().parse_args(argv)
    with warnings.catch_warnings():
        # numpy's and scipy's floating-point notes are not messages for the user: a case they concern ends in one line.
        warnings.simplefilter("ignore", RuntimeWarning)
        return _run(args)


def _run(args) -> int:
    """One command, its errors turned into one line and an exit code."""
    from pounding.cli.parser import error_line
    from pounding.errors import ConvergenceError, InputError, SimulationError
    from pounding.output import describe_os_error

    try:
        status = _COMMANDS[args.command](args)
        sys.stdout.flush()  # a full disk or a closed pipe on stdout shows here, not at exit
        return status
    except InputError as error:  # a library argument named as the option typed, a case file's key as written
        print(f"pounding {args.command}: error: {error_line(args.command, error)}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except (ConvergenceError, SimulationError) as error:  # a case the methods cannot compute: one line, no traceback
        print(f"pounding {args.command}: failed: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"pounding {args.command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # The reader (e.g. `head`) left early; that is not an error of ours.
        sys.stderr.close()
        return 0
    except OSError as error:  # a read-only folder, a full disk (a file or stdout): one line, no traceback
        print(f"pounding {args.command}: error: {describe_os_error(error)}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
