"""What ``estimate`` and ``simulate`` print for a case of several contacts: the largest force over all contacts, then
a table of the contacts, in the case's order."""

from __future__ import annotations

import json
import math

from pounding import defaults
from pounding.case.case import contact_label
from pounding.closed_form.row import safe_side_statement


def _contact_columns(case) -> list[str]:
    return [f"{number:>2d}  {f'{c.between[0]}-{c.between[1]}':<9s}  {f'{c.levels[0]}/{c.levels[1]}':<6s}"
            for number, c in enumerate(case.contacts, start=1)]


_HEAD = " #  buildings  floors"


def row_estimate_lines(case, result, shown, capacity: float | None, check=None) -> list[str]:
    """``estimate``'s text for a :class:`~pounding.closed_form.row.RowEstimate`, in ``shown``'s units; with the
    :class:`~pounding.studies.check.RowCheck` ``check``, each contact's Monte Carlo beside it."""
    force, length = shown.force, shown.length
    distribution = result.force_max_distribution
    governing = case.contacts[result.governing]
    lines = [
        f"case                        {case.name} ({'stationary' if case.excitation.stationary else 'non-stationary'}, "
        f"{case.excitation.duration:.4g} s)",
        f"buildings                   {len(case.buildings)}, left to right; {len(case.contacts)} contacts",
        "largest force over all contacts (each contact's estimate on its two buildings; contacts taken as independent)",
        f"  expected extreme force    {force(result.force_expected)}",
        f"  F_max fractiles           " + ", ".join(f"{100 * float(key):g} %: {force(distribution.quantile(float(key)))}"
                                                    for key in defaults.FORCE_QUANTILES),
        f"  pounding probability      {100 * result.pounding_probability:.1f} % (at any contact)",
        f"  governing contact         {contact_label(governing)}",
    ]
    if capacity is not None:
        lines.append(f"  P(F_max > {force(capacity)})  {100 * result.probability_exceeding(capacity):.1f} % (at any contact)")
    if check is not None:
        verdict = "agrees" if check.agrees else f"does not agree: {force(check.force_max_mean)} stands"
        lines.append(f"  Monte Carlo ({check.records} records)  {force(check.force_max_mean)}; the closed form {verdict}")
    target = f"{100 * result.target_probability:g} %"
    header = f"{_HEAD}  {'gap':>9s}  {'E[F_max]':>10s}  {'84 %':>10s}  {'pounding':>8s}  {'gap for ' + target:>14s}"
    if capacity is not None:
        header += f"  {'gap for cap.':>12s}"
    if check is not None:
        header += f"  {'Monte Carlo':>11s}  verdict"
    lines += ["contacts", header]
    for index, (text, contact, estimate) in enumerate(zip(_contact_columns(case), case.contacts, result.contacts)):
        row = (f"{text}  {length(contact.gap):>9s}  {force(estimate.force_expected):>10s}  "
               f"{force(estimate.force_max_distribution.quantile(0.84)):>10s}  {100 * estimate.pounding_probability:>6.1f} %  "
               f"{length(estimate.required_gap):>14s}")
        if capacity is not None:
            row += f"  {length(estimate.gap_for_capacity(capacity)):>12s}"
        if check is not None:
            mine = check.contacts[index]
            row += f"  {force(mine.force_max_mean):>11s}  {'agrees' if mine.agrees else 'MC stands'}"
        lines.append(row)
    lines.append(f"accuracy, largest force: {result.measured_accuracy}")
    lines.append(f"accuracy, each contact:  {safe_side_statement(result.contact_accuracy)}")
    lines += [f"warning: {warning}" for warning in result.warnings]
    return lines


