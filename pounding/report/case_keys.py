"""Keys of a case file as the report names them: the unit of each key in a
unit system, its label in words, and the file with its defaults and
equivalent spellings made explicit, so that two files that describe the
same case compare equal key by key (:func:`normalized_case_file`).

Light: no physics is computed here beyond the conversions the case file
itself defines (a storey's period from its mass and stiffness, a yield drift
to its Bouc-Wen law, a PGA to its G0)."""

from __future__ import annotations

import copy
import dataclasses
import math
import re

from pounding import defaults
from pounding.hazard.excitation import CloughPenzien, Excitation, ShinozukaSato
from pounding.units import SI, UnitSystem, unit_system

__all__ = ["DEFAULTS", "file_units", "key_label", "key_unit", "normalized_case_file", "to_units"]



def _field_defaults(cls, names: tuple[str, ...]) -> dict:
    return {f.name: f.default for f in dataclasses.fields(cls) if f.name in names}


_SAMPLING = _field_defaults(Excitation, ("time_step", "cutoff_frequency", "synthesis_factor"))
# The parser's defaults for keys a case file may leave out (pounding.case.case, pounding.case.excitation and
# the dataclasses they build); tests/test_report_provenance.py checks each against the parser.
DEFAULTS = {
    "excitation": {"spectrum": "kanai-tajimi", "envelope": "none"},
    "process": _SAMPLING,
    "design": {**_SAMPLING, "synthesis_factor": defaults.DESIGN_SYNTHESIS_FACTOR},
    "shinozuka-sato": _field_defaults(ShinozukaSato, ("B1", "B2")),
    "clough-penzien": _field_defaults(CloughPenzien, ("omega_f", "xi_f")),
    "ec8": {"spectrum_type": 1},
    "building": {"damping_ratio": 0.05},
    "bouc_wen": {"alpha": 1.0, "A": 1.0, "beta": 0.0, "gamma": 0.0, "n": 1.0},
    "hysteresis": {"n": 1.0, "beta_share": 0.5},
    "contact": {"model": "jankowski", "restitution": 0.65, "levels": [1, 1]},
}

# Units that are the same in every system ("g": accelerations written in g whatever the file's units).
_FIXED = {
    "excitation.pga": "g", "excitation.ag": "g", "excitation.SDS": "g", "excitation.SD1": "g",
    "excitation.accelerations": "g", "excitation.periods": "s", "excitation.TL": "s",
    "excitation.duration": "s", "excitation.time_step": "s", "excitation.cutoff_frequency": "rad/s",
    "excitation.omega_g": "rad/s", "excitation.omega_f": "rad/s", "excitation.xi_g": "-", "excitation.xi_f": "-",
    "excitation.B1": "1/s", "excitation.B2": "1/s", "excitation.scale": "-", "excitation.synthesis_factor": "-",
    "buildings.*.damping_ratio": "-", "buildings.*.storeys.*.period": "s",
    "buildings.*.storeys.*.bouc_wen.alpha": "-", "buildings.*.storeys.*.bouc_wen.A": "-",
    "buildings.*.storeys.*.bouc_wen.n": "-", "buildings.*.storeys.*.hysteresis.post_yield_ratio": "-",
    "buildings.*.storeys.*.hysteresis.n": "-", "buildings.*.storeys.*.hysteresis.beta_share": "-",
    "contact.restitution": "-", "contact.levels": "-",
}
# Units that follow the file's system, as powers of length, force, mass and time.
_DIMENSIONS = {
    "excitation.G0": {"length": 2, "time": -3},
    "buildings.*.storeys.*.mass": {"mass": 1},
    "buildings.*.storeys.*.stiffness": {"force": 1, "length": -1},
    "buildings.*.storeys.*.damping": {"force": 1, "length": -1, "time": 1},
    "buildings.*.storeys.*.hysteresis.yield_drift": {"length": 1},
    "buildings.*.storeys.*.hysteresis.yield_force": {"force": 1},
    "contact.gap": {"length": 1},
}

_LABELS = {
    "G0": "G0 (Kanai-Tajimi intensity)", "pga": "expected PGA", "omega_g": "omega_g (ground frequency)",
    "xi_g": "xi_g (ground damping ratio)", "B1": "envelope B1", "B2": "envelope B2", "ag": "a_g (EN 1998-1)",
    "TL": "T_L", "gap": "gap", "restitution": "coefficient of restitution e", "levels": "contact floors",
    "model": "contact law", "stiffness": "stiffness", "period": "period T", "mass": "mass",
    "damping_ratio": "damping ratio", "yield_drift": "yield drift", "yield_force": "yield force",
    "post_yield_ratio": "post-yield ratio",
}


def _pattern(key: str) -> str:
    return re.sub(r"\.\d+(?=\.|$)", ".*", key)


def _dimension(key: str, data: dict) -> dict | str | None:
    """The unit of ``key`` of the case file ``data``: a fixed label, powers of the file's units, or None (a text)."""
    pattern = _pattern(key)
    if pattern in _FIXED:
        return _FIXED[pattern]
    if pattern in _DIMENSIONS:
        return _DIMENSIONS[pattern]
    if pattern in ("buildings.*.storeys.*.bouc_wen.beta", "buildings.*.storeys.*.bouc_wen.gamma"):
        storey = _at(data, key.rsplit(".", 2)[0])
        n = storey.get("bouc_wen", {}).get("n", DEFAULTS["bouc_wen"]["n"]) if isinstance(storey, dict) else 1.0
        return {"length": -_number_or(n, 1.0)}
    if pattern == "contact.stiffness":
        from pounding.mechanics.contact import contact_law

        try:
            exponent = contact_law(data.get("contact", {}).get("model", "jankowski"), "contact.model").stiffness_exponent
        except ValueError:
            return None
        return {"force": 1, "length": -exponent}
    return None


