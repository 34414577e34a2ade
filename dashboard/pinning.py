"""Pin and compare: the page keeps one state of the case ("pinned": its closed-form estimate and everything its
plots showed, :class:`~pounding.report.Snapshot`, as computed, never recomputed, with its check against simulated
records and its Monte Carlo study at its gap when they were run) while the inputs change; the headline then shows
both states' key numbers and the change (current minus pinned) in the units shown and in %, and both states'
Monte Carlo means and verdicts where run; the force-against-gap curve and the distribution of F_max draw the pinned
state dashed beside the current one, and the pair exports as one page (:func:`pounding.report.write_comparison`).
The numbers and the change are the library's (:func:`pounding.report.differences`,
:func:`pounding.report.monte_carlo_comparison`); this only holds the pinned state and draws it."""

from __future__ import annotations

import html
from dataclasses import dataclass, replace

import param

from dashboard.uploads import new_folder, remove
from pounding.display_units import display
from pounding.report import Snapshot, StateMonteCarlo, differences, monte_carlo_comparison, write_comparison
from pounding.report.comparison import COMPARISON_NAMES, distribution_points

__all__ = ["PINNED_CSS", "PINNED_LABEL", "PinnedOverlay", "PinnedState", "Pinning", "pin_controls", "pinned_html"]

PINNED_LABEL = "pinned E[F_max]"
"""The pinned curve's entry in the force-against-gap plot's legend."""
_STYLE = {"color": "#ff7f0e", "line_dash": "dashed", "line_width": 2}
_ROW_CSS = ("pin-force", "pin-f84", "pin-probability", "pin-gap")
"""The CSS class of each row of :func:`pinned_html`, in the order of :func:`pounding.report.differences`; then, where
a state has a Monte Carlo, "pin-monte-carlo" (the means) and "pin-verdict"."""

PINNED_CSS = """
.headline table.pinned { border-collapse: collapse; margin: 2px 0 6px; font-size: 13px; width: 100%; }
.headline table.pinned th, .headline table.pinned td { padding: 1px 6px; text-align: left; border-bottom: 1px solid #e4e4e4; }
.headline table.pinned td.pinned-value { color: #a35200; }
.headline table.pinned td.pinned-value, .headline table.pinned td.current-value { white-space: nowrap; }
.headline table.pinned td.change { font-weight: 700; }
.headline p.pinned-note { font-size: 12px; color: #555; margin: 0 0 6px; }
"""


@dataclass(frozen=True)
class PinnedState:
    """A state of the page kept for comparison.

    Attributes
    ----------
    snapshot : Snapshot
        What the page showed for it: its ``estimate`` (the headline's numbers) and ``gap_curve``; its ``check``
        (the check of that estimate against simulated records) and ``monte_carlo`` (the page's study at its gap)
        where they were run, else None and ().
    name : str
        The case's name on the page when pinned ("section5-T2-0.4 (modified)").
    """

    snapshot: Snapshot
    name: str

    @property
    def estimate(self):
        """The pinned :class:`~pounding.closed_form.estimator.Estimate`."""
        return self.snapshot.estimate

    @property
    def monte_carlo(self) -> StateMonteCarlo | None:
        """The pinned state's Monte Carlo (its check, else its study at its gap), or None."""
        return StateMonteCarlo.of_snapshot(self.snapshot)


