"""The static report: :func:`write_report` writes a snapshot to one
self-contained HTML file for a design note: the title and where the inputs
came from (a preset, modified or not: :mod:`.provenance`), a summary led by the
verdict (the estimate checked against the Monte Carlo of its case), the
inputs as a table, the results, numbered figures with captions, the method;
the tool's version, the date and the command that made it. Everything but the
plots is static HTML (read without JavaScript); it prints on A4
(:mod:`.print_css`). Bokeh is imported when a report is made."""

from __future__ import annotations

import dataclasses
import html
import math
import os
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from pounding import __version__
from pounding.case.case import Case, load_case
from pounding.case.engineering import engineering_terms
from pounding.output import check_target, write_atomic
from pounding.presets import preset_text
from pounding.report.bokeh_embed import without_external
from pounding.report.card import RESULT_CSS, result_html
from pounding.report.case_keys import key_label
from pounding.report.distribution_section import quantiles_table
from pounding.report.figure_section import figures_html, report_figures
from pounding.report.inputs_section import inputs_html
from pounding.report.method_section import method_notes
from pounding.report.print_css import REPORT_CSS
from pounding.report.provenance import ReportProvenance
from pounding.report.snapshot import Snapshot, compute_snapshot
from pounding.report.summary import summary_html, with_capacity_check, with_check

# --- the static report ---------------------------------------------------------

REPORT_NOTE = (
    "A snapshot of one state: the plots are interactive (zoom, pan, hover) but nothing is recomputed; "
    "change parameters in the dashboard (pounding dashboard) and export again."
)


