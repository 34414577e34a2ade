"""The design chart: a static Bokeh page of the sweep's table (Bokeh is
imported when a chart is written)."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from pounding.output import write_atomic
from pounding.studies.sweeps.store import FIELD


def write_chart(table, paths: Sequence[str], path: str | os.PathLike, units: str = "SI", title: str = "Sweep",
                field: str = FIELD) -> Path:
    """The design chart: expected extreme force and pounding probability
    against the first varied key, closed form (lines) and Monte Carlo (dots,
    95 % CI whiskers); one colour per combination of the other varied keys.

    A static HTML page (Bokeh, resources inline: no server, no network),
    written atomically (:func:`pounding.output.write_atomic`; a bad target is
    refused with a :class:`~pounding.errors.ArgumentError` naming ``field``).
    Returns ``path``.
    """
    from bokeh.embed import file_html
    from bokeh.layouts import row
    from bokeh.models import ColumnDataSource, Legend, Whisker
    from bokeh.palettes import Category10_10
    from bokeh.plotting import figure
    from bokeh.resources import INLINE

    path = Path(path)
    x_path = paths[0] if paths else None
    x_label = f"{x_path} [{units} units of the case file]" if x_path else "point"
    x_column = x_path or "point"
    others = list(paths[1:])
    groups = [((), table)] if not others else list(table.groupby(others, sort=False))
    force = figure(title="Expected extreme pounding force", x_axis_label=x_label, y_axis_label="E[F_max] [kN]",
                   width=560, height=420, tools="pan,wheel_zoom,box_zoom,reset,save,hover")
    probability = figure(title="Probability of pounding", x_axis_label=x_label, y_axis_label="P(at least one impact) [-]",
                         width=560, height=420, y_range=(-0.02, 1.02), tools="pan,wheel_zoom,box_zoom,reset,save,hover")
    items_force, items_probability = [], []
    for number, (group_values, group) in enumerate(groups):
        colour = Category10_10[number % 10]
        group = group.sort_values(x_column)
        group_values = group_values if isinstance(group_values, tuple) else (group_values,)
        label = ", ".join(f"{p}={v:g}" for p, v in zip(others, group_values)) or "case"
        source = ColumnDataSource({
            "x": group[x_column].to_numpy(),
            "estimate": group["estimate_force_N"].to_numpy() / 1e3,
            "paper": group["paper_force_N"].to_numpy() / 1e3,
            "mc": group["mc_force_mean_N"].to_numpy() / 1e3,
            "low": group["mc_force_ci_low_N"].to_numpy() / 1e3,
            "high": group["mc_force_ci_high_N"].to_numpy() / 1e3,
            "p_estimate": group["estimate_pounding_probability"].to_numpy(),
            "p_mc": group["mc_pounding_fraction"].to_numpy(),
        })
        lines = [force.line("x", "estimate", source=source, color=colour, line_width=2)]
        paper = force.line("x", "paper", source=source, color=colour, line_dash="dashed")
        dots = force.scatter("x", "mc", source=source, color=colour, size=7)
        force.add_layout(Whisker(source=source, base="x", lower="low", upper="high", line_color=colour))
        items_force += [(f"{label}: closed form", lines), (f"{label}: paper Eq. 12-30", [paper]), (f"{label}: Monte Carlo, 95 % CI", [dots])]
        p_line = probability.line("x", "p_estimate", source=source, color=colour, line_width=2)
        p_dots = probability.scatter("x", "p_mc", source=source, color=colour, size=7)
        items_probability += [(f"{label}: closed form", [p_line]), (f"{label}: Monte Carlo fraction", [p_dots])]
    for plot, items in ((force, items_force), (probability, items_probability)):
        legend = Legend(items=items, click_policy="hide", label_text_font_size="8pt")
        plot.add_layout(legend, "below")
    text = file_html(row(force, probability), resources=INLINE, title=title)
    write_atomic(path, text, field, make_parents=True)
    return path
