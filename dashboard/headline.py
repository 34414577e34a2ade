"""The dashboard's headline: the answer first (the expected extreme force, its
84th percentile, the probability of pounding, the gap needed), the verdict of
its check against simulated records under it (and, where the closed form does
not agree, the records' force and gap in its place), the Monte Carlo verdict
once a study has run, the warnings in one or two sentences with their advice in
the page's terms (dropped once followed), and the diagnostics folded away.
Every number comes from the library's estimate and its check
(``pounding.studies.check.EstimateCheck``); this only formats them."""

from __future__ import annotations

import html
import math
from collections.abc import Callable

from pounding.closed_form.regimes import CHECK_ADVICE
from pounding.display_units import display
from pounding.errors import ConvergenceError
from pounding.report import monte_carlo_check
from pounding.studies.check import unpounded_bound

__all__ = ["CHECKING", "HEADLINE_CSS", "headline_html", "held_note"]

CHECKING = "Checking against simulated records\u2026"
"""The verdict line while the check of the estimate shown runs."""

HEADLINE_CSS = """
.headline { font-size: 14px; line-height: 1.35; }
.headline .numbers { display: grid; grid-template-columns: repeat(2, minmax(150px, 1fr)); gap: 6px 14px; margin: 4px 0 8px; }
.headline .number { border-left: 4px solid #0b4f8a; padding: 2px 8px; }
.headline .number .value { font-size: 22px; font-weight: 700; color: #0b4f8a; display: block; }
.headline .number .what { font-size: 12px; color: #444; }
.headline p { margin: 4px 0; }
.headline .verdict { font-weight: 600; }
.headline .check-verdict { font-weight: 600; margin: 0 0 6px; min-height: 4.05em; }  /* three lines: the verdict replaces "Checking..." without moving the page */
.headline .check-verdict.checking { font-weight: 400; color: #555; }
.headline .check-verdict.failed { font-weight: 400; color: #8a4b00; }
.headline .number .closed-form { font-size: 12px; color: #444; }
.headline .warning { color: #8a4b00; }
.headline .accuracy { color: #555; font-size: 12px; }
.headline details { font-size: 12px; color: #333; margin-top: 6px; }
.headline details table { border-collapse: collapse; }
.headline details td, .headline details th { padding: 1px 8px; text-align: left; border-bottom: 1px solid #eee; }
.headline.stale { opacity: 0.5; }
.headline .held { color: #c62828; font-weight: 600; }
"""

_ADVICE = (
    (CHECK_ADVICE, "Check it with the Monte Carlo tab.", "monte_carlo"),
    ("Use `pounding simulate --design-gap", "Use the Monte Carlo design gap (Monte Carlo tab).", "design_gap"),
)


def _in_page_terms(warning: str, done: set[str]) -> str | None:
    """The warning with its advice as this page offers it; None when the advice has been followed and nothing else is said."""
    for command, instead, study in _ADVICE:
        if command in warning:
            head = warning[: warning.index(command)].rstrip()
            if study in done:
                return head or None
            return f"{head} {instead}".strip()
    return warning


def held_note(refusals: list[str], waiting: str = "") -> str:
    """The line that says the numbers are of the last inputs taken: which inputs were refused (their reasons begin
    with the input's name, ``"Gap: ..."``), or what the page waits for; '' when the numbers are of the inputs shown."""
    lines = []
    if refusals:
        names = ", ".join(reason.split(":", 1)[0] for reason in refusals)
        lines.append(f"Not taken: {names} (see the input in red). The numbers below are still those of the last valid inputs.")
    if waiting:
        lines.append(waiting)
    return "".join(f'<p class="held">{html.escape(text)}</p>' for text in lines)


def _number(value: str, what: str, css: str) -> str:
    return f'<div class="number"><span class="value {css}">{value}</span><span class="what">{what}</span></div>'


def _records_of(check) -> str:
    """The records of a check in words: "144 simulated records", "14 recorded motions"."""
    plural = "s" if check.records != 1 else ""
    return f"{check.records} recorded motion{plural}" if check.seed is None else f"{check.records} simulated record{plural}"


