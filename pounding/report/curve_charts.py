"""Self-contained HTML charts of a fragility curve and of a force spectrum
(Bokeh, resources inline: they open offline), with their numbers as a table
readable without JavaScript. Bokeh is imported when a chart is written."""

from __future__ import annotations

import html
import os
from pathlib import Path

import numpy as np

from pounding.display_units import display
from pounding.output import write_atomic
from pounding.units import STANDARD_GRAVITY

__all__ = ["BAND_LABEL", "band_label", "fragility_chart", "legend_below", "spectrum_chart", "write_chart_page"]

BAND_LABEL = "closed form, measured accuracy"
"""The legend of a closed-form curve's band of measured accuracy; :func:`band_label` adds its regimes."""


def band_label(ranges) -> str:
    """The legend of a band over points of these :class:`~pounding.closed_form.regimes.MeasuredRange` s: "closed
    form, measured accuracy (frequent, moderate gap, rare)", each regime once, in the curve's order."""
    regimes = list(dict.fromkeys(r.regime for r in ranges))
    return f"{BAND_LABEL} ({', '.join(regimes)})" if regimes else BAND_LABEL


LEGEND_ROW = 18
"""[px] Height of one row of a legend under a plot (10 px text, 14 px glyphs)."""


def legend_below(plot, columns: int = 1) -> None:
    """Put every legend of ``plot`` under its frame, ``columns`` entries a row, and make the plot taller by the rows
    it takes, so that the frame keeps its size: inside the frame a legend covers data (a hysteresis loop, a curve),
    and beside it long entries take the frame's width."""
    import math

    for legend in list(plot.legend):
        for side in (plot.center, plot.right, plot.left, plot.above, plot.below):
            if legend in side:
                side.remove(legend)
        legend.location, legend.orientation, legend.ncols = "top_left", "horizontal" if columns > 1 else "vertical", columns
        legend.label_text_font_size, legend.glyph_height, legend.label_height = "10px", 14, 14
        legend.spacing, legend.padding, legend.margin = 4, 4, 4
        plot.add_layout(legend, "below")
        plot.height += math.ceil(len(legend.items) / columns) * LEGEND_ROW + 16


SPECTRUM_RECORDS_SHOWN = 5
"""Records whose own (deterministic, Jankowski-style) spectrum a force-spectrum chart draws in grey."""

_STYLE = """body{font-family:system-ui,sans-serif;margin:1.5em;color:#222}
table{border-collapse:collapse;font-size:0.85em;margin-top:1em}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}
caption{text-align:left;font-weight:600;padding:4px 0}p.note{max-width:60em;font-size:0.9em}"""


def _figure(title: str, x_label: str, y_label: str, **options):
    from bokeh.plotting import figure

    return figure(title=title, x_axis_label=x_label, y_axis_label=y_label, width=620, height=420,
                  tools="pan,wheel_zoom,box_zoom,reset,save,hover", output_backend="canvas", **options)


def _table(caption: str, header: list[str], rows: list[list[str]]) -> str:
    head = "".join(f"<th>{html.escape(cell)}</th>" for cell in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(cell)}</td>" for cell in row) + "</tr>" for row in rows)
    return f"<table><caption>{html.escape(caption)}</caption><tr>{head}</tr>{body}</table>"


def write_chart_page(path: str | os.PathLike, title: str, layout, note: str, table: str, field: str = "path") -> Path:
    """One HTML file: ``title``, the Bokeh ``layout``, ``note`` (plain text) and the numbers' ``table`` (HTML);
    written atomically (:func:`pounding.output.write_atomic`)."""
    from pounding.report.bokeh_embed import embedded

    script, (division,), library = embedded([layout])
    page = (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{_STYLE}</style>{library}{script}</head><body><h1>{html.escape(title)}</h1>{division}"
            f"<p class='note'>{html.escape(note)}</p>{table}</body></html>")
    path = Path(path)
    write_atomic(path, page, field)
    return path


