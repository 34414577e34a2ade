"""The pounding dashboard as a Panel component: :class:`PoundingDashboard`.

``PoundingDashboard()`` in a notebook cell shows it inline (after
``pn.extension()``); ``pounding dashboard`` and ``panel serve dashboard/app.py``
serve the same class in a template. Importing this module serves nothing and
changes no global state of the caller.

The view is thin: widgets made from the model's parameters (``model.py``), the
headline (``headline.py``), and plots whose data the library computes.
"""

from __future__ import annotations

import contextlib
import html
import io
from pathlib import Path

import panel as pn
import param

from dashboard.contacts import ONE_CONTACT, ROW_CSS, contacts_html, row_headline_html
from dashboard.headline import HEADLINE_CSS, headline_html, held_note
from dashboard.input_widgets import InputField
from dashboard.jobs import StudyJob
from dashboard.model import PoundingModel, input_key
from dashboard.pinning import PINNED_CSS, PinnedOverlay, pin_controls, pinned_html
from dashboard.runner import shared_pool
from dashboard.studies import ONE_CONTACT_STUDIES
from dashboard.tabs import LazyTabs
from dashboard.upload_widget import FileUpload
from dashboard.uploads import MAX_CASE_BYTES, MAX_RECORD_BYTES, MAX_RECORD_FILES, new_folder, remove, size_text
from dashboard.visibility import visible
from pounding.display_units import display
from pounding.report import Figures, StateMonteCarlo, case_provenance, write_report
from pounding.report.contacts import ContactHistory, RowSnapshot

__all__ = ["PoundingDashboard"]

TITLE = "pounding: how hard will two adjacent buildings hit each other?"

REDRAW_DELAY_MS = 150
"""The plots are redrawn this long after a new result, so that the headline (the number the user waits for)
reaches the browser and is painted before the larger plot data; changes in between give one redraw."""

GAP_PLOT_HEIGHT = 440
"""[px] The gap plot with its legend under the frame, one entry a row: the frame about 235 px high, 165 px with every entry shown."""
INLINE_PLOT_MIN_WIDTH = 560
"""[px] The gap plot's narrowest inline: its title (about 310 px) and its legend (about 300 px) fit beside the axes."""
INLINE_RESULTS_MIN_WIDTH = 500
"""[px] Inline, the results go under the inputs when the cell leaves them less than this beside."""

PAGE_CSS = """
.change-note { font-size: 12px; color: #335; }
"""
BUTTON_CSS = ".bk-btn[disabled] { opacity: 0.4 !important; cursor: not-allowed !important; filter: grayscale(100%); }"
"""Inside each button's shadow root: a disabled button greyed out, not a paler colour of an active one."""

def _session():
    """The session's document when served (None in a notebook or a script)."""
    doc = pn.state.curdoc
    return doc if doc is not None and doc.session_context is not None else None


SHAPING = ("units", "advanced", "contact_model", "ground_motion", "intensity", "code", "scaling", "envelope", "buildings_in_row",
           "floors_meet")
"""The model's inputs that decide which others apply or what unit they take: with :data:`SHAPING_BUILDING`, the only
ones whose change relabels the page."""
SHAPING_BUILDING = ("storeys", "hysteresis", "n")
"""Each building's inputs that decide which others apply or what unit they take."""


