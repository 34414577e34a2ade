"""The report's summary: the numbers a design note quotes, as a static HTML
table (readable without JavaScript), led by the verdict: the estimate checked
against the Monte Carlo of its case (:func:`with_check`, the library's
:class:`~pounding.studies.check.EstimateCheck`) and the force and gap the tool
stands behind, in the report's display units."""

from __future__ import annotations

import dataclasses
import html
import math
from collections.abc import Callable
from dataclasses import dataclass

from pounding import defaults
from pounding.closed_form.estimator import Estimate
from pounding.closed_form.regimes import without_check_advice
from pounding.display_units import Display, display
from pounding.report.snapshot import MonteCarloPoint, Snapshot
from pounding.simulation.plan import MonteCarloPlan
from pounding.studies.check import (
    EstimateCheck,
    capacity_check_sentence,
    check_estimate,
    check_gap_for_capacity,
    closed_form_agrees,
    unpounded_bound,
)

__all__ = ["MonteCarloCheck", "capacity_gap", "code_checks_html", "gap_sentence", "matching_study", "monte_carlo_check",
           "summary_rows", "summary_html", "verdict_html", "with_capacity_check", "with_check"]


def matching_study(snapshot: Snapshot) -> MonteCarloPoint | None:
    """The last Monte Carlo study of the snapshot at the case's own gap, or None."""
    points = [m for m in snapshot.monte_carlo if m.gap == snapshot.case.contact.gap]
    return points[-1] if points else None


def with_check(snapshot: Snapshot, progress: Callable[[int, int], None] | None = None) -> Snapshot:
    """The snapshot with its verdict (``snapshot.check``): as given; else :func:`~pounding.studies.check.check_estimate`
    of its estimate on the records of the matching study (:func:`matching_study`: its count and seed, so the numbers
    are the study's); else on as many records as the check's precision asks, seeded as the snapshot
    (``defaults.SEED`` unless given). ``progress(done, total)`` counts the check's records.

    Raises ValueError where the given check is of another estimate (another force or target probability)."""
    check = snapshot.check
    if check is not None:
        e = snapshot.estimate
        if (check.closed_form_force, check.target_probability) != (e.force_expected, e.target_probability):
            raise ValueError("snapshot.check is the check of another estimate: its closed-form force or target probability "
                             "differs from the snapshot's")
        return snapshot
    study = matching_study(snapshot)
    plan = (MonteCarloPlan(None, snapshot.seed, progress=progress) if study is None
            else MonteCarloPlan(study.records, study.seed, progress=progress))
    return dataclasses.replace(snapshot, check=check_estimate(snapshot.estimate, plan))


def with_capacity_check(snapshot: Snapshot, progress: Callable[[int, int], None] | None = None) -> Snapshot:
    """The snapshot with the Monte Carlo at the gap for its capacity (``snapshot.capacity_check``,
    :func:`~pounding.studies.check.check_gap_for_capacity` on the records of ``snapshot.check``): as given; unchanged
    without a capacity or a check. ``progress(done, total)`` counts its records."""
    if snapshot.capacity is None or snapshot.check is None or snapshot.capacity_check is not None:
        return snapshot
    at_gap = check_gap_for_capacity(snapshot.estimate, snapshot.capacity, snapshot.check, progress)
    return dataclasses.replace(snapshot, capacity_check=at_gap)


def capacity_gap(snapshot: Snapshot) -> float | None:
    """The closed form's gap for the snapshot's capacity [m] (:meth:`~pounding.closed_form.estimator.Estimate.gap_for_capacity`,
    taken from ``capacity_check`` when made: computed once); None without a capacity."""
    if snapshot.capacity is None:
        return None
    if snapshot.capacity_check is not None:
        return snapshot.capacity_check["gap"]
    return snapshot.estimate.gap_for_capacity(snapshot.capacity)


def _study_words(check: EstimateCheck) -> str:
    plural = "s" if check.records > 1 else ""
    return (f"{check.records} recorded motion{plural}" if check.seed is None
            else f"{check.records} record{plural}, seed {check.seed}")


