"""Argument types of the command line, shared by its subcommands.

Each refuses a bad value with a message naming what is allowed; argparse
prefixes it with the option as typed (``argument --tolerance: ...``) and the
command exits 2.
"""

from __future__ import annotations

import argparse
import math

from pounding import defaults

__all__ = ["add_capacity", "add_units", "bounded_number", "capacity_newtons", "increasing_values", "probability", "record_count", "study_size", "tolerance",
           "whole_number_type"]


def _shown(text: str) -> str:
    return repr(text if len(text) <= 40 else text[:37] + "...")


def whole_number_type(minimum: int, maximum: int | None = None, limit: str | None = None):
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


record_count = whole_number_type(1, defaults.MAX_RECORDS, "records")
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


def add_capacity(parser: argparse.ArgumentParser, what: str, required: bool = False) -> None:
    """``--capacity F``: a force the contact can take, in the forces' display unit (kN; kgf with ``--units
    kgf-cm-s``), > 0; ``what`` says what it adds to the command's output ("also the probability that F_max exceeds
    it"). Read it in N with :func:`capacity_newtons`."""
    parser.add_argument("--capacity", type=capacity, metavar="F", default=None, required=required,
                        help=f"a capacity F (kN; kgf with --units kgf-cm-s){': ' + what if what else ''}")


def capacity_newtons(args) -> float | None:
    """``--capacity`` in N: given in the display unit of forces, kN, or kgf with ``--units kgf-cm-s`` (converted here,
    once, as every force printed is shown in it); None when not given."""
    if args.capacity is None:
        return None
    from pounding.display_units import display  # light: no numerical library

    return args.capacity * display(args.units).force_scale


def add_units(parser: argparse.ArgumentParser, what: str) -> None:
    """``--units``: the unit systems of the library, named as the dashboard's unit switch names them; SI (kN, mm) by
    default. ``what`` says what they apply to ("the forces and lengths printed")."""
    from pounding.units import UNIT_SYSTEMS  # light: no numerical library

    parser.add_argument("--units", choices=tuple(UNIT_SYSTEMS), default="SI",
                        help=f"units of {what}: SI shows kN and mm, kgf-cm-s kgf and cm (default SI); --json is always SI (N, m)")


def increasing_values(unit: str, minimum_count: int = 2, maximum: float = math.inf):
    """An argparse type: ``start:stop:count`` (``count`` >= ``minimum_count`` values from ``start`` to ``stop``,
    both ends included) or ``a,b,c``; every value a finite number > 0 and at most ``maximum`` in ``unit``, strictly
    increasing."""

    def number(text: str, whole: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{_shown(text.strip())} in {_shown(whole)} is not a number") from None
        if not (math.isfinite(value) and value > 0):
            raise argparse.ArgumentTypeError(f"every value must be a finite number > 0 {unit}, got {_shown(text.strip())}")
        if value > maximum:
            raise argparse.ArgumentTypeError(f"every value must be at most {maximum:g} {unit}, got {_shown(text.strip())}")
        return value

    def parse(text: str) -> tuple[float, ...]:
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise argparse.ArgumentTypeError(f"a range is start:stop:count, got {_shown(text)}")
            start, stop = number(parts[0], text), number(parts[1], text)
            try:
                count = int(parts[2])
            except ValueError:
                raise argparse.ArgumentTypeError(f"count must be a whole number, got {_shown(parts[2].strip())}") from None
            if count < minimum_count:
                raise argparse.ArgumentTypeError(f"count must be >= {minimum_count}, got {count}")
            if not start < stop:
                raise argparse.ArgumentTypeError(f"the range must increase: start < stop, got {_shown(text)}")
            if count > defaults.MAX_SWEEP_POINTS and defaults.limits_enabled():
                raise argparse.ArgumentTypeError(f"{count:,} points exceed the limit of {defaults.MAX_SWEEP_POINTS:,} "
                                                 f"({defaults.LIMITS_VARIABLE}=off lifts it)")
            step = (stop - start) / (count - 1)
            values = tuple(float(f"{start + i * step:.12g}") for i in range(count - 1)) + (stop,)
        else:
            values = tuple(number(item, text) for item in text.split(","))
            if len(values) < minimum_count:
                raise argparse.ArgumentTypeError(f"give at least {minimum_count} values (start:stop:count or a,b,c), got {_shown(text)}")
        if any(b <= a for a, b in zip(values, values[1:])):
            raise argparse.ArgumentTypeError(f"the values must increase strictly, got {_shown(text)}")
        return values

    return parse


def study_size(case, args, treated: str = "integrated once") -> tuple[int, int]:
    """The records and seed of a study from ``--records`` and ``--seed``: for recorded motions, all of them (saying
    on stderr, if either was given, that they do not apply and that each record is ``treated``)."""
    import sys

    if case.recorded:
        if args.records is not None or args.seed is not None:
            print(f"pounding {args.command}: note: --records and --seed do not apply to recorded motions: each of the "
                  f"{len(case.hazard.records)} is {treated}", file=sys.stderr)
        return len(case.hazard.records), defaults.SEED
    return args.records or defaults.RECORDS, defaults.SEED if args.seed is None else args.seed
