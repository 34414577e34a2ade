"""The specs of a sweep's ``vary``: ``PATH=VALUES`` parsed, key paths checked, a sweep's
``vary`` argument normalised to a list of (path, values)."""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable, Mapping, Sequence

from pounding import defaults
from pounding.errors import ArgumentError, check_limit, quote

_SIGNIFICANT_DIGITS = 12  # start:stop:count grids are rounded to this, so 0:0.05:11 gives 0.015, not 0.015000000000000001


def _plain(value):
    """A number as a Python int or float (numpy scalars converted); anything else as it is."""
    if isinstance(value, bool) or type(value).__name__ == "bool_" or not isinstance(value, numbers.Real):
        return value
    return int(value) if isinstance(value, numbers.Integral) else float(value)


def _finite(value) -> bool:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    try:
        return math.isfinite(value)
    except OverflowError:  # an int beyond the floats
        return False


def _number(text: str, spec: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ArgumentError("vary", f"{spec!r}: {text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise ArgumentError("vary", f"{spec!r}: {text.strip()!r} is not a finite number")
    return value


def parse_values(text: str, spec: str | None = None) -> tuple[float, ...]:
    """The values of a ``vary`` spec.

    Parameters
    ----------
    text : str
        ``start:stop:count`` (``count`` evenly spaced values, both ends
        included, rounded to 12 significant digits) or ``a,b,c``.
    spec : str, optional
        The whole spec, for error messages.

    Returns
    -------
    tuple of float

    Raises
    ------
    ArgumentError
        Field ``vary``: malformed range or list, a value that is not a
        finite number, a count that is not a whole number >= 1, a repeated value.
    """
    spec = text if spec is None else spec
    if not text.strip():
        raise ArgumentError("vary", f"{spec!r}: no values; give start:stop:count or a,b,c")
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise ArgumentError("vary", f"{spec!r}: a range is start:stop:count (three parts), got {len(parts)} part(s)")
        start, stop = _number(parts[0], spec), _number(parts[1], spec)
        try:
            count = int(parts[2])
        except ValueError:
            raise ArgumentError("vary", f"{spec!r}: count must be a whole number >= 1, got {parts[2].strip()!r}") from None
        if count < 1:
            raise ArgumentError("vary", f"{spec!r}: count must be a whole number >= 1, got {count}")
        check_limit("vary", count, defaults.MAX_SWEEP_POINTS, f"values in {_short(spec)}", "give a coarser grid", error=ArgumentError)
        if count == 1:
            if start != stop:
                raise ArgumentError("vary", f"{spec!r}: one value from start != stop is ambiguous; give count >= 2")
            return (start,)
        step = (stop - start) / (count - 1)
        values = [float(f"{start + i * step:.{_SIGNIFICANT_DIGITS}g}") for i in range(count - 1)] + [stop]
    else:
        items = text.split(",")
        if any(not item.strip() for item in items):
            raise ArgumentError("vary", f"{spec!r}: empty value in the list; give a,b,c")
        check_limit("vary", len(items), defaults.MAX_SWEEP_POINTS, f"values in {_short(spec)}", "give fewer values", error=ArgumentError)
        values = [_number(item, spec) for item in items]
    seen = set()
    for value in values:
        if value in seen:
            raise ArgumentError("vary", f"{spec!r}: value {value:g} appears twice")
        seen.add(value)
    return tuple(values)


def _short(spec: str) -> str:
    return repr(spec if len(spec) <= 40 else spec[:37] + "...")


def check_point_count(vary: list[tuple[str, tuple[float, ...]]]) -> int:
    """The number of points of a sweep, the product of the counts of values;
    :class:`ArgumentError` naming ``vary`` above :data:`~pounding.defaults.MAX_SWEEP_POINTS`."""
    count = math.prod(len(values) for _, values in vary)
    check_limit("vary", count, defaults.MAX_SWEEP_POINTS, "sweep points (every combination of the values)", "vary fewer values", error=ArgumentError)
    return count


def parse_vary(spec: str) -> tuple[str, tuple[float, ...]]:
    """Split a ``vary`` spec ``PATH=VALUES`` into its path and values.

    Only the syntax is checked here; whether ``PATH`` names a key of the case
    is checked by :func:`sweep`.

    Raises
    ------
    ArgumentError
        Field ``vary``, naming the spec and what is wrong.
    """
    path, equals, values = spec.partition("=")
    path = path.strip()
    if not equals:
        raise ArgumentError("vary", f"{spec!r}: expected PATH=VALUES, e.g. contact.gap=0:2:5 or contact.gap=0.5,1,2")
    if not path:
        raise ArgumentError("vary", f"{spec!r}: no key path before '='")
    _check_path_syntax(path, spec)
    return path, parse_values(values, spec)


def _check_path_syntax(path: str, spec: str) -> None:
    if any(not part for part in path.split(".")):
        raise ArgumentError("vary", f"{spec!r}: empty part in the key path {path!r}")


def normalized_vary(vary: Mapping[str, Sequence[float] | str] | Iterable[str] | None) -> list[tuple[str, tuple[float, ...]]]:
    """``vary`` as a list of (path, values); values given as a spec string are parsed."""
    if vary is None:
        return []
    if isinstance(vary, str):
        raise ArgumentError("vary", "give a dict {path: values} or a list of PATH=VALUES specs, not one string")
    items = vary.items() if isinstance(vary, Mapping) else [parse_vary(spec) for spec in vary]
    out, seen = [], set()
    for path, values in items:
        if not isinstance(path, str) or not path:
            raise ArgumentError("vary", f"key path must be a non-empty string, got {path!r}")
        _check_path_syntax(path, path)
        if path in seen:
            raise ArgumentError("vary", f"{path!r} is varied twice; give all its values in one spec")
        seen.add(path)
        if isinstance(values, str):
            values = parse_values(values, f"{path}={values}")
        else:
            if isinstance(values, str) or not hasattr(values, "__len__"):
                raise ArgumentError("vary", f"{path!r}: give the values as a list or a spec string, got {type(values).__name__}")
            check_limit("vary", len(values), defaults.MAX_SWEEP_POINTS, f"values of {path!r}", "give fewer values", error=ArgumentError)
            values = tuple(_plain(v) for v in values)
            if not values:
                raise ArgumentError("vary", f"{path!r}: no values")
            for value in values:
                if not _finite(value):
                    raise ArgumentError("vary", f"{path!r}: {quote(value)} is not a finite number")
            if len(set(values)) != len(values):
                raise ArgumentError("vary", f"{path!r}: a value appears twice")
        out.append((path, values))
    check_point_count(out)
    return out
