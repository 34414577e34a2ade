"""The dashboard's messages for a bad input: one line naming the input as the page labels it, and the case
file's key beside it (never a command-line option: the page has no command line)."""

from __future__ import annotations

from pounding.errors import ArgumentError, CaseError, ConvergenceError, SimulationError

__all__ = ["message"]

_LABELS = {
    "period": "period", "mass": "storey mass", "stiffness": "storey stiffness", "damping_ratio": "damping ratio",
    "bouc_wen.alpha": "Bouc-Wen alpha", "bouc_wen.A": "Bouc-Wen A", "bouc_wen.beta": "Bouc-Wen beta",
    "bouc_wen.gamma": "Bouc-Wen gamma", "bouc_wen.n": "Bouc-Wen n", "hysteresis.yield_drift": "yield drift",
    "hysteresis.yield_force": "yield force", "hysteresis.post_yield_ratio": "post-yield ratio", "hysteresis.n": "Bouc-Wen n",
    "hysteresis.beta_share": "Bouc-Wen beta share",
}


def message(error: Exception) -> str:
    """One line naming the input: the case file's field, then the widget's name; a library call's
    argument by its name in words (``target_probability``: "target probability"), never a flag."""
    if isinstance(error, ArgumentError):
        return f"Invalid input: {error.field.replace('_', ' ')}: {error.message}"
    if isinstance(error, CaseError):
        field = error.field
        parts = field.split(".")
        where = ""
        if parts[0] == "buildings" and len(parts) >= 2:
            rest = ".".join(parts[4:]) if len(parts) >= 4 and parts[2] == "storeys" else ".".join(parts[2:])
            where = f"building {parts[1]}, {_LABELS.get(rest, rest)}" if rest else f"building {parts[1]}"
        elif parts[0] == "contact":
            where = f"contact {'.'.join(parts[1:])}"
        elif parts[0] == "excitation":
            where = f"excitation {'.'.join(parts[1:])}"
        elif field.startswith("--"):  # a command-line option: the page's input of the same name ("records")
            return f"Invalid input: {field[2:]}: {error.message}"
        prefix = f"{where} ({field})" if where else field
        return f"Invalid input: {prefix}: {error.message}"
    if isinstance(error, ConvergenceError):
        return f"No estimate for these inputs: {error}"
    if isinstance(error, SimulationError):
        return f"A time history failed: {error}"
    return f"These inputs cannot be computed: {error}"  # never a class name: the page's reader knows none
