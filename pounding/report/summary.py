"""The report's summary: the numbers a design note quotes, as a static HTML
table (readable without JavaScript), and the Monte Carlo check of the closed
form (:func:`monte_carlo_check`), in the report's display units."""

from __future__ import annotations

import html
import math
from dataclasses import dataclass

from pounding import defaults
from pounding.display_units import Display, display
from pounding.report.snapshot import MonteCarloPoint, Snapshot

__all__ = ["MonteCarloCheck", "matching_study", "monte_carlo_check", "summary_rows", "summary_html"]


@dataclass(frozen=True)
class MonteCarloCheck:
    """Where a closed-form E[F_max] lies against a Monte Carlo study of the same case.

    Attributes
    ----------
    within : bool or None
        True inside the study's 95 % confidence interval of the mean F_max; None when the
        study has no interval (too few records).
    relative : float
        (closed form - Monte Carlo mean) / Monte Carlo mean [-]; nan when the mean is 0.
    text : str
        One line: "within the Monte Carlo 95 % interval", or "below it: 15 % under the Monte Carlo mean".
    """

    within: bool | None
    relative: float
    text: str


def monte_carlo_check(force_expected: float, study: MonteCarloPoint) -> MonteCarloCheck:
    """Compare the closed form's E[F_max] [N] with the mean F_max [N] of ``study`` and its 95 % interval."""
    mean = study.force_max_mean
    relative = (force_expected - mean) / mean if mean > 0 else math.nan
    share = f"{100 * abs(relative):.0f} % {'under' if relative < 0 else 'over'} the Monte Carlo mean"
    if not (math.isfinite(study.force_low) and math.isfinite(study.force_high)):
        return MonteCarloCheck(None, relative, f"no 95 % interval from {study.records} record(s); {share}")
    if study.force_low <= force_expected <= study.force_high:
        return MonteCarloCheck(True, relative, f"within the Monte Carlo 95 % interval ({share})")
    side = "below" if force_expected < study.force_low else "above"
    return MonteCarloCheck(False, relative, f"{side} the Monte Carlo 95 % interval: {share}")


def matching_study(snapshot: Snapshot) -> MonteCarloPoint | None:
    """The last Monte Carlo study of the snapshot at the case's own gap, or None."""
    points = [m for m in snapshot.monte_carlo if m.gap == snapshot.case.contact.gap]
    return points[-1] if points else None


def summary_rows(snapshot: Snapshot, units: str = "SI") -> list[tuple[str, str, str]]:
    """The summary as (quantity, value with its unit, note) rows."""
    d = display(units)
    e, case = snapshot.estimate, snapshot.case
    distribution = e.force_max_distribution
    duration = case.excitation.duration
    rows = [("expected extreme pounding force E[F_max]", d.force(e.force_expected), "recommended (gap-aware) closed form")]
    for key in defaults.FORCE_QUANTILES:
        probability = float(key)
        rows.append((f"F_max, {100 * probability:g} % fractile", d.force(distribution.quantile(probability)),
                     "closed-form distribution of F_max"))
    rows += [
        ("probability of pounding", f"{100 * e.pounding_probability:.3g} %",
         f"during the {duration:g} s record, at the gap of {d.length(case.contact.gap)}"),
        (f"gap needed for {100 * e.target_probability:g} % probability of no pounding", d.length(e.required_gap),
         f"closed form; SRSS rule {d.length(e.separation_rules['srss'])}, ABS {d.length(e.separation_rules['abs'])}"),
        ("paper's F_e (Eq. 14)", d.force(e.paper.force_expected), "for comparison: independent of the gap"),
    ]
    study = matching_study(snapshot)
    if study is None:
        rows.append(("Monte Carlo check", "not run", "no records were simulated for this report"))
    else:
        check = monte_carlo_check(e.force_expected, study)
        rows += [
            ("Monte Carlo mean F_max", d.force(study.force_max_mean),
             f"{study.records} records, seed {study.seed}; pounding in {100 * study.pounding_fraction:.0f} % of them"),
            ("Monte Carlo 95 % interval of the mean", _interval(d, study), "confidence interval of the mean F_max"),
            ("closed form against Monte Carlo", check.text, ""),
        ]
    gap = snapshot.design_gap
    if gap is not None:
        rows.append((f"Monte Carlo gap for {100 * gap.target_probability:g} % no pounding", d.length(gap.gap),
                     f"{gap.n_records} records' free motion, seed {gap.seed}; 90 % upper bound {d.length(gap.upper_bound)}"))
    return rows


def _interval(d: Display, study: MonteCarloPoint) -> str:
    if not (math.isfinite(study.force_low) and math.isfinite(study.force_high)):
        return "n/a (too few records)"
    return f"{d.force(study.force_low)} to {d.force(study.force_high)}"


def summary_html(snapshot: Snapshot, units: str = "SI") -> str:
    """The summary table, with the estimator's warnings below it."""
    cells = []
    for quantity, value, note in summary_rows(snapshot, units):
        css = "number"
        if quantity == "closed form against Monte Carlo":
            css = "verdict-within" if value.startswith("within") else "verdict-outside"
        cells.append(f'<tr><th>{html.escape(quantity)}</th><td class="{css}">{html.escape(value)}</td>'
                     f"<td>{html.escape(note)}</td></tr>")
    warnings = "".join(f'<p class="warning">&#9888; {html.escape(w)}</p>' for w in snapshot.estimate.warnings)
    return ('<table class="summary"><thead><tr><th>quantity</th><th>value</th><th>note</th></tr></thead><tbody>'
            + "".join(cells) + "</tbody></table>" + warnings)
