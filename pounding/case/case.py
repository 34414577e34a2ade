"""A case: the excitation, a row of buildings and the contacts between neighbours.

Cases load from TOML (see README.md for the schema) or from a built-in
preset; quantities are converted to SI here, once.
"""

from __future__ import annotations

import codecs
import dataclasses
import difflib
import math
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from pounding import defaults
from pounding.case.excitation import read_excitation
from pounding.case.fields import build, check_keys, number, quantity, to_si
from pounding.errors import ArgumentError, CaseError, check_limit, described, quote
from pounding.hazard.excitation import Excitation
from pounding.hazard.sources import DesignSpectrum, RecordedMotions
from pounding.mechanics.contact import Contact, contact_law
from pounding.mechanics.structures import BoucWen, Building, Storey, check_storey_count
from pounding.presets import preset_description, preset_names, preset_text
from pounding.units import SI, UNIT_SYSTEMS, UnitSystem, unit_system

__all__ = ["ALIGNED", "DEFAULT_PRESET", "Case", "as_case", "case_from_dict", "check_row_size", "contact_label", "load_case",
           "preset_description", "preset_names", "read_case_file"]

DEFAULT_PRESET = defaults.CASE


@dataclass(frozen=True)
class Case:
    """Adjacent buildings in a row under a random ground motion, and the
    contacts between neighbouring floors.

    Parameters
    ----------
    excitation : Excitation
    buildings : tuple of Building
        Two or more, left to right: a positive displacement of a building
        closes the gap to its right neighbour.
    contacts : tuple of Contact, or one Contact
        At most one per pair of floors, in the case's order (each names the
        buildings it joins: ``Contact.between``).
    name, description : str
    title : str
        A short human name for lists (a preset's: "Section 5 (one storey each), T2 = 0.4 s"); optional.
    units : str
        The unit system the case was written in (for display only: every
        quantity held here is SI).
    hazard : DesignSpectrum, RecordedMotions or None
        Where the excitation came from (:mod:`pounding.hazard.sources`): for recorded
        motions, the Monte Carlo integrates ``hazard.records`` and the closed
        form takes ``excitation``, the spectrum fitted to them.
    """

    excitation: Excitation
    buildings: tuple[Building, ...]
    contacts: tuple[Contact, ...]
    name: str = "case"
    description: str = ""
    units: str = "SI"
    hazard: DesignSpectrum | RecordedMotions | None = None
    title: str = ""

    def __post_init__(self):
        if not isinstance(self.excitation, Excitation):
            raise CaseError("excitation", f"must be an Excitation, got {described(self.excitation)}")
        object.__setattr__(self, "buildings", _as_tuple(self.buildings, "buildings", "Building"))
        if len(self.buildings) < 2:
            raise CaseError("buildings", f"a case has at least two buildings, got {len(self.buildings)}")
        for index, building in enumerate(self.buildings, start=1):
            if not isinstance(building, Building):
                raise CaseError(f"buildings.{index}", f"must be a Building, got {described(building)}")
        check_row_size(self.buildings)
        contacts = (self.contacts,) if isinstance(self.contacts, Contact) else self.contacts
        object.__setattr__(self, "contacts", _as_tuple(contacts, "contacts", "Contact"))
        for key in ("name", "description", "title"):
            if not isinstance(getattr(self, key), str):
                raise CaseError(key, f"must be a string, got {described(getattr(self, key))}")
        if not (isinstance(self.units, str) and self.units in UNIT_SYSTEMS):
            raise CaseError("units", f"must be one of {', '.join(UNIT_SYSTEMS)}, got {quote(self.units)}")
        if self.hazard is not None and not isinstance(self.hazard, (DesignSpectrum, RecordedMotions)):
            raise CaseError("hazard", f"must be a DesignSpectrum, RecordedMotions or None, got {described(self.hazard)}")
        if isinstance(self.hazard, RecordedMotions):
            _check_record_lengths(self.hazard, self.buildings)
        _check_contacts(self.contacts, self.buildings)

    @property
    def recorded(self) -> bool:
        """Whether the Monte Carlo integrates recorded accelerograms (not synthetic records)."""
        return isinstance(self.hazard, RecordedMotions)

    @property
    def contact(self) -> Contact:
        """The case's one contact; :class:`CaseError` naming ``contacts`` when it has several
        (take each with :meth:`pair`)."""
        if len(self.contacts) != 1:
            raise CaseError("contacts", f"the case has {len(self.contacts)} contacts and this takes one; "
                                        "estimate, simulate, fragility and spectrum take several")
        return self.contacts[0]

    def with_contact(self, **changes) -> Case:
        """The case with its one contact changed (``gap=``, ``restitution=``, ...: :class:`Contact`'s fields)."""
        return dataclasses.replace(self, contacts=(dataclasses.replace(self.contact, **changes),))

    def floor_mass(self, building: int, level: int) -> float:
        """Mass of floor ``level`` of building ``building``, both counted from 1 [kg]."""
        return self.buildings[building - 1].storeys[level - 1].mass

    def reduced_mass_of(self, contact: Contact) -> float:
        """m1 m2 / (m1 + m2) of the floors ``contact`` joins [kg] (Eq. 4, 13)."""
        m1, m2 = (self.floor_mass(b, level) for b, level in zip(contact.between, contact.levels))
        return m1 * m2 / (m1 + m2)

    @property
    def contact_masses(self) -> tuple[float, float]:
        """Masses of the two colliding floors of the one contact [kg]."""
        return tuple(self.floor_mass(b, level) for b, level in zip(self.contact.between, self.contact.levels))

    @property
    def reduced_mass(self) -> float:
        """m1 m2 / (m1 + m2) of the one contact's floors [kg] (Eq. 4, 13)."""
        return self.reduced_mass_of(self.contact)

    def pair(self, index: int) -> Case:
        """Contact ``index`` (from 0, the case's order) with its two buildings alone: a two-building case
        under the same excitation (its name says which contact it is)."""
        contact = self.contacts[index]
        if len(self.contacts) == 1 and contact.between == (1, 2) and len(self.buildings) == 2:
            return self
        left, right = contact.between
        return dataclasses.replace(
            self, buildings=(self.buildings[left - 1], self.buildings[right - 1]),
            contacts=(dataclasses.replace(contact, between=(1, 2)),), name=f"{self.name}, {contact_label(contact)}",
        )