def _number_or(value, default: float) -> float:
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else default


def _at(data, key: str):
    node = data
    for part in key.split("."):
        if isinstance(node, list) and part.isdigit() and 1 <= int(part) <= len(node):
            node = node[int(part) - 1]
        elif isinstance(node, dict) and part in node:
            node = node[part]
        else:
            return None
    return node


def file_units(data: dict) -> UnitSystem:
    """The unit system a parsed case file is written in (SI when it says none, or none known)."""
    try:
        return unit_system(data.get("units", SI.name))
    except ValueError:
        return SI


def key_unit(key: str, data: dict, units: str = "SI") -> str:
    """The unit of case-file key ``key`` (``"contact.gap"``) shown in the unit system ``units``;
    ``""`` for a text (a law's name), ``"-"`` for a pure number."""
    dimension = _dimension(key, data)
    if dimension is None:
        return ""
    if isinstance(dimension, str):
        return dimension
    return unit_system(units).label(**dimension) or "-"


def to_units(key: str, value, data: dict, units: str = "SI"):
    """``value`` of key ``key`` of the case file ``data`` (in the file's units) in the unit system ``units``.
    Texts, and numbers whose unit is the same in every system, are returned as they are; lists element by element."""
    dimension = _dimension(key, data)
    if not isinstance(dimension, dict):
        return value
    if isinstance(value, list):
        return [to_units(key, v, data, units) for v in value]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return value
    return unit_system(units).from_si(file_units(data).to_si(float(value), **dimension), **dimension)


def key_label(key: str) -> str:
    """A case-file key in words: ``buildings.2.storeys.1.period`` is "building 2, storey 1: period T"."""
    parts = key.split(".")
    where, rest = [], []
    index = 0
    while index < len(parts):
        part = parts[index]
        if part in ("buildings", "storeys") and index + 1 < len(parts) and parts[index + 1].isdigit():
            where.append(f"{part[:-1]} {parts[index + 1]}")
            index += 2
            continue
        rest.append(part)
        index += 1
    if rest and rest[0] in ("excitation", "contact"):
        where.append(rest.pop(0))
    name = " ".join(_LABELS.get(part, part) if i == len(rest) - 1 else part for i, part in enumerate(rest))
    return f"{', '.join(where)}: {name}" if where and name else ", ".join(where) or name


# --- normalized case files --------------------------------------------------------------


def normalized_case_file(data: dict) -> dict:
    """A copy of the parsed case file ``data`` with every default the parser would take written in,
    and a one-storey building's mass, stiffness and period all given (from the two the file gives).
    ``name``, ``title`` and ``description`` are left out: they change no number of the case."""
    data = copy.deepcopy({key: value for key, value in data.items() if key not in ("name", "title", "description")})
    excitation = data.get("excitation")
    if isinstance(excitation, dict):
        if isinstance(excitation.get("records"), str):
            excitation["records"] = [excitation["records"]]
        if "records" not in excitation:
            _fill(excitation, DEFAULTS["excitation"])
            _fill(excitation, DEFAULTS["design" if excitation["spectrum"] == "design" else "process"])
            for form in (excitation.get("envelope"), excitation.get("spectrum"), excitation.get("code")):
                if isinstance(form, str) and form in DEFAULTS:
                    _fill(excitation, DEFAULTS[form])
    for building in data.get("buildings", []) if isinstance(data.get("buildings"), list) else []:
        if not isinstance(building, dict):
            continue
        _fill(building, DEFAULTS["building"])
        storeys = building.get("storeys")
        for storey in storeys if isinstance(storeys, list) else []:
            if not isinstance(storey, dict):
                continue
            if len(storeys) == 1:
                _complete_period(storey)
            if "hysteresis" in storey and isinstance(storey["hysteresis"], dict):
                _fill(storey["hysteresis"], DEFAULTS["hysteresis"])
            else:
                law = storey.setdefault("bouc_wen", {"alpha": 1.0})
                if isinstance(law, dict):
                    _fill(law, DEFAULTS["bouc_wen"])
    if isinstance(data.get("contact"), dict):
        _fill(data["contact"], DEFAULTS["contact"])
    return data


def _fill(table: dict, defaults: dict) -> None:
    for key, value in defaults.items():
        table.setdefault(key, copy.deepcopy(value))


def _complete_period(storey: dict) -> None:
    """Mass, stiffness and period of a one-storey building, the third from the two given (any coherent units)."""
    given = {key: storey[key] for key in ("mass", "stiffness", "period") if _positive(storey.get(key))}
    if len(given) != 2:
        return
    if "period" not in given:
        storey["period"] = 2.0 * math.pi * math.sqrt(given["mass"] / given["stiffness"])
    elif "mass" not in given:
        storey["mass"] = given["stiffness"] / (2.0 * math.pi / given["period"]) ** 2
    else:
        storey["stiffness"] = given["mass"] * (2.0 * math.pi / given["period"]) ** 2


def _positive(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and value > 0
