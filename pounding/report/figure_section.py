"""The report's figures: numbered, each with a caption that states its key
numbers (static HTML, read without JavaScript), the Bokeh plots sized to
A4's printable width and embedded with :func:`bokeh.embed.components`.
Bokeh is imported when the figures are built."""

from __future__ import annotations

import html
import math
from dataclasses import dataclass

import numpy as np

from pounding import defaults
from pounding.display_units import Display, display
from pounding.report.distribution_section import distribution_figure, matching_records
from pounding.report.figures import Figures
from pounding.report.hazard_section import SPECTRUM_RECORDS, hazard_figure, scaled_records_figure
from pounding.report.inputs_section import SPECTRUM_NAMES, code_parameters
from pounding.report.print_css import FIGURE_WIDTH
from pounding.report.snapshot import MonteCarloPoint, Snapshot
from pounding.report.summary import matching_study

__all__ = ["ReportFigure", "figures_html", "report_figures"]

_GAP = 10  # [px] between two plots of one figure


@dataclass(frozen=True)
class ReportFigure:
    """One numbered figure of the report.

    Attributes
    ----------
    title : str
        What it shows, for the list of figures.
    caption : str
        Plain text: what is drawn and its key numbers, with their units.
    plots : tuple
        Bokeh figures, drawn side by side.
    """

    title: str
    caption: str
    plots: tuple


def fixed_width(plots: tuple) -> tuple:
    """Plots of fixed size sharing :data:`FIGURE_WIDTH`: printed as drawn, never wider than the page."""
    width = (FIGURE_WIDTH - _GAP * (len(plots) - 1)) // len(plots)
    for plot in plots:
        plot.sizing_mode = "fixed"
        plot.width = width
    return plots


def report_figures(snapshot: Snapshot, units: str = "SI") -> list[ReportFigure]:
    """The report's figures in order, with captions in ``units``."""
    d = display(units)
    case, e = snapshot.case, snapshot.estimate
    plots = Figures()
    checked = _checked_study(snapshot)
    plots.fill(snapshot, units, snapshot.monte_carlo + ((checked,) if checked is not None else ()), snapshot.design_gap)
    shown = [ReportFigure("Distribution of the extreme pounding force F_max", _distribution_caption(snapshot, d),
                          (distribution_figure(snapshot, units),))]
    hazard = hazard_figure(case, snapshot.seed, units)
    if hazard is not None:
        scaled = scaled_records_figure(case)
        if scaled is not None:
            hazard_ = case.hazard
            source = f" ({hazard_.source})" if hazard_.source else ""
            shown.append(ReportFigure(
                "The records against the design spectrum",
                f"The 5 %-damped spectra of the {len(hazard_.records)} records{source}, scaled {hazard_.scaling}: each "
                "record (grey), their mean (red), the design spectrum (black) and the expected spectrum of the process "
                "the closed form takes (dashed).", (scaled,)))
        shown.append(ReportFigure("The ground motion's spectrum", _hazard_caption(snapshot), (hazard,)))
    shown.append(ReportFigure("Expected extreme force and probability of pounding against the gap", _gap_caption(snapshot, d), (plots.gap,)))
    shown.append(ReportFigure(
        "Power spectral densities of the ground acceleration and of the relative velocity",
        "Two-sided power spectral densities: left, the ground acceleration the closed form takes "
        f"(expected PGA of its records {_pga_g(snapshot):.3g} g); right, the relative velocity of the contact floors of the "
        f"statistically linearized pair (RMS {d.velocity(e.sigma_relative_velocity)}, the storeys' yielding beyond the linearization included).",
        (plots.psd_ground, plots.psd_velocity)))
    history = snapshot.history
    if history is not None:
        peaks = [float(np.max(np.abs(history.drift[:, history.floor(b, 1)]))) for b in (1, 2)]
        forces = [float(np.max(np.abs(history.storey_force[:, history.floor(b, 1)]))) for b in (1, 2)]
        shown.append(ReportFigure(
            "Hysteresis loops of the first storeys in one record",
            f"Restoring force against drift of the first storey of building 1 (left) and 2 (right) in record {snapshot.record} "
            f"of the study seeded {snapshot.seed} (Bouc-Wen, solid; the equivalent linear storey, dashed; during "
            f"impacts, dots). Largest drift {d.length(peaks[0])} and {d.length(peaks[1])}; largest restoring force "
            f"{d.force(forces[0])} and {d.force(forces[1])}.",
            tuple(plots.hysteresis)))
        summary = history.summary
        shown.append(ReportFigure(
            "Pounding force during one record",
            f"Pounding force during record {snapshot.record} of the study seeded {snapshot.seed}: {summary['impacts']} impact(s), "
            f"the largest {d.force(summary['force_max'])} (largest penetration {d.length(summary['penetration_max'])}). "
            f"One record of many: the expected extreme over all records is {d.force(e.force_expected)}.",
            (plots.contact,)))
    for figure in shown:
        fixed_width(figure.plots)
    return shown


