"""The result card: :func:`result_html` shows a :class:`~.snapshot.Snapshot`'s
estimates as HTML, styled by :data:`RESULT_CSS`."""

from __future__ import annotations

import html
import math

from pounding.display_units import Display, display
from pounding.report.snapshot import MonteCarloPoint, Snapshot
from pounding.simulation.monte_carlo import DesignGap
from pounding.studies.check import EstimateCheck

# --- the result card -----------------------------------------------------------


def _row(label: str, recommended: str, paper: str, css: str = "") -> str:
    return f'<tr class="{css}"><th>{label}</th><td>{recommended}</td><td>{paper}</td></tr>'


def result_html(
    snapshot: Snapshot,
    units: str = "SI",
    monte_carlo: MonteCarloPoint | None = None,
    monte_carlo_note: str = "",
    design_gap: DesignGap | None = None,
    design_gap_note: str = "",
    check: EstimateCheck | None = None,
) -> str:
    """The result card: recommended and paper's F_e side by side, each with its chain.

    ``monte_carlo`` is a study of exactly this case (shown beside F_e);
    ``monte_carlo_note`` says why none is shown. ``design_gap`` is the Monte
    Carlo design gap of this case for the closed form's target probability
    (shown beside the closed-form gap); ``design_gap_note`` says why none is
    shown. With neither, the card has no line for it.
    """
    d = display(units)
    e, p, case = snapshot.estimate, snapshot.estimate.paper, snapshot.case
    rate = "1/s"
    stationary = case.excitation.stationary
    linearized = e.response  # the paper's sigmas: the linearized pair's, without the residual's response
    sigma_paper = (
        d.velocity(linearized.sigma_relative_velocity)
        if stationary
        else d.velocity(p.sigma_relative_velocity_equivalent) + " (stationary equivalent)"
    )
    rows = [
        _row(
            "expected extreme pounding force F<sub>e</sub>",
            f'<span class="fe-recommended">{d.force(e.force_expected)}</span>',
            f'<span class="fe-paper">{d.force(p.force_expected)}</span>',
            "headline",
        ),
        _row("RMS relative displacement", d.length(e.sigma_relative_displacement), d.length(linearized.sigma_relative_displacement)),
        _row("RMS relative velocity", d.velocity(e.sigma_relative_velocity), sigma_paper),
        _row("crossing rate", f"{e.upcrossing_rate:.4g} {rate}", f"{p.crossing_rate:.4g} {rate}"),
        _row("effective duration", f"{case.excitation.duration:.4g} s", f"{p.duration_effective:.4g} s"),
        _row("peak factor", "(over the gap: no single factor)", "n/a" if p.peak_factor is None else f"{p.peak_factor:.4g} (Davenport)"),
        _row("expected impact velocity", d.velocity(e.relative_velocity_expected), d.velocity(p.relative_velocity_expected)),
        _row("peak penetration", "n/a", d.length(p.penetration_expected)),
        _row("peak force ratio K(e)", f"{e.peak_force_ratio:.4g} (free masses)", "1 (undamped Hertz)"),
        _row("buildings' force braking an impact", d.force(e.opposing_force), "(not modelled)"),
        _row(
            "impacts' damping of the motion before an approach",
            f"RMS relative velocity {100 * (1 - e.impacting_velocity_ratio):.1f} % lower",
            "(not modelled)",
        ),
        _row("expected number of impacts", f"{e.impacts_expected:.4g} (approaches; rebounds not counted)", "(ignores the gap)"),
    ]
    if monte_carlo is not None:
        mc = (
            f'<span class="mc-mean">{d.force(monte_carlo.force_max_mean)}</span> '
            f"(95 % CI {d.force(monte_carlo.force_low)} to {d.force(monte_carlo.force_high)}; "
            f"{monte_carlo.records} records, seed {monte_carlo.seed}; pounding in {100 * monte_carlo.pounding_fraction:.0f} %)"
        )
    elif check is not None:
        low, high = check.force_max_confidence_interval
        study = f"{check.records} records" + ("" if check.seed is None else f", seed {check.seed}")
        mc = (
            f'<span class="mc-mean">{d.force(check.force_max_mean)}</span> '
            f"(95 % CI {d.force(low)} to {d.force(high)}; {study}; pounding in {100 * check.pounding_fraction:.0f} %); "
            f"the closed form {'agrees' if check.agrees else 'does not agree'}"
        )
    else:
        mc = html.escape(monte_carlo_note or "not run")
    summary = (
        f'<p class="probability">Probability of pounding during the {case.excitation.duration:g} s record: '
        f'<b><span class="pounding-probability">{100 * e.pounding_probability:.3g} %</span></b> '
        f"at the gap of {d.length(case.contact.gap)}. "
        f'Gap for {100 * e.target_probability:g} % probability of no pounding: '
        f'<b><span class="required-gap">{d.length(e.required_gap)}</span></b> '
        f"(SRSS {d.length(e.separation_rules['srss'])}, ABS {d.length(e.separation_rules['abs'])}, "
        f"DDC {d.length(e.separation_rules['ddc'])}).</p>"
        f"{_design_gap_html(snapshot, d, design_gap, design_gap_note)}"
        f'<p class="monte-carlo">Monte Carlo mean F<sub>max</sub>: {mc}</p>'
    )
    measured = e.measured_accuracy if (check or snapshot.check) is None else e.accuracy.statement(with_verdict=True)
    summary += f'<p class="measured-accuracy">Recommended F<sub>e</sub>: {html.escape(measured)}</p>'
    if e.warnings:
        summary += "".join(f'<p class="estimate-warning">&#9888; {html.escape(w)}</p>' for w in e.warnings)
    return (
        '<div class="pounding-result">'
        "<table><thead><tr><th></th><th>recommended (gap-aware)</th><th>paper (Rahimi &amp; Soltani 2016)</th></tr></thead><tbody>"
        + "".join(rows)
        + "</tbody></table>"
        + summary
        + "</div>"
    )