def contact_label(contact: Contact) -> str:
    """A contact in words: "buildings 1-2, floors 3/2"."""
    (left, right), (level_left, level_right) = contact.between, contact.levels
    return f"buildings {left}-{right}, floors {level_left}/{level_right}"


def _as_tuple(values, key: str, kind: str) -> tuple:
    if isinstance(values, (str, bytes, Mapping)) or not hasattr(values, "__len__"):
        raise CaseError(key, f"must be a tuple of {kind}, got {described(values)}")
    return tuple(values)


def check_row_size(buildings) -> None:
    """:class:`CaseError` naming ``buildings`` for a row beyond :data:`~pounding.defaults.MAX_BUILDINGS` or
    :data:`~pounding.defaults.MAX_ROW_STOREYS` storeys in all."""
    check_limit("buildings", len(buildings), defaults.MAX_BUILDINGS, "buildings in a row", "assess the row a few buildings at a time")
    check_limit("buildings", sum(b.n_storeys for b in buildings), defaults.MAX_ROW_STOREYS, "storeys in the row",
                "lump storeys together or assess fewer buildings")


def _check_contacts(contacts: tuple, buildings: tuple, wheres: tuple[str, ...] | None = None) -> None:
    """Each contact joins neighbours that exist, at floors they have, once; errors name ``wheres`` (the keys as the
    case file writes them), ``contact`` or ``contacts.i`` by default."""
    if not contacts:
        raise CaseError("contacts", "a case needs at least one contact")
    if wheres is None:
        wheres = ("contact",) if len(contacts) == 1 else tuple(f"contacts.{i}" for i in range(1, len(contacts) + 1))
    seen = {}
    for where, contact in zip(wheres, contacts):
        if not isinstance(contact, Contact):
            raise CaseError(where, f"must be a Contact, got {described(contact)}")
        left, right = contact.between
        if right > len(buildings):
            raise CaseError(f"{where}.between", f"building {right} does not exist: the case has {len(buildings)} buildings")
        for building, level in zip(contact.between, contact.levels):
            storeys = buildings[building - 1].n_storeys
            if level > storeys:
                raise CaseError(f"{where}.levels", f"building {building} has {storeys} storey(s); its contact level must lie "
                                                   f"in 1..{storeys}, got {quote(level)}")
        key = (contact.between, contact.levels)
        if key in seen:
            raise CaseError(f"{where}.levels", f"floors {contact.levels[0]}/{contact.levels[1]} of buildings {left}-{right} "
                                               f"already meet in {seen[key]}; give each pair of floors once")
        seen[key] = where


