"""The report's distribution of the extreme force: the closed-form CDF of F_max
(G31) beside the records' empirical one when a Monte Carlo study was run, and
the fractiles as a table. Bokeh is imported when the figure is built."""

from __future__ import annotations

import html

import numpy as np

from pounding import defaults
from pounding.display_units import display
from pounding.report.curve_charts import legend_below
from pounding.report.snapshot import MonteCarloPoint, Snapshot
from pounding.report.summary import matching_study
from pounding.simulation.result import quantile_interval

__all__ = ["distribution_figure", "matching_records", "quantiles_table"]


def matching_records(snapshot: Snapshot) -> MonteCarloPoint | None:
    """The Monte Carlo study of the summary (:func:`~.summary.matching_study`), if it kept its records' F_max."""
    study = matching_study(snapshot)
    return study if study is not None and study.force_max_values else None


def distribution_figure(snapshot: Snapshot, units: str = "SI"):
    """P(F_max <= f): the closed form as a line (its step at 0 the probability of no impact), the records' as steps."""
    from bokeh.plotting import figure

    shown = display(units)
    distribution = snapshot.estimate.force_max_distribution
    plot = figure(title="Distribution of the extreme pounding force F_max", x_axis_label=f"F_max [{shown.force_unit}]",
                  y_axis_label="P(F_max <= f) [-]", y_range=(-0.02, 1.02), height=320, output_backend="canvas",
                  sizing_mode="stretch_width", tools="pan,wheel_zoom,box_zoom,reset,save,hover")
    forces = np.concatenate([[0.0], distribution.forces])
    cdf = np.concatenate([[0.0], distribution.cdf])  # the atom at 0: no impact during the record
    plot.line(forces / shown.force_scale, cdf, line_width=2, color="#1f77b4", legend_label="closed form")
    study = matching_records(snapshot)
    if study is not None:
        ordered = np.sort(np.asarray(study.force_max_values))
        steps = np.arange(1, ordered.size + 1) / ordered.size
        plot.step(np.concatenate([[0.0], ordered]) / shown.force_scale, np.concatenate([[0.0], steps]), mode="after",
                  color="#ff7f0e", legend_label=f"Monte Carlo, {study.records} records")
    legend_below(plot, columns=2)
    return plot


def quantiles_table(snapshot: Snapshot, units: str = "SI") -> str:
    """The 50th, 84th and 95th percentiles of F_max, closed form and (when run) Monte Carlo with 95 % intervals."""
    shown = display(units)
    distribution = snapshot.estimate.force_max_distribution
    study = matching_records(snapshot)
    header = "<tr><th>fractile</th><th>closed form</th>" + ("<th>Monte Carlo</th><th>95 % interval</th>" if study else "") + "</tr>"
    rows = [header]
    for key in defaults.FORCE_QUANTILES:
        probability = float(key)
        cells = f"<td>{100 * probability:g} %</td><td>{shown.force(distribution.quantile(probability))}</td>"
        if study is not None:
            value, low, high = quantile_interval(study.force_max_values, probability)
            interval = "n/a (too few records)" if low is None or high is None else f"{shown.force(low)} to {shown.force(high)}"
            cells += f"<td>{shown.force(value)}</td><td>{html.escape(interval)}</td>"
        rows.append(f"<tr>{cells}</tr>")
    no_impact = f"<p>Probability of no impact during the record (closed form): {distribution.no_impact_probability:.3f}.</p>"
    return '<table class="case-table">' + "".join(rows) + "</table>" + no_impact
