"""What the dashboard shows for one case, and the static HTML report of it.

:func:`compute_snapshot` runs the library once for a case (one
linearization, passed to every estimator): both closed-form estimates, force
against gap, the power spectra, one seeded record's hysteresis loops beside
the equivalent linear storeys. The plot builders and :func:`result_html` turn a
:class:`Snapshot` into Bokeh figures and an HTML result card; the dashboard
shows them live and :func:`write_report` writes them to one self-contained
HTML file (all JS/CSS inline, interactive Bokeh plots, opens offline): the
dashboard's *Export* button and ``pounding report`` both call it.

Nothing here computes physics: every number comes from the library. Units:
SI inside; :class:`Display` scales for the page (forces in kN/MN or kgf).

A report always carries the verdict: :func:`with_check` runs the library's
Monte Carlo check of the estimate (:func:`pounding.studies.check.check_estimate`)
unless the snapshot has it; the force-against-gap figure draws the closed form
with the band of its measured accuracy and Monte Carlo points where studies are
at hand (:func:`gap_points`).

This package imports no plotting library at load: Bokeh is imported when
figures are built or a report is written.

Modules (display units are :mod:`pounding.display_units`): :mod:`.snapshot` (the computed
state), :mod:`.card` (the result card), :mod:`.figures` (the plots),
:mod:`.static` (the static report) and its parts: :mod:`.provenance` and
:mod:`.case_keys` (where the inputs came from, what changed from a preset),
:mod:`.summary`, :mod:`.inputs_section`, :mod:`.figure_section`,
:mod:`.distribution_section`, :mod:`.hazard_section`, :mod:`.method_section`,
:mod:`.print_css` (A4); :mod:`.comparison`, two states of a case side by side on one page
(:func:`write_comparison`).
"""

from pounding.display_units import DISPLAY_UNITS, Display, display
from pounding.report.card import RESULT_CSS, result_html
from pounding.report.comparison import (
    Difference,
    StateMonteCarlo,
    comparison_html,
    differences,
    monte_carlo_comparison,
    write_comparison,
)
from pounding.report.figures import PLOTTED_STEPS, Figures
from pounding.report.method_section import method_notes
from pounding.report.provenance import CaseChange, ReportProvenance, case_changes, case_provenance
from pounding.report.snapshot import (
    DEFAULT_RECORD,
    GAP_POINTS,
    PSD_POINTS,
    MonteCarloPoint,
    Snapshot,
    compute_snapshot,
    curve_gaps,
    gap_grid,
    gap_points,
)
from pounding.report.static import REPORT_NOTE, report_html, write_report
from pounding.report.summary import MonteCarloCheck, monte_carlo_check, verdict_html, with_capacity_check, with_check

__all__ = [
    "CaseChange",
    "Difference",
    "comparison_html",
    "differences",
    "monte_carlo_comparison",
    "StateMonteCarlo",
    "write_comparison",
    "DEFAULT_RECORD",
    "DISPLAY_UNITS",
    "GAP_POINTS",
    "method_notes",
    "PLOTTED_STEPS",
    "PSD_POINTS",
    "REPORT_NOTE",
    "RESULT_CSS",
    "Display",
    "Figures",
    "MonteCarloCheck",
    "MonteCarloPoint",
    "ReportProvenance",
    "case_changes",
    "case_provenance",
    "Snapshot",
    "compute_snapshot",
    "curve_gaps",
    "display",
    "gap_grid",
    "gap_points",
    "monte_carlo_check",
    "report_html",
    "result_html",
    "verdict_html",
    "with_capacity_check",
    "with_check",
    "write_report",
]
