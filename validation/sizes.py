"""The scripts' reduced sizes: each ``main`` takes how many cases, records or
seeds to run, the full run's by default, and ``tests/test_validation_scripts.py``
runs them small."""

from __future__ import annotations

__all__ = ["first"]


def first(items, count: int | None) -> list:
    """The first ``count`` of ``items`` (all of them for None)."""
    items = list(items)
    return items if count is None else items[:count]