def _same_numbers(a, b) -> bool:
    """Two cases' physics equal to 1e-9 (relative), whatever unit system they were written in."""
    if dataclasses.is_dataclass(a) and dataclasses.is_dataclass(b):
        if type(a) is not type(b):
            return False
        return all(_same_numbers(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a)
                   if f.name not in ("name", "title", "description", "units"))
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        return len(a) == len(b) and all(_same_numbers(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9)
    try:
        return bool(a == b)
    except ValueError:  # arrays: compared element by element
        return bool(np.array_equal(a, b))


def case_provenance_from_name(case: Case) -> ReportProvenance:
    """The provenance of a case given without one: a preset when its name is a preset's and its numbers are the
    preset's; a preset modified in ways not listed when only its name is; else the case's name."""
    if preset_text(case.name) is None:
        return ReportProvenance(case.name)
    if _same_numbers(case, load_case(case.name)):
        return ReportProvenance(case.name, case.name)
    return ReportProvenance(case.name, case.name, None)


def report_title(case: Case, provenance: ReportProvenance, title: str | None = None) -> str:
    """The report's title: ``title`` or one naming the case, with "modified from preset X" when it is."""
    modified = f"modified from preset {provenance.preset}" if provenance.modified else ""
    if title:
        return f"{title} ({modified})" if modified and modified not in title else title
    if modified:
        named = "" if provenance.source == provenance.preset else f"{provenance.source}, "
        return f"Pounding report: {named}{modified}"
    return f"Pounding report: {provenance.source if provenance.preset else case.name}"


def _provenance_html(case: Case, provenance: ReportProvenance) -> str:
    if provenance.preset is None:
        source = f"Inputs: the case {html.escape(provenance.source)}."
    elif not provenance.modified:
        source = f"Inputs: preset {html.escape(provenance.preset)}, with no modification."
    elif provenance.changes is None:
        source = (f"Inputs: preset {html.escape(provenance.preset)}, modified; the changes are not listed (the report "
                  "was given the case, not its case file): the inputs table below is what was computed.")
    else:
        source = (f"Inputs: preset {html.escape(provenance.preset)}, modified in {len(provenance.changes)} key(s) "
                  '(listed under "Changed from the preset").')
    description = html.escape(case.description)
    if provenance.modified and description:
        description = f"The preset's description (before the changes): {description}"
    return f'<p class="provenance">{source}</p>' + (f'<p class="description">{description}</p>' if description else "")


def changes_html(provenance: ReportProvenance) -> str:
    """The keys changed from the preset: case-file key, the preset's value, this report's, unit."""
    if not provenance.changes or provenance.preset is None:
        return ""
    rows = "".join(
        f"<tr><td>{html.escape(key_label(c.key))}<br><code>{html.escape(c.key)}</code></td>"
        f'<td class="value">{html.escape(_value(_shown(c.before, c.unit)[0]))}</td>'
        f'<td class="value">{html.escape(_value(_shown(c.after, c.unit)[0]))}</td>'
        f"<td>{html.escape(_shown(None, c.unit)[1])}</td></tr>"
        for c in provenance.changes
    )
    return (f"<h3>Changed from the preset {html.escape(provenance.preset)}</h3>"
            '<table class="changes"><thead><tr><th>parameter (case-file key)</th><th>preset</th><th>this report</th>'
            f"<th>unit</th></tr></thead><tbody>{rows}</tbody></table>")


_SHOWN_UNITS = {"m": ("mm", 1e3), "N": ("kN", 1e-3)}
"""The case file's SI lengths and forces in the report's display units (mm, kN), as the rest of the report."""


def _shown(value, unit: str):
    """``value`` in ``unit`` (the case file's) and its unit, lengths and forces in the report's mm and kN."""
    shown, factor = _SHOWN_UNITS.get(unit, (unit, 1.0))
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        value = value * factor
    elif isinstance(value, list):
        value = [v * factor if isinstance(v, (int, float)) and not isinstance(v, bool) else v for v in value]
    return value, shown


def _value(value) -> str:
    """A value as a person reads it: up to 6 significant digits, thousands grouped, no e-notation from 1e-3 to 1e15."""
    if value is None:
        return "not given"
    if isinstance(value, list):
        return ", ".join(_value(v) for v in value)
    if isinstance(value, float):
        magnitude = abs(value)
        if value == 0.0 or not 1e-3 <= magnitude < 1e15:
            return f"{value:.6g}"
        decimals = max(0, 5 - math.floor(math.log10(magnitude)))
        return f"{value:,.{decimals}f}".rstrip("0").rstrip(".") if decimals else f"{value:,.0f}"
    return str(value)


def _made_html(provenance: ReportProvenance) -> str:
    stamp = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    command = f" with <code>{html.escape(provenance.command)}</code>" if provenance.command else ""
    return f'<p class="made">Written {stamp} by pounding {html.escape(__version__)}{command}.</p>'


def report_html(snapshot: Snapshot, units: str = "SI", title: str | None = None,
                provenance: ReportProvenance | None = None) -> str:
    """The report as one HTML document: every script and style inline; the summary, the tables and the
    figures' captions are static HTML, read without JavaScript; the plots are drawn by Bokeh.

    The summary leads with the verdict: the snapshot's Monte Carlo check, run here when it has none
    (:func:`~.summary.with_check`: on the records of a study at the case's gap, else as many as its precision asks);
    with a capacity (``snapshot.capacity``), the gap sized to it and its Monte Carlo on the same records
    (:func:`~.summary.with_capacity_check`)."""
    from pounding.report.contacts import RowSnapshot

    if not isinstance(snapshot, RowSnapshot):
        snapshot = with_capacity_check(with_check(snapshot))
    case = snapshot.case
    provenance = provenance or case_provenance_from_name(case)
    title = report_title(case, provenance, title)
    head = (f"<header><h1>{html.escape(title)}</h1>{_made_html(provenance)}{_provenance_html(case, provenance)}"
            f'<p class="report-note"><i>{REPORT_NOTE}</i></p></header>')
    if isinstance(snapshot, RowSnapshot):  # several contacts: every contact listed (pounding.report.row_report)
        from pounding.report.row_report import row_report_body

        return _page(title, *row_report_body(snapshot, units, head))
    terms = engineering_terms(case)
    history_note = (
        f"Hysteresis and pounding force: record {snapshot.record} of the study seeded {snapshot.seed}."
        if snapshot.history is not None
        else f"The representative record failed: {html.escape(snapshot.history_error)}"
    )
    figures, script, library = figures_html(report_figures(snapshot, units))
    body = (
        head + '<section class="summary"><h2>1. Summary</h2>' + summary_html(snapshot, units) + "</section>"
        '<section class="inputs"><h2>2. Inputs</h2>' + changes_html(provenance) + inputs_html(case, units, terms) + "</section>"
        '<section class="results"><h2>3. Results in detail</h2>'
        + result_html(snapshot, units, design_gap=snapshot.design_gap, check=snapshot.check)
        + f"<p>{history_note}</p><h3>Distribution of the extreme force</h3>" + quantiles_table(snapshot, units) + "</section>"
        '<section class="figures"><h2>4. Figures</h2>' + figures + "</section>"
        '<section class="method">' + method_notes(snapshot.estimate.accuracy_regime) + "</section>"
    )
    return _page(title, body, script, f"<style>{REPORT_CSS}{RESULT_CSS}</style>{library}")


def _page(title: str, body: str, script: str, head: str) -> str:
    """One HTML document: ``head`` (styles, Bokeh's library), ``body`` (the report) and the plots' ``script``."""
    page = (
        f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>'
        f'<meta name="generator" content="pounding {html.escape(__version__)}">{head}</head>'
        f'<body><main class="report">{body}</main>{script}</body></html>\n'
    )
    return without_external(page)


def write_report(path: str | os.PathLike, snapshot: Snapshot | Case, units: str = "SI", title: str | None = None,
                 field: str = "path", provenance: ReportProvenance | None = None) -> Path:
    """Write the static report of ``snapshot`` (or of a case, computed here) to ``path``.

    The file is written atomically (:func:`pounding.output.write_atomic`): to a
    temporary file beside ``path``, then renamed over it, so a failed or
    interrupted write leaves no partial file; its mode is the usual one (0644
    under the default umask).

    Parameters
    ----------
    path : str or PathLike
        The HTML file to write.
    snapshot : Snapshot, RowSnapshot or Case
        What to report (:func:`~.snapshot.compute_snapshot`; a case of several contacts:
        :func:`~.contacts.compute_row_snapshot`, every contact listed). Without its Monte Carlo check
        (``snapshot.check``) the check is run here (:func:`~.summary.with_check`; about a second for the presets).
    units : str
        "SI" or "kgf-cm-s": the units every number is shown in.
    title : str, optional
        The report's title; by default one naming the case (and "modified from preset X" when it is).
    field : str
        The name of ``path`` in error messages.
    provenance : ReportProvenance, optional
        Where the case came from and the command that made the report
        (:func:`~.provenance.case_provenance`). Without it, a case named after a
        preset is that preset when its numbers are the preset's, and "modified from
        preset X" (the changes not listed) when they are not.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    ArgumentError
        ``path`` cannot be a file: empty, an existing device, folder or other
        non-regular file, or in a folder that does not exist (naming ``field``).
    OSError
        The system refused the write (read-only folder, full disk), naming ``path``.
        Both are checked before the report is computed (a full disk excepted).
    """
    check_target(path, field, probe=True)
    if isinstance(snapshot, Case) and len(snapshot.contacts) > 1:
        from pounding.report.contacts import compute_row_snapshot

        snapshot = compute_row_snapshot(snapshot)
    elif isinstance(snapshot, Case):
        snapshot = compute_snapshot(snapshot)
    text = report_html(snapshot, units, title, provenance)
    return write_atomic(path, text, field)
