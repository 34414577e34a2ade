"""What the dashboard shows for one case, and the static HTML report of it.

:func:`compute_snapshot` runs the library once for a case (one
linearization, passed to every estimator): both closed-form estimates, force
against gap, the power spectra, one seeded record's hysteresis loops beside
the equivalent linear storeys. The plot builders and :func:`result_html` turn a
:class:`Snapshot` into HoloViews plots and an HTML result card; the dashboard
shows them live and :func:`write_report` writes them to one self-contained
HTML file (all JS/CSS inline, interactive Bokeh plots, opens offline): the
dashboard's *Export* button and ``pounding report`` both call it.

Nothing here computes physics: every number comes from the library. Units:
SI inside; :class:`Display` scales for the page (forces in kN/MN or kgf).
"""

from __future__ import annotations

import html
import math
import os
import re
import tempfile
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from .case import Case
from .errors import SimulationError
from .estimator import DEFAULT_TARGET_PROBABILITY, Estimate, GapCurve, estimate
from .linearization import equivalent_storey_force, linearize_pair
from .response import psd_relative_velocity
from .simulation import SimulationResult, TimeHistory, simulate_record
from .units import KGF_CM_S, SI, UNIT_SYSTEMS, UnitSystem

__all__ = [
    "DISPLAY_UNITS",
    "Display",
    "MonteCarloPoint",
    "Snapshot",
    "compute_snapshot",
    "display",
    "Figures",
    "report_html",
    "result_html",
    "write_report",
]

DEFAULT_SEED = 1
"""Seed of the study whose record the hysteresis loops show."""
DEFAULT_RECORD = 0
"""Index of that record."""
GAP_POINTS = 41
"""Gaps of the force-versus-gap curve."""
PSD_POINTS = 400
"""Frequencies of the spectra."""


# --- display units -------------------------------------------------------------


@dataclass(frozen=True)
class Display:
    """How numbers are shown: a unit system for inputs, and the units an
    engineer reads results in.

    Attributes
    ----------
    system : UnitSystem
        Units of the case's inputs.
    force_unit, force_scale : str, float
        Force unit and its size [N] (``kN`` = 1e3; switched to MN above 1 MN).
    length_unit, length_scale : str, float
        Unit of displacements, gaps, penetrations and its size [m].
    velocity_unit, velocity_scale : str, float
        [m/s] per unit.
    """

    system: UnitSystem
    force_unit: str
    force_scale: float
    length_unit: str
    length_scale: float
    velocity_unit: str
    velocity_scale: float

    def force(self, value: float | None) -> str:
        """A force [N] as text with its unit, 4 significant digits."""
        if value is None or not math.isfinite(value):
            return "n/a"
        if self.force_unit == "kN" and abs(value) >= 1e6:
            return f"{value / 1e6:.4g} MN"
        return f"{value / self.force_scale:.4g} {self.force_unit}"

    def length(self, value: float | None) -> str:
        if value is None or not math.isfinite(value):
            return "n/a"
        return f"{value / self.length_scale:.4g} {self.length_unit}"

    def velocity(self, value: float | None) -> str:
        if value is None or not math.isfinite(value):
            return "n/a"
        return f"{value / self.velocity_scale:.4g} {self.velocity_unit}"


DISPLAY_UNITS = {
    SI.name: Display(SI, "kN", 1e3, "mm", 1e-3, "m/s", 1.0),
    KGF_CM_S.name: Display(KGF_CM_S, "kgf", KGF_CM_S.force, "cm", KGF_CM_S.length, "cm/s", KGF_CM_S.length),
}


def display(units: str) -> Display:
    """The :class:`Display` of a unit system's name ("SI" or "kgf-cm-s")."""
    if units not in UNIT_SYSTEMS:
        from .errors import CaseError

        raise CaseError("units", f"unknown unit system {units!r}; allowed: {', '.join(UNIT_SYSTEMS)}")
    return DISPLAY_UNITS[units]


