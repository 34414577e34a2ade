"""The pounding dashboard: a thin Panel view on ``dashboard/model.py``.

Serve with ``pounding dashboard`` or ``panel serve dashboard/app.py``. It opens
on the paper's Section 5 case (T1 = 1.2 s, T2 = 0.4 s); every change of an
input recomputes the estimates, F_e against the gap, and the spectra,
hysteresis loops and pounding force history shown in tabs (no button). The reduced-sample Monte Carlo and the
Monte Carlo design gap run on request off the event loop; *Export report* downloads the static HTML report of the current state.
"""

from __future__ import annotations

import contextlib
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

_ROOT = Path(__file__).resolve().parent.parent
if str(_ROOT) not in sys.path:  # `panel serve dashboard/app.py` from anywhere
    sys.path.insert(0, str(_ROOT))

import panel as pn  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

from dashboard.model import PoundingModel  # noqa: E402
from pounding.report import RESULT_CSS, Figures, result_html, write_report  # noqa: E402
from pounding.contact import contact_law  # noqa: E402
from pounding.units import unit_system  # noqa: E402

pn.extension(notifications=False)

# One BLAS thread in the server: its matrices have a few dozen rows, and an
# idle OpenBLAS worker spins after every call. Measured on 2 cores: 110 ms of
# CPU per change of input, more than all the rest of the server's work.
threadpool_limits(limits=1, user_api="blas")

TITLE = "pounding: expected extreme pounding force between adjacent buildings"


REDRAW_DELAY_MS = 150
"""The plots are redrawn this long after a change, so that the result card
(the number the user is waiting for) reaches the browser and is painted
before the larger plot data arrives; changes in between give one redraw."""


def _session_schedule():
    """Run a function on this session's event loop (thread-safe)."""
    doc = pn.state.curdoc
    if doc is None or doc.session_context is None:
        return None
    return lambda fn: doc.add_next_tick_callback(fn)


def _session_delay():
    """Run a function on this session's event loop after ``REDRAW_DELAY_MS``."""
    doc = pn.state.curdoc
    if doc is None or doc.session_context is None:
        return None
    return lambda fn: doc.add_timeout_callback(fn, REDRAW_DELAY_MS)


def _session_batch():
    """Batch the page's updates of one change into one message.

    Not ``doc.models.freeze()``: leaving it always recomputes the whole
    document's model graph (about 100 ms for this page), and a change of
    inputs adds or removes no model."""
    doc = pn.state.curdoc
    if doc is None or doc.session_context is None:
        return None

    @contextlib.contextmanager
    def batch():
        with pn.io.hold(doc):
            yield

    return batch


def _unit_label(model: PoundingModel, name: str) -> str:
    """A dimensional input's name with its unit in the current system."""
    u = unit_system(model.units)
    L, F = u.length_label, u.force_label
    base = name.rsplit("_", 1)
    if name.startswith(("beta_", "gamma_")):
        n = getattr(model, f"n_{base[1]}")
        return f"Bouc-Wen {base[0]} [1/{L}^{n:g}]"
    power = contact_law(model.contact_model).stiffness_exponent
    exponent = "" if power == 1 else f"^{power:g}"
    return {
        "mass": f"storey mass [{u.mass_label}]",
        "stiffness": f"storey stiffness [{F}/{L}]",
        "gap": f"gap [{L}]",
        "contact_stiffness": f"contact stiffness [{F}/{L}{exponent}]",
        "G0": f"G0 [{L}^2/s^3]",
    }[base[0] if base[0] in ("mass", "stiffness") else name]