RECORD_PERIODS_MIN = 5.0
"""A record must last at least this many times the longest natural period of the two buildings."""


def _check_record_lengths(motions: RecordedMotions, buildings) -> None:
    longest = max(float(building.periods[0]) for building in buildings)
    for record in motions.records:
        if record.duration < RECORD_PERIODS_MIN * longest:
            raise CaseError(record.name, f"lasts {record.duration:.3g} s, under {RECORD_PERIODS_MIN:g} times the buildings' longest "
                            f"period ({longest:.3g} s): its peak response is not reached; use a longer record")


# --- loading -----------------------------------------------------------------
# Every number is checked here as the file writes it, in the file's units, and
# only then converted to SI: an error quotes the key and the value as written.

_TOP_KEYS = {"units", "name", "title", "description", "excitation", "buildings", "contact", "contacts"}
_BUILDING_KEYS = {"damping_ratio", "storeys"}
_STOREY_KEYS = {"mass", "stiffness", "period", "damping", "bouc_wen", "hysteresis"}
_BOUC_WEN_KEYS = {"alpha", "A", "beta", "gamma", "n"}
_HYSTERESIS_KEYS = {"yield_drift", "yield_force", "post_yield_ratio", "n", "beta_share"}
_CONTACT_KEYS = {"model", "gap", "stiffness", "restitution", "levels", "between"}
ALIGNED = "aligned"
"""``levels = "aligned"``: every floor the two buildings share, floor k with floor k (equal storey heights)."""


def _bouc_wen(table, units: UnitSystem, where: str) -> BoucWen:
    check_keys(table, _BOUC_WEN_KEYS, where)
    values = {key: number(table, key, where, default) for key, default in (("alpha", 1.0), ("A", 1.0), ("beta", 0.0), ("gamma", 0.0), ("n", 1.0))}
    as_written = build(where, BoucWen, **values)  # checked in the file's units: beta, gamma are quoted as written
    n = as_written.n  # beta, gamma multiply |z|^n: [1/length^n]
    converted = {key: to_si(f"{where}.{key}", values[key], units, length=-n) for key in ("beta", "gamma")}
    return build(where, dataclasses.replace, as_written, **converted)


def _from_period(where: str, period: float, mass: float | None, stiffness: float | None) -> tuple[float, float]:
    """Mass and stiffness of a one-storey building given its period and one of them."""
    try:
        omega_squared = (2.0 * math.pi / period) ** 2
        mass, stiffness = (stiffness / omega_squared, stiffness) if mass is None else (mass, mass * omega_squared)
    except (OverflowError, ZeroDivisionError):
        mass = stiffness = math.inf
    if not (math.isfinite(mass) and math.isfinite(stiffness) and mass > 0 and stiffness > 0):
        raise CaseError(f"{where}.period", f"{period:g} s gives a mass or stiffness beyond the range of numbers; check its magnitude")
    return mass, stiffness


def _hysteresis(table, units: UnitSystem, where: str, stiffness: float) -> BoucWen:
    """A storey's law from its yield drift or yield force (G28); lengths and forces in the file's units."""
    check_keys(table, _HYSTERESIS_KEYS, where)
    given = [key for key in ("yield_drift", "yield_force") if key in table]
    if len(given) != 1:
        raise CaseError(where, f"give one of yield_drift and yield_force; got {', '.join(given) or 'none'}")
    if "post_yield_ratio" not in table:
        raise CaseError(f"{where}.post_yield_ratio", "is required: the post-yield to initial stiffness ratio, in [0, 1)")
    if given == ["yield_drift"]:
        drift = quantity(table, "yield_drift", where, units, strict=True, length=1)
    else:
        drift = quantity(table, "yield_force", where, units, strict=True, force=1) / stiffness
    options = {key: number(table, key, where) for key in ("post_yield_ratio", "n", "beta_share") if key in table}
    return build(where, BoucWen.from_yield_drift, drift, **options)