# --- the computed state --------------------------------------------------------


@dataclass(frozen=True)
class MonteCarloPoint:
    """Summary of one Monte Carlo study: mean extreme force [N] with its 95 %
    confidence interval [N], pounding fraction [-], at ``gap`` [m]."""

    gap: float
    records: int
    seed: int
    force_max_mean: float
    force_low: float
    force_high: float
    pounding_fraction: float

    @classmethod
    def from_result(cls, result: SimulationResult) -> MonteCarloPoint:
        low, high = result.force_max_confidence_interval
        return cls(
            result.case.contact.gap, result.n_records, result.seed, result.force_max_mean, low, high, result.pounding_fraction
        )


@dataclass(frozen=True, eq=False)
class Snapshot:
    """Everything shown for one case; all SI.

    Attributes
    ----------
    case : Case
    linearized : tuple of two LinearizedBuilding
    estimate : Estimate
    gap_curve : GapCurve
    omega : ndarray
        Circular frequencies of the spectra [rad/s].
    psd_ground : ndarray
        Two-sided PSD of ground acceleration [m^2/s^3] (Eq. 7).
    psd_velocity : ndarray
        Two-sided PSD of the relative velocity at the contact floors [m^2/s].
    history : TimeHistory or None
        Record ``record`` of the study seeded ``seed``; None if it failed.
    history_error : str
        Why ``history`` is None.
    equivalent_force : tuple of two ndarray
        Restoring force of the equivalent linear storeys along the record's drifts [N].
    seed, record : int
    monte_carlo : tuple of MonteCarloPoint
        Studies of this case (at any gap) to show beside the estimates.
    """

    case: Case
    linearized: tuple
    estimate: Estimate
    gap_curve: GapCurve
    omega: np.ndarray
    psd_ground: np.ndarray
    psd_velocity: np.ndarray
    history: TimeHistory | None
    history_error: str
    equivalent_force: tuple
    seed: int = DEFAULT_SEED
    record: int = DEFAULT_RECORD
    monte_carlo: tuple = field(default=())


def gap_grid(case: Case, result: Estimate, points: int = GAP_POINTS) -> np.ndarray:
    """Gaps [m] from 0 past the required gap and twice the case's gap, with the case's gap among them."""
    top = max(1.25 * result.required_gap, 2.0 * case.contact.gap, 1e-3)
    return np.unique(np.append(np.linspace(0.0, top, points), case.contact.gap))


def compute_snapshot(
    case: Case,
    seed: int = DEFAULT_SEED,
    record: int = DEFAULT_RECORD,
    target_probability: float = DEFAULT_TARGET_PROBABILITY,
    monte_carlo: tuple = (),
) -> Snapshot:
    """Run the library once for ``case``: the linearization is computed once and shared.

    Raises whatever the library raises for an impossible case (``CaseError``,
    ``ConvergenceError``); a failed record is kept in ``history_error``.
    """
    linearized = linearize_pair(case)
    result = estimate(case, target_probability, linearized=linearized)
    curve = result.gap_curve(gap_grid(case, result))
    omega = np.geomspace(0.3, case.excitation.cutoff_frequency, PSD_POINTS)
    psd_ground = np.asarray(case.excitation.spectrum.psd(omega), dtype=float)
    psd_velocity = psd_relative_velocity(case, linearized, omega)
    history, history_error, equivalent = None, "", ()
    try:
        history = simulate_record(case, seed, record)
    except SimulationError as error:
        history_error = str(error)
    if history is not None:
        equivalent = tuple(
            equivalent_storey_force(lin, history.time, history.drift[:, [history.floor(b, j + 1) for j in range(lin.building.n_storeys)]])
            for b, lin in enumerate(linearized, start=1)
        )
    return Snapshot(
        case, linearized, result, curve, omega, psd_ground, psd_velocity, history, history_error, equivalent, seed, record,
        tuple(monte_carlo),
    )


# --- the result card -----------------------------------------------------------


