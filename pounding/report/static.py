"""The static report: :func:`write_report` writes a snapshot's result card and
plots to one self-contained HTML file. Bokeh is imported when a report is made."""

from __future__ import annotations

import html
import os
import re
from datetime import datetime, timezone
from pathlib import Path

from ..case import Case
from ..filter_bank import FilterBank
from ..output import check_target, write_atomic
from ..regimes import accuracy_data
from ..display_units import display
from .card import RESULT_CSS, result_html
from .distribution_section import distribution_figure, quantiles_table
from .figures import Figures
from .hazard_section import hazard_figure, storeys_table
from .snapshot import Snapshot, compute_snapshot

# --- the static report ---------------------------------------------------------


def method_notes() -> str:
    """The method note, with the accuracy measured where pounding is frequent (pounding/data/accuracy.json)."""
    frequent = accuracy_data()["force"]["kanai-tajimi"]["frequent"]
    statement = (f"Within 10 % of Monte Carlo on {frequent['within_10_percent']} of {frequent['cases']} tested cases "
                 "where pounding is frequent (gap below sigma_X / 2, broad-band motion, small residual).")
    return _METHOD_NOTES.replace("{frequent}", statement)


_METHOD_NOTES = """
<h2>Method</h2>
<ul class="method-notes">
<li><b>Buildings.</b> Shear buildings with a Bouc-Wen law in every storey (Rahimi &amp; Soltani 2016, Eq. 1-2, 36-39);
damping c = 2 xi sqrt(k m) for one storey, stiffness-proportional on the first mode for more.</li>
<li><b>Ground motion.</b> Gaussian records of the case's spectrum (Kanai-Tajimi, Eq. 7; Clough-Penzien; or, for a design
spectrum, a compatible bank of band-pass filtered white noises that both methods use), optionally modulated by the
Shinozuka-Sato envelope (Eq. 8-9), by spectral representation; record i of a study is seeded on its own. Recorded
motions are integrated as sampled, each once, and the closed form takes a spectrum fitted to them.</li>
<li><b>Contact.</b> Jankowski's nonlinear viscoelastic law (Eq. 3-5) with the impact damping
2 xi sqrt(beta sqrt(delta) m1 m2/(m1+m2)) (Eq. 4 as printed is dimensionally inconsistent).</li>
<li><b>Monte Carlo ("exact").</b> Nonlinear time histories (Eq. 10-11) integrated with an error-controlled
Dormand-Prince 5(4) scheme that locates every impact; halving its tolerance moves the mean F<sub>max</sub> by less than 0.1 %.</li>
<li><b>Paper's estimate.</b> Statistical linearization (Eq. 19-21), variances with cross terms (Eq. 16-18, 25),
Davenport's peak factor with the rate of Eq. 24 (Eq. 23), Michaelov's equivalent stationary process for modulated
motion (Eq. 26-30), force by Eq. 13-14 with delta^1.5.</li>
<li><b>Recommended estimate.</b> The same linearized pair, with its response to the part of the Bouc-Wen law
that the linearization drops (an input independent of the ground motion) added; impacts counted as crossings of
the gap (Rice) at the rate per unit time spent below the gap, with clumps (Vanmarcke), the response built up from
rest; the largest approach counted on the motion that the impacts before it leave (their damping, as much as the
pair remembers them); each impact's peak force is the contact law's own, K(e) times the undamped Hertz peak,
lowered by the buildings' own forces that brake the approach at the gap. {frequent} Less accurate in
the other regimes, and not reliable when pounding is rare (warnings say so).
The derivation and the accuracy table by regime are in the project's docs (theory.md, accuracy.md).</li>
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
    rows.append(f"<tr><th>excitation</th><td>{_excitation_text(case, u)}</td></tr>")
    return '<table class="case-table">' + "".join(rows) + "</table>"


def _excitation_text(case: Case, u) -> str:
    """The excitation in one line, whatever its form."""
    excitation, s = case.excitation, case.excitation.spectrum
    envelope = "stationary" if excitation.stationary else f"Shinozuka-Sato envelope (B1 = {excitation.envelope.B1:g}, B2 = {excitation.envelope.B2:g})"
    if isinstance(s, FilterBank):
        target = html.escape(case.hazard.target.describe()) if case.hazard is not None else "a filter bank"
        return (f"design spectrum {target}, as a compatible bank of {len(s.frequencies)} band-pass filtered white noises (the same PSD "
                f"for both methods); duration {excitation.duration:g} s, {envelope}")
    shape = f"{type(s).__name__}: G0 = {u.from_si(s.G0, length=2):.4g} {u.length_label}^2/s^3, omega_g = {s.omega_g:.4g} rad/s, xi_g = {s.xi_g:.4g}"
    if case.recorded:
        fitted = case.hazard.fitted
        return (f"{len(case.hazard.records)} recorded motions ({html.escape(case.hazard.scaling)}): "
                f"{html.escape(', '.join(case.hazard.names[:5]))}{', ...' if len(case.hazard.records) > 5 else ''}; "
                f"the closed form takes a fitted {shape} over {fitted.duration:.3g} s ({html.escape(fitted.duration_definition)})")
    return f"{shape}; duration {excitation.duration:g} s, {envelope}"


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
            + "<h2>Ground motion and storeys</h2>"
            + storeys_table(case, units, snapshot.estimate.to_dict())
            + "<h2>Result</h2>"
            + result_html(snapshot, units, matching[-1] if matching else None, "not run for this report", snapshot.design_gap)
            + f"<p>{history_note}</p>"
            + "<h2>Distribution of the extreme force</h2>"
            + quantiles_table(snapshot, units)
        ),
        sizing_mode="stretch_width",
    )
    figures = Figures()
    figures.fill(snapshot, units, snapshot.monte_carlo, snapshot.design_gap)
    hazard = hazard_figure(case, snapshot.seed)
    layout = column(
        header,
        distribution_figure(snapshot, units),
        *([hazard] if hazard is not None else []),
        figures.gap,
        row(figures.psd_ground, figures.psd_velocity, sizing_mode="stretch_width"),
        row(*figures.hysteresis, sizing_mode="stretch_width"),
        figures.contact,
        Div(text=method_notes(), sizing_mode="stretch_width"),
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


def write_report(path: str | os.PathLike, snapshot: Snapshot | Case, units: str = "SI", title: str | None = None,
                 field: str = "path") -> Path:
    """Write the static report of ``snapshot`` (or of a case, computed here) to ``path``.

    The file is written atomically (:func:`pounding.output.write_atomic`): to a
    temporary file beside ``path``, then renamed over it, so a failed or
    interrupted write leaves no partial file; its mode is the usual one (0644
    under the default umask).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    CaseError
        ``path`` cannot be a file: empty, an existing device, folder or other
        non-regular file, or in a folder that does not exist (naming ``field``).
    OSError
        The system refused the write (read-only folder, full disk), naming ``path``.
        Both are checked before the report is computed (a full disk excepted).
    """
    check_target(path, field, probe=True)
    if isinstance(snapshot, Case):
        snapshot = compute_snapshot(snapshot)
    text = report_html(snapshot, units, title)
    return write_atomic(path, text, field)
