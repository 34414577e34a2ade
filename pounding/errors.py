"""Exceptions raised at the library's boundary, and the checks of its inputs
shared by the dataclasses, the loader and the command line."""

from __future__ import annotations

import math
import numbers

from pounding import defaults

__all__ = [
    "ArgumentError",
    "CaseError",
    "ConvergenceError",
    "InputError",
    "SimulationError",
    "check_limit",
    "check_probability",
    "described",
    "finite_number",
    "finite_numbers",
    "quote",
    "whole_number",
]


class InputError(ValueError):
    """An input is out of its allowed range or malformed.

    Parameters
    ----------
    field : str
        The offending input: a key of a case file (:class:`CaseError`) or an
        argument of a library call (:class:`ArgumentError`).
    message : str
        What is wrong and what is allowed.
    """

    def __init__(self, field: str, message: str):
        self.field = field
        self.message = message
        super().__init__(f"{field}: {message}")

    def under(self, prefix: str) -> "InputError":
        """The same error (same class), with its field placed under ``prefix``."""
        if not prefix:
            return self
        return type(self)(f"{prefix}.{self.field}" if self.field else prefix, self.message)


class CaseError(InputError):
    """A key of a case file is out of its allowed range or malformed.

    ``field`` is the key's dotted path as the file writes it
    (``"buildings.2.storeys.1.mass"``), buildings and storeys counted from 1;
    a dataclass of the case (``Storey``, ``Contact``...) names its own key
    (``"mass"``), which the loader places under its table. A file the case
    reads (a case file, a record) is named by its path, and line if known.
    """


class ArgumentError(InputError):
    """An argument of a library call is out of its allowed range or malformed.

    ``field`` is the Python argument's name (``"records"``, ``"vary"``,
    ``"path"``); the command line shows it as the option typed (``--records``).
    """


class SimulationError(RuntimeError):
    """A time-history analysis failed (NaN, runaway response, step-size underflow)."""


class ConvergenceError(RuntimeError):
    """An iteration (e.g. statistical linearization) did not converge."""


def quote(value, width: int = 40) -> str:
    """``repr(value)``, shortened to ``width`` characters (messages stay one short line)."""
    if isinstance(value, float) or (isinstance(value, numbers.Real) and not isinstance(value, numbers.Integral)):
        try:
            text = repr(float(value))  # 2.0 stays 2.0: a float where a whole number is needed shows
            text = text if len(text) <= 12 else f"{float(value):.6g}"
        except (OverflowError, ValueError):
            text = repr(value)
    elif isinstance(value, numbers.Integral) and not isinstance(value, bool):
        number = int(value)
        text = str(number) if abs(number) < 10**15 else f"{float(number):.6g}" if abs(number) < 10**300 else "a huge number"
    else:
        text = repr(value)
    return text if len(text) <= width else text[: width - 3] + "..."


def described(value) -> str:
    """``value``'s type and shortened repr, for a message: ``"str 'x'"``."""
    return f"{type(value).__name__} {quote(value)}"


def _is_number(value) -> bool:
    # numpy's float and integer scalars are numbers.Real; bool and numpy.bool_ are refused.
    return isinstance(value, numbers.Real) and not isinstance(value, bool) and type(value).__name__ != "bool_"


def finite_numbers(field: str, values, error: type[InputError] = CaseError) -> tuple[float, ...]:
    """``values`` as a tuple of Python floats, each checked by :func:`finite_number` as ``field.1``, ``field.2``, ..."""
    try:
        items = tuple(values)
    except TypeError:
        raise error(field, f"must be a sequence of numbers, got {quote(values)}") from None
    return tuple(finite_number(f"{field}.{i}", v, error) for i, v in enumerate(items, start=1))


def finite_number(field: str, value, error: type[InputError] = CaseError) -> float:
    """``value`` as a Python float: a finite real number (Python or numpy scalar);
    ``error`` (:class:`CaseError` or :class:`ArgumentError`) naming ``field`` otherwise."""
    if not _is_number(value):
        raise error(field, f"must be a finite number, got {quote(value)}")
    try:
        number = float(value)
    except (OverflowError, ValueError, TypeError):
        raise error(field, f"must be a finite number, got {quote(value)}") from None
    if not math.isfinite(number):
        raise error(field, f"must be a finite number, got {quote(value)}")
    return number


def whole_number(field: str, value, minimum: int | None = None, maximum: int | None = None,
                 error: type[InputError] = CaseError) -> int:
    """``value`` as a Python int: a whole number (Python or numpy integer) in
    [``minimum``, ``maximum``]; ``error`` naming ``field`` otherwise."""
    if not (_is_number(value) and isinstance(value, numbers.Integral)):
        allowed = f" >= {minimum}" if minimum is not None and maximum is None else ""
        raise error(field, f"must be a whole number{allowed}, got {quote(value)}")
    number = int(value)
    if minimum is not None and number < minimum or maximum is not None and number > maximum:
        allowed = f"from {minimum} to {maximum}" if maximum is not None and minimum is not None else (
            f">= {minimum}" if maximum is None else f"<= {maximum}")
        raise error(field, f"must be a whole number {allowed}, got {quote(number)}")
    return number


def check_limit(field: str, count, limit: int, what: str, remedy: str, error: type[InputError] = CaseError) -> None:
    """Raise ``error`` naming ``field`` when ``count`` exceeds ``limit``
    (one of the resource limits of :mod:`pounding.defaults`) while the limits
    are on (:func:`pounding.defaults.limits_enabled`).

    ``what`` names the counted thing ("samples per record"), ``remedy`` what
    to change; the message says how to lift the limits.
    """
    if not math.isfinite(count) or count > limit and defaults.limits_enabled():
        amount = f"{count:,.0f}" if math.isfinite(count) and count < 1e15 else f"{count:.3g}"
        lift = f" ({defaults.LIMITS_VARIABLE}=off lifts it)" if math.isfinite(count) else ""
        raise error(field, f"{amount} {what} exceed the limit of {limit:,}; {remedy}{lift}")


def check_probability(value, field: str = "target_probability", error: type[InputError] = ArgumentError) -> float:
    """``value`` as a float if it lies in (0, 1); ``error`` naming ``field`` otherwise
    (an :class:`ArgumentError` unless told: a probability is asked of a call, not of a case file)."""
    try:
        number = float(value) if _is_number(value) else math.nan
    except (OverflowError, ValueError, TypeError):
        number = math.nan
    if not 0.0 < number < 1.0:
        raise error(field, f"must lie in (0, 1), got {quote(value)}")
    return number