def check_sentence(check, units: str = "SI") -> str:
    """The verdict of an :class:`~pounding.studies.check.EstimateCheck` in one sentence, every number with its unit:
    what the records gave, whether the closed form agrees, and which force, 84th percentile and gap the headline shows
    (the records' where the check stands behind theirs)."""
    shown = display(units)
    force, length = shown.force, shown.length
    low, high = check.force_max_confidence_interval
    if check.force_max_mean == 0.0:
        found = f"none pounded (pounding below {100 * unpounded_bound(check.records):.1f} %, 95 % confidence)"
        verdict = ("the closed form agrees" if check.agrees else f"the closed form's probability of pounding, "
                   f"{100 * check.closed_form_pounding_probability:.1f} %, is more than they allow: the force above is theirs")
    else:
        interval = f"95 % interval {force(low)} to {force(high)}" if math.isfinite(high - low) else "one record, no interval"
        found = f"{force(check.force_max_mean)} ({interval})"
        side = "under" if check.error < 0 else "over"
        verdict = ("the closed form agrees" if check.agrees else f"the closed form's {force(check.closed_form_force)} is "
                   f"{100 * abs(check.error):.0f} % {side} it: the force above is the records' mean")
    if check.quantiles_source != "closed form":
        verdict += ("; the 84th percentile above is theirs too" if not check.agrees else
                    "; they spread wider than the closed form: the 84th percentile above is theirs")
    gap = ""
    if check.gap_source != "closed form":
        gap = (f"; for {100 * check.target_probability:.4g} % no pounding they need a gap of {length(check.required_gap)}, "
               f"more than the closed form's {length(check.closed_form_gap)}: the gap above is theirs")
    return f"Checked on {_records_of(check)}: {found}; {verdict}{gap}."


def _check_line(check, units: str, checking: bool, check_error: str) -> str:
    """The line under the numbers: the check's verdict, or that it runs, or why it failed; '' without a check."""
    if check is not None:
        return f'<p class="check-verdict">{html.escape(check_sentence(check, units))}</p>'
    if check_error:
        return f'<p class="check-verdict failed">Could not check against simulated records: {html.escape(check_error)}</p>'
    return f'<p class="check-verdict checking">{CHECKING}</p>' if checking else ""


