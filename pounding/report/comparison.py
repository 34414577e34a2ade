"""Two states of a case side by side, "pinned" and "current" (a design alternative, a lecture slide): their key
numbers and the change from one to the other (:func:`differences`, in the units shown and in %), each state's
Monte Carlo beside its closed form where one was run (:func:`monte_carlo_comparison`: the mean F_max, the change,
whether the closed form agrees), the inputs that differ (:func:`input_differences`), the force-against-gap curves
and the distributions of F_max on one chart each, and the page that holds them (:func:`write_comparison`). Every
number is of the two snapshots as computed (their estimates, their checks and studies): nothing is recomputed
here. Bokeh is imported when a chart is built."""

from __future__ import annotations

import html
import math
import os
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from pounding import __version__
from pounding.closed_form.estimator import Estimate
from pounding.display_units import Display, display
from pounding.output import check_target, write_atomic
from pounding.report.bokeh_embed import embedded, without_external
from pounding.report.inputs_section import input_rows
from pounding.report.print_css import FIGURE_WIDTH, REPORT_CSS
from pounding.report.snapshot import MonteCarloPoint, Snapshot
from pounding.report.summary import matching_study
from pounding.studies.check import EstimateCheck

__all__ = ["COMPARISON_NAMES", "NO_MONTE_CARLO", "Difference", "StateMonteCarlo", "comparison_html", "differences", "distribution_points",
           "input_differences", "monte_carlo_comparison", "write_comparison"]

COMPARISON_NAMES = ("pinned", "current")
"""What the two states are called on the page and in the comparison report."""

_PINNED_STYLE = {"color": "#ff7f0e", "line_dash": "dashed", "line_width": 2}
"""How the pinned state is drawn beside the current one (solid blue)."""


@dataclass(frozen=True)
class Difference:
    """One key number of the two states, SI.

    Attributes
    ----------
    quantity : str
        What it is, in words ("expected extreme force").
    kind : str
        "force" [N], "length" [m] or "probability" [-]: how it is shown.
    pinned, current : float
        Its value in each state.
    """

    quantity: str
    kind: str
    pinned: float
    current: float

    @property
    def change(self) -> float:
        """Current minus pinned (SI)."""
        return self.current - self.pinned

    @property
    def relative_change(self) -> float:
        """The change over the pinned value [-]; nan when the pinned value is 0."""
        return self.change / self.pinned if self.pinned != 0 else math.nan

    def value_text(self, value: float, shown: Display) -> str:
        """``value`` (one of the states') with its unit."""
        if self.kind == "force":
            return shown.force(value)
        if self.kind == "length":
            return shown.length(value)
        return f"{100 * value:.3g} %"

    def change_text(self, shown: Display) -> str:
        """The change with its unit and in %: "+12.5 kN (+8.1 %)"; a probability's in percentage points."""
        change = self.change
        if not math.isfinite(change):  # a state without this number
            return "n/a"
        if change == 0:
            return "no change"
        if self.kind == "probability":
            absolute = f"{100 * change:+.3g} percentage points"
        else:
            absolute = self.value_text(change, shown)
            absolute = absolute if absolute.startswith(("-", "n/a")) else f"+{absolute}"
        relative = self.relative_change
        if math.isfinite(relative):
            return f"{absolute} ({100 * relative:+.3g} %)"
        return f"{absolute} (from zero)"


def differences(pinned: Estimate, current: Estimate) -> tuple[Difference, ...]:
    """The key numbers of two estimates: the expected extreme force, its 84th percentile, the probability of
    pounding and the gap needed for each one's target probability of no pounding."""
    target = "the target" if pinned.target_probability != current.target_probability else \
        f"{100 * current.target_probability:.4g} %"
    return (
        Difference("expected extreme force", "force", pinned.force_expected, current.force_expected),
        Difference("84th percentile of the force", "force", pinned.force_max_distribution.quantile(0.84),
                   current.force_max_distribution.quantile(0.84)),
        Difference("probability of pounding", "probability", pinned.pounding_probability, current.pounding_probability),
        Difference(f"gap for {target} no pounding", "length", pinned.required_gap, current.required_gap),
    )