def _design_gap_html(snapshot: Snapshot, d: Display, result: DesignGap | None, note: str) -> str:
    """The Monte Carlo design gap beside the closed form's, for the same target probability."""
    e = snapshot.estimate
    if result is None:
        if not note:
            return ""
        return f'<p class="monte-carlo-gap">Monte Carlo gap for {100 * e.target_probability:g} % no pounding: {html.escape(note)}</p>'
    if result.target_probability != e.target_probability:
        raise ValueError(f"design_gap is for {result.target_probability}, the closed form for {e.target_probability}: not comparable")
    bound = (
        f'90 % upper confidence bound <span class="mc-design-gap-bound">{d.length(result.upper_bound)}</span>'
        if math.isfinite(result.upper_bound)
        else f'<span class="mc-design-gap-bound">too few records for a 90 % upper confidence bound: it needs {result.records_for_bound}</span>'
    )
    # Below 1 the closed form is the narrower gap: more records would pound at it than the target allows.
    ratio = f"{e.required_gap / result.gap:.3g}" if result.gap > 0 else "n/a"
    return (
        f'<p class="monte-carlo-gap">Monte Carlo gap for {100 * result.target_probability:g} % no pounding: '
        f'<b><span class="mc-design-gap">{d.length(result.gap)}</span></b> '
        f"({bound}; free motion of "
        f'<span class="mc-design-gap-records">{result.n_records}</span> records, seed {result.seed}); '
        f'closed form / Monte Carlo = <span class="design-gap-ratio">{ratio}</span> [-].</p>'
    )


RESULT_CSS = """
.pounding-result table { border-collapse: collapse; font-size: 14px; }
.pounding-result th, .pounding-result td { padding: 3px 10px; border-bottom: 1px solid #ddd; text-align: left; }
.pounding-result tr.headline td { font-size: 20px; font-weight: bold; color: #0b4f8a; }
.pounding-result p { font-size: 14px; margin: 6px 0; }
.pounding-result p.estimate-warning { color: #8a4b00; }
.pounding-result p.measured-accuracy { color: #555; font-size: 0.9em; }
"""