def _storey(table, units: UnitSystem, where: str, single: bool) -> Storey:
    check_keys(table, _STOREY_KEYS, where)
    if "bouc_wen" in table and "hysteresis" in table:
        raise CaseError(f"{where}.hysteresis", "give bouc_wen or hysteresis, not both")
    given = [key for key in ("mass", "stiffness", "period") if key in table]
    if "period" in given and not single:
        raise CaseError(f"{where}.period", "applies to one-storey buildings only; give mass and stiffness per storey")
    if len(given) != 2:
        allowed = "mass and stiffness, or two of mass, stiffness and period" if single else "mass and stiffness"
        raise CaseError(where, f"give {allowed}; got {', '.join(given) or 'none'}")
    mass = quantity(table, "mass", where, units, strict=True, mass=1) if "mass" in table else None
    stiffness = quantity(table, "stiffness", where, units, strict=True, force=1, length=-1) if "stiffness" in table else None
    if "period" in table:
        period = number(table, "period", where)
        if period <= 0:
            raise CaseError(f"{where}.period", f"must be > 0 s, got {period:g} s")
        mass, stiffness = _from_period(where, period, mass, stiffness)
    _check_floor_mass(where, mass, units, "mass" if "mass" in table else "stiffness")
    damping = quantity(table, "damping", where, units, strict=False, force=1, length=-1, time=1) if "damping" in table else None
    if "hysteresis" in table:
        bouc_wen = _hysteresis(table["hysteresis"], units, f"{where}.hysteresis", stiffness)
    else:
        bouc_wen = _bouc_wen(table.get("bouc_wen", {"alpha": 1.0}), units, f"{where}.bouc_wen")
    return build(where, Storey, mass, stiffness, bouc_wen, damping)


def _check_floor_mass(where: str, mass: float, units: UnitSystem, key: str) -> None:
    """Refuse a floor mass [kg] outside :data:`~pounding.defaults.FLOOR_MASS_RANGE`, naming ``key`` (the mass, or the
    stiffness it came from with the period) and the range in the file's units."""
    low, high = defaults.FLOOR_MASS_RANGE
    if not low <= mass <= high:
        label = units.mass_label
        given = "" if key == "mass" else f" gives a floor mass of {units.from_si(mass, mass=1):.3g} {label}, which"
        raise CaseError(f"{where}.{key}", f"{given} must lie in [{units.from_si(low, mass=1):.3g}, "
                                          f"{units.from_si(high, mass=1):.3g}] {label} (a model's floor to ten million tonnes)".lstrip())


def _building(table, units: UnitSystem, where: str) -> Building:
    check_keys(table, _BUILDING_KEYS, where)
    storeys = table.get("storeys")
    if not isinstance(storeys, list) or not storeys:
        raise CaseError(f"{where}.storeys", "at least one [[buildings.storeys]] table is required")
    check_storey_count(f"{where}.storeys", len(storeys))  # before any storey is read
    built = tuple(
        _storey(storey, units, f"{where}.storeys.{index}", single=len(storeys) == 1)
        for index, storey in enumerate(storeys, start=1)
    )
    return build(where, Building, built, number(table, "damping_ratio", where, 0.05))