@dataclass(frozen=True)
class StateMonteCarlo:
    """A state's Monte Carlo beside its closed form: its check against simulated records
    (:func:`~pounding.studies.check.check_estimate`) where made, else a study at its gap.

    Attributes
    ----------
    force_max_mean : float
        The records' mean F_max [N].
    records : int
        Their number.
    agrees : bool or None
        Whether the closed form agrees with them (the check's rule); None for a study that is not a check.
    error : float
        The closed form's E[F_max] over the mean, minus 1 [-]; nan where no record pounded.
    """

    force_max_mean: float
    records: int
    agrees: bool | None
    error: float

    @classmethod
    def of(cls, estimate: Estimate, check: EstimateCheck | None = None,
           study: MonteCarloPoint | None = None) -> StateMonteCarlo | None:
        """The Monte Carlo of the state whose closed form is ``estimate``: its ``check`` (of that estimate) when
        given, else ``study`` (at its gap); None with neither."""
        if check is not None:
            return cls(check.force_max_mean, check.records, check.agrees, check.error)
        if study is None:
            return None
        mean = study.force_max_mean
        return cls(mean, study.records, None, estimate.force_expected / mean - 1.0 if mean > 0.0 else math.nan)

    @classmethod
    def of_snapshot(cls, snapshot: Snapshot) -> StateMonteCarlo | None:
        """:meth:`of` the snapshot's estimate, its ``check`` and its last study at its own gap."""
        return cls.of(snapshot.estimate, snapshot.check, matching_study(snapshot))

    def verdict(self) -> str:
        """Whether the closed form agrees, in words: "agrees (3 % under the mean of 144 records)"."""
        plural = "s" if self.records != 1 else ""
        if math.isfinite(self.error):
            where = f"{100 * abs(self.error):.0f} % {'under' if self.error < 0 else 'over'} the mean of {self.records} record{plural}"
        else:
            where = f"no record of {self.records} pounded"
        if self.agrees is None:
            return f"not checked: {where}"
        return f"{'agrees' if self.agrees else 'does not agree'} ({where})"


NO_MONTE_CARLO = "no Monte Carlo run"
"""A state's verdict where it has no Monte Carlo."""


def monte_carlo_comparison(pinned: StateMonteCarlo | None,
                           current: StateMonteCarlo | None) -> tuple[Difference, tuple[str, str]] | None:
    """The two states' Monte Carlo means F_max (a :class:`Difference`: its change current minus pinned, n/a where a
    state has none) and each one's verdict in words (:meth:`StateMonteCarlo.verdict`, :data:`NO_MONTE_CARLO`); None
    where neither state has a Monte Carlo."""
    if pinned is None and current is None:
        return None
    mean = Difference("Monte Carlo mean of the extreme force", "force",
                      math.nan if pinned is None else pinned.force_max_mean,
                      math.nan if current is None else current.force_max_mean)
    return mean, tuple(NO_MONTE_CARLO if state is None else state.verdict() for state in (pinned, current))


def input_differences(pinned: Estimate, current: Estimate, units: str = "SI") -> list[tuple[str, str, str, str]]:
    """The inputs that differ between the two estimates' cases, as the report's inputs table shows them (its
    display units): (parameter, pinned value, current value, unit); "none" where one state has no such input
    (another form of ground motion, fewer storeys). The target probability of no pounding too, when it differs."""
    def keyed(estimate):
        group, rows = "", {}
        for row in input_rows(estimate.case, units):
            if isinstance(row, str):
                group = row
            else:
                rows[(group, row[0])] = row[1:]
        return rows

    before, after = keyed(pinned), keyed(current)
    out = []
    for key in [*after, *(k for k in before if k not in after)]:
        old, new = before.get(key), after.get(key)
        if old == new:
            continue
        unit = (new or old)[1]
        out.append((f"{key[0]}, {key[1]}", old[0] if old else "none", new[0] if new else "none", unit))
    if pinned.target_probability != current.target_probability:
        out.append(("target probability of no pounding", f"{100 * pinned.target_probability:.4g}",
                    f"{100 * current.target_probability:.4g}", "%"))
    return out


