"""A case of several contacts (a row of buildings, or floors meeting at several
levels) as the dashboard and the report show it: :class:`RowSnapshot` (the
library's :class:`~pounding.closed_form.row.RowEstimate`, one record's time
history of the whole case, and its check against Monte Carlo,
:func:`~pounding.studies.check.check_row`), the table of contacts
(:func:`contacts_table_html`), the governing contact in words
(:func:`governing_words`) and each contact's force in one record
(:class:`ContactHistory`). Every number comes from the library; this only
formats it, in display units. Bokeh is imported when a figure is built."""

from __future__ import annotations

import dataclasses
import html
import math
from dataclasses import dataclass

from pounding import defaults
from pounding.case.case import Case, contact_label
from pounding.closed_form.estimator import estimate
from pounding.closed_form.row import RowEstimate
from pounding.display_units import display
from pounding.errors import SimulationError
from pounding.report.figures import plotted_steps
from pounding.simulation.monte_carlo import TimeHistory, simulate_record
from pounding.simulation.plan import MonteCarloPlan
from pounding.studies.check import RowCheck, check_row

__all__ = ["CONTACT_COLOURS", "CONTACTS_CSS", "ContactHistory", "RowSnapshot", "compute_row_snapshot", "contacts_table_html",
           "governing_words", "row_check_sentence", "several_contacts", "with_row_check"]

CONTACT_COLOURS = ("#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22")
"""One colour a contact, in the case's order (repeated past ten)."""

CONTACTS_CSS = """
table.contacts { border-collapse: collapse; font-size: 12px; margin: 4px 0 8px; }
table.contacts th, table.contacts td { padding: 2px 6px; border-bottom: 1px solid #ddd; text-align: right; white-space: nowrap; }
table.contacts th:first-child, table.contacts td:first-child { text-align: left; }
table.contacts tr.governing td { font-weight: 700; background: #f3f7fb; }
"""


def several_contacts(case: Case | None) -> bool:
    """Whether ``case`` has more than one contact (None: no)."""
    return case is not None and len(case.contacts) > 1


@dataclass(frozen=True, eq=False)
class RowSnapshot:
    """What the dashboard and the report show for a case of several contacts; all SI.

    Attributes
    ----------
    case : Case
    estimate : RowEstimate
    history : TimeHistory or None
        Record ``record`` of the study seeded ``seed``, every contact acting; None if it failed.
    history_error : str
        Why ``history`` is None.
    seed, record : int
    check : RowCheck or None
        The estimate checked against one Monte Carlo study of the whole case (:func:`with_row_check`).
    capacity : float or None
        A force the contacts can take [N]: P(F_max > capacity) at any contact is then stated.
    """

    case: Case
    estimate: RowEstimate
    history: TimeHistory | None
    history_error: str = ""
    seed: int = defaults.SEED
    record: int = 0
    check: RowCheck | None = None
    capacity: float | None = None


def compute_row_snapshot(case: Case, seed: int = defaults.SEED, record: int = 0,
                         target_probability: float = defaults.TARGET_PROBABILITY, result: RowEstimate | None = None) -> RowSnapshot:
    """The closed form of ``case`` (``result`` when already made) and record ``record`` of the study seeded ``seed``;
    a failed record is kept in ``history_error``."""
    result = estimate(case, target_probability) if result is None else result
    history, error = None, ""
    try:
        history = simulate_record(case, seed, record)
    except SimulationError as failure:
        error = str(failure)
    return RowSnapshot(case, result, history, error, seed, record)


def with_row_check(snapshot: RowSnapshot, plan: MonteCarloPlan | None = None) -> RowSnapshot:
    """The snapshot with its check (:func:`~pounding.studies.check.check_row`), as given, else on ``plan`` (default:
    as many records as the check's precision asks, seeded as the snapshot)."""
    if snapshot.check is not None:
        return snapshot
    plan = MonteCarloPlan(None, snapshot.seed) if plan is None else plan
    return dataclasses.replace(snapshot, check=check_row(snapshot.estimate, plan))


def governing_words(result: RowEstimate) -> str:
    """The contact with the largest E[F_max], in words: "buildings 2-3, floors 3/3"."""
    return contact_label(result.case.contacts[result.governing])


def _records_words(check) -> str:
    plural = "s" if check.records != 1 else ""
    return f"{check.records} recorded motion{plural}" if check.seed is None else f"{check.records} simulated record{plural}"


