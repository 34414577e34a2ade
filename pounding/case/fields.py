"""Reading the fields of a case file: each number checked as the file writes
it, in the file's units, and only then converted to SI, so that an error
quotes the key and the value as written."""

from __future__ import annotations

import math
from collections.abc import Mapping

from pounding.errors import CaseError, InputError, described, finite_number, quote
from pounding.units import UnitSystem

__all__ = ["build", "check_keys", "choice", "number", "quantity", "text_list", "to_si"]


def check_keys(table, allowed: set[str], where: str) -> None:
    if not isinstance(table, Mapping):
        raise CaseError(where or "case", f"must be a table, got {described(table)}")
    for key in table:
        if key not in allowed:
            written = quote(key) if not isinstance(key, str) or len(key) > 40 else key
            field = f"{where}.{written}" if where else written
            raise CaseError(field, f"unknown key; allowed here: {', '.join(sorted(allowed))}")


def number(table, key: str, where: str, default=None) -> float:
    value = table.get(key, default)
    if value is None:
        raise CaseError(f"{where}.{key}", "is required")
    return finite_number(f"{where}.{key}", value)


def to_si(field: str, value: float, units: UnitSystem, **dimensions) -> float:
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


def quantity(table, key: str, where: str, units: UnitSystem, *, strict: bool, default=None, **dimensions) -> float:
    """A dimensional number of the file: > 0 (``strict``) or >= 0, checked in
    the file's units, then converted to SI."""
    value = number(table, key, where, default)
    if not (value > 0 if strict else value >= 0):
        label = units.label(**dimensions)
        raise CaseError(f"{where}.{key}", f"must be {'>' if strict else '>='} 0 {label}, got {value:g} {label}")
    return to_si(f"{where}.{key}", value, units, **dimensions)


def build(where: str, constructor, *args, **kwargs):
    """Call a dataclass constructor (or a function of the case's values), placing its errors under ``where``:
    an argument it refuses came from the case file, so it is named as the key there."""
    try:
        return constructor(*args, **kwargs)
    except InputError as error:
        raise CaseError(error.field, error.message).under(where) from None


def choice(table, key: str, allowed: tuple[str, ...], where: str, default: str) -> str:
    value = table.get(key, default)
    if not (isinstance(value, str) and value in allowed):
        raise CaseError(f"{where}.{key}", f"unknown {key} {quote(value)}; allowed: {', '.join(allowed)}")
    return value


def text_list(table, key: str, where: str) -> list[str]:
    """A non-empty list of strings (file names, globs)."""
    value = table.get(key)
    if isinstance(value, str):
        value = [value]
    if not (isinstance(value, list) and value and all(isinstance(item, str) and item for item in value)):
        raise CaseError(f"{where}.{key}", f"must be a list of file names or globs, e.g. [\"motions/*.AT2\"], got {quote(value)}")
    return value
