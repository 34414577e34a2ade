"""The dashboard's tabs. The plots that cost a computation of their own (the distribution of F_max, the
fragility curve, the ground motion against its target) are built only when their tab is open, off the event
loop, the newest request only; the others are filled in place with the rest of the page."""

from __future__ import annotations

import dataclasses

import numpy as np
import panel as pn

from dashboard.messages import message
from dashboard.pinning import overlay_distribution
from dashboard.runner import Latest
from pounding.display_units import display
from pounding.errors import ConvergenceError, InputError, SimulationError
from pounding.units import STANDARD_GRAVITY

__all__ = ["FRAGILITY_POINTS", "LazyTabs"]

FRAGILITY_POINTS = 20
"""PGAs of the dashboard's fragility curve, from 0.1 to 2 times the case's own expected PGA."""


def distribution_plot(dashboard, snapshot, units: str, capacity: float):
    from pounding.report.distribution_section import distribution_figure

    if len(snapshot.case.contacts) > 1:
        from dashboard.contacts import ONE_CONTACT

        return pn.pane.Markdown(ONE_CONTACT["distribution"], css_classes=["one-contact"])

    studies = dashboard.model.monte_carlo_points()
    figure = distribution_figure(dataclasses.replace(snapshot, monte_carlo=studies), units)
    top = snapshot.estimate.force_max_distribution.quantile(0.999)
    largest = max((max(m.force_max_values, default=0.0) for m in studies), default=0.0)
    if max(top, largest) > 0:  # the tabulated CDF runs to 10 sigma_V: show where the probability is
        figure.x_range.end = 1.05 * max(top, largest) / display(units).force_scale
    overlay_distribution(figure, dashboard.model.pinned, units)
    return figure


def fragility_plot(dashboard, snapshot, units: str, capacity: float):
    from pounding.case.scaling import PeakGroundAcceleration
    from pounding.report.curve_charts import fragility_chart
    from pounding.studies.fragility import fragility_curve

    reference = PeakGroundAcceleration(snapshot.case).reference
    curve = fragility_curve(snapshot.case, capacity, reference * np.linspace(0.1, 2.0, FRAGILITY_POINTS))
    layout, note, _ = fragility_chart(curve, units)
    tallest = max(figure.height for figure in layout.children)  # 420 px, and the legend under the frame
    for figure in layout.children:
        figure.sizing_mode, figure.height = "stretch_width", tallest - 80
    layout.sizing_mode = "stretch_width"
    return pn.Column(pn.pane.Bokeh(layout, sizing_mode="stretch_width"), pn.pane.Markdown(note, styles={"font-size": "12px"}),
                     sizing_mode="stretch_width")


def hazard_plot(dashboard, snapshot, units: str, capacity: float):
    from pounding.case.engineering import ground_motion_terms
    from pounding.report.hazard_section import hazard_figure, scaled_records_figure

    case = snapshot.case
    figure = hazard_figure(case, snapshot.seed)
    terms = ground_motion_terms(case)
    text = (f"{terms['source']}: expected PGA {terms['pga_expected'] / STANDARD_GRAVITY:.3f} g, "
            f"RMS {terms['rms_acceleration'] / STANDARD_GRAVITY:.3f} g.")
    if figure is None:  # a process given by its parameters: its PSD is the 'Spectra' tab's
        return pn.pane.Markdown(text + " Its power spectral density is in the 'Spectra' tab.")
    shown = []
    if case.recorded:
        source = f" {case.hazard.source}." if case.hazard.source else ""
        text = f"{len(case.hazard.records)} recorded motions.{source} Scaled {case.hazard.scaling}. " + text
        # the records' mean Sa beside the code spectrum (and the expected Sa of the process the closed form takes)
        scaled = scaled_records_figure(case)
        if scaled is not None:
            shown.append(pn.pane.Bokeh(scaled, sizing_mode="stretch_width"))
    shown.append(pn.pane.Bokeh(figure, sizing_mode="stretch_width"))
    return pn.Column(pn.pane.Markdown(text), *shown, sizing_mode="stretch_width")


_BUILDERS = {"distribution": distribution_plot, "fragility": fragility_plot, "hazard": hazard_plot}


class LazyTabs:
    """Tabs whose entries are panels, or the name of a builder (:data:`_BUILDERS`) run when that tab is open."""

    def __init__(self, dashboard, entries):
        self.dashboard = dashboard
        model = dashboard.model
        self._latest = Latest(model._compute_off_loop, model._schedule)
        self._lazy: dict[int, tuple[str, pn.Column]] = {}
        self._shown: dict[int, tuple] = {}
        tabs = []
        for index, (title, content) in enumerate(entries):
            if isinstance(content, str):
                holder = pn.Column(pn.pane.Markdown("Computing..."), sizing_mode="stretch_width", min_height=200)
                self._lazy[index] = (content, holder)
                content = holder
            tabs.append((title, content))
        self.panel = pn.Tabs(*tabs, dynamic=True, sizing_mode="stretch_width", css_classes=["plot-tabs"])
        self.panel.param.watch(lambda _event: self.refresh(), "active")
        model.param.watch(lambda _event: self.refresh(), ["capacity", "pinned"])
        model.monte_carlo_job.param.watch(lambda _event: self.refresh(), "result")

    def refresh(self) -> None:
        """Build the open tab's plot if its inputs changed since it was built."""
        index = self.panel.active
        if index not in self._lazy:
            return
        model = self.dashboard.model
        snapshot = model.snapshot
        kind, holder = self._lazy[index]
        key = (id(snapshot), model.units, model.capacity, len(model.monte_carlo_points()), id(model.pinned))
        if snapshot is None or self._shown.get(index) == key:
            return
        self._shown[index] = key
        units, capacity = model.units, display(model.units).to_si(model.capacity, force=1)
        build = _BUILDERS[kind]

        def work(current, deliver):
            try:
                content = build(self.dashboard, snapshot, units, capacity)
            except (InputError, ConvergenceError, SimulationError, ValueError, ArithmeticError) as error:
                content = pn.pane.Alert(message(error), alert_type="warning")
            deliver(lambda: holder.__setitem__(slice(None), [content]))

        self._latest.request(work)
