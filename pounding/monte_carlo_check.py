"""The closed form against a Monte Carlo study of the same case, in one line: within the study's 95 %
confidence interval of the mean, or how far below or above it."""

from __future__ import annotations

import math

__all__ = ["verdict", "verdict_text"]


def verdict(estimate: float, low: float, high: float) -> tuple[str, float]:
    """Where ``estimate`` [N] lies against the Monte Carlo 95 % interval [``low``, ``high``] [N] of E[F_max]:
    ``("within", 0.0)``, or ``("below", r)`` / ``("above", r)`` with r = estimate / the nearer end - 1 [-]
    (``("undefined", nan)`` when the interval is not finite: one record, or none pounded)."""
    if not (math.isfinite(low) and math.isfinite(high) and math.isfinite(estimate)):
        return "undefined", math.nan
    if low <= estimate <= high:
        return "within", 0.0
    if estimate < low:
        return "below", (estimate / low - 1.0) if low > 0 else -math.inf
    return "above", (estimate / high - 1.0) if high > 0 else math.inf


def verdict_text(estimate: float, low: float, high: float) -> str:
    """:func:`verdict` as a short phrase: "within the Monte Carlo 95 % interval", "4.8 % below it"."""
    where, ratio = verdict(estimate, low, high)
    if where == "within":
        return "within the Monte Carlo 95 % interval"
    if where == "undefined":
        return "no Monte Carlo interval to compare with (run 2 or more records)"
    size = f"{100 * abs(ratio):.1f} %" if math.isfinite(ratio) else "far"
    return f"{size} {where} the Monte Carlo 95 % interval"