def _row(label: str, recommended: str, paper: str, css: str = "") -> str:
    return f'<tr class="{css}"><th>{label}</th><td>{recommended}</td><td>{paper}</td></tr>'


def result_html(snapshot: Snapshot, units: str = "SI", monte_carlo: MonteCarloPoint | None = None, monte_carlo_note: str = "") -> str:
    """The result card: recommended and paper's F_e side by side, each with its chain.

    ``monte_carlo`` is a study of exactly this case (shown beside F_e);
    ``monte_carlo_note`` says why none is shown.
    """
    d = display(units)
    e, p, case = snapshot.estimate, snapshot.estimate.paper, snapshot.case
    rate = "1/s"
    stationary = case.excitation.stationary
    sigma_paper = d.velocity(e.sigma_relative_velocity) if stationary else d.velocity(p.sigma_relative_velocity_equivalent) + " (sigma_eq, Eq. 29)"
    rows = [
        _row(
            "expected extreme pounding force F<sub>e</sub>",
            f'<span class="fe-recommended">{d.force(e.force_expected)}</span>',
            f'<span class="fe-paper">{d.force(p.force_expected)}</span>',
            "headline",
        ),
        _row("sigma of relative displacement", d.length(e.sigma_relative_displacement), d.length(e.sigma_relative_displacement)),
        _row("sigma of relative velocity", d.velocity(e.sigma_relative_velocity), sigma_paper),
        _row("crossing rate", f"{e.upcrossing_rate:.4g} {rate} (nu<sub>0</sub><sup>+</sup>)", f"{p.crossing_rate:.4g} {rate} (nu, Eq. 24)"),
        _row("effective duration", f"{case.excitation.duration:.4g} s", f"{p.duration_effective:.4g} s"),
        _row("peak factor", "(over the gap: no single factor)", f"{p.peak_factor:.4g} (Davenport, Eq. 23)"),
        _row("expected impact velocity", d.velocity(e.relative_velocity_expected), d.velocity(p.relative_velocity_expected)),
        _row("peak penetration", "n/a", d.length(p.penetration_expected)),
        _row("peak force ratio K(e)", f"{e.peak_force_ratio:.4g}", "1 (undamped Hertz)"),
        _row("expected number of impacts", f"{e.impacts_expected:.4g}", "(ignores the gap)"),
    ]
    if monte_carlo is not None:
        mc = (
            f'<span class="mc-mean">{d.force(monte_carlo.force_max_mean)}</span> '
            f"(95 % CI {d.force(monte_carlo.force_low)} to {d.force(monte_carlo.force_high)}; "
            f"{monte_carlo.records} records, seed {monte_carlo.seed}; pounding in {100 * monte_carlo.pounding_fraction:.0f} %)"
        )
    else:
        mc = html.escape(monte_carlo_note or "not run")
    summary = (
        f'<p class="probability">Probability of pounding during the {case.excitation.duration:g} s record: '
        f'<b><span class="pounding-probability">{100 * e.pounding_probability:.3g} %</span></b> '
        f"at the gap of {d.length(case.contact.gap)}. "
        f'Gap for {100 * e.target_probability:.0f} % probability of no pounding: '
        f'<b><span class="required-gap">{d.length(e.required_gap)}</span></b> '
        f"(SRSS {d.length(e.separation_rules['srss'])}, ABS {d.length(e.separation_rules['abs'])}, "
        f"DDC {d.length(e.separation_rules['ddc'])}).</p>"
        f'<p class="monte-carlo">Monte Carlo mean F<sub>max</sub>: {mc}</p>'
    )
    summary += f'<p class="measured-accuracy">Recommended F<sub>e</sub>: {html.escape(e.measured_accuracy)} (docs/estimator.md).</p>'
    if e.warnings:
        summary += "".join(f'<p class="estimate-warning">&#9888; {html.escape(w)}</p>' for w in e.warnings)
    return (
        '<div class="pounding-result">'
        "<table><thead><tr><th></th><th>recommended (gap-aware)</th><th>paper (Eq. 12-30)</th></tr></thead><tbody>"
        + "".join(rows)
        + "</tbody></table>"
        + summary
        + "</div>"
    )