def _contacts(table, units: UnitSystem, where: str, buildings: tuple) -> list[tuple[str, Contact]]:
    """The contacts of one ``[contact]`` or ``[[contacts]]`` table, with the key each is named by: one, or one per
    shared floor for ``levels = "aligned"``."""
    check_keys(table, _CONTACT_KEYS, where)
    model = table.get("model", "jankowski")
    exponent = contact_law(model, f"{where}.model").stiffness_exponent
    between = table.get("between", [1, 2])
    levels = table.get("levels", [1, 1])
    if levels == ALIGNED:
        between = build(where, Contact, gap=0.0, stiffness=1.0, between=between).between  # checked before it is used
        if between[1] > len(buildings):
            raise CaseError(f"{where}.between", f"building {between[1]} does not exist: the case has {len(buildings)} buildings")
        shared = min(buildings[b - 1].n_storeys for b in between)
        levels = [[k, k] for k in range(1, shared + 1)]
    elif not isinstance(levels, list):
        raise CaseError(f"{where}.levels", f"must be two floor numbers [left building, right building] or {ALIGNED!r}, "
                                           f"got {quote(levels)}")
    else:
        levels = [levels]
    common = dict(gap=quantity(table, "gap", where, units, strict=False, length=1),
                  stiffness=_contact_stiffness(table, units, where, exponent),
                  restitution=number(table, "restitution", where, 0.65), model=model, between=between)
    return [(where, build(where, Contact, levels=pair, **common)) for pair in levels]


def _all_contacts(data, units: UnitSystem, buildings: tuple) -> tuple[Contact, ...]:
    """The ``[contact]`` table or the ``[[contacts]]`` array, checked against the buildings with the file's keys."""
    if ("contact" in data) == ("contacts" in data):
        raise CaseError("contacts", "give one [contact] table or an array of [[contacts]] tables" +
                        ("" if "contact" in data else "; neither is given"))
    if "contact" in data:
        found = _contacts(data["contact"], units, "contact", buildings)
    else:
        tables = data["contacts"]
        if not isinstance(tables, list) or not tables:
            raise CaseError("contacts", "must be an array of [[contacts]] tables, at least one")
        found = [item for i, table in enumerate(tables, start=1) for item in _contacts(table, units, f"contacts.{i}", buildings)]
    wheres, contacts = zip(*found)
    _check_contacts(contacts, buildings, wheres)
    return contacts


def _contact_stiffness(table, units: UnitSystem, where: str, exponent: float) -> float:
    """The contact stiffness [SI], refused outside :data:`~pounding.defaults.CONTACT_STIFFNESS_RANGE` in the file's units."""
    stiffness = quantity(table, "stiffness", where, units, strict=True, force=1, length=-exponent)
    low, high = defaults.CONTACT_STIFFNESS_RANGE
    if not low <= stiffness <= high:
        label = units.label(force=1, length=-exponent)
        raise CaseError(f"{where}.stiffness", f"must lie in [{units.from_si(low, force=1, length=-exponent):.3g}, "
                                               f"{units.from_si(high, force=1, length=-exponent):.3g}] {label}; got "
                                               f"{units.from_si(stiffness, force=1, length=-exponent):.3g}")
    return stiffness


def _text(data, key: str, default: str) -> str:
    value = data.get(key, default)
    if not isinstance(value, str):
        raise CaseError(key, f"must be a string, got {described(value)}")
    return value


def case_from_dict(data: Mapping, name: str = "case", base_directory: str | os.PathLike | None = None) -> Case:
    """Build a :class:`Case` from the parsed TOML schema (see README.md),
    converting to SI. Raises :class:`CaseError` naming the offending key as
    the file writes it, and quoting the value in the file's units. Recorded
    motions' paths are relative to ``base_directory`` (the current directory
    by default; the case file's directory when loaded from a file)."""
    if not isinstance(data, Mapping):
        raise ArgumentError("case", f"must be the case file's table (a dict), got {described(data)}")
    check_keys(data, _TOP_KEYS, "")
    units = unit_system(data.get("units", SI.name))
    for key in ("excitation", "buildings"):
        if key not in data:
            raise CaseError(key, "is required")
    buildings = data["buildings"]
    if not isinstance(buildings, list) or len(buildings) < 2:
        count = len(buildings) if isinstance(buildings, list) else 0
        raise CaseError("buildings", f"two or more [[buildings]] tables are required, left to right, got {count}")
    check_limit("buildings", len(buildings), defaults.MAX_BUILDINGS, "buildings in a row", "assess the row a few buildings at a time")
    if not isinstance(name, str):
        raise CaseError("name", f"must be a string, got {described(name)}")
    built = tuple(_building(b, units, f"buildings.{i}") for i, b in enumerate(buildings, start=1))
    check_row_size(built)
    contacts = _all_contacts(data, units, built)
    excitation, hazard = read_excitation(data["excitation"], units, Path(base_directory or "."),
                                         lambda: [float(b.periods[0]) for b in built])
    return build(
        "",
        Case,
        excitation=excitation,
        hazard=hazard,
        buildings=built,
        contacts=contacts,
        name=_text(data, "name", name),
        description=_text(data, "description", ""),
        title=_text(data, "title", ""),
        units=units.name,
    )


