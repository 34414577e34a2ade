"""A case in an engineer's terms, whatever form its file used: each storey's
yield drift and yield force, the ground motion's peak and RMS acceleration,
and where the motion came from (a design spectrum, recorded motions)."""

from __future__ import annotations

import math

import numpy as np

from pounding.case.case import Case
from pounding.hazard.sources import DesignSpectrum

__all__ = ["engineering_terms", "fundamental_periods", "ground_motion_terms", "storey_terms"]


_NAMES = {"KanaiTajimi": "Kanai-Tajimi", "CloughPenzien": "Clough-Penzien"}


def _finite(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def storey_terms(case: Case) -> list[dict]:
    """One entry per storey of both buildings (SI): yield drift [m] and yield force [N]
    (None for an elastic storey), post-yield ratio, the Bouc-Wen n and beta / (beta + gamma)."""
    rows = []
    for number, building in enumerate(case.buildings, start=1):
        for level, storey in enumerate(building.storeys, start=1):
            law = storey.bouc_wen
            share = law.beta / (law.beta + law.gamma) if storey.yields else None
            rows.append({"building": number, "storey": level, "stiffness": storey.stiffness, "mass": storey.mass,
                         "yield_drift": _finite(storey.yield_drift), "yield_force": _finite(storey.yield_force),
                         "post_yield_ratio": law.alpha, "n": law.n, "beta_share": share})
    return rows


def ground_motion_terms(case: Case) -> dict:
    """The excitation's expected peak and RMS ground acceleration [m/s^2] (of its records, below the cutoff), its source,
    and for recorded motions the records' own mean peak."""
    from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration, rms_acceleration

    excitation = case.excitation
    source = ("recorded motions" if case.recorded else f"design spectrum ({case.hazard.code})"
              if isinstance(case.hazard, DesignSpectrum) else _NAMES.get(type(excitation.spectrum).__name__, "filter bank"))
    terms = {"source": source, "pga_expected": expected_peak_ground_acceleration(excitation),
             "rms_acceleration": rms_acceleration(excitation)}
    if case.recorded:
        terms["records_pga_mean"] = float(np.mean([record.peak for record in case.hazard.records]))
    return terms


def fundamental_periods(case: Case) -> tuple[float, ...]:
    """Each building's fundamental period [s]."""
    return tuple(float(building.periods[0]) for building in case.buildings)


def engineering_terms(case: Case) -> dict:
    """The keys ``storeys``, ``ground_motion`` and, where they apply, ``fitted_excitation``, ``suite_spectrum``,
    ``fit_quality`` (recorded motions: S1-S8), ``record_files``, ``record_scaling``, ``record_source``,
    ``record_metadata`` and ``spectrum_scaling`` (recorded motions) and ``design_spectrum`` of ``estimate --json`` (SI)."""
    terms = {"storeys": storey_terms(case), "ground_motion": ground_motion_terms(case)}
    if case.recorded:
        terms["fitted_excitation"] = case.hazard.fitted.to_dict()
        if case.hazard.suite is not None:
            terms["suite_spectrum"] = case.hazard.suite.to_dict()
            terms["fit_quality"] = case.hazard.fit_quality(fundamental_periods(case)).to_dict()
        terms["record_files"] = case.hazard.names
        terms["record_scaling"] = case.hazard.scaling
        terms["record_source"] = case.hazard.source
        terms["record_metadata"] = case.hazard.metadata
        if case.hazard.spectrum_scaling is not None:
            terms["spectrum_scaling"] = case.hazard.spectrum_scaling.to_dict()
    elif isinstance(case.hazard, DesignSpectrum):
        terms["design_spectrum"] = case.hazard.to_dict()
    return terms