RESULT_CSS = """
.pounding-result table { border-collapse: collapse; font-size: 14px; }
.pounding-result th, .pounding-result td { padding: 3px 10px; border-bottom: 1px solid #ddd; text-align: left; }
.pounding-result tr.headline td { font-size: 20px; font-weight: bold; color: #0b4f8a; }
.pounding-result p { font-size: 14px; margin: 6px 0; }
.pounding-result p.estimate-warning { color: #8a4b00; }
.pounding-result p.measured-accuracy { color: #555; font-size: 0.9em; }
"""


# --- plots ---------------------------------------------------------------------

_NAN2 = np.full(2, np.nan)


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
        from bokeh.models import ColumnDataSource, HoverTool, LinearAxis, Range1d, Whisker
        from bokeh.plotting import figure

        common = dict(output_backend="canvas", sizing_mode="stretch_width", tools="pan,wheel_zoom,box_zoom,reset,save")
        cds = lambda **columns: ColumnDataSource(data=columns)  # noqa: E731
        self.sources = {
            "gap": cds(gap=[], force=[], paper=[], probability=[]),
            "current": cds(gap=[], force=[]),
            "marker": cds(gap=[], force=[]),
            "required": cds(gap=[], probability=[]),
            "mc": cds(gap=[], force=[], low=[], high=[], fraction=[]),
            "psd_ground": cds(omega=[], ground=[]),
            "psd_velocity": cds(omega=[], velocity=[]),
            "hysteresis1": cds(drift=[], force=[], equivalent=[]),
            "hysteresis2": cds(drift=[], force=[], equivalent=[]),
            "impact1": cds(drift=[], force=[]),
            "impact2": cds(drift=[], force=[]),
            "contact": cds(time=[], force=[]),
        }
        src = self.sources

        g = figure(title="Expected extreme pounding force against the gap", height=340, **common)
        g.extra_y_ranges = {"probability": Range1d(0.0, 1.02)}
        g.add_layout(LinearAxis(y_range_name="probability", axis_label="probability of pounding [-]"), "right")
        g.line("gap", "force", source=src["gap"], color="#1f77b4", line_width=2, legend_label="recommended E[F_max]")
        g.line("gap", "paper", source=src["gap"], color="#d62728", line_dash="dashed", line_width=2, legend_label="paper F_e (gap-independent)")
        g.line("gap", "probability", source=src["gap"], color="#2ca02c", y_range_name="probability", legend_label="probability of pounding")
        g.line("gap", "force", source=src["marker"], color="#555555", line_dash="dotted")
        g.scatter("gap", "force", source=src["current"], color="#1f77b4", size=11, legend_label="current gap")
        g.line("gap", "probability", source=src["required"], color="#2ca02c", line_dash="dashdot", y_range_name="probability",
               legend_label="gap needed for the target")
        g.add_layout(Whisker(base="gap", lower="low", upper="high", source=src["mc"], line_color="black"))
        g.scatter("gap", "force", source=src["mc"], color="black", marker="square", size=8, legend_label="Monte Carlo mean F_max (95 % CI)")
        g.scatter("gap", "fraction", source=src["mc"], color="#2ca02c", marker="triangle", size=8, y_range_name="probability",
                  legend_label="Monte Carlo pounding fraction")
        g.legend.click_policy = "hide"
        g.add_layout(g.legend[0], "right")  # beside the plot: the curves fill its corners
        g.add_tools(HoverTool(tooltips=[("gap", "@gap"), ("force", "@force")]))
        self.gap = g

        self.psd_ground = figure(title="Ground acceleration PSD (two-sided, Eq. 7)", height=300, x_axis_type="log", y_axis_type="log", **common)
        self.psd_ground.line("omega", "ground", source=src["psd_ground"], color="#7f7f7f", line_width=2)
        self.psd_velocity = figure(
            title="Relative velocity PSD at the contact floors (linearized pair)", height=300, x_axis_type="log", y_axis_type="log", **common
        )
        self.psd_velocity.line("omega", "velocity", source=src["psd_velocity"], color="#1f77b4", line_width=2)
        for f in (self.psd_ground, self.psd_velocity):
            f.xaxis.axis_label = "circular frequency [rad/s]"

        self.hysteresis = []
        for b in (1, 2):
            h = figure(title=f"Building {b}, storey 1, one record", height=320, **common)
            h.line("drift", "equivalent", source=src[f"hysteresis{b}"], color="#ff7f0e", line_dash="dashed", alpha=0.8,
                   legend_label="equivalent linear (Eq. 19)")
            h.line("drift", "force", source=src[f"hysteresis{b}"], color="#1f77b4", legend_label="Bouc-Wen")
            h.scatter("drift", "force", source=src[f"impact{b}"], color="#d62728", size=4, legend_label="during impact")
            h.legend.location = "top_left"
            h.legend.click_policy = "hide"
            self.hysteresis.append(h)
        self.contact = figure(title="Pounding force during the record", height=230, **common)
        self.contact.line("time", "force", source=src["contact"], color="#d62728")
        self.contact.xaxis.axis_label = "time [s]"

    @property
    def all(self) -> list:
        return [self.gap, self.psd_ground, self.psd_velocity, *self.hysteresis, self.contact]

    def fill(self, snapshot: Snapshot | None, units: str = "SI", monte_carlo: tuple = ()) -> None:
        """Show ``snapshot`` (None: empty plots) in ``units``, with Monte Carlo points."""
        d = display(units)
        fs, ls, vs = d.force_scale, d.length_scale, d.velocity_scale
        src = self.sources
        # axis labels
        self.gap.xaxis.axis_label = f"gap [{d.length_unit}]"
        self.gap.yaxis[0].axis_label = f"expected extreme force [{d.force_unit}]"
        self.psd_ground.yaxis.axis_label = f"S_g [{d.length_unit}^2/s^3]"
        self.psd_velocity.yaxis.axis_label = f"S_V [({d.velocity_unit})^2 s]"
        for h in self.hysteresis:
            h.xaxis.axis_label = f"storey drift [{d.length_unit}]"
            h.yaxis.axis_label = f"restoring force [{d.force_unit}]"
        self.contact.yaxis.axis_label = f"pounding force [{d.force_unit}]"
        if snapshot is None:
            for source in src.values():
                _refill(source, **{key: [] for key in source.data})
            return
        curve = snapshot.gap_curve
        paper = np.nan if curve.paper_force_expected is None else curve.paper_force_expected / fs
        force = curve.force_expected / fs
        _refill(src["gap"], gap=curve.gaps / ls, force=force, paper=np.full(curve.gaps.size, paper), probability=curve.pounding_probability)
        gap = snapshot.case.contact.gap / ls
        _refill(src["current"], gap=[gap], force=[snapshot.estimate.force_expected / fs])
        top = np.nanmax([*force, paper, 0.0])
        _refill(src["marker"], gap=[gap, gap], force=[0.0, top])
        required = snapshot.estimate.required_gap / ls
        _refill(src["required"], gap=[required, required], probability=[0.0, 1.0])
        points = [m for m in monte_carlo if math.isfinite(m.force_low)]
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
        shown = None if history is None else _plotted_steps(history)
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
            _refill(src["contact"], time=[], force=[])
        else:
            _refill(src["contact"], time=history.time[shown], force=history.contact_force[shown] / fs)


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


