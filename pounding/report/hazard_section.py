"""The report's ground motion: the design spectrum against the records' mean
spectrum, or the recorded motions' periodogram against the fitted spectrum.
Bokeh is imported when the figure is built."""

from __future__ import annotations

import numpy as np

from pounding import defaults
from pounding.case.case import Case
from pounding.display_units import display
from pounding.report.curve_charts import legend_below
from pounding.hazard.response_spectra import pseudo_acceleration_spectrum
from pounding.hazard.sources import DesignSpectrum
from pounding.simulation.ground_motion import ground_motion_batches
from pounding.units import STANDARD_GRAVITY

__all__ = ["SPECTRUM_RECORDS", "hazard_figure", "scaled_records_figure"]

SPECTRUM_RECORDS = 20
"""Synthetic records whose mean response spectrum the report sets against a design spectrum."""


def hazard_figure(case: Case, seed: int = defaults.SEED, units: str = "SI"):
    """The design spectrum, its random-vibration counterpart and the mean spectrum of
    :data:`SPECTRUM_RECORDS` records drawn from it; or, for recorded motions, their
    mean periodogram against the fitted spectrum (in ``units``' lengths). None for a process given by its parameters."""
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
        plot = figure(title="Design spectrum and the records drawn from it",
                      x_axis_type="log", x_axis_label="period T [s]", y_axis_label="pseudo-acceleration Sa (5 %) [g]", **common)
        plot.line(periods, np.asarray(compatible.target) / STANDARD_GRAVITY, line_width=3, color="black", legend_label="design spectrum")
        plot.line(periods, np.asarray(compatible.expected) / STANDARD_GRAVITY, line_dash="dashed", color="#1f77b4",
                  legend_label="random vibration, the PSD both methods use")
        plot.scatter(resolved, mean / STANDARD_GRAVITY, color="#d62728", size=5,
                     legend_label=f"mean of {SPECTRUM_RECORDS} records (seed {seed})")
    else:
        shown = display(units)
        fitted = case.hazard.fitted
        omega = np.asarray(fitted.frequencies)
        plot = figure(title=f"Recorded motions ({len(case.hazard.records)}): mean periodogram and the fitted spectra",
                      x_axis_type="log", y_axis_type="log", x_axis_label="circular frequency [rad/s]",
                      y_axis_label=f"two-sided PSD of ground acceleration [{shown.length_unit}^2/s^3]", **common)
        periodogram = np.asarray(fitted.periodogram) / shown.length_scale**2
        positive = periodogram > 0
        plot.line(omega[positive], periodogram[positive], color="#7f7f7f", legend_label="records' mean periodogram")
        suite = case.hazard.suite
        if suite is not None:
            band = omega[omega <= suite.cutoff_frequency]
            plot.line(band, suite.bank.psd(band) / suite.peak_to_mean / shown.length_scale**2, line_width=3, color="#1f77b4",
                      legend_label="filter bank (the closed form's)")
        plot.line(omega, fitted.spectrum.psd(omega) / shown.length_scale**2, line_width=2, line_dash="dashed",
                  color="#ff7f0e", legend_label=f"{fitted.to_dict()['spectrum']} (a description)")
    plot.legend.click_policy = "hide"
    legend_below(plot, columns=2)
    return plot


def scaled_records_figure(case: Case):
    """Records scaled to a design spectrum: the target over the matching range, the scaled records' mean Sa and
    each record's, and the expected Sa of the process the closed form takes (C1-C3, of the fitted spectrum).
    None unless the case's records were scaled to a spectrum."""
    scaling = getattr(case.hazard, "spectrum_scaling", None)
    if scaling is None:
        return None
    from bokeh.plotting import figure

    from pounding.hazard.compatible_psd import random_vibration_spectrum

    periods = np.asarray(scaling.periods)
    in_g = 1.0 / STANDARD_GRAVITY
    plot = figure(title=f"{len(case.hazard.records)} records scaled to the design spectrum ({scaling.fit})", x_axis_type="log",
                  x_axis_label="period T [s]", y_axis_label="pseudo-acceleration Sa (5 %) [g]", output_backend="canvas",
                  sizing_mode="stretch_width", height=320, tools="pan,wheel_zoom,box_zoom,reset,save")
    scaled = scaling.factors[:, None] * scaling.spectra
    for row in scaled:
        plot.line(periods, row * in_g, color="#bbbbbb", line_width=1, legend_label="each record, as scaled")
    plot.line(periods, np.asarray(scaling.target) * in_g, line_width=3, color="black", legend_label="design spectrum")
    if scaling.fit == "not-below" and scaling.not_below != 1:
        plot.line(periods, scaling.not_below * np.asarray(scaling.target) * in_g, line_dash="dotted", color="black",
                  legend_label=f"{scaling.not_below:g} x the design spectrum")
    plot.line(periods, scaled.mean(axis=0) * in_g, line_width=3, color="#d62728", legend_label="records' mean, as scaled")
    # The process the closed form takes: its expected Sa (random vibration, C1-C3); it follows whatever spectrum is fitted.
    excitation = case.excitation
    expected = random_vibration_spectrum(excitation.spectrum, periods, excitation.duration, excitation.envelope,
                                         excitation.cutoff_frequency)
    plot.line(periods, expected * in_g, line_dash="dashed", color="#1f77b4", line_width=2,
              legend_label="the closed form's process (expected Sa)")
    plot.legend.click_policy = "hide"
    legend_below(plot, columns=2)
    return plot