class Pinning(param.Parameterized):
    """The pinned state; mixed into the dashboard's model, which provides ``result``, ``snapshot``, ``case_name()``
    and the studies (:class:`~dashboard.studies.Studies`: ``current_check()``, ``monte_carlo_for_current_gap()``, the
    jobs), and calls :meth:`_watch_studies` once they are made."""

    pinned = param.ClassSelector(class_=PinnedState, default=None, allow_None=True, precedence=-1,
                                 doc="The state kept for comparison (PinnedState), or None.")

    def can_pin(self) -> bool:
        """Whether the page shows a valid state of one contact whose plots are computed (the snapshot of the estimate shown)."""
        return (self.result is not None and self.snapshot is not None and self.snapshot.estimate is self.result
                and len(self.result.case.contacts) == 1)  # a case of several contacts is not compared

    def pin(self) -> bool:
        """Keep the state shown (its estimate and snapshot, as computed); False when there is none to keep."""
        if not self.can_pin():
            return False
        self.pinned = PinnedState(self._with_studies(self.snapshot), self.case_name())
        return True

    def _with_studies(self, snapshot: Snapshot) -> Snapshot:
        """``snapshot`` (of the estimate shown) with the check of that estimate and the study at its gap, where run."""
        study = self.monte_carlo_for_current_gap()
        return replace(snapshot, check=self.current_check(), monte_carlo=() if study is None else (study,))

    def _watch_studies(self) -> None:
        """A check or a study that ends after the pin, of the very state pinned (no input changed since), joins it."""
        for job in (self.check_job, self.monte_carlo_job):
            job.param.watch(self._carry_to_pinned, "result")

    def _carry_to_pinned(self, _event=None) -> None:
        """Add what ended for the pinned estimate; never drop what the pin kept (a change of input clears the
        page's check before its new estimate replaces the pinned one as ``result``)."""
        pinned = self.pinned
        if pinned is None or self.result is not pinned.estimate:
            return
        kept, found = pinned.snapshot, self._with_studies(pinned.snapshot)
        check, monte_carlo = found.check or kept.check, found.monte_carlo or kept.monte_carlo
        if (check, monte_carlo) != (kept.check, kept.monte_carlo):
            self.pinned = PinnedState(replace(kept, check=check, monte_carlo=monte_carlo), pinned.name)

    def current_state(self) -> Snapshot | None:
        """The state shown as a snapshot with its check and study (what :meth:`pin` keeps), or None until its plots
        are computed."""
        return self._with_studies(self.snapshot) if self.can_pin() else None

    def unpin(self) -> None:
        """Forget the pinned state: the page shows the current state alone."""
        self.pinned = None

    def comparison(self):
        """The key numbers of the pinned and the current state (:func:`pounding.report.differences`), or None."""
        if self.pinned is None or self.result is None:
            return None
        return differences(self.pinned.estimate, self.result)


def _row(css: str, quantity: str, pinned: str, current: str, change: str) -> str:
    return (f'<tr class="{css}"><th>{html.escape(quantity)}</th><td class="pinned-value">{html.escape(pinned)}</td>'
            f'<td class="current-value">{html.escape(current)}</td><td class="change">{html.escape(change)}</td></tr>')


def pinned_html(pinned: PinnedState | None, result, units: str = "SI", current: StateMonteCarlo | None = None) -> str:
    """The headline's comparison: each key number pinned and current, and the change; then, where either state has
    a Monte Carlo (the pinned one's kept with it, ``current`` the state shown's:
    :meth:`~pounding.report.StateMonteCarlo.of`), both means with their change and whether each closed form
    agrees; '' when nothing is pinned."""
    if pinned is None or result is None:
        return ""
    shown = display(units)
    rows = "".join(_row(css, d.quantity, d.value_text(d.pinned, shown), d.value_text(d.current, shown), d.change_text(shown))
                   for css, d in zip(_ROW_CSS, differences(pinned.estimate, result)))
    checked = monte_carlo_comparison(pinned.monte_carlo, current)
    if checked is not None:
        mean, verdicts = checked
        rows += _row("pin-monte-carlo", mean.quantity, mean.value_text(mean.pinned, shown), mean.value_text(mean.current, shown),
                     mean.change_text(shown))
        rows += _row("pin-verdict", "closed form against Monte Carlo", *verdicts, "")
    said = "Change: current minus pinned" + ("." if checked is not None else " (closed form).")
    return (f'<table class="pinned"><thead><tr><th></th><th>{COMPARISON_NAMES[0]}</th><th>{COMPARISON_NAMES[1]}</th>'
            f"<th>change</th></tr></thead><tbody>{rows}</tbody></table>"
            f'<p class="pinned-note">Pinned: {html.escape(pinned.name)}. {said}</p>')


