"""The static report of a case of several contacts (:class:`~pounding.report.contacts.RowSnapshot`): the summary
(the largest force over all contacts, the governing contact, the check against one Monte Carlo study of the whole
case), the table of contacts, the inputs, each contact's force during one record, and the method. The report of a
case of one contact is :func:`~pounding.report.static.report_html`'s own."""

from __future__ import annotations

import html
import math

from pounding.case.engineering import engineering_terms
from pounding.closed_form.regimes import without_check_advice
from pounding.display_units import display
from pounding.report.card import RESULT_CSS
from pounding.report.contacts import (
    CONTACTS_CSS,
    ContactHistory,
    RowSnapshot,
    contacts_table_html,
    governing_words,
    row_check_sentence,
    with_row_check,
)
from pounding.report.curve_charts import LEGEND_ROW, legend_below
from pounding.report.figure_section import ReportFigure, fixed_width, figures_html
from pounding.report.inputs_section import inputs_html
from pounding.report.method_section import method_notes
from pounding.report.print_css import REPORT_CSS

__all__ = ["ROW_METHOD", "contacts_section_html", "row_report_body", "row_summary_html"]

ROW_METHOD = ("Several contacts: each contact's closed form is that of its two buildings alone under the common ground "
              "motion (each building linearized once); the largest force over all contacts takes the contacts' extremes "
              "as independent, which errs on the safe side for floors that sway together. What one impact does to the "
              "motion at another contact is not in the closed form: the Monte Carlo check, every contact acting in the same "
              "time histories, has it (docs/theory.md and docs/accuracy.md, \"Several contacts\").")
"""The method of a case of several contacts, in plain words."""


def row_summary_html(snapshot: RowSnapshot, units: str = "SI") -> str:
    """The governing contact, the check's verdict, the largest force over all contacts (the check's answer where the
    closed form does not agree), its 84th percentile, the probability that any contact pounds, P(F_max > capacity)
    with a capacity, the accuracy and the warnings."""
    d, e, check = display(units), snapshot.estimate, snapshot.check
    case = snapshot.case
    force = e.force_expected if check is None else check.force_answer
    rows = [
        ("governing contact", governing_words(e), "the contact with the largest expected extreme force"),
        ("expected extreme force, largest over all contacts", d.force(force),
         "closed form" if check is None or check.agrees else "Monte Carlo mean: the closed form does not agree"),
        ("84th percentile of the largest force", d.force(e.force_max_distribution.quantile(0.84)), "closed form"),
        ("probability that any contact pounds", f"{100 * e.pounding_probability:.3g} %",
         f"during the {case.excitation.duration:g} s record, contacts taken as independent"),
    ]
    if snapshot.capacity is not None:
        rows.append((f"probability that the largest force exceeds {d.force(snapshot.capacity)}",
                     f"{100 * e.probability_exceeding(snapshot.capacity):.3g} %", "closed form, at any contact"))
    cells = "".join(f'<tr><th>{html.escape(q)}</th><td class="number">{html.escape(v)}</td><td>{html.escape(n)}</td></tr>'
                    for q, v, n in rows)
    verdict = "" if check is None else f'<p class="check-verdict">{html.escape(row_check_sentence(check, units))}</p>'
    warnings = "".join(f'<p class="warning">&#9888; {html.escape(w if check is None else without_check_advice(w))}</p>'
                       for w in e.warnings)  # with the check above them, their advice to run it is dropped
    return (f'<p class="governing">Governing: <b>{html.escape(governing_words(e))}</b> of {len(case.contacts)} contacts '
            f"between {len(case.buildings)} buildings.</p>{verdict}"
            '<table class="summary"><thead><tr><th>quantity</th><th>value</th><th>note</th></tr></thead><tbody>'
            f'{cells}</tbody></table><p class="accuracy">{html.escape(e.measured_accuracy)}</p>{warnings}')


def contacts_section_html(snapshot: RowSnapshot, units: str = "SI") -> str:
    """The table of contacts (:func:`~pounding.report.contacts.contacts_table_html`) and what its columns are."""
    check = snapshot.check
    return (contacts_table_html(snapshot.estimate, units, check, snapshot.capacity)
            + '<p class="contacts-note">Each contact in the case\'s order: its closed form on its two buildings'
            + ("; the Monte Carlo mean with every contact acting" if check is not None else "")
            + ". The governing contact's row is in bold.</p>")


def _history_figure(snapshot: RowSnapshot, units: str) -> ReportFigure | None:
    if snapshot.history is None:
        return None
    history = ContactHistory()
    history.fill(snapshot, units)
    contacts = len(snapshot.case.contacts)
    legend_below(history.figure, columns=2)  # one entry a contact (a legend field: Bokeh counts one item)
    history.figure.height += (math.ceil(contacts / 2) - 1) * LEGEND_ROW
    peaks = ", ".join(f"contact {c + 1} {display(units).force(float(snapshot.history.contact_forces[:, c].max()))}"
                      for c in range(len(snapshot.case.contacts)))
    return ReportFigure("Pounding force at each contact during one record",
                        f"Record {snapshot.record} of the study seeded {snapshot.seed}, every contact acting; "
                        f"one line a contact. Peaks: {peaks}.", fixed_width((history.figure,)))


def row_report_body(snapshot: RowSnapshot, units: str, head: str) -> tuple[str, str, str]:
    """The report's body after ``head`` (its title and provenance), the plots' script, and what goes in the page's
    head (the styles and Bokeh's library). Runs the check (:func:`~pounding.report.contacts.with_row_check`) unless the snapshot has it."""
    snapshot = with_row_check(snapshot)
    case = snapshot.case
    figure = _history_figure(snapshot, units)
    figures, script, library = figures_html([figure]) if figure is not None else ("", "", "")
    history_note = ("" if snapshot.history is not None
                    else f"<p>The representative record failed: {html.escape(snapshot.history_error)}</p>")
    body = (
        head + '<section class="summary"><h2>1. Summary</h2>' + row_summary_html(snapshot, units) + "</section>"
        '<section class="inputs"><h2>2. Inputs</h2>' + inputs_html(case, units, engineering_terms(case)) + "</section>"
        '<section class="results"><h2>3. Contacts</h2>' + contacts_section_html(snapshot, units) + "</section>"
        '<section class="figures"><h2>4. Figures</h2>' + history_note + figures + "</section>"
        '<section class="method">' + method_notes(None) + f'<p class="row-method">{html.escape(ROW_METHOD)}</p></section>'
    )
    return body, script, f"<style>{REPORT_CSS}{RESULT_CSS}{CONTACTS_CSS}</style>{library}"
