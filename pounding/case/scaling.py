"""A case moved along one engineering axis, the others held: the ground motion
scaled to another expected peak ground acceleration (a fragility curve's
abscissa), or the buildings made stiffer or softer to other fundamental
periods (a force spectrum's). docs/fragility.md, F1-F2.

Both act on a loaded :class:`~pounding.case.case.Case`, so the closed form in this
process and the Monte Carlo on Dask workers (which load the case file and
apply the same :func:`adjusted`) integrate the same physics.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from pounding import defaults
from pounding.case.case import Case
from pounding.errors import ArgumentError, CaseError, finite_number, quote
from pounding.hazard.sources import RecordedMotions
from pounding.units import STANDARD_GRAVITY

__all__ = ["ADJUSTMENTS", "PeakGroundAcceleration", "adjusted", "with_fundamental_periods"]

ADJUSTMENTS = ("pga", "period1", "period2")
"""The keys of an adjustment (:func:`adjusted`): the expected PGA [m/s^2], the buildings' fundamental periods [s]."""

_EQUAL_PEAKS = 1e-9  # relative spread of the records' peaks below which a suite is taken as already scaled to one PGA


class PeakGroundAcceleration:
    """``case`` with its ground motion scaled to another expected PGA (F1).

    A random process (Kanai-Tajimi, Clough-Penzien, a design spectrum's filter
    bank) has its intensity G0 scaled by (pga / E[PGA])^2: E[PGA] of its records
    (G29) grows as sqrt(G0) (G30). Recorded motions are each scaled to peak ``|a|`` =
    pga, and the spectra fitted to them (R1-R6, S1-S5) are fitted once, to the suite
    scaled to one common peak, and then scaled by (pga / that peak)^2, as
    scaling every record by a factor scales its periodogram by the factor squared.

    Built once per case; :meth:`case_at` is then cheap (no refit, no second E[PGA]).
    """

    def __init__(self, case: Case):
        if not isinstance(case, Case):
            raise ArgumentError("case", f"must be a Case, got {type(case).__name__}")
        if case.recorded:
            case = _records_at_one_peak(case)
            self.reference = case.hazard.records[0].peak
        else:
            from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration

            self.reference = expected_peak_ground_acceleration(case.excitation)
        self.case = case

    @property
    def reference_g(self) -> float:
        """The case's own expected PGA [g] (for recorded motions, the common peak the suite was scaled to)."""
        return self.reference / STANDARD_GRAVITY

    def case_at(self, pga: float) -> Case:
        """The case with expected PGA ``pga`` [m/s^2] (recorded motions: each record's peak)."""
        pga = finite_number("pga", pga, error=ArgumentError)
        if not pga > 0:
            raise ArgumentError("pga", f"must be > 0 g, got {quote(pga / STANDARD_GRAVITY)} g")
        factor = pga / self.reference
        case = self.case
        excitation = case.excitation
        spectrum = dataclasses.replace(excitation.spectrum, G0=excitation.spectrum.G0 * factor**2)
        hazard = None  # a design spectrum's target is the unscaled one: it no longer describes the motion
        if case.recorded:
            hazard = case.hazard.scaled(factor, f"each to a PGA of {pga / STANDARD_GRAVITY:.4g} g")
        return dataclasses.replace(case, excitation=dataclasses.replace(excitation, spectrum=spectrum), hazard=hazard,
                                   name=f"{case.name} at PGA {pga / STANDARD_GRAVITY:.4g} g")


def _records_at_one_peak(case: Case) -> Case:
    """A recorded case with every record scaled to the suite's largest peak, its spectrum fitted again if they differed."""
    motions = case.hazard
    peaks = np.array([record.peak for record in motions.records])
    if np.ptp(peaks) <= _EQUAL_PEAKS * peaks.max():
        return case
    peak = float(peaks.max())
    records = tuple(record.scaled(peak / record.peak) for record in motions.records)
    cutoff = motions.suite.requested_cutoff if motions.suite is not None else case.excitation.cutoff_frequency
    hazard = RecordedMotions.fit(records, cutoff, "each to one PGA", motions.source)
    return dataclasses.replace(case, excitation=hazard.excitation(), hazard=hazard)


def _scaled_building(building, period: float, where: str):
    """``building`` with every storey stiffness times f = (T / period)^2, T its fundamental period (F2): the mode
    shapes, masses, yield drifts and damping ratio stay; an explicit storey damping is scaled by sqrt(f) to keep it."""
    period = finite_number(where, period, error=ArgumentError)
    low, high = defaults.PERIOD_RANGE
    if not low <= period <= high:
        raise ArgumentError(where, f"must lie in [{low:g}, {high:g}] s, got {quote(period)} s")
    factor = (float(building.periods[0]) / period) ** 2
    storeys = []
    for storey in building.storeys:
        damping = None if storey.damping is None else storey.damping * math.sqrt(factor)
        try:
            storeys.append(dataclasses.replace(storey, stiffness=storey.stiffness * factor, damping=damping))
        except CaseError as error:
            raise ArgumentError(where, f"{period:g} s makes a storey invalid: {error.message}") from None
    return dataclasses.replace(building, storeys=tuple(storeys))


def with_fundamental_periods(case: Case, period1: float | None = None, period2: float | None = None) -> Case:
    """``case`` with building 1 and 2 stiffened or softened to the fundamental periods ``period1``, ``period2``
    [s] (None: kept), masses, yield drifts, damping ratios, contact and ground motion held (F2)."""
    buildings = list(case.buildings)
    for index, period in enumerate((period1, period2)):
        if period is not None:
            buildings[index] = _scaled_building(buildings[index], period, f"period{index + 1}")
    try:
        return dataclasses.replace(case, buildings=tuple(buildings))
    except CaseError as error:  # a recorded motion shorter than five times the new longest period
        field = "period1" if period1 is not None else "period2"
        raise ArgumentError(field, error.message) from None


def adjusted(case: Case, adjustment: Mapping | None, scaling: PeakGroundAcceleration | None = None) -> Case:
    """``case`` moved by ``adjustment`` ({"pga": m/s^2, "period1": s, "period2": s}, any of them; None or {}: as
    it is). ``scaling``: the case's :class:`PeakGroundAcceleration`, when one is at hand (it is built otherwise)."""
    adjustment = dict(adjustment or {})
    unknown = sorted(set(adjustment) - set(ADJUSTMENTS))
    if unknown:
        raise ArgumentError("adjustment", f"unknown key {unknown[0]!r}; allowed: {', '.join(ADJUSTMENTS)}")
    if "pga" in adjustment:
        case = (scaling or PeakGroundAcceleration(case)).case_at(adjustment["pga"])
    if "period1" in adjustment or "period2" in adjustment:
        case = with_fundamental_periods(case, adjustment.get("period1"), adjustment.get("period2"))
    return case