def _sources(check: EstimateCheck) -> tuple[str, str]:
    """Where the force and the gap the tool stands behind come from, in words."""
    force = ("the closed form, which agrees with the Monte Carlo check" if check.agrees
             else "the Monte Carlo mean: the closed form does not agree with it")
    gap = ("the closed form's, which covers the records' own" if check.gap_source == "closed form"
           else "the records' own: the closed form's falls short")
    return force, gap


def verdict_html(snapshot: Snapshot, units: str = "SI") -> str:
    """The verdict, beside the summary's headline: the force and the gap the tool stands behind and where each comes
    from, then the check in two sentences (the Monte Carlo mean, its 95 % interval and records, whether the closed
    form agrees; the records' gap): :meth:`~pounding.studies.check.EstimateCheck.sentences`. Needs ``snapshot.check``
    (:func:`with_check`)."""
    check, d = snapshot.check, display(units)
    if check is None:
        raise ValueError("the snapshot has no check: make it with with_check(snapshot)")
    force_from, gap_from = _sources(check)
    force_sentence, gap_sentence = check.sentences(d.force, d.length)
    css = "verdict-within" if check.agrees else "verdict-outside"
    return (f'<div class="verdict"><p class="answers {css}">The tool stands behind an expected extreme pounding force '
            f'of <b><span class="force-answer">{html.escape(d.force(check.force_answer))}</span></b> '
            f'(<span class="answer-source">{html.escape(force_from)}</span>) and a gap of '
            f'<b><span class="gap-answer">{html.escape(d.length(check.gap_answer))}</span></b> for '
            f"{100 * check.target_probability:g} % probability of no pounding "
            f'(<span class="gap-source">{html.escape(gap_from)}</span>).</p>'
            f'<p class="check-force">{html.escape(force_sentence)}</p><p class="check-gap">{html.escape(gap_sentence)}</p>'
            + (f'<p class="check-fractiles">{html.escape(fractiles)}</p>' if (fractiles := check.fractile_sentence(d.force)) else "")
            + "</div>")


def summary_rows(snapshot: Snapshot, units: str = "SI") -> list[tuple[str, str, str]]:
    """The summary as (quantity, value with its unit, note) rows; the Monte Carlo's from ``snapshot.check`` when
    made (:func:`with_check`)."""
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
        ("paper's F_e (Rahimi & Soltani 2016)", d.force(e.paper.force_expected), "for comparison: independent of the gap"),
    ]
    check = snapshot.check
    if check is None:
        rows.append(("Monte Carlo check", "not run", "no records were simulated"))
    else:
        rows += _check_rows(check, d)
    if snapshot.capacity is not None:
        rows += _capacity_rows(snapshot, d)
    gap = snapshot.design_gap
    if gap is not None:
        rows.append((f"Monte Carlo gap for {100 * gap.target_probability:g} % no pounding (free motion)", d.length(gap.gap),
                     f"{gap.n_records} records' free motion, seed {gap.seed}; 90 % upper bound {d.length(gap.upper_bound)}"))
    return rows


def _capacity_rows(snapshot: Snapshot, d: Display) -> list[tuple[str, str, str]]:
    """P(F_max > capacity) at the gap entered, the gap sized to the capacity, and its Monte Carlo when made."""
    e, capacity, at_gap = snapshot.estimate, snapshot.capacity, snapshot.capacity_check
    force, target = d.force(capacity), f"{100 * (1 - e.target_probability):g} %"
    rows = [(f"probability that F_max exceeds {force}", f"{100 * e.probability_exceeding(capacity):.3g} %",
             f"closed form, at the gap of {d.length(snapshot.case.contact.gap)}"),
            (f"gap for P(F_max > {force}) at most {target}", d.length(capacity_gap(snapshot)),
             "closed form: a force the contact can take, instead of no contact at all")]
    if at_gap is not None:
        low, high = at_gap["probability_exceeding_interval"]
        rows.append((f"Monte Carlo at that gap: records over {force}", f"{100 * at_gap['probability_exceeding']:.3g} %",
                     f"{at_gap['records']} records; 95 % interval {100 * low:.3g} to {100 * high:.3g} %; the target "
                     f"of {target} {'holds' if at_gap['holds'] else 'does not hold'}"))
    return rows