class PinnedOverlay:
    """The pinned state's expected extreme force against the gap, dashed, on the page's force-against-gap figure
    (:class:`pounding.report.Figures`): its own gap marked; hidden, legend entry too, while nothing is pinned."""

    def __init__(self, figure):
        from bokeh.models import ColumnDataSource

        self.curve = ColumnDataSource(data={"gap": [], "force": []})
        self.point = ColumnDataSource(data={"gap": [], "force": []})
        line = figure.line("gap", "force", source=self.curve, legend_label=PINNED_LABEL, **_STYLE)
        dot = figure.scatter("gap", "force", source=self.point, color=_STYLE["color"], size=9, legend_label=PINNED_LABEL)
        figure.y_range.renderers = [*figure.y_range.renderers, line, dot]  # the axis fits the pinned curve too
        self.item = next(item for item in figure.legend[0].items if item.label.value == PINNED_LABEL)
        self.item.visible = False

    def fill(self, pinned: PinnedState | None, units: str = "SI") -> None:
        """Show ``pinned`` in ``units`` (None: nothing)."""
        if pinned is None:
            self.curve.data, self.point.data = {"gap": [], "force": []}, {"gap": [], "force": []}
        else:
            shown, snapshot = display(units), pinned.snapshot
            curve = snapshot.gap_curve
            self.curve.data = {"gap": curve.gaps / shown.length_scale, "force": curve.force_expected / shown.force_scale}
            self.point.data = {"gap": [snapshot.case.contact.gap / shown.length_scale],
                               "force": [snapshot.estimate.force_expected / shown.force_scale]}
        self.item.visible = pinned is not None


def overlay_distribution(figure, pinned: PinnedState | None, units: str = "SI") -> None:
    """Draw the pinned state's distribution of F_max, dashed, on the distribution ``figure`` (and widen its force
    axis to hold it)."""
    if pinned is None:
        return
    shown = display(units)
    forces, cdf = distribution_points(pinned.estimate)
    figure.line(forces / shown.force_scale, cdf, legend_label="pinned (closed form)", **_STYLE)
    top = pinned.estimate.force_max_distribution.quantile(0.999) / shown.force_scale
    end = figure.x_range.end
    if top > 0 and (end is None or 1.05 * top > end):
        figure.x_range.end = 1.05 * top


def pin_controls(dashboard):
    """The Pin and Unpin buttons and the comparison's export (a Panel column), bound to ``dashboard.model``."""
    import panel as pn

    m = dashboard.model
    pin = pn.widgets.Button(name="Pin this state", button_type="primary", width=130,
                            disabled=pn.bind(lambda *_: not m.can_pin(), m.param.result, m.param.snapshot))
    unpin = pn.widgets.Button(name="Unpin", button_type="light", width=80, disabled=pn.bind(lambda p: p is None, m.param.pinned))
    pin.on_click(lambda _event: m.pin())
    unpin.on_click(lambda _event: m.unpin())

    def export():
        if m.pinned is None or m.snapshot is None:
            return None
        for old in dashboard._exports:  # one export at a time on the disk, as the report's
            remove(old)
        folder = new_folder("pounding-comparison-")
        dashboard._exports[:] = [folder]
        name = f"pounding-comparison-{m.case_slug()}.html"
        download.filename = name
        current = m.current_state() or m.snapshot  # its plots not yet computed: the last computed, without studies
        return str(write_comparison(folder / name, m.pinned.snapshot, current, m.units, names=(m.pinned.name, m.case_name())))

    download = pn.widgets.FileDownload(callback=export, filename="pounding-comparison.html", label="Export comparison (HTML)",
                                       button_type="success", auto=True, embed=False, width=220,
                                       visible=pn.bind(lambda p: p is not None, m.param.pinned))
    return pn.Column(pn.Row(pin, unpin), download, margin=0)