def _plotted_steps(history: TimeHistory) -> np.ndarray:
    """Indices of the steps drawn: every step in contact (and its neighbours,
    so each pounding spike keeps its shape), and an even selection of the rest."""
    n = history.time.size
    contact = np.flatnonzero(history.contact_force > 0)
    around = np.concatenate([contact - 1, contact, contact + 1])
    even = np.linspace(0, n - 1, min(n, PLOTTED_STEPS)).astype(np.int64)
    return np.unique(np.clip(np.concatenate([around, even]), 0, n - 1))


# --- the static report ---------------------------------------------------------

METHOD_NOTES = """
<h2>Method</h2>
<ul class="method-notes">
<li><b>Buildings.</b> Shear buildings with a Bouc-Wen law in every storey (Rahimi &amp; Soltani 2016, Eq. 1-2, 36-39);
damping c = 2 xi sqrt(k m) for one storey, stiffness-proportional on the first mode for more.</li>
<li><b>Ground motion.</b> Gaussian records with the Kanai-Tajimi spectrum (Eq. 7), optionally modulated by the
Shinozuka-Sato envelope (Eq. 8-9), by spectral representation; record i of a study is seeded on its own.</li>
<li><b>Contact.</b> Jankowski's nonlinear viscoelastic law (Eq. 3-5) with the impact damping
2 xi sqrt(beta sqrt(delta) m1 m2/(m1+m2)) (Eq. 4 as printed is dimensionally inconsistent).</li>
<li><b>Monte Carlo ("exact").</b> Nonlinear time histories (Eq. 10-11) integrated with an error-controlled
Dormand-Prince 5(4) scheme that locates every impact; halving its tolerance moves the mean F<sub>max</sub> by less than 0.1 %.</li>
<li><b>Paper's estimate.</b> Statistical linearization (Eq. 19-21), variances with cross terms (Eq. 16-18, 25),
Davenport's peak factor with the rate of Eq. 24 (Eq. 23), Michaelov's equivalent stationary process for modulated
motion (Eq. 26-30), force by Eq. 13-14 with delta^1.5.</li>
<li><b>Recommended estimate.</b> The same linearized pair; impacts counted as crossings of the gap (Rice), with
returns after an impact (Zhuravlev's mirror argument) and clumps (Vanmarcke), the response built up from rest;
each impact's peak force is the contact law's own, K(e) times the undamped Hertz peak. Within 10 % of Monte
Carlo on 20 of 25 tested cases with the gap below sigma_X; not reliable when pounding is rare (a warning says so).
Derivation and accuracy table: docs/estimator.md.</li>
</ul>
"""