def _check_rows(check: EstimateCheck, d: Display) -> list[tuple[str, str, str]]:
    target = f"{100 * check.target_probability:g} %"
    low, high = check.force_max_confidence_interval
    interval = f"{d.force(low)} to {d.force(high)}" if math.isfinite(high - low) else "n/a (one record)"
    if check.force_max_mean > 0.0:
        side = "under" if check.error < 0 else "over"
        how = (f"{100 * abs(check.error):.0f} % {side} the Monte Carlo mean; it agrees inside the 95 % interval or "
               f"within {100 * defaults.CHECK_TOLERANCE:g} %")
    else:
        how = (f"no record pounded, so pounding under {100 * unpounded_bound(check.records):.1f} % (95 % confidence); the "
               f"closed form's probability is {100 * check.closed_form_pounding_probability:.1f} %")
    force_from, gap_from = _sources(check)
    return [
        ("Monte Carlo mean F_max", d.force(check.force_max_mean),
         f"{_study_words(check)}; pounding in {100 * check.pounding_fraction:.0f} % of them"),
        ("Monte Carlo 95 % interval of the mean", interval, "confidence interval of the mean F_max"),
        ("closed form against Monte Carlo", "agrees" if check.agrees else "does not agree", how),
        (f"Monte Carlo gap for {target} no pounding", d.length(check.required_gap), "the same records"),
        ("force the tool stands behind", d.force(check.force_answer), force_from),
        (f"gap the tool stands behind for {target} no pounding", d.length(check.gap_answer), gap_from),
    ]


def gap_sentence(snapshot: Snapshot, units: str = "SI") -> str:
    """Whether the gap entered is adequate, in one plain sentence: against the gap the tool stands behind for the
    target probability of no pounding (the check's answer when made, else the closed form's)."""
    d, e = display(units), snapshot.estimate
    needed = snapshot.check.gap_answer if snapshot.check is not None else e.required_gap
    entered = snapshot.case.contact.gap
    verdict = "is adequate" if entered >= needed else "is not adequate"
    sentence = (f"The gap entered, {d.length(entered)}, {verdict} for {100 * e.target_probability:g} % probability of no "
                f"pounding: that takes {d.length(needed)}.")
    if snapshot.capacity is None:
        return sentence
    force, sized = d.force(snapshot.capacity), capacity_gap(snapshot)
    enough = "enough" if entered >= sized else "not enough"
    return (f"{sentence} For a capacity of {force}, the probability that the largest force exceeds it is "
            f"{100 * e.probability_exceeding(snapshot.capacity):.3g} % at the gap entered; a gap of {d.length(sized)} "
            f"keeps it at or below {100 * (1 - e.target_probability):g} %, so the gap entered is {enough} for that force.")


def code_checks_html(snapshot: Snapshot, units: str = "SI") -> str:
    """Each design code's separation rule against the gap entered, in the code's words, and what stands in for the
    code's displacements (:attr:`~pounding.closed_form.estimator.Estimate.code_checks`)."""
    d, gap = display(units), snapshot.case.contact.gap
    lines = "".join(
        f'<li class="code-check {"met" if c.met else "not-met"}"><b>{html.escape(c.title)}</b>: required '
        f'{html.escape(d.length(c.required_gap))} ({html.escape(c.short_rule)}); entered {html.escape(d.length(gap))}: '
        f'<b>{"met" if c.met else "not met"}</b>.</li>' for c in snapshot.estimate.code_checks)
    note = ("The codes' displacements are design values; here the closed form's expected peak displacements of each "
            "contact floor take their place (EN 1998-1 4.4.2.7(4)'s factor 0.7 not applied).")
    return f'<ul class="code-checks">{lines}</ul><p class="code-note"><i>{html.escape(note)}</i></p>'


