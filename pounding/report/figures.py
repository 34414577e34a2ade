"""The plots: :class:`Figures`, the Bokeh figures of a snapshot and their data
sources. Bokeh is imported when the figures are built, not with this module."""

from __future__ import annotations

import math

import numpy as np

from pounding.display_units import display
from pounding.report.curve_charts import BAND_LABEL, band_label, legend_below
from pounding.report.snapshot import Snapshot
from pounding.simulation.monte_carlo import DesignGap, TimeHistory
from pounding.units import STANDARD_GRAVITY

# --- plots ---------------------------------------------------------------------

class Figures:
    """The Bokeh figures of a snapshot (canvas backend) and their data sources.

    Built once; :meth:`fill` puts a snapshot's data into the sources in place,
    so a live page only sends new numbers. The dashboard keeps one per session;
    the report fills one and writes it.

    Attributes
    ----------
    gap, psd_ground, psd_velocity, hysteresis (two), contact : bokeh figure
    """

    def __init__(self):
        from bokeh.models import (
            ColumnDataSource,
            HoverTool,
            LinearAxis,
            Range1d,
            Whisker,
        )
        from bokeh.plotting import figure

        common = dict(output_backend="canvas", sizing_mode="stretch_width", tools="pan,wheel_zoom,box_zoom,reset,save")
        cds = lambda **columns: ColumnDataSource(data=columns)  # noqa: E731
        self.sources = {
            "gap": cds(gap=[], force=[], paper=[], probability=[]),
            "band": cds(gap=[], low=[], high=[]),
            "current": cds(gap=[], force=[]),
            "marker": cds(gap=[], force=[]),
            "required": cds(gap=[], probability=[]),
            "design_gap": cds(gap=[], probability=[]),
            "mc": cds(gap=[], force=[], low=[], high=[], fraction=[]),
            "psd_ground": cds(omega=[], ground=[]),
            "psd_velocity": cds(omega=[], velocity=[]),
            "hysteresis1": cds(drift=[], force=[], equivalent=[]),
            "hysteresis2": cds(drift=[], force=[], equivalent=[]),
            "impact1": cds(drift=[], force=[]),
            "impact2": cds(drift=[], force=[]),
            "contact": cds(time=[], force=[]),
            "relative": cds(time=[], relative=[]),
            "gap_line": cds(time=[], gap=[]),
            "ground": cds(time=[], acceleration=[]),
        }
        src = self.sources

        g = figure(title="Expected extreme pounding force against the gap", height=340, **common)
        g.extra_y_ranges = {"probability": Range1d(0.0, 1.02)}
        g.add_layout(LinearAxis(y_range_name="probability", axis_label="probability of pounding [-]"), "right")
        band = g.varea("gap", "low", "high", source=src["band"], fill_color="#1f77b4", fill_alpha=0.15,
                       legend_label=BAND_LABEL)
        g.line("gap", "force", source=src["gap"], color="#1f77b4", line_width=2, legend_label="recommended E[F_max]")
        g.line("gap", "paper", source=src["gap"], color="#d62728", line_dash="dashed", line_width=2, legend_label="paper F_e (gap-independent)")
        g.line("gap", "probability", source=src["gap"], color="#2ca02c", y_range_name="probability", legend_label="probability of pounding")
        g.line("gap", "force", source=src["marker"], color="#555555", line_dash="dotted")
        g.scatter("gap", "force", source=src["current"], color="#1f77b4", size=11, legend_label="current gap")
        g.line("gap", "probability", source=src["required"], color="#2ca02c", line_dash="dashdot", y_range_name="probability",
               legend_label="gap needed for the target")
        g.line("gap", "probability", source=src["design_gap"], color="black", line_dash="dashdot", y_range_name="probability",
               legend_label="Monte Carlo gap for the target")
        g.add_layout(Whisker(base="gap", lower="low", upper="high", source=src["mc"], line_color="black"))
        g.scatter("gap", "force", source=src["mc"], color="black", marker="square", size=8, legend_label="Monte Carlo mean F_max (95 % CI)")
        g.scatter("gap", "fraction", source=src["mc"], color="#2ca02c", marker="triangle", size=8, y_range_name="probability",
                  legend_label="Monte Carlo pounding fraction")
        g.legend.click_policy = "hide"
        legend_below(g, columns=2)  # the curves fill the frame's corners; beside it, the band's long entry squeezes it
        # The Monte Carlo entries show only when there is a study to show (see fill).
        self._monte_carlo_legend = {
            item.label.value: item for item in g.legend[0].items if item.label.value.startswith("Monte Carlo")
        }
        g.add_tools(HoverTool(tooltips=[("gap", "@gap"), ("force", "@force")]))
        # The band follows the regime's measured range, unbounded above in some: the axis fits the curves, not it.
        g.y_range.renderers = [r for r in g.renderers if r is not band and getattr(r, "y_range_name", "default") == "default"]
        self._band_legend = next(item for item in g.legend[0].items if item.label.value == BAND_LABEL)
        self.gap = g

        self.psd_ground = figure(title="Ground acceleration PSD", height=300, x_axis_type="log", y_axis_type="log", **common)
        self.psd_ground.line("omega", "ground", source=src["psd_ground"], color="#7f7f7f", line_width=2)
        self.psd_velocity = figure(title="Relative velocity PSD, contact floors", height=300, x_axis_type="log",
                                   y_axis_type="log", **common)
        self.psd_velocity.line("omega", "velocity", source=src["psd_velocity"], color="#1f77b4", line_width=2)
        for f in (self.psd_ground, self.psd_velocity):
            f.xaxis.axis_label = "circular frequency [rad/s]"

        self.hysteresis = []
        for b in (1, 2):
            h = figure(title=f"Building {b}, storey 1, one record", height=320, **common)
            h.line("drift", "equivalent", source=src[f"hysteresis{b}"], color="#ff7f0e", line_dash="dashed", alpha=0.8,
                   legend_label="equivalent linear")
            h.line("drift", "force", source=src[f"hysteresis{b}"], color="#1f77b4", legend_label="Bouc-Wen")
            h.scatter("drift", "force", source=src[f"impact{b}"], color="#d62728", size=4, legend_label="during impact")
            h.legend.click_policy = "hide"
            legend_below(h, columns=2)  # inside the frame it covered the loops
            self.hysteresis.append(h)
        self.contact = figure(title="Pounding force during the record", height=230, **common)
        self.contact.line("time", "force", source=src["contact"], color="#d62728")
        # The same record's relative displacement of the contact floors against the gap, and the ground motion.
        self.relative = figure(title="Relative displacement of the contact floors, x1 - x2", height=200, x_range=self.contact.x_range, **common)
        self.relative.line("time", "relative", source=src["relative"], color="#1f77b4", legend_label="x1 - x2")
        self.relative.line("time", "gap", source=src["gap_line"], color="#d62728", line_dash="dashed", legend_label="gap")
        legend_below(self.relative, columns=2)
        self.ground = figure(title="Ground acceleration of the record", height=180, x_range=self.contact.x_range, **common)
        self.ground.line("time", "acceleration", source=src["ground"], color="#7f7f7f")
        self.ground.yaxis.axis_label = "acceleration [g]"
        for plot in (self.contact, self.relative, self.ground):
            plot.xaxis.axis_label = "time [s]"

    @property
    def all(self) -> list:
        return [self.gap, self.psd_ground, self.psd_velocity, *self.hysteresis, self.contact, self.relative, self.ground]

    def fill(self, snapshot: Snapshot | None, units: str = "SI", monte_carlo: tuple = (), design_gap: DesignGap | None = None) -> None:
        """Show ``snapshot`` (None: empty plots) in ``units``, with Monte Carlo
        points and the Monte Carlo design gap (``design_gap``) of this case."""
        d = display(units)
        fs, ls, vs = d.force_scale, d.length_scale, d.velocity_scale
        src = self.sources
        # axis labels
        self.gap.xaxis.axis_label = f"gap [{d.length_unit}]"
        self.gap.yaxis[0].axis_label = f"expected extreme force [{d.force_unit}]"
        self.psd_ground.yaxis.axis_label = f"two-sided PSD [{d.length_unit}^2/s^3]"
        self.psd_velocity.yaxis.axis_label = f"two-sided PSD [({d.velocity_unit})^2 s]"
        for h in self.hysteresis:
            h.xaxis.axis_label = f"storey drift [{d.length_unit}]"
            h.yaxis.axis_label = f"restoring force [{d.force_unit}]"
        self.contact.yaxis.axis_label = f"pounding force [{d.force_unit}]"
        self.relative.yaxis.axis_label = f"x1 - x2 [{d.length_unit}]"
        if snapshot is None:
            for source in src.values():
                _refill(source, **{key: [] for key in source.data})
            return
        curve = snapshot.gap_curve
        paper = np.nan if curve.paper_force_expected is None else curve.paper_force_expected / fs
        force = curve.force_expected / fs
        _refill(src["gap"], gap=curve.gaps / ls, force=force, paper=np.full(curve.gaps.size, paper), probability=curve.pounding_probability)
        if snapshot.gap_accuracy:
            from bokeh.core.properties import value

            low, high = snapshot.gap_band()
            ceiling = 10.0 * max(float(np.nanmax(curve.force_expected)), 1e-300)  # "unbounded" drawn off the axis
            _refill(src["band"], gap=curve.gaps / ls, low=low / fs, high=np.minimum(high, ceiling) / fs)
            self._band_legend.label = value(band_label(snapshot.gap_accuracy))  # a text, not a column
        else:
            _refill(src["band"], gap=[], low=[], high=[])
        self._band_legend.visible = bool(snapshot.gap_accuracy)
        gap = snapshot.case.contact.gap / ls
        _refill(src["current"], gap=[gap], force=[snapshot.estimate.force_expected / fs])
        top = np.nanmax([*force, paper, 0.0])
        _refill(src["marker"], gap=[gap, gap], force=[0.0, top])
        required = snapshot.estimate.required_gap / ls
        _refill(src["required"], gap=[required, required], probability=[0.0, 1.0])
        if design_gap is None:
            _refill(src["design_gap"], gap=[], probability=[])
        else:
            _refill(src["design_gap"], gap=[design_gap.gap / ls] * 2, probability=[0.0, 1.0])
        points = [m for m in monte_carlo if math.isfinite(m.force_low)]
        for label, item in self._monte_carlo_legend.items():
            item.visible = (design_gap is not None) if label == "Monte Carlo gap for the target" else bool(points)
        _refill(
            src["mc"],
            gap=[m.gap / ls for m in points], force=[m.force_max_mean / fs for m in points], low=[m.force_low / fs for m in points],
            high=[m.force_high / fs for m in points], fraction=[m.pounding_fraction for m in points],
        )
        velocity = np.where(snapshot.psd_velocity > 0, snapshot.psd_velocity, np.nan)
        if np.any(np.isfinite(velocity)):
            velocity = np.where(velocity < np.nanmax(velocity) * 1e-8, np.nan, velocity)  # its fall to 0 past the cutoff
        _refill(src["psd_ground"], omega=snapshot.omega, ground=snapshot.psd_ground / ls**2)
        _refill(src["psd_velocity"], omega=snapshot.omega, velocity=velocity / vs**2)
        history = snapshot.history
        shown = None if history is None else plotted_steps(history)
        for b in (1, 2):
            if history is None:
                _refill(src[f"hysteresis{b}"], drift=[], force=[], equivalent=[])
                _refill(src[f"impact{b}"], drift=[], force=[])
                continue
            column = history.floor(b, 1)
            drift = history.drift[shown, column] / ls
            restoring = history.storey_force[shown, column] / fs
            equivalent = snapshot.equivalent_force[b - 1][shown, 0] / fs
            _refill(src[f"hysteresis{b}"], drift=drift, force=restoring, equivalent=equivalent)
            impact = history.contact_force[shown] > 0
            _refill(src[f"impact{b}"], drift=drift[impact], force=restoring[impact])
        if history is None:
            for key in ("contact", "relative", "gap_line", "ground"):
                _refill(src[key], **{column: [] for column in src[key].data})
            return
        time = history.time[shown]
        _refill(src["contact"], time=time, force=history.contact_force[shown] / fs)
        relative = history.displacement[shown, history.floor(1, snapshot.case.contact.levels[0])] \
            - history.displacement[shown, history.floor(2, snapshot.case.contact.levels[1])]
        _refill(src["relative"], time=time, relative=relative / ls)
        _refill(src["gap_line"], time=[time[0], time[-1]], gap=[gap, gap])
        _refill(src["ground"], time=time, acceleration=history.ground_acceleration[shown] / STANDARD_GRAVITY)
        where = f"record {snapshot.record} of the study seeded {snapshot.seed}"
        self.contact.title.text = f"Pounding force during {where}"
        self.ground.title.text = f"Ground acceleration of {where}"


def _refill(source, **columns) -> None:
    """Replace a plot's data, unless it is unchanged: an unchanged source sends
    nothing to the browser, which then does not repaint that plot (most
    changes of input leave the ground spectrum, and the Monte Carlo points, as they are)."""
    old = source.data
    if old.keys() == columns.keys() and all(
        np.array_equal(np.asarray(old[key], dtype=float), np.asarray(value, dtype=float), equal_nan=True) for key, value in columns.items()
    ):
        return
    source.data = columns


PLOTTED_STEPS = 1500
"""Integration steps drawn per curve outside the impacts: the kernel's steps
crowd into the impacts, and the plots need no more to show the loops."""


def plotted_steps(history: TimeHistory) -> np.ndarray:
    """Indices of the steps drawn: every step in contact at any contact (and its neighbours,
    so each pounding spike keeps its shape), and an even selection of the rest."""
    n = history.time.size
    contact = np.flatnonzero(np.any(history.contact_forces > 0, axis=1))  # in contact at any contact
    around = np.concatenate([contact - 1, contact, contact + 1])
    even = np.linspace(0, n - 1, min(n, PLOTTED_STEPS)).astype(np.int64)
    return np.unique(np.clip(np.concatenate([around, even]), 0, n - 1))