def row_check_sentence(check: RowCheck, units: str = "SI") -> str:
    """The verdict of a :class:`~pounding.studies.check.RowCheck` in one sentence: the records' largest force over
    all contacts, and whether the closed form agrees (where it does not, the force to quote is theirs)."""
    force = display(units).force
    low, high = check.force_max_confidence_interval
    if check.force_max_mean == 0.0:
        found = "no contact pounded"
    else:
        interval = f"95 % interval {force(low)} to {force(high)}" if math.isfinite(high - low) else "one record, no interval"
        found = f"largest force over all contacts {force(check.force_max_mean)} ({interval})"
    verdict = ("the closed form agrees" if check.agrees else
               f"the closed form's {force(check.closed_form_force)} does not agree: the force above is the records' mean")
    return f"Checked on {_records_words(check)}, every contact acting: {found}; {verdict}."


def contacts_table_html(result: RowEstimate, units: str = "SI", check: RowCheck | None = None,
                        capacity: float | None = None) -> str:
    """The table of contacts, one row each in the case's order: buildings, floors, gap, E[F_max], its 84th percentile,
    the probability of pounding, the gap for the target (each contact's closed form on its two buildings), with
    ``check`` each contact's Monte Carlo mean (every contact acting), with ``capacity`` [N] P(F_max > capacity);
    the governing contact's row marked."""
    shown = display(units)
    target = f"{100 * result.target_probability:.4g} %"
    heads = ["contact", "buildings", "floors", "gap", "E[F<sub>max</sub>]", "84th percentile", "P(pounding)",
             f"gap for {target} no pounding"]
    if capacity is not None:
        heads.append(f"P(F<sub>max</sub> &gt; {html.escape(shown.force(capacity))})")
    if check is not None:
        heads.append(f"Monte Carlo mean F<sub>max</sub> ({check.records} records)")
    rows = []
    for index, (contact, one) in enumerate(zip(result.case.contacts, result.contacts)):
        cells = [
            ("number", str(index + 1)),
            ("buildings", f"{contact.between[0]}-{contact.between[1]}"),
            ("floors", f"{contact.levels[0]}/{contact.levels[1]}"),
            ("gap", shown.length(contact.gap)),
            ("force-expected", shown.force(one.force_expected)),
            ("f84", shown.force(one.force_max_distribution.quantile(0.84))),
            ("pounding-probability", f"{100 * one.pounding_probability:.3g} %"),
            ("required-gap", shown.length(one.required_gap)),
        ]
        if capacity is not None:
            cells.append(("p-exceed", f"{100 * one.probability_exceeding(capacity):.3g} %"))
        if check is not None:
            cells.append(("mc-mean", shown.force(check.contacts[index].force_max_mean)))
        css = "contact governing" if index == result.governing else "contact"
        rows.append(f'<tr class="{css}" data-contact="{index + 1}">'
                    + "".join(f'<td class="{name}">{html.escape(text)}</td>' for name, text in cells) + "</tr>")
    head = "".join(f"<th>{text}</th>" for text in heads)
    return f'<table class="contacts"><thead><tr>{head}</tr></thead><tbody>{"".join(rows)}</tbody></table>'


class ContactHistory:
    """The pounding force at each contact during one record: one line a contact, labelled in words, in one figure
    whose data (one row a contact) is replaced in place by :meth:`fill`."""

    def __init__(self, height: int = 260):
        from bokeh.models import ColumnDataSource, HoverTool
        from bokeh.plotting import figure

        self.source = ColumnDataSource(data={"time": [], "force": [], "label": [], "colour": []})
        self.figure = figure(title="Pounding force at each contact during the record", height=height, output_backend="canvas",
                             sizing_mode="stretch_width", tools="pan,wheel_zoom,box_zoom,reset,save")
        self.figure.multi_line("time", "force", source=self.source, line_color="colour", line_width=1.5, legend_field="label")
        self.figure.add_tools(HoverTool(tooltips=[("contact", "@label")]))
        self.figure.xaxis.axis_label = "time [s]"
        self.figure.legend.location = "top_left"

    def fill(self, snapshot: RowSnapshot | None, units: str = "SI") -> None:
        """Show ``snapshot``'s record (None, or a failed record: no lines) in ``units``."""
        shown = display(units)
        self.figure.yaxis.axis_label = f"pounding force [{shown.force_unit}]"
        history = None if snapshot is None else snapshot.history
        if history is None:
            self.source.data = {"time": [], "force": [], "label": [], "colour": []}
            return
        contacts = snapshot.case.contacts
        steps = plotted_steps(history)
        time = history.time[steps]
        self.source.data = {
            "time": [time] * len(contacts),
            "force": [history.contact_forces[steps, c] / shown.force_scale for c in range(len(contacts))],
            "label": [f"{c + 1}: {contact_label(contact)}" for c, contact in enumerate(contacts)],
            "colour": [CONTACT_COLOURS[c % len(CONTACT_COLOURS)] for c in range(len(contacts))],
        }
        self.figure.title.text = f"Pounding force at each contact during record {snapshot.record} of the study seeded {snapshot.seed}"