def _band(plot, x, force, ranges, scale: float) -> list[str]:
    """Shade a closed-form E[F_max] curve's band of measured accuracy on ``plot`` (``force`` [N] at ``x``, one
    :class:`~pounding.closed_form.regimes.MeasuredRange` a point, forces shown divided by ``scale``); the axis keeps
    fitting the curves, a band unbounded above runs off it. Returns the band at each point as text, for the table."""
    from pounding.closed_form.regimes import accuracy_band

    if not ranges:
        return []
    low, high = accuracy_band(force, ranges)
    ceiling = 10.0 * max(float(np.max(force)), 1e-300)
    band = plot.varea(x=x, y1=low / scale, y2=np.minimum(high, ceiling) / scale, fill_color="#1f77b4", fill_alpha=0.15,
                      legend_label=band_label(ranges))
    plot.y_range.renderers = [r for r in plot.renderers if r is not band]
    return [f"{lo / scale:.4g}-" + (f"{hi / scale:.4g}" if np.isfinite(hi) else "unbounded") + f" ({r.regime})"
            for lo, hi, r in zip(low, high, ranges)]


def _band_note(ranges) -> str:
    if not ranges:
        return ""
    return (" The shaded band is where the Monte Carlo E[F_max] lay given the closed form's, by the errors measured in "
            "each point's regime (pounding/data/accuracy.json: E[F_max] / (1 + highest) to E[F_max] / (1 + lowest); "
            "unbounded above where the closed form was measured at 0 while records pounded); it is measured for E[F_max] "
            "only, so the other curves have none.")


def fragility_chart(curve, units: str = "SI"):
    """The Bokeh layout, note and table of a :class:`~pounding.studies.fragility.FragilityCurve`."""
    from bokeh.layouts import row
    from bokeh.models import ColumnDataSource, Span, Whisker

    shown = display(units)
    pga = curve.pga / STANDARD_GRAVITY
    fine = np.geomspace(curve.pga[0], curve.pga[-1], 200)
    probability = _figure(f"P(F_max > {shown.force(curve.capacity)})", "expected peak ground acceleration [g]",
                          "probability of exceeding [-]", y_range=(-0.02, 1.02))
    probability.line(pga, curve.probability, line_width=2, color="#1f77b4", legend_label="closed form")
    if curve.lognormal is not None:
        probability.line(fine / STANDARD_GRAVITY, curve.lognormal.probability(fine), line_dash="dashed", color="#1f77b4",
                         legend_label="lognormal fit to the closed form")
    forces = _figure("Extreme pounding force", "expected peak ground acceleration [g]", f"F_max [{shown.force_unit}]")
    forces.line(pga, curve.force_expected / shown.force_scale, line_width=2, color="#1f77b4", legend_label="E[F_max], closed form")
    forces.line(pga, curve.force_84 / shown.force_scale, line_width=2, line_dash="dotdash", color="#1f77b4",
                legend_label="84th percentile, closed form")
    forces.add_layout(Span(location=curve.capacity / shown.force_scale, dimension="width", line_color="#d62728", line_dash="dashed"))
    bands = _band(forces, pga, curve.force_expected, curve.accuracy, shown.force_scale)
    header = ["PGA [g]", "P closed form", f"E[F_max] [{shown.force_unit}]", f"F_84 [{shown.force_unit}]"]
    rows = [[f"{a:.4g}", f"{p:.3f}", f"{f / shown.force_scale:.4g}", f"{q / shown.force_scale:.4g}"]
            for a, p, f, q in zip(pga, curve.probability, curve.force_expected, curve.force_84)]
    if bands:
        header.append(f"E[F_max] measured accuracy [{shown.force_unit}]")
        rows = [r + [b] for r, b in zip(rows, bands)]
    mc = curve.monte_carlo
    if mc is not None:
        exceeding = mc.exceeding(curve.capacity)
        intervals = mc.intervals(curve.capacity)
        source = ColumnDataSource({"x": pga, "p": exceeding / mc.records, "low": intervals[:, 0], "high": intervals[:, 1]})
        probability.scatter("x", "p", source=source, size=7, color="#ff7f0e", legend_label=f"Monte Carlo, {mc.records} records, 95 % interval")
        probability.add_layout(Whisker(source=source, base="x", lower="low", upper="high", line_color="#ff7f0e"))
        if curve.lognormal_monte_carlo is not None:
            probability.line(fine / STANDARD_GRAVITY, curve.lognormal_monte_carlo.probability(fine), line_dash="dotted",
                             color="#ff7f0e", legend_label="lognormal fit to Monte Carlo")
        forces.scatter(pga, [np.mean(f) / shown.force_scale for f in mc.force_max], size=7, color="#ff7f0e",
                       legend_label="E[F_max], Monte Carlo")
        header += ["P Monte Carlo", "95 % interval"]
        rows = [r + [f"{k / mc.records:.3f}", f"{lo:.3f}-{hi:.3f}"] for r, k, (lo, hi) in zip(rows, exceeding, intervals)]
    for plot in (probability, forces):
        legend_below(plot)
    fits = []
    for label, fit in (("closed form", curve.lognormal), ("Monte Carlo", curve.lognormal_monte_carlo if mc else None)):
        if fit is not None:
            fits.append(f"{label}: median {fit.median / STANDARD_GRAVITY:.3g} g, dispersion {fit.dispersion:.3g}"
                        + (" (at its bound: not pinned by the data)" if fit.at_bound else ""))
    note = (f"Case {curve.case.name}; its own expected PGA is {curve.reference_pga / STANDARD_GRAVITY:.3g} g. The ground motion is "
            "scaled to each PGA; the closed form is G31 at each, the lognormal curves are maximum-likelihood fits"
            + (" (" + "; ".join(fits) + ")." if fits else ".") + _band_note(curve.accuracy))
    return row(probability, forces), note, _table("Fragility curve", header, rows)