def headline_html(result, units: str = "SI", capacity: float | None = None, monte_carlo=None, design_gap=None,
                  name: str = "", check=None, checking: bool = False, check_error: str = "", held: str = "",
                  pinned: str = "", gap_for_capacity: Callable[[float], float] | None = None) -> str:
    """The headline of an :class:`~pounding.closed_form.estimator.Estimate` ``result``; ``capacity`` [N] adds P(F_max > capacity)
    and the gap for it, from ``gap_for_capacity(capacity)`` [m] (default ``result.gap_for_capacity``; the page passes
    its model's, computed once per estimate and capacity);
    ``monte_carlo`` a :class:`~pounding.report.MonteCarloPoint` of exactly this case, ``design_gap`` its Monte Carlo
    design gap, each when run. ``check``, the :class:`~pounding.studies.check.EstimateCheck` of exactly ``result``,
    puts its verdict under the numbers; where the closed form does not agree, the force is the records' (the closed
    form's beside it), and so are the 84th percentile where the check stands behind the records' fractiles and the
    gap where the records need a wider one; the measured accuracy is then stated in full.
    Without it, ``checking`` says that the check runs, ``check_error`` why it failed. ``held`` (:func:`held_note`)
    comes first: the numbers are of the last inputs taken. ``pinned`` (:func:`dashboard.pinning.pinned_html`), the
    comparison with a pinned state, follows the name."""
    shown = display(units)
    case = result.case
    distribution = result.force_max_distribution
    closed_force, closed_f84 = shown.force(result.force_expected), shown.force(distribution.quantile(0.84))
    closed_gap = shown.length(result.required_gap)
    force = _number(closed_force, "expected extreme force E[F<sub>max</sub>]", "fe-recommended")
    f84 = _number(closed_f84, "84th percentile of F<sub>max</sub>", "f84")
    gap = _number(closed_gap, f"gap for {100 * result.target_probability:.4g} % no pounding", "required-gap")
    if check is not None and check.answer_source != "closed form":
        force = _number(shown.force(check.force_answer), f"expected extreme force E[F<sub>max</sub>]: mean of {_records_of(check)}"
                        f'<span class="closed-form"> (closed form <span class="fe-recommended">{closed_force}</span>)</span>',
                        "force-answer")
    if check is not None and check.quantiles_source != "closed form":
        f84 = _number(shown.force(check.quantiles_answer["0.84"]), f"84th percentile of F<sub>max</sub>, {_records_of(check)}"
                      f'<span class="closed-form"> (closed form <span class="f84">{closed_f84}</span>)</span>', "check-f84")
    if check is not None and check.gap_source != "closed form":
        gap = _number(shown.length(check.gap_answer), f"gap for {100 * result.target_probability:.4g} % no pounding, "
                      f'from {_records_of(check)}<span class="closed-form"> (closed form <span class="required-gap">'
                      f"{closed_gap}</span>)</span>", "gap-answer")
    numbers = [
        force,
        f84,
        _number(f"{100 * result.pounding_probability:.3g} %", f"probability of pounding in {case.excitation.duration:.3g} s "
                f"at a gap of {shown.length(case.contact.gap)}", "pounding-probability"),
        gap,
    ]
    if capacity is not None:
        numbers.append(_number(f"{100 * result.probability_exceeding(capacity):.3g} %", f"P(F<sub>max</sub> &gt; {shown.force(capacity)})",
                               "p-exceed"))
        try:
            gap_capacity = shown.length((gap_for_capacity or result.gap_for_capacity)(capacity))
        except ConvergenceError:  # the probability stays above the target up to twice the gap for no pounding
            gap_capacity = f"over {shown.length(2 * result.required_gap)}"
        numbers.append(_number(gap_capacity, f"gap for P(F<sub>max</sub> &gt; "
                               f"{shown.force(capacity)}) &le; {100 * (1 - result.target_probability):.4g} %", "gap-capacity"))
    lines = [_check_line(check, units, checking, check_error)]
    done = {"monte_carlo", "design_gap"} if check is not None else set()  # the check is the study the advice asks for
    if monte_carlo is not None:
        done.add("monte_carlo")
        text = monte_carlo_check(result, monte_carlo).text  # the rule of the check above (studies.check.closed_form_agrees)
        lines.append(f'<p class="verdict">Monte Carlo ({monte_carlo.records} records): <span class="mc-mean">'
                     f'{shown.force(monte_carlo.force_max_mean)}</span>, 95 % interval {shown.force(monte_carlo.force_low)} to '
                     f'{shown.force(monte_carlo.force_high)}; <span class="mc-verdict">{html.escape(text)}</span>.</p>')
    if design_gap is not None:
        done.add("design_gap")
        lines.append(f'<p class="verdict">Monte Carlo gap for {100 * design_gap.target_probability:.4g} % no pounding: '
                     f'<span class="mc-design-gap">{shown.length(design_gap.gap)}</span> ({design_gap.n_records} records).</p>')
    warnings = [w for w in (_in_page_terms(w, done) for w in result.warnings) if w]
    lines += [f'<p class="warning">&#9888; {html.escape(w)}</p>' for w in warnings]
    # beside a verdict the measured range is stated in full, however wide (pounding.closed_form.regimes.SIGNABLE_ERROR)
    accuracy = result.measured_accuracy if check is None else result.accuracy.statement(with_verdict=True)
    lines.append(f'<p class="accuracy">{html.escape(accuracy)}</p>')
    title = f'<b class="case-name">{html.escape(name)}</b>' if name else ""
    return (f'<div class="headline">{held}{code_clauses_line(result, shown)}{title}'
            f'{pinned}<div class="numbers">{"".join(numbers)}</div>' + "".join(lines) + _details(result, shown) + "</div>")


def code_clauses_line(result, shown) -> str:
    """The codes' separation rules against the gap entered, in one line: the headline's first."""
    gap = shown.length(result.case.contact.gap)
    parts = [f'{html.escape(c.title)}: {html.escape(shown.length(c.required_gap))} required, <b>{"met" if c.met else "not met"}</b>'
             for c in result.code_checks]
    return f'<p class="code-clauses">Codes, for the {html.escape(gap)} entered: {"; ".join(parts)}.</p>'


def _details(result, shown) -> str:
    """The diagnostics, folded: the response, the count, the paper's estimate, the separation rules."""
    paper = result.paper
    rules = result.separation_rules
    rows = [
        ("RMS relative displacement of the contact floors", shown.length(result.sigma_relative_displacement)),
        ("RMS relative velocity of the contact floors", shown.velocity(result.sigma_relative_velocity)),
        ("expected number of impacts", f"{result.impacts_expected:.3g}"),
        ("expected largest approach speed", shown.velocity(result.relative_velocity_expected)),
        ("95th percentile of F<sub>max</sub>", shown.force(result.force_max_distribution.quantile(0.95))),
        ("the paper's estimate (Rahimi & Soltani 2016)", shown.force(paper.force_expected)),
        ("gap by SRSS / ABS / DDC", f"{shown.length(rules['srss'])} / {shown.length(rules['abs'])} / {shown.length(rules['ddc'])}"),
        ("regime of the estimate", html.escape(result.accuracy_regime)),
    ]
    body = "".join(f"<tr><th>{label}</th><td>{value}</td></tr>" for label, value in rows)
    return f"<details><summary>Details</summary><table>{body}</table></details>"
