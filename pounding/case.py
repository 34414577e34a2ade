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

from . import defaults
from .contact import Contact, contact_law
from .errors import CaseError, check_limit, described, finite_number, quote
from .excitation import CloughPenzien, Excitation, KanaiTajimi, ShinozukaSato
from .presets import preset_description, preset_names, preset_text
from .structures import BoucWen, Building, Storey, check_storey_count
from .units import SI, UNIT_SYSTEMS, UnitSystem, unit_system

__all__ = ["DEFAULT_PRESET", "Case", "as_case", "case_from_dict", "load_case", "read_case_file", "preset_description", "preset_names"]

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
    """

    excitation: Excitation
    buildings: tuple[Building, Building]
    contact: Contact
    name: str = "case"
    description: str = ""
    units: str = "SI"

    def __post_init__(self):
        if not isinstance(self.excitation, Excitation):
            raise CaseError("excitation", f"must be an Excitation, got {described(self.excitation)}")
        buildings = self.buildings
        if isinstance(buildings, (str, bytes, Mapping)) or not hasattr(buildings, "__len__"):
            raise CaseError("buildings", f"must be a tuple of two Building, got {described(buildings)}")
        if len(buildings) != 2:
            raise CaseError("buildings", f"a case has exactly two buildings, got {len(buildings)}")
        object.__setattr__(self, "buildings", tuple(buildings))
        for number, building in enumerate(self.buildings, start=1):
            if not isinstance(building, Building):
                raise CaseError(f"buildings.{number}", f"must be a Building, got {described(building)}")
        if not isinstance(self.contact, Contact):
            raise CaseError("contact", f"must be a Contact, got {described(self.contact)}")
        for key in ("name", "description"):
            if not isinstance(getattr(self, key), str):
                raise CaseError(key, f"must be a string, got {described(getattr(self, key))}")
        if not (isinstance(self.units, str) and self.units in UNIT_SYSTEMS):
            raise CaseError("units", f"must be one of {', '.join(UNIT_SYSTEMS)}, got {quote(self.units)}")
        for number, (level, building) in enumerate(zip(self.contact.levels, self.buildings), start=1):
            if level > building.n_storeys:
                raise CaseError(
                    "contact.levels",
                    f"building {number} has {building.n_storeys} storey(s); its contact level must lie in 1..{building.n_storeys}, got {quote(level)}",
                )

    @property
    def contact_masses(self) -> tuple[float, float]:
        """Masses of the two colliding floors [kg]."""
        return tuple(b.storeys[level - 1].mass for b, level in zip(self.buildings, self.contact.levels))

    @property
    def reduced_mass(self) -> float:
        """m1 m2 / (m1 + m2) of the colliding floors [kg] (Eq. 4, 13)."""
        m1, m2 = self.contact_masses
        return m1 * m2 / (m1 + m2)


# --- loading -----------------------------------------------------------------
# Every number is checked here as the file writes it, in the file's units, and
# only then converted to SI: an error quotes the key and the value as written.

_TOP_KEYS = {"units", "name", "description", "excitation", "buildings", "contact"}
_EXCITATION_KEYS = {"spectrum", "G0", "omega_g", "xi_g", "omega_f", "xi_f", "duration", "envelope", "B1", "B2", "time_step", "cutoff_frequency", "synthesis_factor"}
_BUILDING_KEYS = {"damping_ratio", "storeys"}
_STOREY_KEYS = {"mass", "stiffness", "period", "damping", "bouc_wen"}
_BOUC_WEN_KEYS = {"alpha", "A", "beta", "gamma", "n"}
_CONTACT_KEYS = {"model", "gap", "stiffness", "restitution", "levels"}
SPECTRA = ("kanai-tajimi", "clough-penzien")
ENVELOPES = ("none", "shinozuka-sato")


def _check_keys(table, allowed: set[str], where: str) -> None:
    if not isinstance(table, Mapping):
        raise CaseError(where or "case", f"must be a table, got {described(table)}")
    for key in table:
        if key not in allowed:
            written = quote(key) if not isinstance(key, str) or len(key) > 40 else key
            field = f"{where}.{written}" if where else written
            raise CaseError(field, f"unknown key; allowed here: {', '.join(sorted(allowed))}")


def _number(table, key: str, where: str, default=None) -> float:
    value = table.get(key, default)
    if value is None:
        raise CaseError(f"{where}.{key}", "is required")
    return finite_number(f"{where}.{key}", value)


def _to_si(field: str, value: float, units: UnitSystem, **dimensions) -> float:
    """``value``, written in ``units``, in SI; :class:`CaseError` if it leaves the floats."""
    if value == 0.0:
        return 0.0
    try:
        converted = units.to_si(value, **dimensions)
    except OverflowError:
        converted = math.inf
    if not math.isfinite(converted) or converted == 0.0:
        label = units.label(**dimensions)
        raise CaseError(field, f"{value:g} {label} is beyond the range of numbers once in SI; give a value of sensible magnitude")
    return converted


def _quantity(table, key: str, where: str, units: UnitSystem, *, strict: bool, default=None, **dimensions) -> float:
    """A dimensional number of the file: > 0 (``strict``) or >= 0, checked in
    the file's units, then converted to SI."""
    value = _number(table, key, where, default)
    if not (value > 0 if strict else value >= 0):
        label = units.label(**dimensions)
        raise CaseError(f"{where}.{key}", f"must be {'>' if strict else '>='} 0 {label}, got {value:g} {label}")
    return _to_si(f"{where}.{key}", value, units, **dimensions)


