"""The report's ground motion and storeys in an engineer's terms: the design
spectrum against the records' mean spectrum, or the recorded motions'
periodogram against the fitted spectrum; and each storey's yield drift and
yield force. Bokeh is imported when the figure is built."""

from __future__ import annotations

import html

import numpy as np

from .. import defaults
from ..case import Case
from ..engineering import engineering_terms
from ..ground_motion import ground_motion_batches
from ..hazard import DesignSpectrum
from ..response_spectra import pseudo_acceleration_spectrum
from ..units import STANDARD_GRAVITY, unit_system

__all__ = ["SPECTRUM_RECORDS", "hazard_figure", "storeys_table"]

SPECTRUM_RECORDS = 20
"""Synthetic records whose mean response spectrum the report sets against a design spectrum."""


def storeys_table(case: Case, units: str, terms: dict | None = None) -> str:
    """An HTML table of the ground motion's peak and RMS acceleration and of each storey's yield drift and force."""
    u = unit_system(units)
    terms = terms or engineering_terms(case)
    motion = terms["ground_motion"]
    g = STANDARD_GRAVITY
    rows = [f"<tr><th>ground motion</th><td colspan=4>{html.escape(motion['source'])}: expected PGA {motion['pga_expected'] / g:.3f} g, "
            f"RMS {motion['rms_acceleration'] / g:.3f} g"
            + (f"; the records' mean PGA {motion['records_pga_mean'] / g:.3f} g" if "records_pga_mean" in motion else "")
            + "</td></tr>",
            (f"<tr><th>storey</th><th>yield drift [{u.length_label}]</th><th>yield force [{u.force_label}]</th>"
             "<th>post-yield ratio</th><th>Bouc-Wen n</th></tr>")]
    for storey in terms["storeys"]:
        drift, force = storey["yield_drift"], storey["yield_force"]
        rows.append(f"<tr><td>building {storey['building']}, storey {storey['storey']}</td>"
                    f"<td>{'elastic' if drift is None else f'{u.from_si(drift, length=1):.4g}'}</td>"
                    f"<td>{'elastic' if force is None else f'{u.from_si(force, force=1):.4g}'}</td>"
                    f"<td>{storey['post_yield_ratio']:g}</td><td>{storey['n']:g}</td></tr>")
    return '<table class="case-table">' + "".join(rows) + "</table>"


def hazard_figure(case: Case, seed: int = defaults.REPORT_SEED):
    """The design spectrum, its random-vibration counterpart and the mean spectrum of
    :data:`SPECTRUM_RECORDS` records drawn from it; or, for recorded motions, their
    mean periodogram against the fitted spectrum. None for a process given by its parameters."""
    if case.hazard is None:
        return None
    from bokeh.plotting import figure

    common = dict(output_backend="canvas", sizing_mode="stretch_width", height=320, tools="pan,wheel_zoom,box_zoom,reset,save")
    if isinstance(case.hazard, DesignSpectrum):
        compatible = case.hazard.compatible
        periods = np.asarray(compatible.periods)
        _, records, time_step = next(ground_motion_batches(case, seed, range(SPECTRUM_RECORDS)))
        resolved = periods[periods >= 10 * time_step]
        mean = pseudo_acceleration_spectrum(records, time_step, resolved).mean(axis=0)
        plot = figure(title=f"Design spectrum ({html.escape(case.hazard.target.describe())}) and the records drawn from it",
                      x_axis_type="log", x_axis_label="period T [s]", y_axis_label="pseudo-acceleration Sa (5 %) [g]", **common)
        plot.line(periods, np.asarray(compatible.target) / STANDARD_GRAVITY, line_width=3, color="black", legend_label="design spectrum")
        plot.line(periods, np.asarray(compatible.expected) / STANDARD_GRAVITY, line_dash="dashed", color="#1f77b4",
                  legend_label="random vibration, the PSD both methods use")
        plot.scatter(resolved, mean / STANDARD_GRAVITY, color="#d62728", size=5,
                     legend_label=f"mean of {SPECTRUM_RECORDS} records (seed {seed})")
    else:
        fitted = case.hazard.fitted
        omega = np.asarray(fitted.frequencies)
        plot = figure(title=f"Recorded motions ({len(case.hazard.records)}): mean periodogram and the fitted {fitted.to_dict()['spectrum']} spectrum",
                      x_axis_type="log", y_axis_type="log", x_axis_label="circular frequency [rad/s]",
                      y_axis_label="two-sided PSD of ground acceleration [m^2/s^3]", **common)
        positive = np.asarray(fitted.periodogram) > 0
        plot.line(omega[positive], np.asarray(fitted.periodogram)[positive], color="#7f7f7f", legend_label="records' mean periodogram")
        plot.line(omega, fitted.spectrum.psd(omega), line_width=3, color="#1f77b4", legend_label="fitted (the closed form's)")
    plot.legend.location = "top_right"
    plot.legend.click_policy = "hide"
    return plot