class PoundingDashboard(pn.viewable.Viewer):
    """The dashboard on one case: inputs in engineering terms, the headline, the plots, Monte Carlo beside.

    Parameters
    ----------
    model : PoundingModel, optional
        The inputs and results (a new one on the default preset when not given).
    """

    model = param.ClassSelector(class_=PoundingModel, constant=True)

    def __init__(self, compute_inline: bool = False, **params):
        doc = _session()
        if "model" not in params:
            schedule = (lambda fn: doc.add_next_tick_callback(fn)) if doc else None
            batch = (lambda: pn.io.hold(doc)) if doc else None
            submit = shared_pool().submit if doc and not compute_inline else None
            # the automatic check needs a live session to bring its verdict to: without one (a notebook executed and
            # exported), a verdict landing mid-export made the static page differ from run to run
            params["model"] = PoundingModel(schedule=schedule, batch=batch, submit=submit, check=doc is not None)
        super().__init__(**params)
        self._delay = (lambda fn: doc.add_timeout_callback(fn, REDRAW_DELAY_MS)) if doc else (lambda fn: fn())
        self._batch = (lambda: pn.io.hold(doc)) if doc else contextlib.nullcontext
        self._widgets: list[InputField] = []
        self._exports: list[Path] = []  # the folders of this session's exported reports
        if doc is not None:  # the session's files go with it
            doc.on_session_destroyed(lambda _context: self.close())
        self._build()

    # --- widgets -------------------------------------------------------------------

    def _widget(self, name: str, owner: param.Parameterized | None = None, **options):
        """The widget of input ``name`` of ``owner`` (default: the model; else one of its buildings), with the reason
        a typed number was refused under it."""
        owner = owner or self.model
        field = InputField(self.model, owner, name, input_key(self.model, owner, name), **options)
        self._widgets.append(field)
        return field.panel

    def _inputs(self, *names: str, owner: param.Parameterized | None = None) -> list:
        return [self._widget(name, owner) for name in names]

    def _building_card(self, building) -> pn.Card:
        names = ("storeys", "period", "mass", "stiffness", "damping_ratio", "hysteresis", "yield_drift", "yield_force",
                 "post_yield_ratio", "n", "beta_share", "alpha", "A", "beta", "gamma")
        widgets = self._inputs(*names, owner=building)
        self._widgets[-len(names) + names.index("stiffness")].widget.disabled = True  # derived from the period
        card = pn.Card(*widgets, title=f"Building {building.number}", collapsed=True, sizing_mode="stretch_width")
        if building.number > 2:  # in a row of three only
            card.visible = pn.bind(lambda count: count >= building.number, self.model.param.buildings_in_row)
        return card

    def _build(self) -> None:
        m = self.model
        self.records_upload = FileUpload(m.upload_records, self._refuse_upload, accept=".AT2,.at2,.csv,.txt", multiple=True,
                                         max_bytes=MAX_RECORD_BYTES, max_files=MAX_RECORD_FILES, sizing_mode="stretch_width")
        self.case_upload = FileUpload(self._on_case_file, self._refuse_upload, accept=".toml", max_bytes=MAX_CASE_BYTES,
                                      sizing_mode="stretch_width")
        def upload_error():
            return pn.pane.HTML(pn.bind(html.escape, m.param.upload_error), visible=pn.bind(bool, m.param.upload_error),
                                css_classes=["upload-refused"], styles={"color": "#c62828", "font-size": "12px"},
                                sizing_mode="stretch_width")
        self.case_download = pn.widgets.FileDownload(callback=lambda: io.StringIO(m.toml()), filename="case.toml",
                                                     label="Download the case (TOML)", button_type="light", sizing_mode="stretch_width")
        uploaded = pn.pane.Markdown(pn.bind(lambda names: ("Uploaded: " + ", ".join(names)) if names else "No records uploaded yet.",
                                            m.param.uploaded), sizing_mode="stretch_width", styles={"font-size": "12px"})
        self.sidebar = pn.Column(
            self._widget("preset"),
            pn.Card(*self._inputs("buildings_in_row", "floors_meet", "gap", "target_probability", "capacity", "restitution"),
                    title="Design", sizing_mode="stretch_width"),
            pn.Card(*self._inputs("ground_motion", "intensity", "pga", "G0", "omega_g", "xi_g", "record_set", "component",
                                  "scaling", "scale", "records_pga", "fit", "code", "ag", "ground_type", "spectrum_type", "SDS", "SD1", "TL"),
                    pn.Column(pn.pane.Markdown(f"Records: PEER .AT2 or two columns (time s, acceleration g), up to "
                                               f"{size_text(MAX_RECORD_BYTES)} each, {MAX_RECORD_FILES} at most:", margin=(0, 10),
                                               css_classes=["upload-limit"]),
                              self.records_upload, upload_error(), uploaded,
                              visible=pn.bind(lambda form: form == "recorded motions", m.param.ground_motion), sizing_mode="stretch_width"),
                    *self._inputs("duration", "envelope", "B1", "B2"),
                    title="Ground motion", collapsed=True, sizing_mode="stretch_width"),
            *(self._building_card(building) for building in m.buildings()),
            pn.Card(*(self._widget("contact_floor", building) for building in m.buildings()),
                    *self._inputs("contact_model", "contact_stiffness"), title="Contact", collapsed=True, sizing_mode="stretch_width"),
            pn.Card(self._widget("units"), self._widget("advanced"), self.case_download,
                    pn.pane.Markdown(f"Upload a case file (TOML, up to {size_text(MAX_CASE_BYTES)}):", margin=(0, 10)), self.case_upload,
                    upload_error(),
                    title="Units and case file", collapsed=True, sizing_mode="stretch_width"),
            sizing_mode="stretch_width",
        )
        m.param.watch(self._refresh_inputs, list(SHAPING))
        for building in m.buildings():
            building.param.watch(self._refresh_inputs, list(SHAPING_BUILDING))
        self._refresh_inputs()
        m.param.watch(self._show_refusals, "refused")

        self.error = pn.pane.Alert(pn.bind(lambda e: e or "ok", m.param.error), alert_type="danger",
                                   visible=pn.bind(bool, m.param.error), sizing_mode="stretch_width", css_classes=["input-error"])
        self.note = pn.pane.Markdown(m.param.note, css_classes=["change-note"], visible=pn.bind(bool, m.param.note), sizing_mode="stretch_width")
        self.headline = pn.pane.HTML(
            pn.bind(self._headline, m.param.result, m.param.units, m.param.capacity, m.monte_carlo_job.param.result,
                    m.design_gap_job.param.result, m.param.error, m.check_job.param.result, m.check_job.param.error,
                    m.param.refused, m.param.waiting, m.param.pinned),
            stylesheets=[HEADLINE_CSS, PINNED_CSS, ROW_CSS], sizing_mode="stretch_width", min_width=380,
        )
        self.export = pn.widgets.FileDownload(callback=self._export, filename="pounding-report.html", label="Export report (HTML)",
                                              button_type="success", disabled=pn.bind(lambda s: s is None, m.param.snapshot),
                                              auto=True, embed=False, width=200, stylesheets=[BUTTON_CSS])

        self.figures = Figures()
        self.contact_history = ContactHistory()
        self._fill_plots()
        self._redraw_pending = False
        m.param.watch(self._request_redraw, ["snapshot", "units", "pinned"])
        for job in (m.monte_carlo_job, m.design_gap_job):
            job.param.watch(self._request_redraw, "result")
        bokeh = lambda fig, **kw: pn.pane.Bokeh(fig, sizing_mode="stretch_width", **kw)  # noqa: E731
        gap_figure = self.figures.gap
        gap_figure.height = GAP_PLOT_HEIGHT
        self.pinned_overlay = PinnedOverlay(gap_figure)
        legend = gap_figure.legend[0]  # under the frame (Figures), one entry a row: two would be wider than the plot
        legend.orientation, legend.ncols = "vertical", 1
        self.gap_plot = bokeh(gap_figure, min_height=GAP_PLOT_HEIGHT)
        # a Bokeh pane's own visibility must not change once shown (Panel re-syncs its stylesheets and fails): its column's does
        one_contact = pn.bind(lambda row: not row, m.param.several_contacts)
        gap_area = self._gap_area = pn.Column(self.gap_plot, sizing_mode="stretch_width", margin=0, visible=one_contact)
        self.contacts = pn.pane.HTML(pn.bind(self._contacts, m.param.result, m.param.units, m.param.capacity, m.check_job.param.result),
                                     stylesheets=[ROW_CSS], sizing_mode="stretch_width", css_classes=["contacts-pane"],
                                     visible=m.param.several_contacts)
        one = lambda kind: pn.pane.Markdown(ONE_CONTACT[kind], visible=m.param.several_contacts,  # noqa: E731
                                            css_classes=["one-contact"], sizing_mode="stretch_width")
        single = lambda *plots: pn.Row(*plots, sizing_mode="stretch_width", visible=one_contact)  # noqa: E731

        self.tabs = LazyTabs(self, [
            ("Monte Carlo", self._monte_carlo_panel()),
            ("Distribution of F_max", "distribution"),
            ("Fragility", "fragility"),
            ("Ground motion", "hazard"),
            ("Spectra", pn.Column(one("spectra"), single(bokeh(self.figures.psd_ground), bokeh(self.figures.psd_velocity)),
                                  sizing_mode="stretch_width")),
            ("Hysteresis loops", pn.Column(one("hysteresis"), single(*(bokeh(h) for h in self.figures.hysteresis)),
                                           sizing_mode="stretch_width")),
            ("Force history", pn.Column(
                pn.Column(bokeh(self.contact_history.figure), sizing_mode="stretch_width", visible=m.param.several_contacts),
                pn.Column(bokeh(self.figures.contact), bokeh(self.figures.relative), bokeh(self.figures.ground),
                          sizing_mode="stretch_width", visible=one_contact),
                sizing_mode="stretch_width")),
        ])
        self.headline_column = pn.Column(self.headline, self.export, pin_controls(self), width=430)
        self.main = pn.Column(
            self.error, self.note,
            pn.Row(self.headline_column, pn.Column(gap_area, self.contacts, sizing_mode="stretch_width"), sizing_mode="stretch_width"),
            self.tabs.panel,
            sizing_mode="stretch_width",
        )

    def _job_controls(self, job: StudyJob, run, run_label: str, cancel_label: str, css: str) -> tuple:
        """A study's buttons (run, cancel), its progress bar and its status, bound to its job."""
        m = self.model
        button = lambda **options: pn.widgets.Button(stylesheets=[BUTTON_CSS], **options)  # noqa: E731
        start = button(name=run_label, button_type="primary", disabled=pn.bind(lambda r, s: r or s is None, job.param.running, m.param.result))
        stop = button(name=cancel_label, button_type="warning", disabled=pn.bind(lambda r: not r, job.param.running))
        start.on_click(lambda _event: run())
        stop.on_click(lambda _event: job.cancel())
        progress = pn.indicators.Progress(value=job.param.progress, max=100, width=260, css_classes=[f"{css}-progress"],
                                          visible=job.param.running)
        status = pn.pane.Markdown(job.param.status, css_classes=[f"{css}-status"])
        return start, stop, progress, status

    def _monte_carlo_panel(self) -> pn.Column:
        m = self.model
        self.run, self.cancel, self.progress, mc_status = self._job_controls(
            m.monte_carlo_job, m.run_monte_carlo, "Run Monte Carlo", "Cancel", "mc")
        self.run_design_gap, self.cancel_design_gap, self.design_gap_progress, design_gap_status = self._job_controls(
            m.design_gap_job, m.run_design_gap, "Monte Carlo design gap", "Cancel design gap", "design-gap")
        records = self._widget("records", width=220, sizing_mode=None)
        seed = self._widget("seed", width=160, sizing_mode=None)
        return pn.Column(
            pn.pane.Markdown(ONE_CONTACT_STUDIES, visible=m.param.several_contacts, css_classes=["one-contact"]),
            pn.pane.Markdown("Nonlinear time histories of the same buildings with pounding (the 'exact' method): the mean "
                             "F_max with its 95 % interval beside the estimate, and the gap for the target from the records' free motion."),
            pn.Row(records, seed),
            pn.Row(self.run, self.cancel, self.progress),
            mc_status,
            pn.Row(self.run_design_gap, self.cancel_design_gap, self.design_gap_progress),
            design_gap_status,
            sizing_mode="stretch_width",
        )

    def _refresh_inputs(self, *_events) -> None:
        """Show the inputs that apply, each labelled with its unit in the system shown."""
        m = self.model
        shown = display(m.units)
        dims = {owner: owner.dimensions() for owner in (m, *m.buildings())}
        for field in self._widgets:
            owner, name = field.owner, field.name
            if name in ("preset", "units", "advanced", "records", "seed"):
                continue
            field.visible = visible(m, owner, name)
            label = owner.param[name].label
            field.widget.name = f"{label} [{shown.label(**dims[owner][name])}]" if name in dims[owner] else label

    def _show_refusals(self, *_events) -> None:
        for field in self._widgets:
            field.show_refusal(self.model.refused)

    # --- outputs -------------------------------------------------------------------

    def _headline(self, result, units, capacity, _points, _design_gap, error, _check, _check_error, refused, waiting, pinned) -> str:
        m = self.model
        held = held_note(list(refused.values()), waiting)
        if result is None:
            text = "No result: the inputs are invalid (see the message above)." if error else "Computing..."
            return f'<div class="headline stale">{held}<p>{text}</p></div>'
        capacity_si = display(units).to_si(capacity, force=1)
        check, check_error = m.current_check(), m.check_error()
        if len(result.case.contacts) > 1:
            return row_headline_html(result, units, capacity_si, m.case_name(), check=check, checking=m.checks and check is None
                                     and not check_error, check_error=check_error, held=held, pinned=pinned is not None)
        return headline_html(result, units, capacity_si, m.monte_carlo_for_current_gap(), m.current_design_gap(), m.case_name(),
                             check=check, checking=m.checks and check is None and not check_error, check_error=check_error,
                             held=held, pinned=pinned_html(pinned, result, units,
                                                           StateMonteCarlo.of(result, check, m.monte_carlo_for_current_gap())),
                             gap_for_capacity=m.gap_for_capacity)

    def _contacts(self, result, units, capacity, _check) -> str:
        """The table of contacts of a case of several contacts ('' for one)."""
        return contacts_html(result, units, self.model.current_check(), display(units).to_si(capacity, force=1))

    def _request_redraw(self, *_events) -> None:
        if not self._redraw_pending:
            self._redraw_pending = True
            self._delay(self._redraw)

    def _redraw(self) -> None:
        self._redraw_pending = False
        m = self.model
        with self._batch():
            self._fill_plots()
            self.pinned_overlay.fill(m.pinned, m.units)
        self.tabs.refresh()

    def _fill_plots(self) -> None:
        """Put the snapshot's data in the plots: one contact's, or each contact's force (several contacts)."""
        m = self.model
        row = isinstance(m.snapshot, RowSnapshot)
        self.figures.fill(None if row else m.snapshot, m.units, m.monte_carlo_points(), m.current_design_gap())
        self.contact_history.fill(m.snapshot if row else None, m.units)

    def _refuse_upload(self, reason: str) -> None:
        self.model.upload_error = reason

    def _on_case_file(self, files: dict[str, bytes]) -> None:
        for name, content in files.items():
            self.model.upload_error = ""
            self.model.load_toml(content, name)

    def close(self) -> None:
        """Remove the session's files (uploaded records, exported reports): its page has closed."""
        self.model.close()
        for folder in self._exports:
            remove(folder)
        self._exports.clear()

    def _export(self):
        from dataclasses import replace

        m = self.model
        if m.snapshot is None:
            return None
        capacity = display(m.units).to_si(m.capacity, force=1)  # the page's capacity, as the headline reads it
        if isinstance(m.snapshot, RowSnapshot):
            snapshot = replace(m.snapshot, capacity=capacity)
        else:
            snapshot = replace(m.snapshot, monte_carlo=m.monte_carlo_points(), design_gap=m.current_design_gap(), capacity=capacity)
        check = m.current_check()  # the page's own check of this very estimate: the report takes it, not a second run
        if check is not None and snapshot.estimate is m.result:
            snapshot = replace(snapshot, check=check)
        for old in self._exports:  # the browser has the report before: one at a time on the disk
            remove(old)
        folder = new_folder("pounding-report-")
        self._exports[:] = [folder]
        name = f"pounding-report-{m.case_slug()}.html"
        self.export.filename = name
        command = "pounding dashboard (Export report)"
        if m.case_file_name:  # an uploaded case file: the report names it, not the preset shown before
            source = f"{m.case_file_name}{' (modified in the dashboard)' if m.changes() else ''}"
            provenance = case_provenance(m.case_file(), None, source=source, command=command, units=m.units)
        else:
            provenance = case_provenance(m.case_file(), m.preset, command=command, units=m.units)
        return str(write_report(folder / name, snapshot, m.units, provenance=provenance))

    def template(self) -> pn.template.FastListTemplate:
        """The served page: a template with the inputs in its sidebar."""
        page = pn.template.FastListTemplate(title=TITLE, sidebar=[self.sidebar], main=[self.main], sidebar_width=340,
                                            theme_toggle=False, font_url="", header_background="#0b4f8a")
        page.config.raw_css.append(PAGE_CSS)
        return page

    def __panel__(self):
        """Inline, in a notebook cell of any width: the inputs, the headline and the gap plot side by side where
        they fit, else wrapped one under the other; the gap plot never narrower than its legend and title
        (:data:`INLINE_PLOT_MIN_WIDTH`)."""
        plot = pn.Column(self._gap_area, self.contacts, sizing_mode="stretch_width", styles={"flex": f"1 1 {INLINE_PLOT_MIN_WIDTH}px"})
        results = pn.Column(self.error, self.note,
                            pn.FlexBox(self.headline_column, plot, flex_wrap="wrap", sizing_mode="stretch_width"),
                            self.tabs.panel, sizing_mode="stretch_width", styles={"flex": f"1 1 {INLINE_RESULTS_MIN_WIDTH}px"})
        return pn.FlexBox(pn.Column(self.sidebar, width=340), results, flex_wrap="wrap", sizing_mode="stretch_width",
                          stylesheets=[PAGE_CSS])