def _build(where: str, constructor, *args, **kwargs):
    """Call a dataclass constructor, placing its errors under ``where``."""
    try:
        return constructor(*args, **kwargs)
    except CaseError as error:
        raise error.under(where) from None


def _name(table, key: str, allowed: tuple[str, ...], where: str, default: str) -> str:
    value = table.get(key, default)
    if not (isinstance(value, str) and value in allowed):
        raise CaseError(f"{where}.{key}", f"unknown {key} {quote(value)}; allowed: {', '.join(allowed)}")
    return value


def _excitation(table, units: UnitSystem) -> Excitation:
    where = "excitation"
    _check_keys(table, _EXCITATION_KEYS, where)
    spectrum_name = _name(table, "spectrum", SPECTRA, where, "kanai-tajimi")
    G0 = _quantity(table, "G0", where, units, strict=False, length=2, time=-3)
    omega_g, xi_g = _number(table, "omega_g", where), _number(table, "xi_g", where)
    if spectrum_name == "kanai-tajimi":
        for key in ("omega_f", "xi_f"):
            if key in table:
                raise CaseError(f"{where}.{key}", "applies to spectrum = 'clough-penzien' only")
        spectrum = _build(where, KanaiTajimi, G0, omega_g, xi_g)
    else:
        spectrum = _build(
            where, CloughPenzien, G0, omega_g, xi_g, _number(table, "omega_f", where, 2.0), _number(table, "xi_f", where, 0.6)
        )
    envelope_name = _name(table, "envelope", ENVELOPES, where, "none")
    if envelope_name == "none":
        for key in ("B1", "B2"):
            if key in table:
                raise CaseError(f"{where}.{key}", "applies to envelope = 'shinozuka-sato' only")
        envelope = None
    else:
        envelope = _build(where, ShinozukaSato, _number(table, "B1", where, 0.085), _number(table, "B2", where, 0.17))
    optional = {key: _number(table, key, where) for key in ("time_step", "cutoff_frequency") if key in table}
    if "synthesis_factor" in table:
        optional["synthesis_factor"] = table["synthesis_factor"]  # an integer; Excitation checks it
    return _build(where, Excitation, spectrum, _number(table, "duration", where), envelope, **optional)


def _bouc_wen(table, units: UnitSystem, where: str) -> BoucWen:
    _check_keys(table, _BOUC_WEN_KEYS, where)
    values = {key: _number(table, key, where, default) for key, default in (("alpha", 1.0), ("A", 1.0), ("beta", 0.0), ("gamma", 0.0), ("n", 1.0))}
    as_written = _build(where, BoucWen, **values)  # checked in the file's units: beta, gamma are quoted as written
    n = as_written.n  # beta, gamma multiply |z|^n: [1/length^n]
    converted = {key: _to_si(f"{where}.{key}", values[key], units, length=-n) for key in ("beta", "gamma")}
    return _build(where, dataclasses.replace, as_written, **converted)


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