def _checked_study(snapshot: Snapshot) -> MonteCarloPoint | None:
    """The summary's Monte Carlo check as a point at the case's gap, where no study there is drawn already."""
    if snapshot.check is None or matching_study(snapshot) is not None:
        return None
    return MonteCarloPoint.from_check(snapshot.check, snapshot.case.contact.gap)


def _pga_g(snapshot: Snapshot) -> float:
    """The expected PGA of the case's records [g]."""
    from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration
    from pounding.units import STANDARD_GRAVITY

    return expected_peak_ground_acceleration(snapshot.case.excitation) / STANDARD_GRAVITY


def _distribution_caption(snapshot: Snapshot, d: Display) -> str:
    distribution = snapshot.estimate.force_max_distribution
    fractiles = ", ".join(f"{100 * float(p):g} % {d.force(distribution.quantile(float(p)))}" for p in defaults.FORCE_QUANTILES)
    text = (f"Probability that the largest pounding force of a {snapshot.case.excitation.duration:g} s record stays below f: "
            f"closed form (line), its step at 0 the probability of no impact, {distribution.no_impact_probability:.3f}. "
            f"Fractiles: {fractiles}.")
    study = matching_records(snapshot)
    if study is not None:
        median = float(np.quantile(np.asarray(study.force_max_values), 0.5))
        text += f" Steps: the empirical distribution of {study.records} Monte Carlo records (median {d.force(median)})."
    return text


def _hazard_caption(snapshot: Snapshot) -> str:
    hazard = snapshot.case.hazard
    if snapshot.case.recorded:
        name = SPECTRUM_NAMES.get(type(hazard.fitted.spectrum).__name__, "")
        return (f"The mean periodogram of the {len(hazard.records)} recorded motions ({hazard.scaling}), the filter bank "
                f"fitted to it, which the closed form takes (at the strong motion's mean level), and the {name} spectrum "
                "that describes it; the Monte Carlo integrates the records themselves.")
    code = ", ".join(f"{name} {value} {unit}".strip() for name, value, unit in code_parameters(hazard))
    return (f"The design spectrum ({code}; 5 % damping), the random-vibration spectrum of the filter bank both methods use "
            f"(dashed) and the mean 5 %-damped spectrum of {SPECTRUM_RECORDS} records drawn from it (seed {snapshot.seed}, dots); "
            f"expected PGA of the records {_pga_g(snapshot):.3g} g.")