def summary_html(snapshot: Snapshot, units: str = "SI") -> str:
    """The codes' clauses for the gap entered (:func:`code_checks_html`), whether the gap is adequate
    (:func:`gap_sentence`), the verdict (:func:`verdict_html`, when the snapshot has its check), the summary table,
    and the estimator's warnings below it."""
    cells = []
    for quantity, value, note in summary_rows(snapshot, units):
        css = "number"
        if quantity == "closed form against Monte Carlo":
            css = "verdict-within" if value == "agrees" else "verdict-outside"
        cells.append(f'<tr><th>{html.escape(quantity)}</th><td class="{css}">{html.escape(value)}</td>'
                     f"<td>{html.escape(note)}</td></tr>")
    checked = snapshot.check is not None  # the check the warnings advise stands above them: the advice is dropped
    warnings = "".join(f'<p class="warning">&#9888; {html.escape(without_check_advice(w) if checked else w)}</p>'
                       for w in snapshot.estimate.warnings)
    verdict = verdict_html(snapshot, units) if checked else ""
    adequate = f'<p class="gap-adequate"><b>{html.escape(gap_sentence(snapshot, units))}</b></p>'
    if snapshot.capacity_check is not None:
        d = display(units)
        at_gap = capacity_check_sentence(snapshot.capacity_check, snapshot.capacity, snapshot.estimate.target_probability,
                                         d.force, d.length)
        adequate += f'<p class="capacity-check">{html.escape(at_gap)}</p>'
    return (code_checks_html(snapshot, units) + adequate + verdict + '<table class="summary"><thead><tr><th>quantity</th><th>value</th><th>note</th></tr></thead><tbody>'
            + "".join(cells) + "</tbody></table>" + warnings)


# --- the verdict on one study of the page -----------------------------------------------------------


@dataclass(frozen=True)
class MonteCarloCheck:
    """Whether a closed-form E[F_max] agrees with one Monte Carlo study of the same case, by the rule of every
    verdict (:func:`~pounding.studies.check.closed_form_agrees`): the dashboard's line on a study it ran.

    Attributes
    ----------
    agrees : bool
        The rule's answer: inside the study's 95 % interval of the mean F_max or within
        ``defaults.CHECK_TOLERANCE`` of that mean (where no record pounded: a probability of pounding the records allow).
    relative : float
        (closed form - Monte Carlo mean) / Monte Carlo mean [-]; nan when the mean is 0.
    text : str
        One clause: "the estimate agrees: inside the 95 % interval, 3 % under the mean".
    """

    agrees: bool
    relative: float
    text: str


def monte_carlo_check(estimate: Estimate, study: MonteCarloPoint) -> MonteCarloCheck:
    """The closed form's ``estimate`` against ``study``, a Monte Carlo of the same case (its mean F_max [N] and
    95 % interval [N]): :func:`~pounding.studies.check.closed_form_agrees` and why, in words."""
    mean = study.force_max_mean
    agrees = closed_form_agrees(estimate, mean, (study.force_low, study.force_high), study.records)
    verdict = "the estimate agrees" if agrees else "the estimate does not agree"
    if not mean > 0:
        allowed = 100 * unpounded_bound(study.records)
        return MonteCarloCheck(agrees, math.nan, f"{verdict}: no record pounded, so pounding under {allowed:.1f} % (95 % "
                               f"confidence), and its probability of pounding is {100 * estimate.pounding_probability:.1f} %")
    force = estimate.force_expected
    relative = force / mean - 1.0
    share = f"{100 * abs(relative):.0f} % {'under' if relative < 0 else 'over'} the mean"
    tolerance = f"{100 * defaults.CHECK_TOLERANCE:g} %"
    low, high = study.force_low, study.force_high
    if not math.isfinite(high - low):
        where = f"within {tolerance}" if agrees else f"more than {tolerance}"
        return MonteCarloCheck(agrees, relative, f"{verdict}: {share}, {where} (one record: no 95 % interval)")
    if low <= force <= high:
        return MonteCarloCheck(agrees, relative, f"{verdict}: inside the 95 % interval, {share}")
    side = "below" if force < low else "above"
    if agrees:
        return MonteCarloCheck(agrees, relative, f"{verdict}: {share}, within {tolerance} ({side} the 95 % interval)")
    return MonteCarloCheck(agrees, relative, f"{verdict}: {side} the 95 % interval and {share}, more than {tolerance}")