def spectrum_chart(spectrum, units: str = "SI"):
    """The Bokeh layout, note and table of a :class:`~pounding.studies.force_spectrum.ForceSpectrum`."""
    from bokeh.models import ColumnDataSource, Whisker

    shown = display(units)
    scale = shown.force_scale
    plot = _figure("Stochastic pounding-force spectrum", "fundamental period of building 1, T1 [s]", f"F_max [{shown.force_unit}]")
    mc = spectrum.monte_carlo
    if mc is not None:
        for index in range(min(SPECTRUM_RECORDS_SHOWN, mc.records)):
            plot.line(spectrum.period1, [f[index] / scale for f in mc.force_max], color="#bbbbbb", line_width=1,
                      legend_label="single records (deterministic spectra)")
    plot.line(spectrum.period1, spectrum.force_mean / scale, line_width=2, color="#1f77b4", legend_label="E[F_max], closed form")
    plot.line(spectrum.period1, spectrum.force_84 / scale, line_width=2, line_dash="dotdash", color="#1f77b4",
              legend_label="84th percentile, closed form")
    bands = _band(plot, spectrum.period1, spectrum.force_mean, spectrum.accuracy, scale)
    header = ["T1 [s]", "T2 [s]", f"E[F_max] [{shown.force_unit}]", f"F_84 [{shown.force_unit}]", "P(pounding)"]
    rows = [[f"{t1:.4g}", f"{t2:.4g}", f"{f / scale:.4g}", f"{q / scale:.4g}", f"{p:.3f}"]
            for t1, t2, f, q, p in zip(spectrum.period1, spectrum.period2, spectrum.force_mean, spectrum.force_84,
                                        spectrum.pounding_probability)]
    if mc is not None:
        mean_interval = mc.force_mean_interval()
        q84, q84_interval = mc.quantile(0.84)
        source = ColumnDataSource({"x": spectrum.period1, "mean": mc.force_mean / scale, "low": mean_interval[:, 0] / scale,
                                   "high": mean_interval[:, 1] / scale, "q84": q84 / scale})
        plot.scatter("x", "mean", source=source, size=7, color="#ff7f0e", legend_label=f"E[F_max], Monte Carlo ({mc.records} records), 95 % CI")
        plot.add_layout(Whisker(source=source, base="x", lower="low", upper="high", line_color="#ff7f0e"))
        plot.scatter("x", "q84", source=source, size=7, marker="triangle", color="#ff7f0e", legend_label="84th percentile, Monte Carlo")
        header += [f"E[F_max] MC [{shown.force_unit}]", f"F_84 MC [{shown.force_unit}]"]
        rows = [r + [f"{m / scale:.4g}", f"{q / scale:.4g}"] for r, m, q in zip(rows, mc.force_mean, q84)]
    if bands:
        header.append(f"E[F_max] measured accuracy [{shown.force_unit}]")
        rows = [r + [b] for r, b in zip(rows, bands)]
    plot.width = 900
    legend_below(plot, columns=2)
    note = (f"Case {spectrum.case.name}: each building made stiffer or softer to the periods shown (masses, yield drifts, "
            "damping ratio, gap, restitution and ground motion held). Jankowski's pounding force response spectrum is "
            "the peak force of one record against the period; this is its mean and 84th percentile over the random "
            "ground motion" + (", with the first records' own spectra in grey." if mc is not None else ".")
            + _band_note(spectrum.accuracy))
    return plot, note, _table("Force spectrum", header, rows)
