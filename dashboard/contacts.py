"""The dashboard for a case of several contacts (a row of buildings, floors meeting at several levels): the headline
names the governing contact and gives the largest force over all contacts (:func:`row_headline_html`), the table of
contacts goes where the force-against-gap plot of one contact is (:func:`contacts_html`), and where a plot or a
study takes one contact only the page says so (:data:`ONE_CONTACT`). Every number comes from the library's
:class:`~pounding.closed_form.row.RowEstimate` and its check (:class:`~pounding.studies.check.RowCheck`); the table is
the report's (:func:`pounding.report.contacts.contacts_table_html`)."""

from __future__ import annotations

import html

from dashboard.headline import CHECKING, _in_page_terms
from pounding.display_units import display
from pounding.report.contacts import CONTACTS_CSS, contacts_table_html, governing_words, row_check_sentence

__all__ = ["ONE_CONTACT", "ROW_CSS", "contacts_html", "row_headline_html"]

ONE_CONTACT = {
    "gap": "The force against the gap is drawn for a case of one contact. This case has several: each contact's gap "
           "for the target is in the table above.",
    "spectra": "The relative velocity spectrum is drawn for a case of one contact; this case has several.",
    "hysteresis": "The hysteresis loops are drawn for a case of one contact; this case has several: each contact's "
                  "force during the record is in the 'Force history' tab.",
    "distribution": "The distribution of the largest force is drawn for a case of one contact; this case has several: "
                    "each contact's 84th percentile is in the table of contacts.",
    "pinning": "Pinning compares states of a case of one contact; this case has several.",
}
"""What the page says where a plot or a study takes one contact only."""

ROW_CSS = CONTACTS_CSS + """
.headline .governing { font-weight: 600; margin: 2px 0 4px; }
.contacts-panel .note { font-size: 12px; color: #444; }
"""


def _number(value: str, what: str, css: str) -> str:
    return f'<div class="number"><span class="value {css}">{value}</span><span class="what">{what}</span></div>'


def row_headline_html(result, units: str = "SI", capacity: float | None = None, name: str = "", check=None,
                      checking: bool = False, check_error: str = "", held: str = "", pinned: bool = False) -> str:
    """The headline of a :class:`~pounding.closed_form.row.RowEstimate` ``result``: the governing contact, the largest
    force over all contacts (the records' mean where ``check``, its :class:`~pounding.studies.check.RowCheck`, does not
    agree), its 84th percentile, the probability that any contact pounds, with ``capacity`` [N] P(F_max > capacity);
    the check's verdict (or that it runs, ``checking``, or why it failed, ``check_error``), the warnings and the
    accuracy. ``held`` (:func:`dashboard.headline.held_note`) comes first; ``pinned``: a state is pinned, which this
    case cannot be compared with."""
    shown = display(units)
    case = result.case
    force = shown.force(result.force_expected)
    numbers = [_number(force, "expected extreme force E[F<sub>max</sub>], largest over all contacts", "fe-recommended")]
    if check is not None and check.answer_source != "closed form":
        numbers = [_number(shown.force(check.force_answer), "expected extreme force E[F<sub>max</sub>], largest over all "
                           f'contacts: the records\' mean<span class="closed-form"> (closed form <span class="fe-recommended">'
                           f"{force}</span>)</span>", "force-answer")]
    numbers += [
        _number(shown.force(result.force_max_distribution.quantile(0.84)), "84th percentile of the largest force", "f84"),
        _number(f"{100 * result.pounding_probability:.3g} %", f"probability that any contact pounds in "
                f"{case.excitation.duration:.3g} s", "pounding-probability"),
    ]
    if capacity is not None:
        numbers.append(_number(f"{100 * result.probability_exceeding(capacity):.3g} %",
                               f"P(F<sub>max</sub> &gt; {shown.force(capacity)}) at any contact", "p-exceed"))
    if check is not None:
        line = f'<p class="check-verdict">{html.escape(row_check_sentence(check, units))}</p>'
    elif check_error:
        line = f'<p class="check-verdict failed">Could not check against simulated records: {html.escape(check_error)}</p>'
    else:
        line = f'<p class="check-verdict checking">{CHECKING}</p>' if checking else ""
    done = {"monte_carlo"} if check is not None else set()
    warnings = [w for w in (_in_page_terms(w, done) for w in result.warnings) if w]
    lines = [line, *(f'<p class="warning">&#9888; {html.escape(w)}</p>' for w in warnings),
             f'<p class="accuracy">{html.escape(result.measured_accuracy)}</p>']
    if pinned:
        lines.append(f'<p class="accuracy">{html.escape(ONE_CONTACT["pinning"])}</p>')
    title = f'<b class="case-name">{html.escape(name)}</b>' if name else ""
    governing = (f'<p class="governing">governing: <span class="governing-contact">{html.escape(governing_words(result))}'
                 f"</span> ({len(case.contacts)} contacts between {len(case.buildings)} buildings)</p>")
    return (f'<div class="headline">{held}{title}{governing}<div class="numbers">{"".join(numbers)}</div>'
            + "".join(lines) + "</div>")


def contacts_html(result, units: str = "SI", check=None, capacity: float | None = None) -> str:
    """The table of contacts (the report's) under a heading, and the note that the force against the gap takes one
    contact; '' for a case of one contact or none."""
    if result is None or len(result.case.contacts) < 2:
        return ""
    note = "Each contact's closed form on its two buildings" + (
        "; the Monte Carlo mean with every contact acting" if check is not None else "") + ". The governing contact in bold."
    return (f'<div class="contacts-panel"><b>Contacts</b>{contacts_table_html(result, units, check, capacity)}'
            f'<p class="note">{html.escape(note)}</p><p class="note">{html.escape(ONE_CONTACT["gap"])}</p></div>')