# --- the charts ------------------------------------------------------------------------------------------


def _drawn(pinned: Snapshot, current: Snapshot):
    """The states in the order drawn, with their style: the pinned one, dashed, over the current one (where they are
    one curve, the dashes show on it)."""
    return ((COMPARISON_NAMES[1], current, {"color": "#1f77b4", "line_width": 2}), (COMPARISON_NAMES[0], pinned, _PINNED_STYLE))


def _gap_chart(pinned: Snapshot, current: Snapshot, shown: Display):
    """Both states' expected extreme force against the gap, each state's own gap marked."""
    from bokeh.plotting import figure

    plot = figure(title="Expected extreme force against the gap", x_axis_label=f"gap [{shown.length_unit}]",
                  y_axis_label=f"expected extreme force [{shown.force_unit}]", height=340, width=FIGURE_WIDTH,
                  output_backend="canvas", tools="pan,wheel_zoom,box_zoom,reset,save,hover")
    for name, snapshot, style in _drawn(pinned, current):
        curve = snapshot.gap_curve
        plot.line(curve.gaps / shown.length_scale, curve.force_expected / shown.force_scale, legend_label=name, **style)
        plot.scatter([snapshot.case.contact.gap / shown.length_scale], [snapshot.estimate.force_expected / shown.force_scale],
                     color=style["color"], size=9, legend_label=f"{name}: its gap")
    plot.legend.location = "top_right"
    plot.legend.click_policy = "hide"
    return plot


def _distribution_chart(pinned: Snapshot, current: Snapshot, shown: Display):
    """Both states' P(F_max <= f)."""
    from bokeh.plotting import figure

    plot = figure(title="Distribution of the extreme pounding force", x_axis_label=f"F_max [{shown.force_unit}]",
                  y_axis_label="P(F_max <= f) [-]", y_range=(-0.02, 1.02), height=300, width=FIGURE_WIDTH,
                  output_backend="canvas", tools="pan,wheel_zoom,box_zoom,reset,save,hover")
    for name, snapshot, style in _drawn(pinned, current):
        forces, cdf = distribution_points(snapshot.estimate)
        plot.line(forces / shown.force_scale, cdf, legend_label=name, **style)
    top = max(s.estimate.force_max_distribution.quantile(0.999) for s in (pinned, current))
    if top > 0:  # the tabulated CDF runs far past where the probability is
        plot.x_range.end = 1.05 * top / shown.force_scale
    plot.legend.location = "bottom_right"
    return plot


def distribution_points(estimate: Estimate) -> tuple[np.ndarray, np.ndarray]:
    """The distribution of F_max of ``estimate`` as a line: forces [N] and P(F_max <= f), from (0, 0) (its step at 0
    the probability of no impact)."""
    distribution = estimate.force_max_distribution
    return np.concatenate([[0.0], distribution.forces]), np.concatenate([[0.0], distribution.cdf])


# --- the page --------------------------------------------------------------------------------------------

_COMPARISON_CSS = """
.comparison td.change { font-weight: 600; }
.comparison td.pinned { color: #a35200; }
.comparison.numbers td.pinned, .comparison.numbers td.current { white-space: nowrap; }
"""


def _difference_row(d: Difference, shown: Display, css: str = "") -> str:
    named = f' class="{css}"' if css else ""
    return (f'<tr{named}><th>{html.escape(d.quantity)}</th><td class="pinned">{html.escape(d.value_text(d.pinned, shown))}</td>'
            f'<td class="current">{html.escape(d.value_text(d.current, shown))}</td>'
            f'<td class="change">{html.escape(d.change_text(shown))}</td></tr>')