def row_simulation_lines(result, closed_form, shown) -> list[str]:
    """``simulate``'s table of contacts: each contact's Monte Carlo, and the closed form beside it where it was made."""
    force = shown.force
    lines = ["contacts", f"{_HEAD}  {'mean F_max':>10s}  {'95 % CI':>23s}  {'pounding':>8s}  {'impacts':>7s}  {'closed form':>11s}"]
    for index, (text, peaks) in enumerate(zip(_contact_columns(result.case), result.contacts)):
        summary = peaks.to_dict()
        low, high = summary["force_max_confidence_interval"]
        interval = "n/a" if high is None else f"{force(low)} .. {force(high)}"
        closed = "n/a" if closed_form is None else force(closed_form.contacts[index].force_expected)
        lines.append(f"{text}  {force(summary['force_max_mean']):>10s}  {interval:>23s}  {100 * summary['pounding_fraction']:>6.1f} %  "
                     f"{summary['impacts_mean']:>7.2f}  {closed:>11s}")
    return lines


def print_design_gaps(case, gaps, closed_form, failure: str | None, as_json: bool, shown) -> int:
    """``simulate --design-gap P`` on a case of several contacts: each contact's gap for P of no pounding from the
    records' free motion, the closed form's beside it."""
    closed = [None] * len(gaps) if closed_form is None else [c.required_gap for c in closed_form.contacts]
    if as_json:
        contacts = [{"between": list(c.between), "levels": list(c.levels), **gap.to_dict(), "closed_form_required_gap": mine}
                    for c, gap, mine in zip(case.contacts, gaps, closed)]
        failed = {} if failure is None else {"closed_form_error": failure}
        print(json.dumps({"case": case.name, "target_probability": gaps[0].target_probability, "records": gaps[0].n_records,
                          "seed": None if case.recorded else gaps[0].seed, "contacts": contacts, **failed}))
        return 0
    length = shown.length
    target = f"{100 * gaps[0].target_probability:g} %"
    print(f"case            {case.name}")
    print(f"records         {gaps[0].n_records} (free motion: the case's gaps are not used)")
    print(f"gap for {target} no pounding at each contact")
    print(f"{_HEAD}  {'Monte Carlo':>11s}  {'90 % bound':>12s}  {'closed form':>11s}")
    for text, gap, mine in zip(_contact_columns(case), gaps, closed):
        bound = length(gap.upper_bound) if math.isfinite(gap.upper_bound) else "n/a"
        print(f"{text}  {length(gap.gap):>11s}  {bound:>12s}  {length(mine) if mine is not None else 'n/a':>11s}")
    if failure is not None:
        print(f"closed form     n/a: {failure}")
    return 0


def row_report(args, case, path, progress_bar, provenance) -> int:
    """``pounding report`` of a case of several contacts: the closed form of every contact, its check against one
    Monte Carlo study of the whole case (``--records`` records, else as many as the check's precision asks), and the
    report listing every contact. ``--gap-points`` and ``--design-gap`` take a case of one contact."""
    import dataclasses

    from pounding.cli.arguments import capacity_newtons
    from pounding.errors import ArgumentError
    from pounding.report.contacts import compute_row_snapshot, with_row_check
    from pounding.report.static import write_report
    from pounding.simulation.plan import MonteCarloPlan

    for flag, given in (("--gap-points", args.gap_points), ("--design-gap", args.design_gap)):
        if given:
            raise ArgumentError(flag, f"takes a case of one contact; this case has {len(case.contacts)} contacts "
                                      "(the report lists each contact's gap for the target)")
    seed = defaults.SEED if args.seed is None else args.seed
    snapshot = compute_row_snapshot(case, seed=seed)
    snapshot = dataclasses.replace(snapshot, capacity=capacity_newtons(args))
    with progress_bar() as progress:
        snapshot = with_row_check(snapshot, MonteCarloPlan(args.records or None, seed, progress=progress))
    write_report(path, snapshot, units=args.units, field="--output", provenance=provenance)
    if args.json:
        print(json.dumps({"report": str(path), **snapshot.estimate.to_dict(), "check": snapshot.check.to_dict()}))
    else:
        print(f"wrote {path} ({path.stat().st_size / 1e6:.1f} MB)")
    return 0
