"""Argument types of the command line, shared by its subcommands.

Each refuses a bad value with a message naming what is allowed; argparse
prefixes it with the option as typed (``argument --tolerance: ...``) and the
command exits 2.
"""

from __future__ import annotations

import argparse
import math

from . import defaults

__all__ = ["bounded_number", "probability", "record_count", "tolerance", "whole_number"]


def _shown(text: str) -> str:
    return repr(text if len(text) <= 40 else text[:37] + "...")


def whole_number(minimum: int, maximum: int | None = None, limit: str | None = None):
    """An argparse type: a whole number >= ``minimum`` (and <= ``maximum``).

    With ``limit`` (what is counted, e.g. ``"records"``) ``maximum`` is a
    resource limit of :mod:`pounding.defaults`, lifted by ``POUNDING_LIMITS=off``.
    """

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a whole number, got {_shown(text)}") from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be >= {minimum}, got {value}")
        if maximum is not None and value > maximum:
            if limit is None:
                raise argparse.ArgumentTypeError(f"must be <= {maximum}, got {value}")
            if defaults.limits_enabled():
                shown = f"{value:,}" if value < 10**15 else f"{value:.3g}"
                raise argparse.ArgumentTypeError(
                    f"{shown} {limit} exceed the limit of {maximum:,} ({defaults.LIMITS_VARIABLE}=off lifts it)"
                )
        return value

    return parse


record_count = whole_number(1, defaults.MAX_RECORDS, "records")
"""An argparse type: a number of records, 1 to :data:`~pounding.defaults.MAX_RECORDS`."""


def bounded_number(low: float, high: float, *, open_low: bool = False, open_high: bool = False):
    """An argparse type: a finite number in [low, high] (an open end with ``open_low``, ``open_high``)."""
    interval = f"{'(' if open_low else '['}{low:g}, {high:g}{')' if open_high else ']'}"

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a number in {interval}, got {_shown(text)}") from None
        above = value > low if open_low else value >= low
        below = value < high if open_high else value <= high
        if not (math.isfinite(value) and above and below):
            raise argparse.ArgumentTypeError(f"must be a number in {interval}, got {_shown(text)}")
        return value

    return parse


probability = bounded_number(0.0, 1.0, open_low=True, open_high=True)
"""An argparse type: a probability in (0, 1)."""
capacity = bounded_number(0.0, 1e15, open_low=True)
"""An argparse type: a capacity [N] > 0 (``--capacity``)."""
tolerance = bounded_number(1e-12, 1e-2)
"""An argparse type: the integrator's relative tolerance, as ``Settings.tolerance`` allows."""
