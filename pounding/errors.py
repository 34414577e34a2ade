"""Exceptions raised at the library's boundary."""

from __future__ import annotations

__all__ = ["CaseError", "ConvergenceError", "SimulationError", "check_probability"]


class CaseError(ValueError):
    """An input is out of its allowed range or malformed.

    Parameters
    ----------
    field : str
        Dotted path of the offending input, as in the case file
        (``"buildings.2.storeys.1.mass"``), buildings and storeys counted from 1.
    message : str
        What is allowed.
    """

    def __init__(self, field: str, message: str):
        self.field = field
        self.message = message
        super().__init__(f"{field}: {message}")

    def under(self, prefix: str) -> "CaseError":
        """The same error, with its field placed under ``prefix``."""
        if not prefix:
            return self
        return CaseError(f"{prefix}.{self.field}" if self.field else prefix, self.message)


class SimulationError(RuntimeError):
    """A time-history analysis failed (NaN, runaway response, step-size underflow)."""


class ConvergenceError(RuntimeError):
    """An iteration (e.g. statistical linearization) did not converge."""


def check_probability(value, field: str = "target_probability") -> None:
    """Raise :class:`CaseError` naming ``field`` unless ``value`` lies in (0, 1)."""
    if isinstance(value, bool) or not (isinstance(value, float | int) and 0.0 < value < 1.0):
        raise CaseError(field, f"must lie in (0, 1), got {value!r}")
