"""A case: the excitation, two buildings and the contact between them.

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

__all__ = ["DEFAULT_PRESET", "Case", "as_case", "case_from_dict", "load_case", "preset_description", "preset_names", "read_case_file"]

DEFAULT_PRESET = defaults.CASE


@dataclass(frozen=True)
class Case:
    """Two adjacent buildings under a random ground motion.

    Parameters
    ----------
    excitation : Excitation
    buildings : tuple of two Building
        Building 1 stands left of building 2: a positive displacement of
        building 1 closes the gap.
    contact : Contact
    name, description : str
    units : str
        The unit system the case was written in (for display only: every
        quantity held here is SI).
    hazard : DesignSpectrum, RecordedMotions or None
        Where the excitation came from (:mod:`pounding.hazard.sources`): for recorded
        motions, the Monte Carlo integrates ``hazard.records`` and the closed
        form takes ``excitation``, the spectrum fitted to them.
    """

    excitation: Excitation
    buildings: tuple[Building, Building]
    contact: Contact
    name: str = "case"
    description: str = ""
    units: str = "SI"
    hazard: DesignSpectrum | RecordedMotions | None = None

    def __post_init__(self):
        if not isinstance(self.excitation, Excitation):
            raise CaseError("excitation", f"must be an Excitation, got {described(self.excitation)}")
        buildings = self.buildings
        if isinstance(buildings, (str, bytes, Mapping)) or not hasattr(buildings, "__len__"):
            raise CaseError("buildings", f"must be a tuple of two Building, got {described(buildings)}")
        if len(buildings) != 2:
            raise CaseError("buildings", f"a case has exactly two buildings, got {len(buildings)}")
        object.__setattr__(self, "buildings", tuple(buildings))
        for index, building in enumerate(self.buildings, start=1):
            if not isinstance(building, Building):
                raise CaseError(f"buildings.{index}", f"must be a Building, got {described(building)}")
        if not isinstance(self.contact, Contact):
            raise CaseError("contact", f"must be a Contact, got {described(self.contact)}")
        for key in ("name", "description"):
            if not isinstance(getattr(self, key), str):
                raise CaseError(key, f"must be a string, got {described(getattr(self, key))}")
        if not (isinstance(self.units, str) and self.units in UNIT_SYSTEMS):
            raise CaseError("units", f"must be one of {', '.join(UNIT_SYSTEMS)}, got {quote(self.units)}")
        if self.hazard is not None and not isinstance(self.hazard, (DesignSpectrum, RecordedMotions)):
            raise CaseError("hazard", f"must be a DesignSpectrum, RecordedMotions or None, got {described(self.hazard)}")
        if isinstance(self.hazard, RecordedMotions):
            _check_record_lengths(self.hazard, self.buildings)
        for index, (level, building) in enumerate(zip(self.contact.levels, self.buildings), start=1):
            if level > building.n_storeys:
                raise CaseError(
                    "contact.levels",
                    f"building {index} has {building.n_storeys} storey(s); its contact level must lie in 1..{building.n_storeys}, got {quote(level)}",
                )

    @property
    def recorded(self) -> bool:
        """Whether the Monte Carlo integrates recorded accelerograms (not synthetic records)."""
        return isinstance(self.hazard, RecordedMotions)

    @property
    def contact_masses(self) -> tuple[float, float]:
        """Masses of the two colliding floors [kg]."""
        return tuple(b.storeys[level - 1].mass for b, level in zip(self.buildings, self.contact.levels))

    @property
    def reduced_mass(self) -> float:
        """m1 m2 / (m1 + m2) of the colliding floors [kg] (Eq. 4, 13)."""
        m1, m2 = self.contact_masses
        return m1 * m2 / (m1 + m2)


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

_TOP_KEYS = {"units", "name", "description", "excitation", "buildings", "contact"}
_BUILDING_KEYS = {"damping_ratio", "storeys"}
_STOREY_KEYS = {"mass", "stiffness", "period", "damping", "bouc_wen", "hysteresis"}
_BOUC_WEN_KEYS = {"alpha", "A", "beta", "gamma", "n"}
_HYSTERESIS_KEYS = {"yield_drift", "yield_force", "post_yield_ratio", "n", "beta_share"}
_CONTACT_KEYS = {"model", "gap", "stiffness", "restitution", "levels"}


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


def _contact(table, units: UnitSystem) -> Contact:
    where = "contact"
    check_keys(table, _CONTACT_KEYS, where)
    model = table.get("model", "jankowski")
    exponent = contact_law(model, f"{where}.model").stiffness_exponent
    levels = table.get("levels", [1, 1])
    if not isinstance(levels, list):
        raise CaseError(f"{where}.levels", f"must be two floor numbers [building 1, building 2], got {quote(levels)}")
    return build(
        where,
        Contact,
        gap=quantity(table, "gap", where, units, strict=False, length=1),
        stiffness=_contact_stiffness(table, units, where, exponent),
        restitution=number(table, "restitution", where, 0.65),
        levels=levels,
        model=model,
    )


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
    for key in ("excitation", "buildings", "contact"):
        if key not in data:
            raise CaseError(key, "is required")
    buildings = data["buildings"]
    if not isinstance(buildings, list) or len(buildings) != 2:
        count = len(buildings) if isinstance(buildings, list) else 0
        raise CaseError("buildings", f"exactly two [[buildings]] tables are required, got {count}")
    if not isinstance(name, str):
        raise CaseError("name", f"must be a string, got {described(name)}")
    excitation, hazard = read_excitation(data["excitation"], units, Path(base_directory or "."),
                                         lambda: [float(_building(b, units, f"buildings.{i}").periods[0])
                                                  for i, b in enumerate(buildings, start=1)])
    return build(
        "",
        Case,
        excitation=excitation,
        hazard=hazard,
        buildings=tuple(_building(b, units, f"buildings.{i}") for i, b in enumerate(buildings, start=1)),
        contact=_contact(data["contact"], units),
        name=_text(data, "name", name),
        description=_text(data, "description", ""),
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