REPORT_NOTE = (
    "A snapshot of one state: the plots are interactive (zoom, pan, hover) but nothing is recomputed; "
    "change parameters in the dashboard (pounding dashboard) and export again."
)


def _case_table(case: Case, units: str) -> str:
    d = display(units)
    u = d.system
    rows = []
    for number, building in enumerate(case.buildings, start=1):
        storey = building.storeys[0]
        bw = storey.bouc_wen
        n = bw.n
        rows.append(
            f"<tr><th>building {number}</th><td>{building.n_storeys} storey(s), T<sub>1</sub> = {building.periods[0]:.4g} s, "
            f"storey 1: m = {u.from_si(storey.mass, mass=1):.4g} {u.mass_label}, "
            f"k = {u.from_si(storey.stiffness, force=1, length=-1):.4g} {u.force_label}/{u.length_label}, "
            f"damping ratio {building.damping_ratio:g}; Bouc-Wen alpha = {bw.alpha:g}, A = {bw.A:g}, "
            f"beta = {u.from_si(bw.beta, length=-n):.4g} 1/{u.length_label}^{n:g}, "
            f"gamma = {u.from_si(bw.gamma, length=-n):.4g} 1/{u.length_label}^{n:g}, n = {n:g}</td></tr>"
        )
    c = case.contact
    exponent = c.stiffness_exponent
    rows.append(
        f"<tr><th>contact</th><td>{c.model}, gap {d.length(c.gap)}, "
        f"stiffness {u.from_si(c.stiffness, force=1, length=-exponent):.4g} {u.force_label}/{u.length_label}^{exponent:g}, "
        f"restitution {c.restitution:g}, levels {c.levels[0]} and {c.levels[1]}</td></tr>"
    )
    s = case.excitation.spectrum
    envelope = "stationary" if case.excitation.stationary else f"Shinozuka-Sato envelope (B1 = {case.excitation.envelope.B1:g}, B2 = {case.excitation.envelope.B2:g})"
    rows.append(
        f"<tr><th>excitation</th><td>{type(s).__name__}: G0 = {u.from_si(s.G0, length=2):.4g} {u.length_label}^2/s^3, "
        f"omega_g = {s.omega_g:g} rad/s, xi_g = {s.xi_g:g}; duration {case.excitation.duration:g} s, {envelope}</td></tr>"
    )
    return '<table class="case-table">' + "".join(rows) + "</table>"


