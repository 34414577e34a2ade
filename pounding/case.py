"""A case: the excitation, two buildings and the contact between them.

Cases load from TOML (see README.md for the schema) or from a built-in
preset; quantities are converted to SI here, once.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from . import defaults
from .contact import Contact, contact_law
from .errors import CaseError
from .excitation import CloughPenzien, Excitation, KanaiTajimi, ShinozukaSato
from .presets import preset_description, preset_names, preset_text
from .structures import BoucWen, Building, Storey
from .units import SI, UnitSystem, unit_system

__all__ = ["DEFAULT_PRESET", "Case", "case_from_dict", "load_case", "preset_description", "preset_names"]

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
        object.__setattr__(self, "buildings", tuple(self.buildings))
        if len(self.buildings) != 2:
            raise CaseError("buildings", f"a case has exactly two buildings, got {len(self.buildings)}")
        for number, (level, building) in enumerate(zip(self.contact.levels, self.buildings), start=1):
            if level > building.n_storeys:
                raise CaseError(
                    "contact.levels",
                    f"building {number} has {building.n_storeys} storey(s); its contact level must lie in 1..{building.n_storeys}, got {level}",
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

_TOP_KEYS = {"units", "name", "description", "excitation", "buildings", "contact"}
_EXCITATION_KEYS = {"spectrum", "G0", "omega_g", "xi_g", "omega_f", "xi_f", "duration", "envelope", "B1", "B2", "time_step", "cutoff_frequency", "synthesis_factor"}
_BUILDING_KEYS = {"damping_ratio", "storeys"}
_STOREY_KEYS = {"mass", "stiffness", "period", "damping", "bouc_wen"}
_BOUC_WEN_KEYS = {"alpha", "A", "beta", "gamma", "n"}
_CONTACT_KEYS = {"model", "gap", "stiffness", "restitution", "levels"}
SPECTRA = ("kanai-tajimi", "clough-penzien")
ENVELOPES = ("none", "shinozuka-sato")


def _check_keys(table, allowed: set[str], where: str) -> None:
    if not isinstance(table, dict):
        raise CaseError(where or "case", "must be a table")
    for key in table:
        if key not in allowed:
            field = f"{where}.{key}" if where else key
            raise CaseError(field, f"unknown key; allowed here: {', '.join(sorted(allowed))}")


def _number(table, key: str, where: str, default=None) -> float:
    value = table.get(key, default)
    if value is None:
        raise CaseError(f"{where}.{key}", "is required")
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise CaseError(f"{where}.{key}", f"must be a finite number, got {value!r}")
    return float(value)


def _build(where: str, constructor, *args, **kwargs):
    """Call a dataclass constructor, placing its errors under ``where``."""
    try:
        return constructor(*args, **kwargs)
    except CaseError as error:
        raise error.under(where) from None


def _excitation(table, units: UnitSystem) -> Excitation:
    where = "excitation"
    _check_keys(table, _EXCITATION_KEYS, where)
    spectrum_name = table.get("spectrum", "kanai-tajimi")
    if spectrum_name not in SPECTRA:
        raise CaseError(f"{where}.spectrum", f"unknown spectrum {spectrum_name!r}; allowed: {', '.join(SPECTRA)}")
    G0 = units.to_si(_number(table, "G0", where), length=2)
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
    envelope_name = table.get("envelope", "none")
    if envelope_name not in ENVELOPES:
        raise CaseError(f"{where}.envelope", f"unknown envelope {envelope_name!r}; allowed: {', '.join(ENVELOPES)}")
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


def _storey(table, units: UnitSystem, where: str, single: bool) -> Storey:
    _check_keys(table, _STOREY_KEYS, where)
    bouc_wen_table = table.get("bouc_wen", {"alpha": 1.0})
    _check_keys(bouc_wen_table, _BOUC_WEN_KEYS, f"{where}.bouc_wen")
    n = _number(bouc_wen_table, "n", f"{where}.bouc_wen", 1.0)
    bouc_wen = _build(
        f"{where}.bouc_wen",
        BoucWen,
        alpha=_number(bouc_wen_table, "alpha", f"{where}.bouc_wen", 1.0),
        A=_number(bouc_wen_table, "A", f"{where}.bouc_wen", 1.0),
        # beta, gamma multiply |z|^n: [1/length^n]
        beta=units.to_si(_number(bouc_wen_table, "beta", f"{where}.bouc_wen", 0.0), length=-n),
        gamma=units.to_si(_number(bouc_wen_table, "gamma", f"{where}.bouc_wen", 0.0), length=-n),
        n=n,
    )
    given = [key for key in ("mass", "stiffness", "period") if key in table]
    if "period" in given and not single:
        raise CaseError(f"{where}.period", "applies to one-storey buildings only; give mass and stiffness per storey")
    if len(given) != 2:
        allowed = "mass and stiffness, or two of mass, stiffness and period" if single else "mass and stiffness"
        raise CaseError(where, f"give {allowed}; got {', '.join(given) or 'none'}")
    mass = units.to_si(_number(table, "mass", where), mass=1) if "mass" in table else None
    stiffness = units.to_si(_number(table, "stiffness", where), force=1, length=-1) if "stiffness" in table else None
    if "period" in table:
        period = _number(table, "period", where)
        if period <= 0:
            raise CaseError(f"{where}.period", f"must be > 0 s, got {period:g}")
        omega_squared = (2.0 * math.pi / period) ** 2
        if mass is None:
            mass = stiffness / omega_squared
        else:
            stiffness = mass * omega_squared
    damping = units.to_si(_number(table, "damping", where), force=1, length=-1) if "damping" in table else None
    return _build(where, Storey, mass, stiffness, bouc_wen, damping)


def _building(table, units: UnitSystem, where: str) -> Building:
    _check_keys(table, _BUILDING_KEYS, where)
    storeys = table.get("storeys")
    if not isinstance(storeys, list) or not storeys:
        raise CaseError(f"{where}.storeys", "at least one [[buildings.storeys]] table is required")
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
    return _build(
        where,
        Contact,
        gap=units.to_si(_number(table, "gap", where), length=1),
        stiffness=units.to_si(_number(table, "stiffness", where), force=1, length=-exponent),
        restitution=_number(table, "restitution", where, 0.65),
        levels=tuple(table.get("levels", (1, 1))),
        model=model,
    )


def case_from_dict(data: dict, name: str = "case") -> Case:
    """Build a :class:`Case` from the parsed TOML schema (see README.md),
    converting to SI. Raises :class:`CaseError` naming the offending key."""
    _check_keys(data, _TOP_KEYS, "")
    units = unit_system(data.get("units", SI.name))
    for key in ("excitation", "buildings", "contact"):
        if key not in data:
            raise CaseError(key, "is required")
    buildings = data["buildings"]
    if not isinstance(buildings, list) or len(buildings) != 2:
        count = len(buildings) if isinstance(buildings, list) else 0
        raise CaseError("buildings", f"exactly two [[buildings]] tables are required, got {count}")
    return _build(
        "",
        Case,
        excitation=_excitation(data["excitation"], units),
        buildings=tuple(_building(b, units, f"buildings.{i}") for i, b in enumerate(buildings, start=1)),
        contact=_contact(data["contact"], units),
        name=str(data.get("name", name)),
        description=str(data.get("description", "")),
        units=units.name,
    )


def _parse(text: str, source: str) -> dict:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise CaseError(source, f"not valid TOML: {error}") from None


def load_case(source: str | Path) -> Case:
    """A case from a TOML file path or a preset name (see ``preset_names()``)."""
    text = preset_text(source) if isinstance(source, str) else None
    if text is not None:
        return case_from_dict(_parse(text, source), name=source)
    path = Path(source)
    if not path.is_file():
        raise CaseError("case", f"{str(source)!r} is neither a TOML file nor a preset; presets: {', '.join(preset_names())}")
    return case_from_dict(_parse(path.read_text(), str(path)), name=path.stem)
