"""Where a report's inputs came from: a preset, a case file or the dashboard,
what was changed from the preset, and the command that made the report.

:func:`case_changes` compares two parsed case files (the TOML tables) key by
key, after writing in the defaults the parser takes and reconciling the
spellings of one case (a storey's period or its mass, a yield drift or its
Bouc-Wen law, a PGA or its G0), so that only real changes are listed, each
with its value before and after in one unit system.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from dataclasses import dataclass

from pounding.errors import ArgumentError
from pounding.presets import preset_text
from pounding.report.case_keys import file_units, key_unit, normalized_case_file, to_units

__all__ = ["CaseChange", "ReportProvenance", "case_changes", "case_provenance"]

RELATIVE_TOLERANCE = 1e-9
"""Numbers closer than this (relative) are the same: a value converted between unit systems and back."""


@dataclass(frozen=True)
class CaseChange:
    """One key of the case file that differs from the preset.

    Attributes
    ----------
    key : str
        Dotted path in the case file, lists counted from 1 (``buildings.2.storeys.1.period``).
    before, after : float, str, list or None
        The value in the preset and in the report's case, in the unit system of
        ``unit``; None where that side does not give the key.
    unit : str
        Unit of ``before`` and ``after`` (``"mm"``, ``"kN/mm"``, ``"g"``); ``"-"`` for a pure
        number, ``""`` for a text.
    """

    key: str
    before: object
    after: object
    unit: str


@dataclass(frozen=True)
class ReportProvenance:
    """Where a report's case came from.

    Attributes
    ----------
    source : str
        What the case was read from, as the user named it: a preset's name, a case file's
        path, "the dashboard".
    preset : str or None
        The preset the case started from, if any.
    changes : tuple of CaseChange or None
        The keys that differ from ``preset`` (:func:`case_changes`); empty for the preset itself;
        None when the case differs from the preset in ways not known (no case file was given).
    command : str or None
        The command line (or dashboard action) that made the report.
    """

    source: str
    preset: str | None = None
    changes: tuple[CaseChange, ...] | None = ()
    command: str | None = None

    @property
    def modified(self) -> bool:
        """True when the case is a preset with changes (listed or not)."""
        return self.preset is not None and (self.changes is None or bool(self.changes))


def case_provenance(after: dict, preset: str | None = None, before: dict | None = None, source: str | None = None,
                    command: str | None = None, units: str = "SI") -> ReportProvenance:
    """The provenance of the case file ``after`` started from ``preset``.

    Parameters
    ----------
    after : dict
        The report's case as a parsed case file (``dashboard`` model's ``case_data()``, a TOML file's table).
    preset : str, optional
        The preset it started from; None for none.
    before : dict, optional
        The preset's parsed case file; read from the preset (:func:`pounding.presets.preset_text`) when None.
    source : str, optional
        What the case was read from; the preset's name, or else ``after``'s ``name``, when None.
    command : str, optional
        The command that made the report.
    units : str
        Unit system of the changes' values (the report's: "SI" or "kgf-cm-s").

    Raises
    ------
    ArgumentError
        ``preset`` names no preset (naming ``preset``).
    """
    changes: tuple[CaseChange, ...] = ()
    if preset is not None:
        if before is None:
            text = preset_text(preset)
            if text is None:
                raise ArgumentError("preset", f"{preset!r} is not a preset ('pounding cases' lists them)")
            before = tomllib.loads(text)
        changes = case_changes(before, after, units)
    return ReportProvenance(source or preset or str(after.get("name", "case")), preset, changes, command)


def case_changes(before: dict, after: dict, units: str = "SI") -> tuple[CaseChange, ...]:
    """The keys in which case file ``after`` differs from case file ``before``.

    Both are parsed case files (TOML tables), each in its own ``units``. Defaults the
    parser takes count as given; a one-storey building's mass, stiffness and period are
    compared all three; a storey given by its yield drift is compared with one given by
    its Bouc-Wen law as that law, and an excitation given by its PGA with one given by
    G0 as that G0. A value neither file gives (a mass implied by the period and stiffness
    both give) is not listed: it follows from those that are. Numbers within :data:`RELATIVE_TOLERANCE` are equal. ``name``,
    ``description`` and ``units`` are not compared.

    Parameters
    ----------
    before, after : dict
        Parsed case files.
    units : str
        Unit system of the values returned ("SI" or "kgf-cm-s").

    Returns
    -------
    tuple of CaseChange
        In the order of ``after``'s keys, then the keys only ``before`` gives.
    """
    old, new = normalized_case_file(before), normalized_case_file(after)
    _same_forms(old, new)
    flat_old, flat_new = _flat(old), _flat(new)
    given = _flat(before).keys() | _flat(after).keys()  # a value neither file gives follows from those listed
    changes = []
    for key in [*flat_new, *(k for k in flat_old if k not in flat_new)]:
        if key == "units" or key not in given:  # the values are compared converted
            continue
        a, b = to_units(key, flat_old.get(key), old, units), to_units(key, flat_new.get(key), new, units)
        if _equal(a, b):
            continue
        unit_before, unit_after = key_unit(key, old, units), key_unit(key, new, units)
        unit = unit_after if a is None else unit_before if b is None or unit_before == unit_after else f"{unit_before} -> {unit_after}"
        changes.append(CaseChange(key, a, b, unit))
    return tuple(changes)


def _flat(data, prefix: str = "") -> dict:
    """Every value of a case file by its dotted key; tables of tables (storeys, buildings) counted from 1,
    lists of numbers or texts kept whole."""
    out = {}
    items = data.items() if isinstance(data, dict) else enumerate(data, start=1)
    for key, value in items:
        path = f"{prefix}{key}"
        if isinstance(value, dict) or (isinstance(value, list) and value and all(isinstance(v, dict) for v in value)):
            out |= _flat(value, path + ".")
        else:
            out[path] = value
    return out


def _equal(a, b) -> bool:
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_equal(x, y) for x, y in zip(a, b))
    numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (a, b))
    if numbers:
        return math.isclose(a, b, rel_tol=RELATIVE_TOLERANCE, abs_tol=0.0) or (math.isnan(a) and math.isnan(b))
    return a == b


# --- one spelling for both sides ------------------------------------------------------------


def _same_forms(old: dict, new: dict) -> None:
    """Where one side gives a storey by its yield drift and the other by its Bouc-Wen law, or the
    excitation by its PGA and the other by G0, rewrite that side in the other's form (in place)."""
    for side, other in ((old, new), (new, old)):
        for b, building in enumerate(_list(side.get("buildings"))):
            other_storeys = _list(_item(_list(other.get("buildings")), b).get("storeys"))
            for s, storey in enumerate(_list(building.get("storeys"))):
                if "hysteresis" in storey and "bouc_wen" in _item(other_storeys, s):
                    law = _bouc_wen(storey)
                    if law is not None:
                        storey.pop("hysteresis")
                        storey["bouc_wen"] = law
        excitation, other_excitation = side.get("excitation"), other.get("excitation")
        if isinstance(excitation, dict) and isinstance(other_excitation, dict) and "pga" in excitation and "G0" in other_excitation \
                and "records" not in excitation:
            g0 = _g0(excitation, side)
            if g0 is not None:
                excitation.pop("pga")
                excitation["G0"] = g0


def _list(value) -> list:
    return [v for v in value if isinstance(v, dict)] if isinstance(value, list) else []


def _item(items: list, index: int) -> dict:
    return items[index] if index < len(items) else {}


def _bouc_wen(storey: dict) -> dict | None:
    """The Bouc-Wen law (file units) of a storey given by its yield drift or yield force (G28); None if it cannot be built."""
    from pounding.mechanics.structures import BoucWen

    table = storey["hysteresis"]
    try:
        drift = table["yield_drift"] if "yield_drift" in table else table["yield_force"] / storey["stiffness"]
        law = BoucWen.from_yield_drift(drift, table["post_yield_ratio"], table["n"], table["beta_share"])
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return None
    return dataclasses.asdict(law)


def _g0(excitation: dict, data: dict) -> float | None:
    """G0 (in the units of case file ``data``) of its excitation given by its expected PGA; None if it cannot be built."""
    from pounding.case.excitation import read_excitation

    units = file_units(data)
    try:
        built, _ = read_excitation(excitation, units, None)
    except (ValueError, TypeError):
        return None
    return to_units("excitation.G0", built.spectrum.G0, {}, units.name)