def _parse(text: str, source: str) -> dict:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise CaseError(source, f"not valid TOML: {error}") from None
    except RecursionError:
        raise CaseError(source, "not valid TOML: nested too deeply") from None


_BOMS = (  # UTF-32 first: its little-endian mark starts with UTF-16's
    (codecs.BOM_UTF32_LE, "utf-32"), (codecs.BOM_UTF32_BE, "utf-32"), (codecs.BOM_UTF8, "utf-8-sig"),
    (codecs.BOM_UTF16_LE, "utf-16"), (codecs.BOM_UTF16_BE, "utf-16"),
)


def _decode(data: bytes, source: str) -> str:
    """The text of a case file: UTF-8 (TOML's encoding), or UTF-16/32 with a byte-order mark."""
    encoding = next((codec for bom, codec in _BOMS if data.startswith(bom)), "utf-8")
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as error:
        byte = data[error.start]
        raise CaseError(
            source, f"not a UTF-8 text file (byte 0x{byte:02x} at offset {error.start}); a case file is TOML: save it as UTF-8"
        ) from None


def _presets_hint(name: str) -> str:
    names = preset_names()
    close = difflib.get_close_matches(name[:100], names, n=1)
    return (f"did you mean {close[0]!r}? " if close else "") + f"presets: {names[0]}, ... ('pounding cases' lists them)"


def _read(source: str | os.PathLike) -> str:
    """The text of the case file at ``source`` (at most MAX_CASE_FILE_BYTES while the limits are on)."""
    path = Path(source)
    try:
        is_file = path.is_file()
    except (OSError, ValueError):  # a name too long, a NUL byte
        is_file = False
    if not is_file:
        raise ArgumentError("case", f"{quote(str(source), 60)} is neither a TOML file nor a preset; {_presets_hint(str(source))}")
    limit = defaults.MAX_CASE_FILE_BYTES
    try:
        with path.open("rb") as file:
            data = file.read(limit + 1 if defaults.limits_enabled() else -1)
    except OSError as error:
        raise ArgumentError("case", f"cannot read {quote(str(source), 80)}: {error.strerror or error}") from None
    check_limit(str(source), len(data), limit, "bytes or more in the case file", "a case file is a few kB")
    return _decode(data, str(source))


def read_case_file(path: str | os.PathLike) -> dict:
    """The parsed TOML of the case file at ``path`` (not yet checked as a case):
    :class:`ArgumentError` naming ``case`` for a missing or unreadable file, :class:`CaseError` naming
    the file for an oversized, non-UTF-8 or malformed one."""
    return _parse(_read(path), str(Path(path)))


def load_case(source: str | os.PathLike | Mapping) -> Case:
    """A case from a preset name (see ``preset_names()``), a TOML file path or
    the parsed case file (a dict, as :func:`case_from_dict`)."""
    if isinstance(source, Mapping):
        return case_from_dict(source)
    if isinstance(source, str):
        text = preset_text(source)
        if text is not None:
            return case_from_dict(_parse(text, source), name=source)
    elif not isinstance(source, os.PathLike):
        raise ArgumentError("case", f"give a preset name, the path of a TOML file or the case file's table, got {described(source)}")
    return case_from_dict(read_case_file(source), name=Path(source).stem, base_directory=Path(source).parent)


def as_case(value) -> Case:
    """``value`` as a :class:`Case`: a Case as it is, a preset name or the path
    of a TOML file loaded by :func:`load_case`; :class:`ArgumentError` naming
    ``case`` for anything else."""
    if isinstance(value, Case):
        return value
    if isinstance(value, (str, os.PathLike)):
        return load_case(value)
    raise ArgumentError("case", f"must be a Case, a preset name or the path of a TOML file, got {described(value)}")