def _gap_caption(snapshot: Snapshot, d: Display) -> str:
    e, case = snapshot.estimate, snapshot.case
    paper = e.paper.force_expected
    text = (f"Expected extreme pounding force E[F_max] (recommended, solid) and probability of pounding (right axis) against the gap. "
            f"At this case's gap of {d.length(case.contact.gap)}: E[F_max] = {d.force(e.force_expected)}, probability of pounding "
            f"{100 * e.pounding_probability:.3g} %. Gap needed for {100 * e.target_probability:g} % probability of no pounding: "
            f"{d.length(e.required_gap)} (vertical dash-dot line).")
    if paper is not None:
        text += f" The paper's F_e, independent of the gap (dashed): {d.force(paper)}."
    if snapshot.gap_accuracy:
        text += (f" Shaded: where the Monte Carlo mean lay, by the closed form's errors measured in each gap's regime "
                 f"({_band_words(snapshot, d)}).")
    study = matching_study(snapshot)
    checked = _checked_study(snapshot)
    if study is not None or checked is not None:
        shown = study or checked
        text += (f" Square at this gap: the Monte Carlo mean F_max of {shown.records} records"
                 f"{'' if study is not None else ' (the summary check)'}, {d.force(shown.force_max_mean)} "
                 f"(95 % interval {d.force(shown.force_low)} to {d.force(shown.force_high)}).")
    others = [m for m in snapshot.monte_carlo if m is not study and math.isfinite(m.force_low)]
    if others:
        records = sorted({m.records for m in others})
        text += (f" Squares at {len(others)} other gap(s): the Monte Carlo mean F_max of "
                 f"{' or '.join(str(r) for r in records)} records each with its 95 % interval ("
                 + "; ".join(f"{d.length(m.gap)}: {d.force(m.force_max_mean)}" for m in others) + ").")
    if snapshot.design_gap is not None:
        text += f" Black dash-dot line: the Monte Carlo gap for the same target, {d.length(snapshot.design_gap.gap)}."
    return text


def _band_words(snapshot: Snapshot, d: Display) -> str:
    """Each regime of the curve once: its gaps, its measured range of errors and the band at its first gap."""
    gaps, (low, high) = snapshot.gap_curve.gaps, snapshot.gap_band()
    words, seen = [], set()
    for index, measured in enumerate(snapshot.gap_accuracy):
        if measured.regime in seen:
            continue
        seen.add(measured.regime)
        top = "no upper bound" if not math.isfinite(high[index]) else d.force(high[index])
        words.append(f"{measured.regime} from {d.length(gaps[index])}: closed form {100 * measured.low:+.0f} % to "
                     f"{100 * measured.high:+.0f} % off Monte Carlo, so {d.force(low[index])} to {top} there")
    return "; ".join(words)


def figures_html(figures: list[ReportFigure]) -> tuple[str, str, str]:
    """The figures as HTML (numbered, captioned, with a list of figures), the script that draws them and
    the inline Bokeh library it needs (only the parts these plots use).

    Each figure is a ``<figure id="figure-N">`` whose caption is ``#figure-N-caption``; the list links to
    both, so a printed PDF keeps both as destinations (the tests read their pages from it)."""
    from pounding.report.bokeh_embed import embedded

    script, divs, library = embedded([plot for figure in figures for plot in figure.plots])
    divs = iter(divs)
    listing, blocks = [], []
    for number, figure in enumerate(figures, start=1):
        anchor = f"figure-{number}"
        listing.append(f'<li><a href="#{anchor}">Figure {number}</a>: {html.escape(figure.title)} '
                       f'(<a href="#{anchor}-caption">caption</a>)</li>')
        plots = "".join(next(divs) for _ in figure.plots)
        blocks.append(
            f'<figure class="report-figure" id="{anchor}">'
            f'<div class="plots">{plots}</div>'
            '<noscript><p class="nojs">This plot is drawn by JavaScript; its numbers are in the caption below.</p></noscript>'
            f'<figcaption id="{anchor}-caption"><a class="figure-label" href="#{anchor}-caption">Figure {number}.</a> '
            f"{html.escape(figure.caption)}</figcaption></figure>"
        )
    return '<ol class="figure-list">' + "".join(listing) + "</ol>" + "".join(blocks), script, library