def report_html(snapshot: Snapshot, units: str = "SI", title: str | None = None) -> str:
    """The report as one HTML document: every script and style inline."""
    from bokeh.embed import file_html
    from bokeh.layouts import column, row
    from bokeh.models import Div
    from bokeh.resources import INLINE

    case = snapshot.case
    title = title or f"pounding report: {case.name}"
    matching = [m for m in snapshot.monte_carlo if m.gap == case.contact.gap]
    stamp = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    history_note = (
        f"Hysteresis: record {snapshot.record} of the study seeded {snapshot.seed}."
        if snapshot.history is not None
        else f"The representative record failed: {html.escape(snapshot.history_error)}"
    )
    header = Div(
        text=(
            f"<style>{RESULT_CSS} .case-table th, .case-table td {{ text-align: left; padding: 2px 8px; font-size: 13px; }}</style>"
            f"<h1>{html.escape(title)}</h1>"
            f"<p>{html.escape(case.description)}</p>"
            f'<p class="report-note"><i>{REPORT_NOTE}</i> Written {stamp} by pounding.</p>'
            + _case_table(case, units)
            + "<h2>Result</h2>"
            + result_html(snapshot, units, matching[-1] if matching else None, "not run for this report")
            + f"<p>{history_note}</p>"
        ),
        sizing_mode="stretch_width",
    )
    figures = Figures()
    figures.fill(snapshot, units, snapshot.monte_carlo)
    layout = column(
        header,
        figures.gap,
        row(figures.psd_ground, figures.psd_velocity, sizing_mode="stretch_width"),
        row(*figures.hysteresis, sizing_mode="stretch_width"),
        figures.contact,
        Div(text=METHOD_NOTES, sizing_mode="stretch_width"),
        sizing_mode="stretch_width",
    )
    return _without_server_scripts(file_html(layout, resources=INLINE, title=title))


_EXTERNAL = re.compile(
    r'<script[^>]*\bsrc="(?!data:)[^"]*"[^>]*>\s*</script>\s*|<link[^>]*\brel="stylesheet"[^>]*\bhref="(?!data:)[^"]*"[^>]*>\s*'
)


def _without_server_scripts(text: str) -> str:
    """Drop ``<script src=...>`` and stylesheet ``<link>`` tags: with Panel
    imported (as in the dashboard's server), Bokeh's inline bundle still names
    server-relative files of Panel's (an ES-module shim, Tabulator's CSS),
    unused by the report, that a file cannot load. Everything the report
    uses is inline."""
    return _EXTERNAL.sub("", text)


def write_report(path: str | os.PathLike, snapshot: Snapshot | Case, units: str = "SI", title: str | None = None) -> Path:
    """Write the static report of ``snapshot`` (or of a case, computed here) to ``path``.

    The file is written atomically: to a temporary file beside ``path``, then
    renamed over it, so a failed or interrupted write leaves no partial file.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    if isinstance(snapshot, Case):
        snapshot = compute_snapshot(snapshot)
    text = report_html(snapshot, units, title)
    descriptor, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8") as stream:
            stream.write(text)
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except FileNotFoundError:
            pass
        raise
    return path
