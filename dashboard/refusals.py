"""Why a value typed into one of the dashboard's inputs is not taken: :func:`refusal`.

Each input's range is its parameter's bounds (``inputs.py``, ``studies.py``), and for the gap a largest value
(:data:`MAX_GAP`). A value outside is refused before it reaches the case: the page shows the input red with the
reason, in the input's units, and the results of the last inputs taken stay, said to be so (``model.py``).
"""

from __future__ import annotations

import math
import numbers
import re

import param

from pounding import defaults
from pounding.display_units import display

__all__ = ["MAX_GAP", "refusal"]

MAX_GAP = 2 * defaults.DISPLACEMENT_LIMIT
"""The largest gap [m] the page takes: two floors, each stopped as a runaway response beyond
``defaults.DISPLACEMENT_LIMIT``, never close a wider one."""

_UPPER_SI = {"gap": MAX_GAP}
"""Largest values [SI] of inputs whose parameter has no upper bound."""
_LIMIT_ADVICE = {"records": " (the command line takes more)"}


def _figure(value: float) -> str:
    """A number as the page writes it in a message: 1,000, 0.25, 1e+308."""
    if value == 0 or 1e-3 <= abs(value) < 1e9:
        return f"{value:,.6g}"
    return f"{value:.3g}"


def _name_and_unit(owner: param.Parameterized, name: str, units: str) -> tuple[str, str, float]:
    """The input's name in words (building's inputs with the building), its unit, and its unit's size [SI]."""
    label = owner.param[name].label or name
    bracket = re.search(r"\s*\[([^\]]*)\]\s*$", label)
    words = label[: bracket.start()] if bracket else label
    unit, size = (bracket.group(1) if bracket and bracket.group(1) != "-" else ""), 1.0
    dims = owner.dimensions().get(name) if hasattr(owner, "dimensions") else None
    if dims:
        shown = display(units)
        unit, size = shown.label(**dims), shown.to_si(1.0, **dims)
    number = getattr(owner, "number", None)
    if number is not None and isinstance(getattr(type(owner), "number", None), int):
        words = f"building {number}'s {words}"
    first = words.split(" ", 1)[0]
    if first.isalpha() and first.islower():  # 'gap' -> 'Gap'; a symbol ('omega_g', 'xi_g') as the page writes it
        words = words[0].upper() + words[1:]
    return words, unit, size


def _with(value: float, unit: str) -> str:
    return f"{_figure(value)} {unit}".rstrip()


def refusal(owner: param.Parameterized, name: str, value, units: str = "SI") -> str:
    """Why ``value`` typed into input ``name`` of ``owner`` (the model, or one of its buildings; dimensional
    values in ``units``) is not taken, in one or two sentences with the allowed range and its unit; '' when
    it is taken."""
    parameter = owner.param[name]
    if not isinstance(parameter, param.Number):
        return ""
    words, unit, size = _name_and_unit(owner, name, units)
    low, high = parameter.bounds or (None, None)
    low_inclusive, high_inclusive = getattr(parameter, "inclusive_bounds", (True, True))
    if high is None and name in _UPPER_SI:
        high, high_inclusive = _UPPER_SI[name] / size, True
    whole = isinstance(parameter, param.Integer)
    span = (f"over {_with(low, unit)} and up to {_with(high, unit)}" if low is not None and high is not None and not low_inclusive
            else f"from {_with(low, unit)} to {_with(high, unit)}" if low is not None and high is not None
            else f"{'over' if not low_inclusive else 'of at least'} {_with(low, unit)}" if low is not None
            else f"up to {_with(high, unit)}" if high is not None else "")
    kind = "a whole number" if whole else "a value"
    advice = _LIMIT_ADVICE.get(name, "")
    asked = f"type {kind} {span}".rstrip()
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return f"{words}: that is not a number; {asked}."
    number = float(value) if not isinstance(value, numbers.Integral) or abs(value) < 1e300 else math.copysign(math.inf, value)
    if not math.isfinite(number):
        return f"{words}: {_figure(number)} is not a finite number; {asked}."
    typed = _with(number, unit)
    if whole and number != math.floor(number):
        return f"{words}: {typed} is not a whole number; {asked}."
    if low is not None and (number < low or (number == low and not low_inclusive)):
        return f"{words}: {typed} was not taken; {asked}."
    if high is not None and (number > high or (number == high and not high_inclusive)):
        return f"{words}: {typed} was not taken; {asked}{advice}."
    return ""