def _storey(table, units: UnitSystem, where: str, single: bool) -> Storey:
    _check_keys(table, _STOREY_KEYS, where)
    bouc_wen = _bouc_wen(table.get("bouc_wen", {"alpha": 1.0}), units, f"{where}.bouc_wen")
    given = [key for key in ("mass", "stiffness", "period") if key in table]
    if "period" in given and not single:
        raise CaseError(f"{where}.period", "applies to one-storey buildings only; give mass and stiffness per storey")
    if len(given) != 2:
        allowed = "mass and stiffness, or two of mass, stiffness and period" if single else "mass and stiffness"
        raise CaseError(where, f"give {allowed}; got {', '.join(given) or 'none'}")
    mass = _quantity(table, "mass", where, units, strict=True, mass=1) if "mass" in table else None
    stiffness = _quantity(table, "stiffness", where, units, strict=True, force=1, length=-1) if "stiffness" in table else None
    if "period" in table:
        period = _number(table, "period", where)
        if period <= 0:
            raise CaseError(f"{where}.period", f"must be > 0 s, got {period:g} s")
        mass, stiffness = _from_period(where, period, mass, stiffness)
    damping = _quantity(table, "damping", where, units, strict=False, force=1, length=-1, time=1) if "damping" in table else None
    return _build(where, Storey, mass, stiffness, bouc_wen, damping)


def _building(table, units: UnitSystem, where: str) -> Building:
    _check_keys(table, _BUILDING_KEYS, where)
    storeys = table.get("storeys")
    if not isinstance(storeys, list) or not storeys:
        raise CaseError(f"{where}.storeys", "at least one [[buildings.storeys]] table is required")
    check_storey_count(f"{where}.storeys", len(storeys))  # before any storey is read
    built = tuple(
        _storey(storey, units, f"{where}.storeys.{number}", single=len(storeys) == 1)
        for number, storey in enumerate(storeys, start=1)
    )
    return _build(where, Building, built, _number(table, "damping_ratio", where, 0.05))


def _contact(table, units: UnitSystem) -> Contact:
    where = "contact"
    _check_keys(table, _CONTACT_KEYS, where)
    model = table.get("model", "jankowski")
    exponent = contact_law(model, f"{where}.model").stiffness_exponent
    levels = table.get("levels", [1, 1])
    if not isinstance(levels, list):
        raise CaseError(f"{where}.levels", f"must be two floor numbers [building 1, building 2], got {quote(levels)}")
    return _build(
        where,
        Contact,
        gap=_quantity(table, "gap", where, units, strict=False, length=1),
        stiffness=_quantity(table, "stiffness", where, units, strict=True, force=1, length=-exponent),
        restitution=_number(table, "restitution", where, 0.65),
        levels=levels,
        model=model,
    )


def _text(data, key: str, default: str) -> str:
    value = data.get(key, default)
    if not isinstance(value, str):
        raise CaseError(key, f"must be a string, got {described(value)}")
    return value


def case_from_dict(data: Mapping, name: str = "case") -> Case:
    """Build a :class:`Case` from the parsed TOML schema (see README.md),
    converting to SI. Raises :class:`CaseError` naming the offending key as
    the file writes it, and quoting the value in the file's units."""
    if not isinstance(data, Mapping):
        raise CaseError("case", f"must be the case file's table (a dict), got {described(data)}")
    _check_keys(data, _TOP_KEYS, "")
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
    return _build(
        "",
        Case,
        excitation=_excitation(data["excitation"], units),
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
        raise CaseError("case", f"{quote(str(source), 60)} is neither a TOML file nor a preset; {_presets_hint(str(source))}")
    limit = defaults.MAX_CASE_FILE_BYTES
    try:
        with path.open("rb") as file:
            data = file.read(limit + 1 if defaults.limits_enabled() else -1)
    except OSError as error:
        raise CaseError("case", f"cannot read {quote(str(source), 80)}: {error.strerror or error}") from None
    check_limit(str(source), len(data), limit, "bytes or more in the case file", "a case file is a few kB")
    return _decode(data, str(source))


def read_case_file(path: str | os.PathLike) -> dict:
    """The parsed TOML of the case file at ``path`` (not yet checked as a case):
    :class:`CaseError` for a missing, unreadable, oversized, non-UTF-8 or malformed file."""
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
        raise CaseError("case", f"give a preset name, the path of a TOML file or the case file's table, got {described(source)}")
    return case_from_dict(read_case_file(source), name=Path(source).stem)


def as_case(value) -> Case:
    """``value`` as a :class:`Case`: a Case as it is, a preset name or the path
    of a TOML file loaded by :func:`load_case`; :class:`CaseError` naming
    ``case`` for anything else."""
    if isinstance(value, Case):
        return value
    if isinstance(value, (str, os.PathLike)):
        return load_case(value)
    raise CaseError("case", f"must be a Case, a preset name or the path of a TOML file, got {described(value)}")
