"""Exceptions raised at the library's boundary."""

from __future__ import annotations

__all__ = ["CaseError", "ConvergenceError", "SimulationError"]


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