def _numbers_html(pinned: Snapshot, current: Snapshot, shown: Display) -> str:
    rows = "".join(_difference_row(d, shown) for d in differences(pinned.estimate, current.estimate))
    checked = monte_carlo_comparison(StateMonteCarlo.of_snapshot(pinned), StateMonteCarlo.of_snapshot(current))
    if checked is not None:
        mean, (before, after) = checked
        rows += (_difference_row(mean, shown, "monte-carlo")
                 + f'<tr class="monte-carlo-verdict"><th>closed form against Monte Carlo</th><td class="pinned">'
                 f'{html.escape(before)}</td><td class="current">{html.escape(after)}</td><td></td></tr>')
    return ('<table class="comparison numbers"><thead><tr><th></th><th>pinned</th><th>current</th>'
            f"<th>change (current minus pinned)</th></tr></thead><tbody>{rows}</tbody></table>")


def _inputs_html(pinned: Snapshot, current: Snapshot, units: str) -> str:
    rows = input_differences(pinned.estimate, current.estimate, units)
    if not rows:
        return "<p>The two states have the same inputs.</p>"
    body = "".join(f'<tr><td>{html.escape(p)}</td><td class="pinned">{html.escape(a)}</td><td>{html.escape(b)}</td>'
                   f"<td>{html.escape(u)}</td></tr>" for p, a, b, u in rows)
    return ('<table class="comparison inputs"><thead><tr><th>parameter</th><th>pinned</th><th>current</th><th>unit</th>'
            f"</tr></thead><tbody>{body}</tbody></table>")


def comparison_html(pinned: Snapshot, current: Snapshot, units: str = "SI", title: str | None = None,
                    names: tuple[str, str] | None = None) -> str:
    """The comparison as one HTML document, every script and style inline: the two states' key numbers and their
    change, the inputs that differ, both force-against-gap curves on one chart and both distributions on another.
    ``names``: each state's case name, shown under the title."""
    shown = display(units)
    title = title or "Pounding: two states compared"
    named = ""
    if names:
        named = (f'<p class="provenance">Pinned: {html.escape(names[0])}. Current: {html.escape(names[1])}. '
                 "Change: current minus pinned.</p>")
    gap, distribution = _gap_chart(pinned, current, shown), _distribution_chart(pinned, current, shown)
    script, divs, library = embedded([gap, distribution])
    stamp = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    body = (
        f'<header><h1>{html.escape(title)}</h1><p class="made">Written {stamp} by pounding {html.escape(__version__)}.</p>'
        f"{named}</header>"
        '<section class="summary"><h2>1. Key numbers</h2>' + _numbers_html(pinned, current, shown)
        + "<p>Closed-form estimates of each state, as computed; where a state was checked against simulated records "
        "(or simulated at its gap), the Monte Carlo mean and whether the closed form agrees follow. Export each "
        "state's own report for its full check.</p></section>"
        '<section class="inputs"><h2>2. Inputs that differ</h2>' + _inputs_html(pinned, current, units) + "</section>"
        '<section class="figures"><h2>3. Figures</h2>'
        f'<figure>{divs[0]}<figcaption>Figure 1. Expected extreme force against the gap: pinned (dashed), current '
        "(solid); the dots are each state's own gap. A change of the gap alone moves the dot along one curve."
        "</figcaption></figure>"
        f"<figure>{divs[1]}<figcaption>Figure 2. Probability that the largest pounding force of a record stays below "
        "f: pinned (dashed), current (solid).</figcaption></figure></section>"
    )
    page = (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>'
            f'<meta name="generator" content="pounding {html.escape(__version__)}">'
            f"<style>{REPORT_CSS}{_COMPARISON_CSS}</style>{library}</head>"
            f'<body><main class="report">{body}</main>{script}</body></html>\n')
    return without_external(page)


def write_comparison(path: str | os.PathLike, pinned: Snapshot, current: Snapshot, units: str = "SI",
                     title: str | None = None, names: tuple[str, str] | None = None, field: str = "path") -> Path:
    """Write :func:`comparison_html` of the two snapshots to ``path`` atomically (as
    :func:`~pounding.report.write_report` does; ``field`` names ``path`` in its errors). Returns ``path``."""
    check_target(path, field, probe=True)
    return write_atomic(path, comparison_html(pinned, current, units, title, names), field)