class Dashboard:
    """Widgets made from the model's parameters, and the output panes."""

    def __init__(self, model: PoundingModel, schedule=None, batch=None, delay=None):
        self.model = model
        m = model
        self._inputs = {}
        slider = pn.widgets.FloatSlider
        number = pn.widgets.FloatInput

        def widget(parameter, kind, **options):
            w = kind.from_param(m.param[parameter], **options)
            self._inputs[parameter] = w
            return w

        def building(b):
            return pn.Card(
                widget(f"storeys_{b}", pn.widgets.IntInput, name="storeys"),
                widget(f"period_{b}", slider, name="period T1 [s]" if b == 1 else "period T2 [s]", format="0.00"),
                widget(f"mass_{b}", number, format="0.000e0"),
                widget(f"stiffness_{b}", number),
                widget(f"damping_ratio_{b}", slider),
                widget(f"alpha_{b}", slider),
                widget(f"A_{b}", slider),
                widget(f"beta_{b}", number),
                widget(f"gamma_{b}", number),
                widget(f"n_{b}", slider),
                title=f"Building {b}", sizing_mode="stretch_width",
            )

        self.sidebar = [
            widget("preset", pn.widgets.Select, name="case (preset)"),
            widget("units", pn.widgets.RadioButtonGroup, name="units"),
            pn.pane.Markdown(
                "All storeys of a building are alike. One storey: the period and mass fix the stiffness; "
                "more storeys: mass and stiffness fix the period.", styles={"font-size": "12px"},
            ),
            building(1),
            building(2),
            pn.Card(
                widget("gap", number, format="0.0000"),
                widget("restitution", slider),
                widget("contact_stiffness", number, format="0.000e0"),
                widget("contact_model", pn.widgets.Select),
                widget("level_1", pn.widgets.IntInput),
                widget("level_2", pn.widgets.IntInput),
                title="Contact", sizing_mode="stretch_width",
            ),
            pn.Card(
                widget("G0", number, format="0.00000e0"),
                widget("omega_g", slider),
                widget("xi_g", slider),
                widget("duration", slider),
                widget("envelope", pn.widgets.RadioButtonGroup),
                widget("B1", number),
                widget("B2", number),
                title="Excitation (Kanai-Tajimi)", sizing_mode="stretch_width",
            ),
        ]
        m.param.watch(self._relabel, ["units", "contact_model", "n_1", "n_2", "storeys_1", "storeys_2"])
        self._relabel()

        self.error = pn.pane.Alert(
            pn.bind(lambda e: e or "ok", m.param.error), alert_type="danger",
            visible=pn.bind(bool, m.param.error), sizing_mode="stretch_width", css_classes=["input-error"],
        )
        self.result = pn.pane.HTML(
            pn.bind(
                self._card, m.param.snapshot, m.param.units, m.param.mc_points, m.param.mc_status, m.param.mc_running,
                m.param.design_gap_result, m.param.design_gap_status, m.param.design_gap_running,
            ),
            sizing_mode="stretch_width",
            stylesheets=[RESULT_CSS],
        )
        # Monte Carlo
        self.run = pn.widgets.Button(name="Run Monte Carlo", button_type="primary", disabled=pn.bind(lambda r, s: r or s is None, m.param.mc_running, m.param.snapshot))
        self.cancel = pn.widgets.Button(name="Cancel", button_type="warning", disabled=pn.bind(lambda r: not r, m.param.mc_running))
        self.run.on_click(lambda _event: m.run_monte_carlo())
        self.cancel.on_click(lambda _event: m.cancel_monte_carlo())
        self.progress = pn.indicators.Progress(value=m.param.mc_progress, max=100, width=260, css_classes=["mc-progress"])
        # The design gap: the same records' free motion (no contact), so the case's gap does not enter.
        self.run_design_gap = pn.widgets.Button(
            name="Monte Carlo design gap", button_type="primary",
            disabled=pn.bind(lambda r, s: r or s is None, m.param.design_gap_running, m.param.snapshot),
        )
        self.cancel_design_gap = pn.widgets.Button(
            name="Cancel design gap", button_type="warning", disabled=pn.bind(lambda r: not r, m.param.design_gap_running)
        )
        self.run_design_gap.on_click(lambda _event: m.run_design_gap())
        self.cancel_design_gap.on_click(lambda _event: m.cancel_design_gap())
        self.design_gap_progress = pn.indicators.Progress(
            value=m.param.design_gap_progress, max=100, width=260, css_classes=["design-gap-progress"]
        )
        self.export = pn.widgets.FileDownload(
            callback=self._export, filename="pounding-report.html", label="Export report (HTML)", button_type="success",
            disabled=pn.bind(lambda s: s is None, m.param.snapshot), auto=True, embed=False,
        )
        monte_carlo = pn.Card(
            pn.Row(pn.widgets.IntSlider.from_param(m.param.records, width=220), pn.widgets.IntInput.from_param(m.param.seed, width=90)),
            pn.Row(self.run, self.cancel, self.progress),
            pn.pane.Markdown(m.param.mc_status, css_classes=["mc-status"]),
            pn.Row(self.run_design_gap, self.cancel_design_gap, self.design_gap_progress),
            pn.pane.Markdown(m.param.design_gap_status, css_classes=["design-gap-status"]),
            title="Reduced-sample Monte Carlo (the 'exact' method)", sizing_mode="stretch_width",
        )

        # Plots: Bokeh figures whose sources are refilled in place. They are
        # redrawn on the next tick, after the result card has gone out, and
        # several quick changes give one redraw.
        self.figures = Figures()
        self.figures.fill(m.snapshot, m.units, tuple(m.mc_points), m.current_design_gap())
        self._schedule = delay or schedule or (lambda fn: fn())
        self._batch = batch or contextlib.nullcontext
        self._redraw_pending = False
        m.param.watch(self._request_redraw, ["snapshot", "units", "mc_points", "design_gap_result"])
        bokeh = lambda fig: pn.pane.Bokeh(fig, sizing_mode="stretch_width")  # noqa: E731

        self.main = [
            pn.Column(self.error, pn.Row(self.result, pn.Column(self.export), sizing_mode="stretch_width"), sizing_mode="stretch_width"),
            monte_carlo,
            bokeh(self.figures.gap),
            # Dynamic tabs: only the open tab is in the browser, so a change
            # repaints two plots, not five (the browser's repaint is most of
            # a change's cost when several sessions share a machine).
            pn.Tabs(
                ("Spectra", pn.Row(bokeh(self.figures.psd_ground), bokeh(self.figures.psd_velocity), sizing_mode="stretch_width")),
                ("Hysteresis loops", pn.Row(*(bokeh(h) for h in self.figures.hysteresis), sizing_mode="stretch_width")),
                ("Pounding force history", bokeh(self.figures.contact)),
                dynamic=True, sizing_mode="stretch_width", css_classes=["plot-tabs"],
            ),
        ]

    def _request_redraw(self, *_events):
        if not self._redraw_pending:
            self._redraw_pending = True
            self._schedule(self._redraw)

    def _redraw(self):
        self._redraw_pending = False
        m = self.model
        with self._batch():
            self.figures.fill(m.snapshot, m.units, tuple(m.mc_points), m.current_design_gap())

    def _relabel(self, *_events):
        m = self.model
        for name in ("G0", "gap", "contact_stiffness", *(f"{k}_{b}" for b in (1, 2) for k in ("mass", "stiffness", "beta", "gamma"))):
            self._inputs[name].name = _unit_label(m, name)
        for b in (1, 2):
            single = getattr(m, f"storeys_{b}") == 1
            self._inputs[f"period_{b}"].disabled = not single
            self._inputs[f"stiffness_{b}"].disabled = single

    def _card(self, snapshot, units, _points, status, running, _design_gap, design_gap_status, design_gap_running):
        # Bound to every parameter the card shows (a study's end may leave its status unchanged); the
        # studies matching the current case come from the model.
        if snapshot is None:
            return '<div class="pounding-result stale"><p>No result: the inputs are invalid (see the message above).</p></div>'
        m = self.model
        current = m.monte_carlo_for_current_gap()
        note = "running..." if running else ("not run for these inputs" if not status or "done" in status else status)
        design_gap_note = (
            "running..." if design_gap_running
            else "not run for these inputs (button Monte Carlo design gap)" if not design_gap_status or "done" in design_gap_status
            else design_gap_status
        )
        return result_html(snapshot, units, current, note, m.current_design_gap(), design_gap_note)

    def _export(self):
        m = self.model
        if m.snapshot is None:
            return None
        snapshot = replace(m.snapshot, monte_carlo=tuple(m.mc_points), design_gap=m.current_design_gap())
        folder = Path(tempfile.mkdtemp(prefix="pounding-report-"))
        name = f"pounding-report-{snapshot.case.name}.html"
        self.export.filename = name
        return str(write_report(folder / name, snapshot, m.units))


# Panel's Fast design links its web font (Open Sans) from Google: the page must
# load with no network, so drop it (this process serves only this app); the
# system sans-serif font is used.
pn.theme.Fast._resources = {**pn.theme.Fast._resources, "font": {}}


def create_app() -> pn.template.FastListTemplate:
    schedule, batch = _session_schedule(), _session_batch()
    model = PoundingModel(schedule=schedule, batch=batch)
    view = Dashboard(model, schedule, batch, _session_delay())
    template = pn.template.FastListTemplate(title=TITLE, sidebar=view.sidebar, main=view.main, sidebar_width=360, theme_toggle=False,
        font_url="",  # no web font: the page needs no network
    )
    template.model = model  # for tests and benchmarks
    return template


create_app().servable()
